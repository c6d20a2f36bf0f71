/* Independent blocks of J M⁻¹ Jᵀ (islands.c): puppets that share no
 * movable particle are solved one by one. Each block is numbered from 0,
 * so a puppet's block in a crowd is the very system it would be alone:
 * two puppets stepped in one world must move, bit for bit, as each does
 * in a world of its own, and the solve must say it split in two. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "mr_physics.h"

/* Fixed steps and no error control that depends on the whole world (the
 * shared step's length would otherwise be set by the busier puppet). */
static mr_world *make_world(void) {
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_CONSTRAINTS | MR_EFFECT_GRAVITY;
  def.dt_initial = def.dt_min = def.dt_max = def.dt_floor = 0.004;
  def.error_length = def.error_speed = 0.0;
  def.deviation_high = 0.4;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  return w;
}

static int ball(mr_world *w, double x, double y, double z, double mass, double vx) {
  mr_particle_def p = mr_default_particle_def();
  p.mass = mass;
  p.position[0] = x;
  p.position[1] = y;
  p.position[2] = z;
  p.velocity[0] = vx;
  int id;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  return id;
}

static void link(mr_world *w, int a, int b) {
  mr_distance_def d = mr_default_distance_def();
  d.a = a;
  d.b = b;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
}

/* A figure hung from a pin: a triangle (a rigid group's distances) on a
 * neck, and an arm of two links swinging from one corner. `shape` changes
 * its masses, size and kick, so two figures are two different systems. */
static void figure(mr_world *w, double x0, double shape) {
  const double s = 0.1 * shape;
  int top = ball(w, x0, 1.0, 0.0, 0.1, 0.0);
  int a = ball(w, x0 - s, 0.8, 0.0, 0.2 * shape, 0.3 * shape);
  int b = ball(w, x0 + s, 0.8, 0.0, 0.2, 0.0);
  int c = ball(w, x0, 0.8 - s, 0.05, 0.3, -0.2);
  int elbow = ball(w, x0 + s + 0.15, 0.8, 0.0, 0.05 * shape, 0.0);
  int hand = ball(w, x0 + s + 0.3, 0.8 + 0.05 * shape, 0.0, 0.04, 0.5);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = top;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  link(w, top, a);
  link(w, a, b);
  link(w, b, c);
  link(w, c, a);
  link(w, b, elbow);
  link(w, elbow, hand);
}

enum { PER_FIGURE = 6 };

/* Pendulums: a pinned pivot and a bob on a link, one block each. */
static void pendulums(mr_world *w, int count, double z) {
  for (int i = 0; i < count; i++) {
    int pivot = ball(w, 0.3 * i, 1.0, z, 0.1, 0.0), bob = ball(w, 0.3 * i + 0.2, 1.0, z, 0.1, 0.0);
    mr_pin_def pin = mr_default_pin_def();
    pin.particle = pivot;
    assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
    link(w, pivot, bob);
  }
}

static void states(const mr_world *w, int first, int count, double *x, double *v) {
  for (int i = 0; i < count; i++)
    assert_int_equal(mr_world_particle_state(w, first + i, &x[3 * i], &v[3 * i]), MR_OK);
}

static void two_figures_apart_move_as_in_worlds_of_their_own(void **state) {
  (void)state;
  mr_world *both = make_world(), *left = make_world(), *right = make_world();
  figure(both, 0.0, 1.0);
  figure(both, 3.0, 1.7);
  figure(left, 0.0, 1.0);
  figure(right, 3.0, 1.7);
  mr_world *const worlds[] = { both, left, right };
  for (int i = 0; i < 3; i++) {
    mr_status st = mr_world_step_to(worlds[i], 1.0, NULL);
    assert_true(st == MR_OK);
  }
  mr_stats s;
  assert_int_equal(mr_world_stats(both, &s), MR_OK);
  assert_int_equal(s.blocks, 2);
  assert_int_equal(s.steps, 250);
  assert_int_equal(mr_world_stats(left, &s), MR_OK);
  assert_int_equal(s.blocks, 1);

  double xb[3 * 2 * PER_FIGURE], vb[3 * 2 * PER_FIGURE], x[3 * PER_FIGURE], v[3 * PER_FIGURE];
  states(both, 0, 2 * PER_FIGURE, xb, vb);
  states(left, 0, PER_FIGURE, x, v);
  assert_memory_equal(xb, x, sizeof x);
  assert_memory_equal(vb, v, sizeof v);
  states(right, 0, PER_FIGURE, x, v);
  assert_memory_equal(xb + 3 * PER_FIGURE, x, sizeof x);
  assert_memory_equal(vb + 3 * PER_FIGURE, v, sizeof v);
  /* They moved, and their links held: the block solve is eq. 8's. */
  double hand[3], elbow[3];
  states(both, 10, 1, elbow, v);
  states(both, 11, 1, hand, v);
  double len = sqrt((hand[0] - elbow[0]) * (hand[0] - elbow[0]) +
                    (hand[1] - elbow[1]) * (hand[1] - elbow[1]) +
                    (hand[2] - elbow[2]) * (hand[2] - elbow[2]));
  assert_true(fabs(len - 0.15 * sqrt(1.0 + (0.05 * 1.7 / 0.15) * (0.05 * 1.7 / 0.15))) < 1e-3);
  const double start[3] = { 3.0 + 0.17 + 0.3, 0.8 + 0.05 * 1.7, 0.0 };
  assert_true(fabs(hand[0] - start[0]) + fabs(hand[1] - start[1]) > 0.05);
  for (int i = 0; i < 3; i++) mr_world_destroy(worlds[i]);
}

/* A link between the two figures makes them one system: one block. */
static void a_link_between_figures_makes_one_block(void **state) {
  (void)state;
  mr_world *w = make_world();
  figure(w, 0.0, 1.0);
  figure(w, 0.6, 1.2);
  link(w, 5, PER_FIGURE + 1); /* the first's hand to the second's corner */
  mr_status st = mr_world_step_to(w, 0.2, NULL);
  assert_true(st == MR_OK);
  mr_stats s;
  assert_int_equal(mr_world_stats(w, &s), MR_OK);
  assert_int_equal(s.blocks, 1);
  mr_world_destroy(w);
}

/* A dependent row in the first of two blocks (a link written twice) is
 * found there and counted for the whole solve, whatever the blocks after
 * it hold; its multiplier is 0, so the world moves as one without it. */
static void a_dependent_row_in_one_block_is_reported_for_the_solve(void **state) {
  (void)state;
  mr_world *w = make_world();
  figure(w, 0.0, 1.0);
  link(w, 0, 1); /* the first figure's neck, again */
  figure(w, 3.0, 1.7);
  assert_int_equal(mr_world_step_to(w, 0.2, NULL), MR_DEPENDENT);
  mr_stats s;
  assert_int_equal(mr_world_stats(w, &s), MR_OK);
  assert_int_equal(s.blocks, 2);
  assert_int_equal(s.dependent_rows, 1);
  assert_true(s.max_multiplier < 100.0);
  /* The dropped row is as if it had not been written. */
  mr_world *plain = make_world();
  figure(plain, 0.0, 1.0);
  figure(plain, 3.0, 1.7);
  assert_int_equal(mr_world_step_to(plain, 0.2, NULL), MR_OK);
  double x[3 * 2 * PER_FIGURE], v[3 * 2 * PER_FIGURE], xp[3 * 2 * PER_FIGURE];
  states(w, 0, 2 * PER_FIGURE, x, v);
  states(plain, 0, 2 * PER_FIGURE, xp, v);
  double worst = 0.0;
  for (int i = 0; i < 3 * 2 * PER_FIGURE; i++) worst = fmax(worst, fabs(x[i] - xp[i]));
  assert_true(worst < 1e-12);
  mr_world_destroy(plain);
  mr_world_destroy(w);
}

/* A pendulum whose pivot follows a hand whose acceleration goes NaN for
 * 30 ms (a broken input device), beside one hung from a pin: two blocks.
 * Its position stays finite, so only the solve of its block sees it. */
static void nan_hand(void *user, double t, double pos[3], double vel[3], double acc[3]) {
  (void)user;
  pos[2] = vel[0] = vel[1] = vel[2] = acc[1] = acc[2] = 0.0;
  pos[0] = pos[1] = 1.0; /* where the hand starts */
  acc[0] = (t >= 0.5 && t < 0.53) ? NAN : 0.0;
}

/* NaN in one block's system is the whole world's divergence (§7): the
 * world resets to its start and carries on, finite, though the other
 * block's solve went well. */
static void nan_in_one_block_resets_the_world(void **state) {
  (void)state;
  mr_world *w = make_world();
  pendulums(w, 1, 0.0);
  int hand = ball(w, 1.0, 1.0, 0.0, 0.1, 0.0), bob = ball(w, 1.2, 1.0, 0.0, 0.1, 0.0);
  mr_curve_def c = mr_default_curve_def();
  c.particle = hand;
  c.fn = nan_hand;
  assert_int_equal(mr_world_add_curve(w, &c, NULL), MR_OK);
  link(w, hand, bob);
  int resets = 0, blocks = 0;
  while (mr_world_time(w) < 1.0) {
    mr_status st = mr_world_step(w, NULL);
    assert_true(st == MR_OK || st == MR_DIVERGED);
    resets += st == MR_DIVERGED;
    mr_stats s;
    assert_int_equal(mr_world_stats(w, &s), MR_OK);
    if (s.blocks > blocks) blocks = s.blocks;
    double x[3];
    assert_int_equal(mr_world_particle_state(w, bob, x, NULL), MR_OK);
    assert_true(isfinite(x[0]) && isfinite(x[1]) && isfinite(x[2]));
  }
  assert_int_equal(blocks, 2);
  /* Within the 30 ms of NaN only: each 4 ms step there, and none after. */
  assert_true(resets >= 1 && resets <= 10);
  mr_world_destroy(w);
}

/* A world of links and parts of puppets that collide, made from *def. */
static mr_world *colliding_world(mr_world_def *def) {
  *def = mr_default_world_def();
  def->effects = MR_EFFECT_CONSTRAINTS | MR_EFFECT_PUPPET_COLLISION;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(def, &w, NULL, 0), MR_OK);
  return w;
}

/* Two dumbbells of different puppets fly into each other: apart they are
 * two blocks, and the contact rows between their spheres join them into
 * one. Their spheres are dead (no restitution), so they go on together,
 * touching, as one block: at the common speed momentum gives, with both
 * links held through the impact (a contact row left in one block alone
 * would push the other's particles past its link). */
static void a_contact_joins_two_blocks(void **state) {
  (void)state;
  mr_world_def def;
  mr_world *w = colliding_world(&def);
  int ids[4];
  const double mass[4] = { 0.3, 0.3, 0.5, 0.5 };
  for (int k = 0; k < 4; k++) {
    mr_particle_def p = mr_default_particle_def();
    p.mass = mass[k];
    p.position[0] = k < 2 ? -0.3 : 0.3;
    p.position[1] = k % 2 ? 0.2 : 0.0;
    p.velocity[0] = k < 2 ? 1.0 : -1.0;
    p.puppet = k / 2;
    assert_int_equal(mr_world_add_particle(w, &p, &ids[k]), MR_OK);
  }
  for (int d = 0; d < 2; d++) {
    link(w, ids[2 * d], ids[2 * d + 1]);
    mr_part_def part = mr_default_part_def();
    part.particles = &ids[2 * d];
    part.count = 2;
    part.radius = 0.05;
    part.restitution = 0.0;
    part.friction = 0.0;
    assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  }
  int fewest = 99, most = 0;
  while (mr_world_time(w) < 1.0) {
    mr_status st = mr_world_step(w, NULL);
    assert_true(st == MR_OK || st == MR_DEPENDENT);
    mr_stats s;
    assert_int_equal(mr_world_stats(w, &s), MR_OK);
    if (s.blocks < fewest) fewest = s.blocks;
    if (s.blocks > most) most = s.blocks;
    assert_true(s.steps < 2000);
  }
  assert_int_equal(fewest, 1);
  assert_int_equal(most, 2);
  const double common = (0.6 - 1.0) / 1.6;
  for (int k = 0; k < 4; k++) {
    double x[3], v[3];
    assert_int_equal(mr_world_particle_state(w, ids[k], x, v), MR_OK);
    assert_true(fabs(v[0] - common) < 1e-3);
  }
  assert_true(mr_world_deviation(w) < 1e-4);
  mr_stats s;
  assert_int_equal(mr_world_stats(w, &s), MR_OK);
  assert_true(s.max_penetration <= def.contact_slop + 1e-3);
  mr_world_destroy(w);
}

/* One contact row may name three blocks: a rod's sphere midway between
 * two free particles (blocks 2 and 0: a block is numbered by its lowest
 * particle) pressed by a dead ball (block 1). While they touch, the row
 * joins all three, and the link hung on particle 0 with them: one system,
 * never the link solved apart from the contact that pushes its end.
 * Joining in the row's order, 2 into 0 and then 2 again into 1, must not
 * leave block 0 out. */
static void a_contact_naming_three_blocks_joins_them_all(void **state) {
  (void)state;
  mr_world_def def;
  mr_world *w = colliding_world(&def);
  const double at[4][2] = { { -0.2, 0 }, { 0, 0.101 }, { 0.2, 0 }, { -0.2, -0.2 } };
  const int puppet[4] = { 0, 1, 0, 0 };
  int ids[4];
  for (int k = 0; k < 4; k++) {
    mr_particle_def p = mr_default_particle_def();
    p.position[0] = at[k][0];
    p.position[1] = at[k][1];
    p.velocity[1] = k == 1 ? -1.0 : 0.0;
    p.puppet = puppet[k];
    assert_int_equal(mr_world_add_particle(w, &p, &ids[k]), MR_OK);
  }
  link(w, ids[0], ids[3]);
  const int rod[2] = { ids[2], ids[0] }, ball_of[1] = { ids[1] };
  const int *parts[2] = { rod, ball_of };
  for (int k = 0; k < 2; k++) {
    mr_part_def part = mr_default_part_def();
    part.particles = parts[k];
    part.count = 2 - k;
    part.radius = 0.05;
    part.segment_spheres = 1 - k; /* the rod's: one, midway */
    part.restitution = 0.0;
    part.friction = 0.0;
    assert_int_equal(mr_world_add_part(w, &part, NULL), MR_OK);
  }
  int touching = 0;
  while (mr_world_time(w) < 0.1) {
    mr_status st = mr_world_step(w, NULL);
    assert_true(st == MR_OK || st == MR_DEPENDENT);
    mr_stats s;
    assert_int_equal(mr_world_stats(w, &s), MR_OK);
    if (s.resting_contacts == 0) continue;
    touching++;
    assert_int_equal(s.blocks, 1);
  }
  assert_true(touching >= 5);
  assert_true(mr_world_deviation(w) < 1e-4);
  mr_world_destroy(w);
}

/* A world grown after it stepped: its blocks are found again, over room
 * for every particle (31 particles first, past the size where the block
 * arrays' room first doubles, then 41). */
static void a_world_grown_after_stepping_finds_its_blocks_again(void **state) {
  (void)state;
  mr_world *w = make_world();
  pendulums(w, 15, 0.0);
  ball(w, 0.0, 2.0, 1.0, 0.1, 0.0); /* alone: no row names it */
  assert_int_equal(mr_world_step_to(w, 0.1, NULL), MR_OK);
  mr_stats s;
  assert_int_equal(mr_world_stats(w, &s), MR_OK);
  assert_int_equal(s.blocks, 15);
  pendulums(w, 5, 0.5);
  assert_int_equal(mr_world_particle_count(w), 41);
  assert_int_equal(mr_world_step_to(w, 0.3, NULL), MR_OK);
  assert_int_equal(mr_world_stats(w, &s), MR_OK);
  assert_int_equal(s.blocks, 20);
  double x[3], v[3];
  assert_int_equal(mr_world_particle_state(w, 40, x, v), MR_OK); /* the last bob swung */
  assert_true(x[1] < 0.99);
  assert_true(mr_world_deviation(w) < 1e-3);
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(two_figures_apart_move_as_in_worlds_of_their_own),
    cmocka_unit_test(a_link_between_figures_makes_one_block),
    cmocka_unit_test(a_dependent_row_in_one_block_is_reported_for_the_solve),
    cmocka_unit_test(nan_in_one_block_resets_the_world),
    cmocka_unit_test(a_contact_joins_two_blocks),
    cmocka_unit_test(a_contact_naming_three_blocks_joins_them_all),
    cmocka_unit_test(a_world_grown_after_stepping_finds_its_blocks_again),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The energy an impulse of eq. 9 may add (impulse.c): the hand's work on
 * a string it yanks is allowed, and a bounce at the same impact keeps its
 * restitution. An impulse that adds energy nothing did work for is made
 * again with every contact resting (hard case 32 is the scene that needed
 * it). The impulse is applied here as the step applies it, through the
 * library's internal header. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "internal.h"

#define RADIUS 0.05
#define HAND   3.0 /* m/s, the frame's speed along −x */

/* A ball resting its lowest point on a floor of restitution e, moving at
 * 1 m/s down and 1 m/s along −x, on a taut string 0.5 m long to a frame
 * point level with it on its −x side; the frame moves away along −x at
 * HAND m/s. */
static mr_world *yanked_while_bouncing(double e) {
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_STRINGS | MR_EFFECT_FRAMES | MR_EFFECT_PLANES;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  mr_frame_def fd = mr_default_frame_def();
  fd.path = MR_FRAME_LINEAR;
  int frame, anchor, ball;
  assert_int_equal(mr_world_add_frame(w, &fd, &frame), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  p.frame = frame;
  p.position[0] = -0.5;
  p.position[1] = RADIUS;
  assert_int_equal(mr_world_add_particle(w, &p, &anchor), MR_OK);
  p = mr_default_particle_def();
  p.position[1] = RADIUS;
  p.velocity[0] = -1.0;
  p.velocity[1] = -1.0;
  p.radius = RADIUS;
  assert_int_equal(mr_world_add_particle(w, &p, &ball), MR_OK);
  mr_string_def s = mr_default_string_def();
  s.frame_particle = anchor;
  s.puppet_particle = ball;
  s.rest_length = 0.5;
  s.mode = MR_STRING_TAUT;
  assert_int_equal(mr_world_add_string(w, &s, NULL), MR_OK);
  mr_plane_def floor = mr_default_plane_def();
  floor.restitution = e;
  floor.friction = 0.0;
  assert_int_equal(mr_world_add_plane(w, &floor, NULL), MR_OK);
  mr_pose away = mr_pose_identity();
  away.position[0] = -HAND;
  assert_int_equal(mr_world_set_frame_target(w, frame, &away, 1.0), MR_OK);
  assert_int_equal(mr_world_ensure_ready(w), 0);
  assert_int_equal(mr_contacts_detect(w, w->x, w->def.contact_slop, &w->contacts), 0);
  assert_int_equal(mr_world_contact_capacity(w, w->contacts.n), 0);
  assert_int_equal(w->contacts.n, 2); /* the floor and the string */
  return w;
}

/* The string snaps taut behind the frame: the ball leaves at the hand's
 * 3 m/s along −x, with 4 m (J/kg) of kinetic energy more, of the hand's
 * 6 m of work; the floor's bounce at the same impact is kept (e = 1 sends
 * it up at 1 m/s, e = 0.5 at 0.5 m/s). */
static void the_hand_may_add_energy_and_a_bounce_keeps_its_restitution(void **state) {
  (void)state;
  const double es[2] = { 1.0, 0.5 };
  for (int k = 0; k < 2; k++) {
    mr_world *w = yanked_while_bouncing(es[k]);
    int collided = 0;
    assert_int_equal(mr_impulses_apply(w, 0.0, &collided), 0);
    const double *v = &w->v[3];
    print_message("e = %.1f: ball leaves at (%.6f, %.6f, %.6f) m/s\n", es[k], v[0], v[1], v[2]);
    assert_true(collided);
    /* to the contact rows' compliance, 1e-6 of their diagonal */
    assert_true(fabs(v[0] + HAND) < 1e-5);
    assert_true(fabs(v[1] - es[k]) < 1e-5);
    assert_true(fabs(v[2]) < 1e-12);
    mr_world_destroy(w);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_hand_may_add_energy_and_a_bounce_keeps_its_restitution),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

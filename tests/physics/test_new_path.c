/* A step's first stage on a frame's new path (eval.c, mr_eval_new_path):
 * where the last evaluation was made, with only the frame's path new, its
 * system is solved again instead of built. It must give the bits a fresh
 * evaluation gives, and must refuse whenever that system is not the one
 * the point would build: after a build or a solve in between, after an
 * evaluation whose rounds released a contact, and after friction rounds.
 * And the memo of evaluations (integrate.c) it sits behind must not take
 * a point evaluated under other contacts for this one. These are read
 * through the library's internal header. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <string.h>

#include "internal.h"
#include "rigs.h"

enum { N = 4 }; /* the anchor, the bob, the tail, a weight on the floor */

typedef struct rig {
  mr_world *w;
  int frame;
  double x[3 * N], v[3 * N], a[3 * N];
} rig;

/* A frame point at (0, 2), a bob on a 1 m taut string at `bob_y`, a tail
 * 0.5 m under the bob on a link, and a weight over a floor with friction:
 * lying on it and sliding at `slide` m/s when `lying`, else 0.5 m above.
 * The contacts are found as a step finds them at its start. */
static void make_rig(rig *r, double bob_y, int lying, double slide) {
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_GRAVITY | MR_EFFECT_STRINGS | MR_EFFECT_FRAMES | MR_EFFECT_CONSTRAINTS |
                MR_EFFECT_PLANES;
  assert_int_equal(mr_world_create(&def, &r->w, NULL, 0), MR_OK);
  mr_frame_def fd = mr_default_frame_def();
  fd.pose.position[1] = 2.0;
  assert_int_equal(mr_world_add_frame(r->w, &fd, &r->frame), MR_OK);
  const int anchor = particle(r->w, 0, 2, 0, 1, r->frame);
  const int bob = particle(r->w, 0, bob_y, 0, 1, -1);
  const int tail = particle(r->w, 0, bob_y - 0.5, 0, 1, -1);
  const int weight = particle(r->w, 1, lying ? 0.0 : 0.5, 0, 1, -1);
  mr_string_def s = mr_default_string_def(); /* taut */
  s.frame_particle = anchor;
  s.puppet_particle = bob;
  s.rest_length = 1.0;
  assert_int_equal(mr_world_add_string(r->w, &s, NULL), MR_OK);
  mr_distance_def d = mr_default_distance_def();
  d.a = bob;
  d.b = tail;
  assert_int_equal(mr_world_add_distance(r->w, &d, NULL), MR_OK);
  mr_plane_def floor = mr_default_plane_def();
  floor.friction = 0.5;
  assert_int_equal(mr_world_add_plane(r->w, &floor, NULL), MR_OK);
  assert_int_equal(mr_world_set_particle_state(r->w, weight, (double[3]){ 1, lying ? 0.0 : 0.5, 0 },
                                               (double[3]){ slide, 0, 0 }),
                   MR_OK);
  assert_int_equal(mr_world_ensure_ready(r->w), 0);
  mr_world *w = r->w;
  assert_int_equal(mr_contacts_detect(w, w->x, w->def.contact_slop, &w->contacts), 0);
  assert_int_equal(mr_world_contact_capacity(w, w->contacts.n), 0);
  assert_int_equal(w->n, N);
}

/* The point: the world's state, copied (an evaluation writes the frame
 * particles into x and v). */
static void at_state(rig *r) {
  memcpy(r->x, r->w->x, sizeof r->x);
  memcpy(r->v, r->w->v, sizeof r->v);
}

static int eval_fresh(rig *r, double *a) {
  at_state(r);
  return mr_eval(r->w, r->w->t, 0.01, r->x, r->v, a);
}

static int eval_again(rig *r, double *a) {
  at_state(r);
  return mr_eval_new_path(r->w, r->w->t, 0.01, r->x, r->v, a);
}

/* The frame heads somewhere new, `dy` up or down: the path from its state
 * now is another curve with the same position and velocity, and another
 * acceleration, along the string. */
static void new_target(rig *r, double dy) {
  mr_pose p = mr_pose_identity();
  p.position[1] = 2.0 + dy;
  assert_int_equal(mr_world_set_frame_target(r->w, r->frame, &p, r->w->t + 0.02), MR_OK);
}

/* The bob hangs on its taut string (a contact row), the tail on its link,
 * the frame heading up: on a new path, the kept system gives what a fresh
 * evaluation gives, bit for bit, whether the string still pulls (the new
 * path heads further up) or lets go (it drops faster than the bob falls:
 * released, and the rest solved again), and the new path's acceleration
 * reaches the bob. */
static void on_a_new_path_the_kept_system_gives_the_fresh_bits(void **state) {
  (void)state;
  const double ups[2] = { 0.3, -0.3 };
  for (int k = 0; k < 2; k++) {
    rig r;
    make_rig(&r, 1.0, 0, 0.0);
    new_target(&r, 0.1);
    double before[3 * N], again[3 * N], fresh[3 * N];
    assert_int_equal(eval_fresh(&r, before), 0);
    assert_int_equal(r.w->contacts.n, 1);
    assert_true(r.w->contact_active[0]); /* the string holds the bob */
    new_target(&r, ups[k]);
    assert_int_equal(eval_again(&r, again), 1);
    const int pulls = r.w->contact_active[0];
    assert_int_equal(eval_fresh(&r, fresh), 0);
    assert_memory_equal(again, fresh, sizeof again);
    assert_true(memcmp(before, fresh, sizeof fresh) != 0);
    assert_int_equal(pulls, ups[k] > 0);
    print_message("bob's upward acceleration: %.17g, then %.17g heading %+.1f m\n", before[4],
                  fresh[4], ups[k]);
    mr_world_destroy(r.w);
  }
}

/* Anything that builds rows or solves in between leaves J, b or A's
 * factor another system's: the kept one is refused. */
static void a_build_or_a_solve_in_between_is_refused(void **state) {
  (void)state;
  rig r;
  make_rig(&r, 1.0, 0, 0.0);
  double a[3 * N];
  assert_int_equal(eval_fresh(&r, a), 0);
  assert_true(mr_rows_build(r.w, r.w->t, r.x, r.v) > 0);
  assert_int_equal(eval_again(&r, a), 0);
  assert_int_equal(eval_fresh(&r, a), 0);
  assert_int_equal(mr_solve_rows(r.w, 1), 0);
  assert_int_equal(eval_again(&r, a), 0);
  assert_int_equal(eval_fresh(&r, a), 0);
  assert_int_equal(eval_again(&r, a), 1); /* nothing in between */
  mr_world_destroy(r.w);
}

/* A rig evaluated afresh at its start, then asked again at the same point:
 * refused. Says whether the string's contact was released and whether
 * friction rounds ran. */
static void refused_at(double bob_y, int lying, double slide, int *released, int *friction) {
  rig r;
  make_rig(&r, bob_y, lying, slide);
  double a[3 * N];
  assert_int_equal(eval_fresh(&r, a), 0);
  *released = 0;
  for (int c = 0; c < r.w->contacts.n; c++)
    if (r.w->contacts.c[c].kind == MR_CONTACT_STRING) *released = !r.w->contact_active[c];
  *friction = r.w->eval_used_h;
  assert_int_equal(eval_again(&r, a), 0);
  mr_world_destroy(r.w);
}

/* The bob stands on its string, right above the frame point: gravity
 * would have the string push, so the solve releases it and solves again
 * without it. The rows kept are that last round's, and a fresh evaluation
 * starts from the string taken up again: refused. */
static void a_system_after_a_released_contact_is_refused(void **state) {
  (void)state;
  int released, friction;
  refused_at(3.0, 0, 0.0, &released, &friction);
  assert_true(released && !friction);
}

/* Friction's rounds change b where friction reaches (the weight sliding on
 * the floor): the system they leave is not the one the point builds. */
static void a_system_after_friction_rounds_is_refused(void **state) {
  (void)state;
  int released, friction;
  refused_at(1.0, 1, 0.5, &released, &friction);
  assert_true(friction && !released);
}

/* The memo (integrate.c) keeps an evaluation with the contacts it held:
 * a bob swinging at its string's length over a floor at its height, one
 * step held by the string alone, the next by the floor alone. The state
 * where the second starts is the first's end, evaluated there, but under
 * the other contact: it is evaluated again, and the step comes out as the
 * same step taken with nothing kept. */
static void a_memo_point_under_other_contacts_is_not_reused(void **state) {
  (void)state;
  double x1[2][3 * N], v1[2][3 * N], x2[2][3 * N], v2[2][3 * N], err;
  for (int kept = 0; kept < 2; kept++) {
    rig r;
    make_rig(&r, 1.0, 0, 0.0);
    mr_world *w = r.w;
    mr_plane_def floor = mr_default_plane_def();
    floor.offset = 1.0; /* under the bob, as it hangs */
    floor.friction = 0.0;
    assert_int_equal(mr_world_add_plane(w, &floor, NULL), MR_OK);
    assert_int_equal(
        mr_world_set_particle_state(w, 1, (double[3]){ 0, 1, 0 }, (double[3]){ 0.8, 0, 0 }), MR_OK);
    assert_int_equal(mr_world_ensure_ready(w), 0);
    const double h = 0.01;
    w->contacts.n = 0;
    assert_int_equal(mr_contact_push(&w->contacts, MR_CONTACT_STRING, 0, -1, 0.0, 0.0), 0);
    assert_int_equal(mr_world_contact_capacity(w, w->contacts.n), 0);
    at_state(&r);
    assert_int_equal(mr_integrate(w, 0.0, h, r.x, r.v, x1[kept], v1[kept], &err), 0);
    w->contacts.n = 0;
    assert_int_equal(mr_contact_push(&w->contacts, MR_CONTACT_PLANE, 1, 1, 0.0, 0.0), 0);
    if (!kept) w->memo.valid = 0;
    assert_int_equal(mr_integrate(w, h, h, x1[kept], v1[kept], x2[kept], v2[kept], &err), 0);
    mr_world_destroy(w);
  }
  assert_memory_equal(x1[0], x1[1], sizeof x1[0]);
  assert_memory_equal(x2[0], x2[1], sizeof x2[0]);
  assert_memory_equal(v2[0], v2[1], sizeof v2[0]);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(on_a_new_path_the_kept_system_gives_the_fresh_bits),
    cmocka_unit_test(a_build_or_a_solve_in_between_is_refused),
    cmocka_unit_test(a_system_after_a_released_contact_is_refused),
    cmocka_unit_test(a_system_after_friction_rounds_is_refused),
    cmocka_unit_test(a_memo_point_under_other_contacts_is_not_reused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The drift projection (project.c, §6.2 after [19]): the Newton rounds
 * that move the particles back onto the constraints. It is reached from
 * the step only when a step ends past the ATS threshold, and its result
 * decides whether the step counts a correction, so it is tested here
 * through the library's internal header. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <string.h>

#include "internal.h"

/* A free 1 kg particle at p tied by links of length `len` to two points of
 * a frame, at a and b; the world ready to project. */
static mr_world *two_links(const double a[3], const double b[3], const double p[3], double len,
                           int *free_id) {
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_CONSTRAINTS | MR_EFFECT_FRAMES;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  mr_frame_def fd = mr_default_frame_def();
  int frame, ids[3];
  assert_int_equal(mr_world_add_frame(w, &fd, &frame), MR_OK);
  const double *at[3] = { a, b, p };
  for (int i = 0; i < 3; i++) {
    mr_particle_def pd = mr_default_particle_def();
    memcpy(pd.position, at[i], sizeof pd.position);
    pd.frame = i < 2 ? frame : -1;
    assert_int_equal(mr_world_add_particle(w, &pd, &ids[i]), MR_OK);
  }
  for (int i = 0; i < 2; i++) {
    mr_distance_def d = mr_default_distance_def();
    d.a = ids[i];
    d.b = ids[2];
    d.length = len;
    assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  }
  assert_int_equal(mr_world_ensure_ready(w), 0);
  *free_id = ids[2];
  return w;
}

/* Links of 1 m from two points 0.1 m apart, the particle between them and
 * 1 mm off their line: both rows point almost along ±x, so the Newton
 * round that shortens both to 1 m throws the particle ~47 m along y and
 * leaves the links 47x too long. That round must be undone, to the bit,
 * and the call must say it made no progress. */
static void a_harmful_round_is_undone_and_reported(void **state) {
  (void)state;
  const double a[3] = { 0, 0, 0 }, b[3] = { 0.1, 0, 0 }, p[3] = { 0.05, 0.001, 0 };
  int id;
  mr_world *w = two_links(a, b, p, 1.0, &id);
  double before[9];
  memcpy(before, w->x, sizeof before);
  double e0 = mr_constraints_deviation(w, w->t, w->x);
  assert_true(e0 > 0.9);
  assert_int_equal(mr_project_positions(w, w->t, w->x, w->v, 1e-9, 20), -1);
  assert_memory_equal(before, w->x, sizeof before);
  assert_true(mr_constraints_deviation(w, w->t, w->x) == e0);
  mr_world_destroy(w);
}

/* Links of 1 m from points 1.2 m apart, the particle 0.5 m above their
 * middle (links 0.781 m): Newton converges, and the call returns how many
 * rounds it took, each one better than the last, ending within the
 * tolerance asked (here 1e-12, far below the ATS's). */
static void rounds_that_help_are_kept_and_counted(void **state) {
  (void)state;
  const double a[3] = { 0, 0, 0 }, b[3] = { 1.2, 0, 0 }, p[3] = { 0.6, 0.5, 0 };
  int id;
  mr_world *w = two_links(a, b, p, 1.0, &id);
  int rounds = mr_project_positions(w, w->t, w->x, w->v, 1e-12, 20);
  assert_true(rounds >= 2 && rounds <= 8);
  assert_true(mr_constraints_deviation(w, w->t, w->x) <= 1e-12);
  double x[3];
  mr_world_particle_state(w, id, x, NULL);
  assert_true(fabs(x[0] - 0.6) < 1e-12 && fabs(x[1] - 0.8) < 1e-9 && x[2] == 0.0);
  /* Already within the tolerance: nothing to do, no round. */
  assert_int_equal(mr_project_positions(w, w->t, w->x, w->v, 1e-6, 20), 0);
  mr_world_destroy(w);
}

/* max_iter bounds the rounds: the converging case above, allowed one
 * round, takes that one and stops, better than it started and still short
 * of the tolerance; the step's fallback (step.c) counts on its 20. */
static void the_rounds_stop_at_max_iter(void **state) {
  (void)state;
  const double a[3] = { 0, 0, 0 }, b[3] = { 1.2, 0, 0 }, p[3] = { 0.6, 0.5, 0 };
  int id;
  mr_world *w = two_links(a, b, p, 1.0, &id);
  const double e0 = mr_constraints_deviation(w, w->t, w->x);
  assert_int_equal(mr_project_positions(w, w->t, w->x, w->v, 1e-12, 1), 1);
  const double e1 = mr_constraints_deviation(w, w->t, w->x);
  assert_true(e1 < e0 && e1 > 1e-12);
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_harmful_round_is_undone_and_reported),
    cmocka_unit_test(rounds_that_help_are_kept_and_counted),
    cmocka_unit_test(the_rounds_stop_at_max_iter),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

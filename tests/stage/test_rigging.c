/* Puppets that read as puppets, as maths: a control frame's wooden bars
 * join its points by the least wood, and the collision spheres are in
 * the draw list only while they are asked for. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "mr_stage.h"

static double bar_length(const double *xyz, const int *pairs, int bars) {
  double total = 0;
  for (int b = 0; b < bars; b++) {
    const double *p = &xyz[3 * pairs[2 * b]], *q = &xyz[3 * pairs[2 * b + 1]];
    total += sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                  (p[2] - q[2]) * (p[2] - q[2]));
  }
  return total;
}

/* Every point is reached from point 0 along the bars. */
static void assert_joined(const int *pairs, int bars, int n) {
  int reached[16] = { 1 };
  for (int round = 0; round < n; round++)
    for (int b = 0; b < bars; b++)
      if (reached[pairs[2 * b]] || reached[pairs[2 * b + 1]])
        reached[pairs[2 * b]] = reached[pairs[2 * b + 1]] = 1;
  for (int i = 0; i < n; i++) assert_true(reached[i]);
}

static void a_wooden_control_joins_its_points_by_the_least_wood(void **state) {
  (void)state;
  int pairs[32];
  /* A cross: the middle and four arms 15 cm out. Joined in the order
   * given and closed round (the wire look) it would be a star polygon;
   * the least wood is the four arms from the middle. */
  double cross[15] = { 0, 0, 0, 0.15, 0, 0, 0, 0, 0.15, -0.15, 0, 0, 0, 0, -0.15 };
  assert_int_equal(mr_frame_bars(cross, 5, pairs), 4);
  for (int b = 0; b < 4; b++) assert_int_equal(pairs[2 * b], 0);
  assert_true(fabs(bar_length(cross, pairs, 4) - 0.6) < 1e-12);
  /* Points on one line, given out of order: each joins its neighbours,
   * never the far ones. */
  double line[12] = { 0, 0, 0, 0.3, 0, 0, 0.1, 0, 0, 0.2, 0, 0 };
  assert_int_equal(mr_frame_bars(line, 4, pairs), 3);
  assert_true(fabs(bar_length(line, pairs, 3) - 0.3) < 1e-12);
  assert_joined(pairs, 3, 4);
  /* puppet.yaml's airplane control: seven points, six bars, no shorter
   * tree (checked against every tree a brute search could build is too
   * many; the sum is the one worked out by hand: head to each shoulder
   * 0.12, each shoulder to its hand 0.1432, to its knee 0.1552). */
  double plane[21] = { 0,    0,    0, -0.12, 0,     0, 0.12, 0,    0, -0.25, 0,
                       0.06, 0.25, 0, 0.06,  -0.08, 0, 0.15, 0.08, 0, 0.15 };
  assert_int_equal(mr_frame_bars(plane, 7, pairs), 6);
  assert_joined(pairs, 6, 7);
  double want =
      2 * 0.12 + 2 * sqrt(0.13 * 0.13 + 0.06 * 0.06) + 2 * sqrt(0.04 * 0.04 + 0.15 * 0.15);
  assert_true(fabs(bar_length(plane, pairs, 6) - want) < 1e-12);
  /* Two points: one bar; one or none: no bar. */
  assert_int_equal(mr_frame_bars(plane, 2, pairs), 1);
  assert_true(pairs[0] == 0 && pairs[1] == 1);
  assert_int_equal(mr_frame_bars(plane, 1, pairs), 0);
  assert_int_equal(mr_frame_bars(NULL, 3, pairs), 0);
}

static void the_frame_style_reads_and_names_both_looks(void **state) {
  (void)state;
  mr_frame_style st = MR_FRAMES_WIRE;
  assert_int_equal(mr_frame_style_parse("solid", &st), 0);
  assert_int_equal(st, MR_FRAMES_SOLID);
  assert_int_equal(mr_frame_style_parse("wire", &st), 0);
  assert_int_equal(st, MR_FRAMES_WIRE);
  assert_int_equal(mr_frame_style_parse("wood", &st), -1);
  assert_string_equal(mr_frame_style_name(MR_FRAMES_WIRE), "wire");
  assert_string_equal(mr_frame_style_name((mr_frame_style)7), "unknown");
  mr_stage_def d = mr_default_stage_def();
  assert_true(d.frame_style == MR_FRAMES_SOLID && d.frame_thickness == 0.025 && !d.show_spheres);
}

/* Does the list hold an item of model m? */
static int has_model(const mr_draw_list *l, int m) {
  for (size_t i = 0; i < l->n_items; i++)
    if (l->items[i].model == m) return 1;
  return 0;
}

/* Three models on three particles: a collision sphere between two that
 * are not. */
static mr_stage *three(bool show, const double *rest) {
  static mr_model_def m[3];
  for (int i = 0; i < 3; i++) {
    m[i] = mr_default_model_def();
    m[i].shape = MR_SHAPE_SPHERE;
    m[i].particles[0] = i;
  }
  m[1].collision = true;
  mr_stage_def d = mr_default_stage_def();
  d.models = m;
  d.n_models = 3;
  d.show_spheres = show;
  mr_stage *s = NULL;
  char msg[256];
  if (mr_stage_create(&d, rest, 3, &s, msg, sizeof msg) != MR_STAGE_OK) fail_msg("%s", msg);
  return s;
}

static void collision_spheres_are_drawn_only_while_asked_for(void **state) {
  (void)state;
  double rest[9] = { 0, 1, 0, 1, 1, 0, 2, 1, 0 }, now[9] = { 0, 1, 0, 1, 3, 0, 2, 1, 0 };
  mr_stage *s = three(false, rest);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(s, now, 3, &l), MR_STAGE_OK);
  assert_int_equal(l->n_items, 2);
  assert_true(has_model(l, 0) && !has_model(l, 1) && has_model(l, 2));
  /* Asked for, it is there, where its particle is now (it moved while
   * hidden). */
  assert_int_equal(mr_stage_show_spheres(s, true), MR_STAGE_OK);
  assert_true(mr_stage_get_def(s)->show_spheres);
  assert_int_equal(mr_stage_update(s, now, 3, &l), MR_STAGE_OK);
  assert_int_equal(l->n_items, 3);
  assert_true(has_model(l, 0) && has_model(l, 1) && has_model(l, 2));
  for (size_t i = 0; i < l->n_items; i++)
    if (l->items[i].model == 1) assert_true(l->items[i].pose.position[1] == 3);
  /* Materials still reach the right item once the spheres moved last. */
  assert_int_equal(mr_stage_show_spheres(s, false), MR_STAGE_OK);
  assert_int_equal(mr_stage_update(s, now, 3, &l), MR_STAGE_OK);
  assert_int_equal(l->n_items, 2);
  assert_false(has_model(l, 1));
  mr_stage_destroy(s);
  /* The def's show_spheres is the start. */
  s = three(true, rest);
  assert_int_equal(mr_stage_update(s, rest, 3, &l), MR_STAGE_OK);
  assert_int_equal(l->n_items, 3);
  mr_stage_destroy(s);
  assert_int_equal(mr_stage_show_spheres(NULL, true), MR_STAGE_ERR_ARG);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_wooden_control_joins_its_points_by_the_least_wood),
    cmocka_unit_test(the_frame_style_reads_and_names_both_looks),
    cmocka_unit_test(collision_spheres_are_drawn_only_while_asked_for),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

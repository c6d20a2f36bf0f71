/* The paper's display modes (§3.3) as poses: each model lands where its
 * particles say, exactly, and a bad frame never moves it. */
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

#define NEAR(a, b, tol) assert_true(fabs((a) - (b)) <= (tol))

static void near3(const double a[3], const double b[3], double tol) {
  for (int i = 0; i < 3; i++)
    if (!(fabs(a[i] - b[i]) <= tol))
      fail_msg("(%.12g, %.12g, %.12g) != (%.12g, %.12g, %.12g)", a[0], a[1], a[2], b[0], b[1],
               b[2]);
}

/* A drawn item's mesh point `local` (placement applied) in the world. */
static void item_apply(const mr_draw_item *it, const double local[3], double out[3]) {
  double scaled[3] = { local[0] * it->scale[0], local[1] * it->scale[1], local[2] * it->scale[2] };
  mr_pose_apply(&it->pose, scaled, out);
}

/* A known rigid motion: a turn of 50° about (1, 2, -1) and a move. */
static mr_pose motion(void) {
  double axis[3] = { 1, 2, -1 }, n = sqrt(6.0), h = 50.0 * 3.14159265358979323846 / 360.0;
  mr_pose m = { { 0.3, -0.2, 1.1 },
                { cos(h), sin(h) * axis[0] / n, sin(h) * axis[1] / n, sin(h) * axis[2] / n } };
  return m;
}

static void moved(const double *rest, size_t n, const mr_pose *m, double *out) {
  for (size_t i = 0; i < n; i++) mr_pose_apply(m, &rest[3 * i], &out[3 * i]);
}

static mr_stage *make(const mr_model_def *models, size_t n_models, const double *rest, size_t n) {
  mr_stage_def d = mr_default_stage_def();
  d.models = (mr_model_def *)models;
  d.n_models = n_models;
  mr_stage *s = NULL;
  char msg[256];
  if (mr_stage_create(&d, rest, n, &s, msg, sizeof msg) != MR_STAGE_OK) fail_msg("%s", msg);
  return s;
}

static void particle_model_sits_on_its_particle_unturned(void **state) {
  (void)state;
  double rest[6] = { 0, 1, 0, 2, 3, 4 }, now[6] = { 0, 1, 0, -1.5, 0.25, 7 };
  mr_model_def m = mr_default_model_def();
  m.particles[0] = 1;
  mr_stage *s = make(&m, 1, rest, 2);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(s, now, 2, &l), MR_STAGE_OK);
  assert_int_equal(l->n_items, 1);
  assert_int_equal(l->n_skins, 0);
  near3(l->items[0].pose.position, &now[3], 0);
  assert_true(l->items[0].pose.orientation[0] == 1.0);
  assert_true(l->items[0].scale[0] == 1 && l->items[0].scale[1] == 1 && l->items[0].scale[2] == 1);
  assert_int_equal(l->items[0].material, -1); /* no materials: the file's own */
  mr_stage_destroy(s);
}

static void link_lays_y_from_a_to_b_scaled_to_their_distance(void **state) {
  (void)state;
  double rest[6] = { 0, 0, 0, 0, 1, 0 };
  double cases[][6] = { { 1, 2, 3, 1.3, 2.4, 3 },
                        { 0, 0, 0, 0, -2, 0 }, /* straight down */
                        { -1, 0.5, 0, -1, 0.5, 0.7 },
                        { 0, 0, 0, 0, 0.25, 0 } };
  mr_model_def m = mr_default_model_def();
  m.display = MR_DISPLAY_LINK;
  m.particles[0] = 0;
  m.particles[1] = 1;
  mr_stage *s = make(&m, 1, rest, 2);
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    const double *a = cases[c], *b = cases[c] + 3;
    const mr_draw_list *l;
    assert_int_equal(mr_stage_update(s, cases[c], 2, &l), MR_STAGE_OK);
    const mr_draw_item *it = &l->items[0];
    double dist = sqrt(pow(b[0] - a[0], 2) + pow(b[1] - a[1], 2) + pow(b[2] - a[2], 2));
    NEAR(it->scale[1], dist, 1e-12);
    assert_true(it->scale[0] == 1 && it->scale[2] == 1);
    double y0[3] = { 0, 0, 0 }, y1[3] = { 0, 1, 0 }, x1[3] = { 1, 0, 0 }, w[3];
    item_apply(it, y0, w);
    near3(w, a, 1e-12);
    item_apply(it, y1, w);
    near3(w, b, 1e-12);
    /* x keeps its size and stays normal to the link. */
    item_apply(it, x1, w);
    double e[3] = { w[0] - a[0], w[1] - a[1], w[2] - a[2] };
    NEAR(sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]), 1, 1e-12);
    NEAR(e[0] * (b[0] - a[0]) + e[1] * (b[1] - a[1]) + e[2] * (b[2] - a[2]), 0, 1e-12);
  }
  mr_stage_destroy(s);
}

static void rigid_model_follows_its_particles_exactly_in_both_orientations(void **state) {
  (void)state;
  double rest[9] = { 0.1, 1.0, 0.0, 0.4, 1.1, 0.0, 0.2, 1.5, 0.3 }, now[9];
  mr_model_def m[2] = { mr_default_model_def(), mr_default_model_def() };
  for (int k = 0; k < 2; k++) {
    m[k].display = MR_DISPLAY_RIGID;
    m[k].particles[0] = 0;
    m[k].particles[1] = 1;
    m[k].particles[2] = 2;
  }
  m[0].orient = MR_RIGID_INITIAL;
  m[1].orient = MR_RIGID_CONFIGURATION;
  mr_stage *s = make(m, 2, rest, 3);
  mr_pose mo = motion();
  moved(rest, 3, &mo, now);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(s, now, 3, &l), MR_STAGE_OK);
  /* Initial: at rest the model is where it was placed (identity), and any
   * world point of it moves by exactly the particles' motion. */
  double probe[3] = { -0.7, 2.0, 0.4 }, want[3], got[3];
  mr_pose_apply(&mo, probe, want);
  item_apply(&l->items[0], probe, got);
  near3(got, want, 1e-12);
  for (int i = 0; i < 4; i++)
    NEAR(fabs(l->items[0].pose.orientation[i]), fabs(mo.orientation[i]), 1e-12);
  /* Configuration: origin on p0, x along p1 - p0, p2 in the x-y plane. */
  const mr_draw_item *c = &l->items[1];
  near3(c->pose.position, now, 1e-12);
  double d01 = sqrt(0.09 + 0.01), along[3] = { d01, 0, 0 };
  item_apply(c, along, got);
  near3(got, &now[3], 1e-12);
  double local2[3];
  mr_pose_unrotate(c->pose.orientation,
                   (double[3]){ now[6] - now[0], now[7] - now[1], now[8] - now[2] }, local2);
  NEAR(local2[2], 0, 1e-12);
  assert_true(local2[1] > 0);
  mr_stage_destroy(s);
}

/* A freeform skin's vertices, blended as the renderer blends them. */
static void blend(const mr_draw_skin *k, const float *v, const int *idx, const float *w, int inf,
                  double out[3]) {
  out[0] = out[1] = out[2] = 0;
  double p[3] = { v[0], v[1], v[2] }, q[3];
  for (int j = 0; j < inf; j++) {
    mr_pose_apply(&k->bones[idx[j]], p, q);
    for (int c = 0; c < 3; c++) out[c] += w[j] * q[c];
  }
}

static void freeform_skin_under_a_rigid_motion_moves_rigidly(void **state) {
  (void)state;
  enum { NB = 6, NV = 27 };
  double rest[3 * NB] = { 0, 0, 0, 0.3, 0, 0, 0, 0.3, 0, 0, 0, 0.3, 0.3, 0.3, 0.1, -0.2, 0.1, 0.2 };
  int bones[NB] = { 0, 1, 2, 3, 4, 5 };
  mr_model_def m = mr_default_model_def();
  m.display = MR_DISPLAY_FREEFORM;
  m.bones = bones;
  m.n_bones = NB;
  mr_stage *s = make(&m, 1, rest, NB);
  float verts[3 * NV];
  for (int i = 0; i < NV; i++) {
    verts[3 * i] = -0.1f + 0.2f * (float)(i % 3);
    verts[3 * i + 1] = -0.1f + 0.2f * (float)((i / 3) % 3);
    verts[3 * i + 2] = -0.1f + 0.2f * (float)(i / 9);
  }
  int idx[4 * NV];
  float w[4 * NV];
  assert_int_equal(mr_stage_skin_bind(verts, NV, rest, NB, 4, idx, w), MR_STAGE_OK);
  double now[3 * NB];
  mr_pose mo = motion();
  moved(rest, NB, &mo, now);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(s, now, NB, &l), MR_STAGE_OK);
  assert_int_equal(l->n_skins, 1);
  assert_int_equal(l->skins[0].n_bones, NB);
  for (int i = 0; i < NV; i++) {
    double p[3] = { verts[3 * i], verts[3 * i + 1], verts[3 * i + 2] }, want[3], got[3];
    mr_pose_apply(&mo, p, want);
    blend(&l->skins[0], &verts[3 * i], &idx[4 * i], &w[4 * i], 4, got);
    near3(got, want, 1e-6); /* the weights are floats */
  }
  mr_stage_destroy(s);
}

static void skin_weights_sum_to_one_and_a_vertex_on_a_bone_takes_it_alone(void **state) {
  (void)state;
  double bones[9] = { 0, 0, 0, 1, 0, 0, 0, 2, 0 };
  float verts[9] = { 0.2f, 0.1f, 0, 1, 0, 0, 5, 5, 5 };
  int idx[12];
  float w[12];
  assert_int_equal(mr_stage_skin_bind(verts, 3, bones, 3, 4, idx, w), MR_STAGE_OK);
  for (int v = 0; v < 3; v++) {
    double sum = 0;
    for (int j = 0; j < 4; j++) sum += w[4 * v + j];
    NEAR(sum, 1, 1e-6);
    /* Three bones for four places: the fourth is unused. */
    assert_int_equal(idx[4 * v + 3], 0);
    assert_true(w[4 * v + 3] == 0);
  }
  /* (0.2, 0.1, 0): nearest bone 0 at d² 0.05, then bone 1 at 0.65, bone 2 at 3.65. */
  assert_int_equal(idx[0], 0);
  assert_int_equal(idx[1], 1);
  assert_int_equal(idx[2], 2);
  double s = 1 / 0.05 + 1 / 0.65 + 1 / 3.65;
  NEAR(w[0], (1 / 0.05) / s, 1e-6);
  NEAR(w[1], (1 / 0.65) / s, 1e-6);
  /* On bone 1: bone 1 alone. */
  assert_int_equal(idx[4], 1);
  assert_true(w[4] == 1 && w[5] == 0 && w[6] == 0);
  /* One influence: the nearest, weight 1. */
  assert_int_equal(mr_stage_skin_bind(verts, 3, bones, 3, 1, idx, w), MR_STAGE_OK);
  assert_int_equal(idx[0], 0);
  assert_true(w[0] == 1);
  assert_int_equal(idx[2], 2);
  assert_int_equal(mr_stage_skin_bind(verts, 3, bones, 3, 5, idx, w), MR_STAGE_ERR_ARG);
  assert_int_equal(mr_stage_skin_bind(verts, 3, bones, 0, 4, idx, w), MR_STAGE_ERR_ARG);
  float bad[3] = { NAN, 0, 0 };
  assert_int_equal(mr_stage_skin_bind(bad, 1, bones, 3, 4, idx, w), MR_STAGE_ERR_VALUE);
}

static void a_point_not_finite_leaves_its_models_where_they_were(void **state) {
  (void)state;
  double rest[12] = { 0, 1, 0, 0.5, 1, 0, 0, 1.5, 0, 0.2, 1.2, 0.4 };
  mr_model_def m[4] = { mr_default_model_def(), mr_default_model_def(), mr_default_model_def(),
                        mr_default_model_def() };
  m[0].particles[0] = 1;
  m[1].display = MR_DISPLAY_LINK;
  m[1].particles[0] = 0;
  m[1].particles[1] = 1;
  m[2].display = MR_DISPLAY_RIGID;
  for (int i = 0; i < 3; i++) m[2].particles[i] = i;
  int bones[4] = { 0, 1, 2, 3 };
  m[3].display = MR_DISPLAY_FREEFORM;
  m[3].bones = bones;
  m[3].n_bones = 4;
  mr_stage_def d = mr_default_stage_def();
  int strings[2] = { 3, 1 };
  d.models = m;
  d.n_models = 4;
  d.strings = strings;
  d.n_strings = 1;
  mr_stage *s = NULL;
  char msg[200];
  assert_int_equal(mr_stage_create(&d, rest, 4, &s, msg, sizeof msg), MR_STAGE_OK);
  double now[12];
  mr_pose mo = motion();
  moved(rest, 4, &mo, now);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(s, now, 4, &l), MR_STAGE_OK);
  mr_draw_item items[3];
  memcpy(items, l->items, sizeof items);
  mr_pose bone_poses[4];
  memcpy(bone_poses, l->skins[0].bones, sizeof bone_poses);
  mr_draw_line line = l->lines[0];
  double bad[12];
  memcpy(bad, rest, sizeof bad);
  bad[4] = NAN; /* point 1: in every model and the string */
  assert_int_equal(mr_stage_update(s, bad, 4, &l), MR_STAGE_OK);
  assert_memory_equal(l->items, items, sizeof items);
  assert_memory_equal(l->skins[0].bones, bone_poses, sizeof bone_poses);
  /* The string keeps its last finite end, and follows the end that moved. */
  near3(l->lines[0].b, line.b, 0);
  near3(l->lines[0].a, &rest[9], 0);
  /* Coincident link ends: no direction, the last pose again. */
  memcpy(bad, now, sizeof bad);
  memcpy(&bad[3], &bad[0], 3 * sizeof(double));
  assert_int_equal(mr_stage_update(s, bad, 4, &l), MR_STAGE_OK);
  assert_memory_equal(&l->items[1], &items[1], sizeof items[1]);
  mr_stage_destroy(s);
}

static void strings_and_wire_control_frames_are_lines_in_their_colours(void **state) {
  (void)state;
  double rest[15] = { 0, 1, 0, 1, 1, 0, 0, 2, 0, 1, 2, 0, 0.5, 2, 1 };
  int strings[4] = { 2, 0, 3, 1 };
  int frame_points[5] = { 2, 3, 4, /* a triangle */ 0, 1 /* a bar */ };
  int frame_count[2] = { 3, 2 };
  mr_stage_def d = mr_default_stage_def();
  d.frame_style = MR_FRAMES_WIRE;
  d.strings = strings;
  d.n_strings = 2;
  d.frame_points = frame_points;
  d.frame_point_count = frame_count;
  d.n_frames = 2;
  d.string_color[0] = 0.25f;
  d.frame_color[0] = 0.75f;
  mr_stage *s = NULL;
  assert_int_equal(mr_stage_create(&d, rest, 5, &s, NULL, 0), MR_STAGE_OK);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(s, rest, 5, &l), MR_STAGE_OK);
  assert_int_equal(l->n_lines, 2 + 3 + 1);
  near3(l->lines[0].a, &rest[6], 0);
  near3(l->lines[0].b, &rest[0], 0);
  near3(l->lines[1].a, &rest[9], 0);
  assert_true(l->lines[0].rgb[0] == 0.25f && l->lines[1].rgb[0] == 0.25f);
  near3(l->lines[4].a, &rest[12], 0); /* the triangle closes: 4 -> 2 */
  near3(l->lines[4].b, &rest[6], 0);
  near3(l->lines[5].a, &rest[0], 0); /* the bar is one line */
  near3(l->lines[5].b, &rest[3], 0);
  for (int i = 2; i < 6; i++) assert_true(l->lines[i].rgb[0] == 0.75f);
  mr_stage_destroy(s);
  /* Solid (the default), a frame is the scene's wooden bars: the strings
   * alone are lines. */
  d.frame_style = MR_FRAMES_SOLID;
  assert_int_equal(mr_stage_create(&d, rest, 5, &s, NULL, 0), MR_STAGE_OK);
  assert_int_equal(mr_stage_update(s, rest, 5, &l), MR_STAGE_OK);
  assert_int_equal(l->n_lines, 2);
  mr_stage_destroy(s);
  d.show_strings = false;
  d.show_frames = false;
  assert_int_equal(mr_stage_create(&d, rest, 5, &s, NULL, 0), MR_STAGE_OK);
  assert_int_equal(mr_stage_update(s, rest, 5, &l), MR_STAGE_OK);
  assert_int_equal(l->n_lines, 0);
  mr_stage_destroy(s);
}

static void materials_change_while_the_show_runs(void **state) {
  (void)state;
  double rest[3] = { 0, 1, 0 };
  mr_model_def m = mr_default_model_def();
  m.particles[0] = 0;
  m.n_materials = 2;
  mr_stage *s = make(&m, 1, rest, 1);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(s, rest, 1, &l), MR_STAGE_OK);
  assert_int_equal(l->items[0].material, 0);
  assert_int_equal(mr_stage_set_material(s, 0, 1), MR_STAGE_OK);
  assert_int_equal(mr_stage_update(s, rest, 1, &l), MR_STAGE_OK);
  assert_int_equal(l->items[0].material, 1);
  assert_int_equal(mr_stage_set_material(s, 0, 2), MR_STAGE_ERR_ARG);
  assert_int_equal(mr_stage_set_material(s, 1, 0), MR_STAGE_ERR_ARG);
  assert_int_equal(l->items[0].material, 1);
  mr_stage_destroy(s);
}

/* Bones on one line know no twist about it: each takes the shortest turn
 * of the line, exact for a turn normal to it; a lone bone only moves. */
static void bones_on_a_line_take_its_shortest_turn_and_a_lone_bone_only_moves(void **state) {
  (void)state;
  double rest[12] = { 0, 1, 0, 0.5, 1, 0, 1, 1, 0, 5, 5, 5 };
  int line[3] = { 0, 1, 2 }, lone[1] = { 3 };
  mr_model_def m[2] = { mr_default_model_def(), mr_default_model_def() };
  m[0].display = m[1].display = MR_DISPLAY_FREEFORM;
  m[0].bones = line;
  m[0].n_bones = 3;
  m[1].bones = lone;
  m[1].n_bones = 1;
  mr_stage *s = make(m, 2, rest, 4);
  /* 40° about z (normal to the line along x), then a move. */
  double h = 40.0 * 3.14159265358979323846 / 360.0;
  mr_pose mo = { { 0.2, 0.1, -0.3 }, { cos(h), 0, 0, sin(h) } };
  double now[12];
  moved(rest, 4, &mo, now);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(s, now, 4, &l), MR_STAGE_OK);
  double probe[3] = { 0.4, 1.3, 0.2 }, want[3], got[3];
  mr_pose_apply(&mo, probe, want);
  for (int b = 0; b < 3; b++) {
    mr_pose_apply(&l->skins[0].bones[b], probe, got);
    near3(got, want, 1e-12);
  }
  /* The lone bone: no turn, its move only. */
  const mr_pose *p = &l->skins[1].bones[0];
  assert_true(p->orientation[0] == 1 && p->orientation[1] == 0 && p->orientation[3] == 0);
  double d[3] = { now[9] - rest[9], now[10] - rest[10], now[11] - rest[11] };
  near3(p->position, d, 1e-12);
  mr_stage_destroy(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(particle_model_sits_on_its_particle_unturned),
    cmocka_unit_test(link_lays_y_from_a_to_b_scaled_to_their_distance),
    cmocka_unit_test(rigid_model_follows_its_particles_exactly_in_both_orientations),
    cmocka_unit_test(freeform_skin_under_a_rigid_motion_moves_rigidly),
    cmocka_unit_test(skin_weights_sum_to_one_and_a_vertex_on_a_bone_takes_it_alone),
    cmocka_unit_test(a_point_not_finite_leaves_its_models_where_they_were),
    cmocka_unit_test(strings_and_wire_control_frames_are_lines_in_their_colours),
    cmocka_unit_test(materials_change_while_the_show_runs),
    cmocka_unit_test(bones_on_a_line_take_its_shortest_turn_and_a_lone_bone_only_moves),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

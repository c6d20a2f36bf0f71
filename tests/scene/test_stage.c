/* The stage sections of a scene file (models:, lights:, stage:, camera:):
 * every key read back, every kind of mistake refused at its
 * file:line:column, and a default stage for scenes without them. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "mr_scene.h"
#include "mr_stage.h"

/* Five particles, a rigid group, a puppet-free scene with a control frame
 * of three points and two strings. */
#define PHYS                                                                     \
  "physics:\n"                                                                   \
  "  effects: [gravity, constraints, strings, control, floor, self_collision]\n" \
  "  floor: {height: -0.5}\n"                                                    \
  "  particles:\n"                                                               \
  "    - {name: a, position: [0, 1, 0], mass: 1}\n"                              \
  "    - {name: b, position: [1, 1, 0], mass: 1}\n"                              \
  "    - {name: c, position: [0, 2, 0], mass: 1}\n"                              \
  "    - {name: d, position: [2, 1, 0], mass: 1, radius: 0.1}\n"                 \
  "    - {name: e, position: [3, 1, 0], mass: 1}\n"                              \
  "  groups: [{name: g, particles: [a, b, c]}]\n"                                \
  "  constraints: [{between: [d, e]}]\n"                                         \
  "  parts: [{particles: [d, e]}]\n"                                             \
  "  control:\n"                                                                 \
  "    pose: {position: [0, 3, 0]}\n"                                            \
  "    points: [{name: p, offset: [0, 0, 0]}, {name: q, offset: [1, 0, 0]},\n"   \
  "             {name: r, offset: [0, 0, 1]}]\n"                                 \
  "  strings: [{from: p, to: a}, {from: q, to: e}]\n"

static void load(const char *name, const char *text, mr_scene *s) {
  mr_scene_error e;
  if (mr_scene_load_text(name, text, strlen(text), s, &e) != MR_SCENE_OK) fail_msg("%s", e.text);
}

static void expect_error(const char *text, const char *expected) {
  mr_scene s;
  mr_scene_error e;
  mr_scene_status st = mr_scene_load_text("t.yaml", text, strlen(text), &s, &e);
  if (st == MR_SCENE_OK) {
    mr_scene_free(&s);
    fail_msg("loaded, expected: %s", expected);
  }
  if (strcmp(e.text, expected) != 0) fail_msg("got      %s\nexpected %s", e.text, expected);
}

/* The scene's points at their start, as the theater gives them to the stage. */
static double *rest_of(const mr_scene *s, size_t *n) {
  *n = s->n_particles + s->n_control_points;
  double *xyz = calloc(3 * *n + 3, sizeof *xyz);
  assert_non_null(xyz);
  for (size_t i = 0; i < s->n_particles; i++)
    memcpy(&xyz[3 * i], s->particles[i].def.position, 3 * sizeof(double));
  for (size_t j = 0; j < s->n_control_points; j++) {
    mr_pose pose;
    mr_scene_frame_pose_at(s, s->control_points[j].frame, 0, &pose);
    mr_scene_control_point_world(s, j, &pose, &xyz[3 * (s->n_particles + j)]);
  }
  return xyz;
}

/* The loaded def is one mr_stage takes as it is. */
static void stage_accepts(const mr_scene *s) {
  size_t n;
  double *xyz = rest_of(s, &n);
  mr_stage *st = NULL;
  char msg[256];
  if (mr_stage_create(&s->stage, xyz, n, &st, msg, sizeof msg) != MR_STAGE_OK) fail_msg("%s", msg);
  const mr_draw_list *l;
  assert_int_equal(mr_stage_update(st, xyz, n, &l), MR_STAGE_OK);
  mr_stage_destroy(st);
  free(xyz);
}

static const char full[] = PHYS
    "models:\n"
    "  - {name: m_particle, shape: cone, particle: d, scale: 0.5, shadow: false}\n"
    "  - {name: m_link, shape: capsule, display: link, between: [d, e], scale: [0.1, 1, 0.2],\n"
    "     material: {color: [1, 0, 0], roughness: 0.25, metallic: 1, emissive: [0, 0.5, 0]}}\n"
    "  - name: m_rigid\n"
    "    file: models/head.obj\n"
    "    display: rigid\n"
    "    group: g\n"
    "    orientation: configuration\n"
    "    position: [1, 2, 3]\n"
    "    rotation: [0, 90, 0]\n"
    "    materials: [{color: [0, 0, 1, 0.5]}, {color: [0, 1, 0]}]\n"
    "  - {name: m_bar, shape: box, display: rigid, particles: [p, q, r]}\n"
    "  - {name: m_skin, shape: sphere, display: freeform, bones: [a, b, c, d], influences: 2}\n"
    "lights:\n"
    "  ambient: [0.1, 0.2, 0.3]\n"
    "  sun: {color: [1, 0.5, 0.25], intensity: 2, shadows: false, shadow_size: 1024, "
    "shadow_filter: 9}\n"
    "  spots:\n"
    "    - {position: [1, 2.5, 1], target: [0, 0.5, 0], angle: 30, color: [1, 1, 0], "
    "intensity: 3}\n"
    "stage:\n"
    "  size: [640, 480]\n"
    "  time_of_day: 0.75\n"
    "  floor: {size: 5, color: [0.1, 0.1, 0.1], color2: [0.9, 0.9, 0.9]}\n"
    "  backdrop: false\n"
    "  sky: {day: [0.5, 0.5, 1], night: [0, 0, 0.1], stars: false}\n"
    "  constellations:\n"
    "    - {name: kite, stars: [[0, 90, 1.0], [90, 0, 0.5]]}\n"
    "  strings: {show: false, color: [0.2, 0.2, 0.2]}\n"
    "  frames: {show: true, color: [0.3, 0.3, 0.3], style: solid, thickness: 0.04}\n"
    "  spheres: true\n"
    "camera:\n"
    "  orbit: {target: [0, 1, 0], distance: 4, azimuth: 30, elevation: 20, fov: 50}\n"
    "  follow: true\n"
    "  facing: 15\n"
    "  views:\n"
    "    - {name: front, position: [0, 1, 3], target: [0, 1, 0], fov: 40}\n"
    "    - {name: side, position: [3, 1, 0]}\n";

static void every_stage_key_is_read_back(void **state) {
  (void)state;
  mr_scene s;
  load("scenes/t.yaml", full, &s);
  const mr_stage_def *d = &s.stage;
  assert_int_equal(d->n_models, 8); /* five, the frame's two bars, d's collision sphere */
  const mr_model_def *m = d->models;
  assert_string_equal(m[0].name, "m_particle");
  assert_int_equal(m[0].shape, MR_SHAPE_CONE);
  assert_int_equal(m[0].display, MR_DISPLAY_PARTICLE);
  assert_int_equal(m[0].particles[0], 3);
  assert_true(m[0].scale[0] == 0.5 && m[0].scale[2] == 0.5 && !m[0].cast_shadow);
  assert_int_equal(m[0].n_materials, 0);
  assert_int_equal(m[0].pos.line, 19);
  assert_int_equal(m[0].pos.column, 5);
  assert_int_equal(m[1].display, MR_DISPLAY_LINK);
  assert_true(m[1].particles[0] == 3 && m[1].particles[1] == 4);
  assert_true(m[1].scale[0] == 0.1 && m[1].scale[1] == 1 && m[1].scale[2] == 0.2);
  assert_int_equal(m[1].n_materials, 1);
  assert_true(m[1].materials[0].base_color[0] == 1 && m[1].materials[0].base_color[3] == 1);
  assert_true(m[1].materials[0].roughness == 0.25f && m[1].materials[0].metallic == 1);
  assert_true(m[1].materials[0].emissive[1] == 0.5f);
  assert_int_equal(m[2].shape, MR_SHAPE_FILE);
  assert_string_equal(m[2].path, "scenes/models/head.obj");
  assert_int_equal(m[2].display, MR_DISPLAY_RIGID);
  assert_int_equal(m[2].orient, MR_RIGID_CONFIGURATION);
  assert_true(m[2].particles[0] == 0 && m[2].particles[1] == 1 && m[2].particles[2] == 2);
  assert_true(m[2].place.position[2] == 3);
  assert_true(fabs(m[2].place.orientation[2] - sqrt(0.5)) < 1e-12); /* 90° about y */
  assert_int_equal(m[2].n_materials, 2);
  assert_true(m[2].materials[0].base_color[3] == 0.5f && m[2].materials[1].base_color[1] == 1);
  assert_int_equal(m[3].orient, MR_RIGID_INITIAL);
  assert_true(m[3].particles[0] == 5 && m[3].particles[1] == 6 && m[3].particles[2] == 7);
  assert_int_equal(m[4].display, MR_DISPLAY_FREEFORM);
  assert_int_equal(m[4].n_bones, 4);
  assert_int_equal(m[4].influences, 2);
  assert_true(m[4].bones[3] == 3 && m[4].bones_rest[3 * 3] == 2 && m[4].bones_rest[1] == 1);
  /* The wooden control: p at the corner of the frame's L, q and r each
   * 1 m from it, joined by two bars (the third, q-r, would be longer). */
  assert_string_equal(m[5].name, "bar:p-q");
  assert_string_equal(m[6].name, "bar:p-r");
  for (int i = 5; i < 7; i++) {
    assert_int_equal(m[i].display, MR_DISPLAY_LINK);
    assert_int_equal(m[i].shape, MR_SHAPE_CAPSULE);
    assert_true(m[i].scale[0] == 0.04 && m[i].scale[1] == 1 && m[i].scale[2] == 0.04);
    assert_true(m[i].materials[0].base_color[0] == 0.3f && !m[i].collision);
  }
  assert_true(m[5].particles[0] == 5 && m[5].particles[1] == 6 && m[6].particles[1] == 7);
  assert_string_equal(m[7].name, "sphere:d");
  assert_true(m[7].particles[0] == 3 && fabs(m[7].scale[1] - 0.2) < 1e-12 && m[7].collision);
  assert_true(d->show_spheres && d->frame_style == MR_FRAMES_SOLID && d->frame_thickness == 0.04);
  const mr_lights_def *l = &d->lights;
  assert_true(l->ambient[2] == 0.3f && l->sun_color[2] == 0.25f && l->sun_intensity == 2);
  assert_true(!l->shadows && l->shadow_size == 1024 && l->shadow_filter == 9);
  assert_int_equal(l->n_spots, 1);
  assert_true(l->spots[0].angle_deg == 30 && l->spots[0].intensity == 3 &&
              l->spots[0].color[2] == 0 && l->spots[0].position[1] == 2.5 &&
              l->spots[0].target[1] == 0.5);
  assert_true(d->width == 640 && d->height == 480 && d->time_of_day == 0.75);
  assert_true(d->floor && d->floor_size == 5 && d->floor_color2[0] == 0.9f);
  assert_true(d->floor_height == -0.5 && !d->backdrop);
  assert_true(d->sky_day[2] == 1 && d->sky_night[2] == 0.1f && !d->stars);
  assert_int_equal(d->n_stars, 2);
  assert_true(fabs(d->star_list[0].dir[1] - 1) < 1e-6 && d->star_list[1].brightness == 0.5f);
  assert_true(fabs(d->star_list[1].dir[0] - 1) < 1e-6);
  assert_true(!d->show_strings && d->string_color[0] == 0.2f);
  assert_true(d->show_frames && d->frame_color[0] == 0.3f);
  assert_true(d->orbit_target[1] == 1 && d->orbit_distance == 4 && d->orbit_azimuth_deg == 30);
  assert_true(d->orbit_elevation_deg == 20 && d->fov_deg == 50);
  assert_true(d->follow && d->facing_deg == 15);
  assert_int_equal(d->n_cameras, 2);
  assert_string_equal(d->cameras[1].name, "side");
  assert_true(d->cameras[0].fov_deg == 40 && d->cameras[1].fov_deg == 45);
  assert_true(d->cameras[1].position[0] == 3 && d->cameras[1].target[1] == 0.6);
  /* The rigging: strings from control point to particle, the frame's
   * three points in order. World ids: particles 0..4, points 5..7. */
  assert_int_equal(d->n_strings, 2);
  assert_true(d->strings[0] == 5 && d->strings[1] == 0 && d->strings[2] == 6 && d->strings[3] == 4);
  assert_int_equal(d->n_frames, 1);
  assert_int_equal(d->frame_point_count[0], 3);
  assert_true(d->frame_points[0] == 5 && d->frame_points[2] == 7);
  stage_accepts(&s);
  mr_scene_free(&s);
}

static void a_scene_without_stage_sections_still_shows_every_particle_and_link(void **state) {
  (void)state;
  mr_scene s;
  load("t.yaml", PHYS, &s);
  const mr_stage_def *d = &s.stage;
  assert_int_equal(d->cookie, MR_DEF_COOKIE);
  /* A capsule per constraint, a sphere per particle, the frame's two
   * wooden bars, and d's collision sphere (hidden). */
  assert_int_equal(d->n_models, 1 + 5 + 2 + 1);
  assert_string_equal(d->models[0].name, "link:d-e");
  assert_int_equal(d->models[0].display, MR_DISPLAY_LINK);
  assert_int_equal(d->models[0].shape, MR_SHAPE_CAPSULE);
  assert_true(d->models[0].particles[0] == 3 && d->models[0].particles[1] == 4);
  assert_true(d->models[0].scale[0] < 0.1 && d->models[0].scale[1] == 1);
  for (int i = 0; i < 5; i++) {
    const mr_model_def *m = &d->models[1 + i];
    assert_int_equal(m->display, MR_DISPLAY_PARTICLE);
    assert_int_equal(m->shape, MR_SHAPE_SPHERE);
    assert_int_equal(m->particles[0], i);
  }
  assert_true(fabs(d->models[4].scale[0] - 0.2) < 1e-12); /* d: its radius 0.1 */
  assert_true(d->models[1].scale[0] > 0 && d->models[1].scale[0] < 0.1);
  assert_true(d->frame_style == MR_FRAMES_SOLID && d->frame_thickness == 0.025);
  assert_true(strcmp(d->models[6].name, "bar:p-q") == 0 && !d->models[6].collision);
  assert_true(d->models[8].collision && !d->show_spheres);
  assert_int_equal(d->n_strings, 2);
  assert_int_equal(d->n_frames, 1);
  assert_true(d->floor_height == -0.5);
  /* The audience's camera: in front (+z), a little below the middle of
   * the points and looking up, from far enough back (test_view.c frames
   * every example scene with it). */
  assert_true(fabs(d->orbit_target[0] - 1.5) < 1e-9 && d->orbit_azimuth_deg == 0);
  assert_true(d->orbit_elevation_deg < 0 && d->orbit_elevation_deg > -10);
  assert_true(d->orbit_distance > 2 && d->orbit_distance < 10);
  assert_false(d->follow);
  assert_int_equal(d->n_cameras, 0);
  assert_true(d->width == 1280 && d->height == 720);
  /* The shadow map's size and filter are the renderer's to choose. */
  assert_true(d->lights.shadows && d->lights.shadow_size == 0 && d->lights.shadow_filter == 0);
  stage_accepts(&s);
  mr_scene_free(&s);
  /* models: [] shows none; the rigging stays: the bars, and the hidden
   * collision sphere. */
  load("t.yaml", PHYS "models: []\n", &s);
  assert_int_equal(s.stage.n_models, 3);
  assert_int_equal(s.stage.n_strings, 2);
  mr_scene_free(&s);
  /* As wire, the frame is lines only: no bars. */
  load("t.yaml", PHYS "models: []\nstage: {frames: {style: wire}}\n", &s);
  assert_int_equal(s.stage.n_models, 1);
  assert_true(s.stage.frame_style == MR_FRAMES_WIRE && s.stage.models[0].collision);
  mr_scene_free(&s);
}

static void a_freeform_puppet_binds_every_particle_of_it(void **state) {
  (void)state;
  const char *text = "physics:\n"
                     "  effects: [gravity, constraints]\n"
                     "  puppets:\n"
                     "    - name: ghost\n"
                     "      offset: [1, 0, 0]\n"
                     "      particles:\n"
                     "        - {name: top, position: [0, 2, 0], mass: 1}\n"
                     "        - {name: hem, position: [0, 1, 0], mass: 1}\n"
                     "      constraints: [{between: [top, hem]}]\n"
                     "models:\n"
                     "  - {name: sheet, file: /abs/ghost.glb, display: freeform, puppet: ghost}\n"
                     "  - {name: tip, shape: sphere, particle: ghost.top}\n";
  mr_scene s;
  load("here.yaml", text, &s);
  const mr_model_def *m = s.stage.models;
  assert_int_equal(s.stage.n_models, 2);
  assert_string_equal(m[0].path, "/abs/ghost.glb");
  assert_int_equal(m[0].n_bones, 2);
  assert_true(m[0].bones[0] == 0 && m[0].bones[1] == 1);
  assert_true(m[0].bones_rest[0] == 1 && m[0].bones_rest[4] == 1); /* placed by the puppet */
  assert_int_equal(m[0].influences, 4);
  assert_int_equal(m[1].particles[0], 0);
  stage_accepts(&s);
  mr_scene_free(&s);
  load("here.yaml",
       "physics:\n  effects: [gravity]\n  particles: [{name: a, position: [0, 1, 0], mass: 1}]\n"
       "models: [{name: m, file: m.obj, particle: a}]\n",
       &s);
  assert_string_equal(s.stage.models[0].path, "m.obj"); /* the scene's folder is the current one */
  mr_scene_free(&s);
}

/* Three particles on one line (no rigid model can hang on them); the
 * sections under test start at line 7. */
#define SMALL                                       \
  "physics:\n"                                      \
  "  effects: [gravity, constraints]\n"             \
  "  particles:\n"                                  \
  "    - {name: a, position: [0, 1, 0], mass: 1}\n" \
  "    - {name: b, position: [1, 1, 0], mass: 1}\n" \
  "    - {name: c, position: [2, 1, 0], mass: 1}\n"

/* `camera: follow` and `camera: {facing: 90}` without an orbit: the
 * audience's camera follows, or sits on the side the puppets face. */
static void the_audience_camera_sits_where_the_puppets_face_and_may_follow(void **state) {
  (void)state;
  mr_scene s;
  load("t.yaml", SMALL "camera: follow\n", &s);
  assert_true(s.stage.follow && s.stage.orbit_azimuth_deg == 0);
  mr_scene_free(&s);
  load("t.yaml", SMALL "camera: {facing: 90, follow: false}\n", &s);
  assert_true(!s.stage.follow && s.stage.orbit_azimuth_deg == 90);
  /* Seen from +x, the points' spread along x is depth: the middle's y
   * and z stay, the eye stands out along +x. */
  double eye[3];
  mr_orbit o = mr_orbit_of_stage(&s.stage);
  mr_orbit_eye(&o, eye);
  assert_true(eye[0] > 2 && fabs(eye[2] - s.stage.orbit_target[2]) < 1e-9);
  mr_scene_free(&s);
}

/* stage.size takes 16 to 16384 pixels each way, both ends included: a
 * window of exactly the bounds opens, one pixel beyond is refused at that
 * number. */
static void stage_size_at_its_bounds(void **state) {
  (void)state;
  mr_scene s;
  load("t.yaml", SMALL "stage: {size: [16, 16384]}\n", &s);
  assert_int_equal(s.stage.width, 16);
  assert_int_equal(s.stage.height, 16384);
  mr_scene_free(&s);
  expect_error(SMALL "stage: {size: [16, 16385]}\n",
               "t.yaml:7:20: expected stage.size between 16 and 16384 pixels, got 16385");
  expect_error(SMALL "stage: {size: [15, 16384]}\n",
               "t.yaml:7:16: expected stage.size between 16 and 16384 pixels, got 15");
}

/* A model takes up to MR_STAGE_MAX_MATERIALS materials, the last one
 * included; one more is refused at the list. */
static void a_model_takes_its_most_materials(void **state) {
  (void)state;
  char list[256] = "", text[1024];
  size_t n = 0;
  for (int i = 0; i < MR_STAGE_MAX_MATERIALS; i++)
    n += (size_t)snprintf(list + n, sizeof list - n, "%s{}", i ? ", " : "");
  snprintf(text, sizeof text,
           SMALL "models: [{name: m, shape: box, particle: a, materials: [%s]}]\n", list);
  mr_scene s;
  load("t.yaml", text, &s);
  assert_int_equal(s.stage.models[0].n_materials, MR_STAGE_MAX_MATERIALS);
  mr_scene_free(&s);
  snprintf(text, sizeof text,
           SMALL "models: [{name: m, shape: box, particle: a, materials: [%s, {}]}]\n", list);
  char want[128];
  snprintf(want, sizeof want, "t.yaml:7:56: expected 1 to %d materials for model 'm', got %d",
           MR_STAGE_MAX_MATERIALS, MR_STAGE_MAX_MATERIALS + 1);
  expect_error(text, want);
}

/* The scene's own sky holds at most 100000 stars in all constellations:
 * exactly that many load, one more is refused at the list that passes
 * the bound. */
static void the_sky_holds_its_most_stars(void **state) {
  (void)state;
  enum { MOST = 100000 };
  static const char star[] = "[0, 45, 1], ";
  const size_t head = strlen(SMALL "stage: {constellations: [{name: a, stars: ["),
               size = head + (MOST + 1) * (sizeof star - 1) + 64;
  char *text = malloc(size);
  assert_non_null(text);
  for (int extra = 0; extra <= 1; extra++) {
    size_t n = (size_t)snprintf(text, size, SMALL "stage: {constellations: [{name: a, stars: [");
    for (int i = 0; i < MOST - 1 + extra; i++, n += sizeof star - 1)
      memcpy(text + n, star, sizeof star - 1);
    n += (size_t)snprintf(text + n, size - n, "]}, {name: b, stars: [[0, 45, 1]]}]}\n");
    if (!extra) {
      mr_scene s;
      load("t.yaml", text, &s);
      assert_int_equal(s.stage.n_stars, MOST);
      mr_scene_free(&s);
    } else {
      const char *line = strstr(text, "stage:"), *list = strstr(text, "{name: b, stars: [");
      char want[96];
      snprintf(want, sizeof want, "t.yaml:7:%d: expected at most %d stars in all",
               (int)(list + strlen("{name: b, stars: ") - line) + 1, MOST);
      expect_error(text, want);
    }
  }
  free(text);
}

static void mistakes_are_refused_at_their_place(void **state) {
  (void)state;
  static const struct {
    const char *text, *error;
  } cases[] = {
    { SMALL "models: [{name: m, shape: sphere, particle: a, colour: [1, 0, 0]}]\n",
      "t.yaml:7:48: unknown key 'colour' in a model; expected one of: name, shape, file, scale, "
      "position, rotation, material, materials, display, particle, between, group, particles, "
      "orientation, bones, puppet, influences, shadow" },
    { SMALL "models: {name: m}\n",
      "t.yaml:7:9: expected a sequence (- item or [a, b]) for models, got a mapping" },
    { SMALL "models: [{name: m, shape: sphere, particle: a, shadow: yes}]\n",
      "t.yaml:7:56: expected true or false for shadow, got 'yes'" },
    { SMALL "models: [{name: m, shape: sphere, particle: a, scale: -1}]\n",
      "t.yaml:7:55: expected scale between 1e-06 and 1e+06, got -1" },
    { SMALL "models: [{name: m, shape: sphere, particle: z}]\n",
      "t.yaml:7:45: expected the name of a particle or control point, got 'z'" },
    { SMALL "models: [{name: m, shape: teapot, particle: a}]\n",
      "t.yaml:7:27: expected shape to be one of: sphere, box, cylinder, capsule, cone, got "
      "'teapot'" },
    { SMALL "models: [{name: m, shape: sphere, file: m.obj, particle: a}]\n",
      "t.yaml:7:41: model 'm' has both shape and file; expected exactly one of shape (a "
      "built-in mesh) or file (a model file)" },
    { SMALL "models: [{name: m, particle: a}]\n",
      "t.yaml:7:10: model 'm' has neither shape nor file; expected exactly one of shape (a "
      "built-in mesh) or file (a model file)" },
    { SMALL "models: [{name: m, shape: box, display: link, between: [a]}]\n",
      "t.yaml:7:56: link model 'm' needs two points; expected between: [a, b], got one" },
    { SMALL "models: [{name: m, shape: box, display: link, between: [a, a]}]\n",
      "t.yaml:7:56: link model 'm' has both ends on 'a'; expected two points" },
    { SMALL "models: [{name: m, shape: box, display: rigid, particles: [a, b, c]}]\n",
      "t.yaml:7:59: rigid model 'm': 'a', 'b' and 'c' lie on one line at the start; "
      "expected three points that span a plane" },
    { SMALL "models: [{name: m, shape: box, display: rigid, particles: [a, a, c]}]\n",
      "t.yaml:7:59: rigid model 'm': 'a', 'a' and 'c' coincide at the start; expected three "
      "points that span a plane" },
    { SMALL "models: [{name: m, shape: box, display: rigid, group: nope}]\n",
      "t.yaml:7:55: expected the name of a group declared under groups, got 'nope'" },
    { SMALL "models: [{name: m, shape: box, particle: a, between: [a, b]}]\n",
      "t.yaml:7:45: key 'between' is for display link; model 'm' is displayed particle" },
    { SMALL "models: [{name: m, shape: box, display: freeform}]\n",
      "t.yaml:7:10: freeform model 'm' has neither bones nor puppet; expected exactly one "
      "of bones or puppet" },
    { SMALL "models: [{name: m, shape: box, display: freeform, bones: [a], influences: 5}]\n",
      "t.yaml:7:75: expected influences between 1 and 4, got 5" },
    { SMALL "models: [{name: m, shape: box, display: wobbly, particle: a}]\n",
      "t.yaml:7:41: expected display to be one of: particle, link, rigid, freeform, got "
      "'wobbly'" },
    { SMALL "models:\n  - {name: m, shape: box, particle: a}\n  - {name: m, shape: box, "
            "particle: b}\n",

      "t.yaml:9:12: a second model named 'm' (the first is at line 8); expected unique names" },
    { SMALL "models: [{name: m, shape: box, particle: a, material: {color: [2, 0, 0]}}]\n",
      "t.yaml:7:64: expected color between 0 and 1, got 2" },
    { SMALL "models: [{name: m, shape: box, particle: a, material: {}, materials: [{}]}]\n",
      "t.yaml:7:70: model 'm' has both material and materials; expected one" },
    { SMALL "lights: {spots: [{}, {}, {}, {}, {}, {}, {}, {}, {}]}\n",
      "t.yaml:7:50: expected at most 8 items in lights.spots, got 9" },
    { SMALL "lights: {ambient: 0.5}\n",
      "t.yaml:7:19: expected [x, y, z] (three numbers) for ambient, got '0.5'" },
    { SMALL "lights: {sun: {shadow_size: 100}}\n",
      "t.yaml:7:29: expected shadow_size between 256 and 8192, got 100" },
    { SMALL "lights: {sun: {shadow_filter: 2}}\n",
      "t.yaml:7:31: expected shadow_filter 1, 4 or 9, got 2" },
    { SMALL "lights: {sun: {shadow_filter: 16}}\n",
      "t.yaml:7:31: expected shadow_filter between 1 and 9, got 16" },
    { SMALL "lights: {spots: [{angle: 90}]}\n",
      "t.yaml:7:26: expected angle between 0.1 and 89 °, got 90" },
    { SMALL "stage: {size: [10, 480]}\n",
      "t.yaml:7:16: expected stage.size between 16 and 16384 pixels, got 10" },
    { SMALL "stage: {time_of_day: 1.5}\n",
      "t.yaml:7:22: expected time_of_day between 0 and 1, got 1.5" },
    { SMALL "stage: {floor: maybe}\n",
      "t.yaml:7:16: expected true or false for stage.floor, got 'maybe'" },
    { SMALL "stage: {backdrop: {distance: 3, colour: [0, 0, 0]}}\n",
      "t.yaml:7:33: unknown key 'colour' in stage.backdrop; expected one of: distance, color" },
    { SMALL "stage: {constellations: [{name: k, stars: [[0, 95, 1]]}]}\n",
      "t.yaml:7:48: expected star elevation between -90 and 90 °, got 95" },
    { SMALL "camera: followme\n",
      "t.yaml:7:9: expected follow or a mapping for camera, got 'followme'" },
    { SMALL "camera: {follow: 1}\n", "t.yaml:7:18: expected true or false for follow, got '1'" },
    { SMALL "camera: {orbit: {elevation: 90}}\n",
      "t.yaml:7:29: expected elevation between -89 and 89 °, got 90" },
    { SMALL "camera: {orbit: {elevation: -90}}\n",
      "t.yaml:7:29: expected elevation between -89 and 89 °, got -90" },
    { SMALL "camera: {views: [{name: a, position: [1, 2, 3], target: [1, 2, 3]}]}\n",
      "t.yaml:7:57: view 'a' has its target at its position; expected a target away from the "
      "camera" },
    { SMALL "camera: {views: [{name: a, position: [0, 0.6, 0]}]}\n",
      "t.yaml:7:38: view 'a' has its target at its position; expected a target away from the "
      "camera" },
    { SMALL "camera: {views: [{name: a, position: [0, 4, 0], target: [0, 1, 0]}]}\n",
      "t.yaml:7:57: view 'a' looks straight down; expected a target off the vertical through "
      "its position (a view's up is +y)" },
    { SMALL "stage: {constellations: [{name: k, stars: [[0, 45]]}]}\n",
      "t.yaml:7:44: expected a star as [azimuth, elevation, brightness]" },
    { SMALL "stage: {spheres: 1}\n", "t.yaml:7:18: expected true or false for spheres, got '1'" },
    { SMALL "stage: {frames: {style: wood}}\n",
      "t.yaml:7:25: expected style to be one of: solid, wire, got 'wood'" },
    { SMALL "stage: {frames: {thickness: 0}}\n",
      "t.yaml:7:29: expected a positive number for thickness, got 0" },
    { SMALL "stage: {strings: {show: true, width: 2}}\n",
      "t.yaml:7:31: unknown key 'width' in stage.strings; expected one of: show, color" },
    { SMALL "camera: {views: [{name: a}, {name: b}, {name: c}, {name: d}, {name: e}, {name: f}, "
            "{name: g}, {name: h}, {name: i}]}\n",

      "t.yaml:7:106: expected at most 8 items in camera.views, got 9" },
    { SMALL "camera: {views: [{name: a}, {name: a}]}\n",
      "t.yaml:7:36: a second view named 'a' (the first is at line 7); expected unique names" },
    { SMALL "camera: {orbit: {fov: 0}}\n",
      "t.yaml:7:23: expected a positive number for fov, got 0" },
    { SMALL "camera: {orbit: {distance: 2, zoom: 1}}\n",
      "t.yaml:7:31: unknown key 'zoom' in camera.orbit; expected one of: target, distance, "
      "azimuth, elevation, fov" },
    { "glove: {}\n" SMALL,
      "t.yaml:1:1: section 'glove' is reserved for the theater and not supported by this "
      "version; expected one of: format, name, sim, physics, mapping, expect, models, "
      "lights, stage, camera" },
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    expect_error(cases[i].text, cases[i].error);
}

/* FORMAT.md's example of the stage sections is a scene that loads, and the
 * stage takes what it becomes. */
static void format_md_stage_example_loads(void **state) {
  (void)state;
  static char doc[262144];
  FILE *f = fopen(MR_SOURCE_DIR "/host/scenes/FORMAT.md", "r");
  assert_non_null(f);
  size_t n = fread(doc, 1, sizeof doc - 1, f);
  fclose(f);
  doc[n] = '\0';
  char *start = strstr(doc, "## The stage: models, lights, stage, camera");
  assert_non_null(start);
  start = strstr(start, "```yaml\n");
  assert_non_null(start);
  start += strlen("```yaml\n");
  char *end = strstr(start, "```");
  assert_non_null(end);
  mr_scene s;
  mr_scene_error e;
  if (mr_scene_load_text("host/scenes/FORMAT.md", start, (size_t)(end - start), &s, &e) !=
      MR_SCENE_OK)
    fail_msg("%s", e.text);
  assert_int_equal(s.stage.n_models, 5 + 2); /* the control's two bars */
  assert_string_equal(s.stage.models[0].path, "host/scenes/models/head.obj");
  assert_int_equal(s.stage.models[4].display, MR_DISPLAY_FREEFORM);
  assert_int_equal(s.stage.lights.n_spots, 1);
  assert_int_equal(s.stage.n_cameras, 2);
  assert_int_equal(s.stage.n_stars, 3);
  assert_int_equal(s.stage.n_strings, 2);
  stage_accepts(&s);
  mr_scene_free(&s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(every_stage_key_is_read_back),
    cmocka_unit_test(a_scene_without_stage_sections_still_shows_every_particle_and_link),
    cmocka_unit_test(a_freeform_puppet_binds_every_particle_of_it),
    cmocka_unit_test(the_audience_camera_sits_where_the_puppets_face_and_may_follow),
    cmocka_unit_test(mistakes_are_refused_at_their_place),
    cmocka_unit_test(stage_size_at_its_bounds),
    cmocka_unit_test(a_model_takes_its_most_materials),
    cmocka_unit_test(the_sky_holds_its_most_stars),
    cmocka_unit_test(format_md_stage_example_loads),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The scene loader: what a good file becomes, and for each kind of bad
 * file the exact file:line:column and message. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "mr_scene.h"
#include "scene_read.h" /* the range table, to hold FORMAT.md to it */
#include "proc.h"

#define BASE                                        \
  "physics:\n"                                      \
  "  effects: [gravity, constraints]\n"             \
  "  particles:\n"                                  \
  "    - {name: a, position: [0, 1, 0], mass: 1}\n" \
  "    - {name: b, position: [1, 1, 0], mass: 2}\n"

/* Loads text as "t.yaml" and expects a failure whose text is exactly
 * `expected`. */
static void expect_error(const char *text, mr_scene_status status, const char *expected) {
  mr_scene s;
  mr_scene_error e;
  mr_scene_status st = mr_scene_load_text("t.yaml", text, strlen(text), &s, &e);
  if (st == MR_SCENE_OK) mr_scene_free(&s);
  assert_int_equal(st, status);
  assert_string_equal(e.text, expected);
}

static void good_scene_loads_with_paper_defaults(void **state) {
  (void)state;
  const char *text = "# a comment\n" BASE "  constraints:\n    - {between: [a, b]}\n";
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load_text("t.yaml", text, strlen(text), &s, &e), MR_SCENE_OK);
  assert_int_equal(s.n_particles, 2);
  assert_string_equal(s.particles[1].name, "b");
  assert_true(s.particles[1].def.mass == 2.0);
  assert_int_equal(s.n_distances, 1);
  assert_true(fabs(s.distances[0].def.length - 1.0) < 1e-15);
  assert_int_equal(s.distances[0].pos.line, 8); /* after the comment line */
  assert_int_equal(s.world.effects, MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS);
  assert_true(s.world.gravity[1] == -9.81);
  /* Settings the file leaves out are the physics library's defaults, which
   * are the paper's. */
  assert_true(s.world.dt_max == mr_default_world_def().dt_max);
  assert_true(s.duration == 10.0);
  mr_scene_free(&s);
}

/* mr_scene_load_unframed reads the same file into the same physics and
 * leaves the stage's framing (the set's size, the audience's camera) as
 * the file gives it; mr_scene_load frames the rest from the track. A bad
 * file is refused the same way by both. */
static void unframed_load_leaves_only_the_framing_out(void **state) {
  (void)state;
  static const char text[] = BASE "  constraints:\n    - {between: [a, b]}\n"
                                  "stage: {proscenium: {width: 7}}\n";
  const char *path = tt_tmp_file("load_unframed.yaml", text, sizeof text - 1);
  mr_scene framed, bare;
  mr_scene_error e;
  assert_int_equal(mr_scene_load(path, &framed, &e), MR_SCENE_OK);
  assert_int_equal(mr_scene_load_unframed(path, &bare, &e), MR_SCENE_OK);
  assert_int_equal(bare.n_particles, framed.n_particles);
  for (size_t i = 0; i < bare.n_particles; i++)
    assert_memory_equal(&bare.particles[i].def, &framed.particles[i].def,
                        sizeof bare.particles[i].def);
  assert_int_equal(bare.n_distances, 1);
  assert_true(bare.distances[0].def.length == framed.distances[0].def.length);
  assert_memory_equal(&bare.world, &framed.world, sizeof bare.world);
  assert_true(bare.stage.set_width == 7.0 && framed.stage.set_width == 7.0);
  assert_true(framed.stage.set_height > 0 && framed.stage.orbit_distance > 0);
  /* Unframed, the camera stays the stage's default, where framing moved it. */
  assert_true(bare.stage.set_height == 0);
  assert_true(bare.stage.orbit_distance != framed.stage.orbit_distance);
  mr_scene_free(&framed);
  mr_scene_free(&bare);

  static const char bad[] = BASE "  constraints:\n    - {between: [a, c]}\n";
  const char *bad_path = tt_tmp_file("load_unframed_bad.yaml", bad, sizeof bad - 1);
  mr_scene_error e2;
  assert_int_not_equal(mr_scene_load(bad_path, &framed, &e), MR_SCENE_OK);
  assert_int_not_equal(mr_scene_load_unframed(bad_path, &bare, &e2), MR_SCENE_OK);
  assert_string_equal(e.text, e2.text);
  assert_int_equal(e.line, e2.line);
  mr_scene_free(&framed);
  mr_scene_free(&bare);
}

static void settings_and_anchors_are_read(void **state) {
  (void)state;
  const char *text = "name: anchors\n"
                     "sim: {duration: 60, fps: 25}\n"
                     "physics:\n"
                     "  effects: [gravity, drag, springs]\n"
                     "  drag: 0.5\n"
                     "  ats: {dt_min: 0.01, dt_max: 0.05, threshold_min: 0.0001, "
                     "threshold_max: 0.01}\n"
                     "  solver: {integrator: rk4, method: ldlt, ks: 50, kd: 10}\n"
                     "  particles:\n"
                     "    - {name: a, position: [0, 1, 0], mass: 1}\n"
                     "    - {name: b, position: [0, 2, 0], mass: 1}\n"
                     "    - {name: c, position: [0, 3, 0], mass: 1}\n"
                     "  springs:\n"
                     "    - &soft {between: [a, b], stiffness: 20, damping: 0.5}\n"
                     "    - {between: [b, c], stiffness: 30}\n"
                     "    - *soft\n";
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load_text("t.yaml", text, strlen(text), &s, &e), MR_SCENE_OK);
  assert_string_equal(s.name, "anchors");
  assert_true(s.duration == 60.0 && s.fps == 25.0);
  assert_true(s.world.drag == 0.5);
  assert_true(s.world.dt_min == 0.01 && s.world.deviation_high == 0.01);
  assert_string_equal(mr_solve_method_name(s.world.solver), "ldlt");
  assert_true(s.world.ks == 50.0);
  assert_int_equal(s.n_forces, 3);
  const mr_spring_def *sp[3];
  for (int i = 0; i < 3; i++) {
    assert_int_equal(s.forces[i].kind, MR_EFFECT_SPRINGS);
    sp[i] = &s.forces[i].def.spring;
  }
  assert_true(sp[0]->stiffness == 20.0);
  /* the alias repeats the anchored spring */
  assert_true(sp[2]->stiffness == 20.0 && sp[2]->damping == 0.5);
  assert_int_equal(sp[2]->a, 0);
  assert_true(sp[1]->damping == mr_default_spring_def().damping); /* left out */
  mr_scene_free(&s);
}

/* A particle and a bar point on a frame that follows keyframes, given
 * after this. */
#define KEYFRAMED                                            \
  "physics:\n"                                               \
  "  effects: [control]\n"                                   \
  "  particles: [{name: a, position: [0, 0, 0], mass: 1}]\n" \
  "  control:\n"                                             \
  "    points: [{name: bar, offset: [1, 0, 0]}]\n"           \
  "    pose: {position: [0, 2, 0]}\n"                        \
  "    track:\n"                                             \
  "      keyframes:\n"

static void keyframes_ease_and_hold(void **state) {
  (void)state;
  const char *text = KEYFRAMED "        - {t: 1, position: [0, 2, 0]}\n"
                               "        - {t: 3, position: [2, 2, 0], rotation: [0, 0, 90]}\n";
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load_text("t.yaml", text, strlen(text), &s, &e), MR_SCENE_OK);
  mr_pose p;
  mr_scene_frame_pose_at(&s, 0, 0.0, &p);
  assert_true(p.position[0] == 0.0 && p.position[1] == 2.0);
  mr_scene_frame_pose_at(&s, 0, 2.0, &p); /* halfway: smoothstep(0.5) = 0.5 */
  assert_true(fabs(p.position[0] - 1.0) < 1e-12);
  mr_scene_frame_pose_at(&s, 0, 1.5, &p); /* smoothstep(0.25) = 0.15625 */
  assert_true(fabs(p.position[0] - 2 * 0.15625) < 1e-12);
  mr_scene_frame_pose_at(&s, 0, 10.0, &p);
  static const double zero[3] = { 0, 0, 0 }, z90[3] = { 0, 0, 90 };
  mr_pose want = mr_pose_from_euler_deg(zero, z90);
  assert_true(p.position[0] == 2.0 &&
              memcmp(p.orientation, want.orientation, sizeof want.orientation) == 0);
  /* 90 degrees about z takes the offset (1, 0, 0) to (0, 1, 0). */
  double w[3];
  mr_scene_control_point_world(&s, 0, &p, w);
  assert_true(fabs(w[0] - 2.0) < 1e-12 && fabs(w[1] - 3.0) < 1e-12 && fabs(w[2]) < 1e-12);
  mr_scene_free(&s);
}

static void oscillation_follows_the_sine(void **state) {
  (void)state;
  const char *text = "physics:\n"
                     "  effects: [control]\n"
                     "  particles: [{name: a, position: [0, 0, 0], mass: 1}]\n"
                     "  control:\n"
                     "    points: [{name: bar, offset: [0, 0, 0]}]\n"
                     "    pose: {position: [0, 2, 0]}\n"
                     "    track: {oscillate: {amplitude: [0.3, 0, 0], frequency: 3}}\n";
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load_text("t.yaml", text, strlen(text), &s, &e), MR_SCENE_OK);
  mr_pose p;
  mr_scene_frame_pose_at(&s, 0, 1.0 / 12.0, &p); /* a quarter period at 3 Hz */
  assert_true(fabs(p.position[0] - 0.3) < 1e-12);
  assert_true(p.position[1] == 2.0);
  mr_scene_free(&s);
}

static void unknown_top_level_key(void **state) {
  (void)state;
  expect_error(BASE "bogus: 1\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:6:1: unknown key 'bogus' in the scene; expected one of: format, name, "
               "sim, physics, mapping, expect, models, lights, stage, camera");
}

static void theater_section_is_reserved(void **state) {
  (void)state;
  expect_error("glove: []\n" BASE, MR_SCENE_ERR_SCHEMA,
               "t.yaml:1:1: section 'glove' is reserved for the theater and not supported by "
               "this version; expected one of: format, name, sim, physics, mapping, expect, "
               "models, lights, stage, camera");
}

static void unknown_particle_key(void **state) {
  (void)state;
  expect_error(BASE "    - {name: c, position: [2, 1, 0], masss: 1}\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:6:38: unknown key 'masss' in a particle; expected one of: name, "
               "position, velocity, mass, radius, pinned");
}

static void nan_is_refused(void **state) {
  (void)state;
  expect_error(BASE "    - {name: c, position: [2, .nan, 0], mass: 1}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:31: expected a finite number for position, got '.nan'");
  expect_error(BASE "    - {name: c, position: [2, 1, 0], mass: .inf}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:44: expected a finite number for mass, got '.inf'");
  expect_error(BASE "    - {name: c, position: [2, 1, 0], mass: NaN}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:44: expected a finite number for mass, got 'NaN'");
}

static void negative_and_zero_mass_are_refused(void **state) {
  (void)state;
  expect_error(BASE "    - {name: c, position: [2, 1, 0], mass: -1}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:44: expected a positive mass in kg for particle 'c', got -1");
  expect_error(BASE "    - {name: c, position: [2, 1, 0], mass: 0}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:44: expected a positive mass in kg for particle 'c', got 0");
}

static void coincident_particles_are_refused(void **state) {
  (void)state;
  expect_error(BASE "    - {name: c, position: [1, 1, 0], mass: 1}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:7: particle 'c' coincides with particle 'b' (line 5); expected "
               "distinct positions");
}

static void zero_length_constraints_are_refused(void **state) {
  (void)state;
  expect_error(BASE "  constraints:\n    - {between: [a, a]}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:7:17: zero-length constraint: both ends are 'a'; expected two particles");
  expect_error(BASE "  constraints:\n    - {between: [a, b], length: 0}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:7:33: zero-length constraint between 'a' and 'b'; expected a length "
               "above 1e-06 m");
}

static void undeclared_effect_is_refused(void **state) {
  (void)state;
  expect_error(BASE "  springs:\n    - {between: [a, b], stiffness: 10}\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:7:5: springs are declared but effect 'springs' is not listed in "
               "physics.effects");
}

static void unknown_names_and_shapes(void **state) {
  (void)state;
  expect_error(BASE "  constraints:\n    - {between: [a, z]}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:7:21: expected the name of a particle declared under particles, got 'z'");
  expect_error(BASE "    - {name: c, position: [2, 1], mass: 1}\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:6:27: expected [x, y, z] (three numbers) for position, got a sequence "
               "of 2 items");
  expect_error(BASE "    - {name: c, position: [2, 1, 0], mass: \"heavy\"}\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:6:44: expected a number for mass, got 'heavy'");
  expect_error(BASE "  effects2: []\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:6:3: unknown key 'effects2' in physics; expected one of: effects, "
               "gravity, drag, ats, solver, contact, particles, control, constraints, groups, "
               "springs, strings, sine_springs, antigravity, triggered, floor, parts, "
               "string_correction, puppets");
}

/* A word that is not in the enum's own name table is an error at its
 * place, never skipped in favour of the default; the table's words, with
 * '_' for '-', reach the world definition. */
static void integrator_and_method_come_from_the_libraries_tables(void **state) {
  (void)state;
  expect_error(BASE "  solver: {integrator: rk5}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:24: expected integrator to be one of: rk4, euler, "
               "semi-implicit-euler, midpoint, got 'rk5'");
  expect_error(BASE "  solver: {method: qr}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:20: expected method to be one of: gauss-seidel, cg, ldlt, eigen, "
               "got 'qr'");
  const char *text = BASE "  solver: {integrator: semi_implicit_euler, method: cg}\n";
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load_text("t.yaml", text, strlen(text), &s, &e), MR_SCENE_OK);
  assert_int_equal(s.world.integrator, MR_INTEGRATOR_SEMI_IMPLICIT_EULER);
  assert_int_equal(s.world.solver, MR_SOLVE_CG);
  mr_scene_free(&s);
}

/* Every applied-force kind of the physics that has elements (all but
 * gravity and drag) has a section in scene files, named as the physics
 * names the kind: a kind added to MR_FORCE_KINDS without a scene reader
 * fails here. */
static void every_physics_force_kind_has_a_scene_section(void **state) {
  (void)state;
  static const struct {
    uint32_t bit;
    const char *name;
  } kinds[] = {
#define X(id, stem, name) { MR_EFFECT_##id, name },
    MR_FORCE_KINDS(X)
#undef X
  };
  int sections = 0;
  for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
    if (kinds[i].bit == MR_EFFECT_GRAVITY || kinds[i].bit == MR_EFFECT_DRAG) continue;
    char key[64], text[512];
    snprintf(key, sizeof key, "%s", kinds[i].name);
    for (char *c = key; *c; c++) *c = *c == '-' ? '_' : *c;
    snprintf(text, sizeof text,
             "physics:\n  effects: [%s]\n  particles: [{name: a, position: [0, 1, 0], "
             "mass: 1}]\n  %s: []\n",
             kinds[i].name, key);
    mr_scene s;
    mr_scene_error e;
    mr_scene_status st = mr_scene_load_text("t.yaml", text, strlen(text), &s, &e);
    if (st != MR_SCENE_OK) fail_msg("force kind '%s': %s", kinds[i].name, e.text);
    mr_scene_free(&s);
    sections++;
  }
  assert_true(sections >= 5); /* springs, strings, antigravity, triggered, sine springs */
}

static void unknown_alias_is_refused(void **state) {
  (void)state;
  expect_error(BASE "    - *nope\n", MR_SCENE_ERR_SYNTAX,
               "t.yaml:6:7: expected a defined anchor for alias '*nope'");
}

static void duplicate_keys_are_refused(void **state) {
  (void)state;
  expect_error(BASE "physics: {}\n", MR_SCENE_ERR_SYNTAX,
               "t.yaml:6:1: duplicate key 'physics' (first at line 1, column 1)");
}

static void degenerate_groups_are_refused(void **state) {
  (void)state;
  expect_error(BASE "    - {name: c, position: [2, 1, 0], mass: 1}\n"
                    "  groups:\n    - {name: bar, particles: [a, b, c]}\n",
               MR_SCENE_ERR_VALUE,
               "t.yaml:8:37: group 'bar': 'a', 'b' and 'c' are collinear; expected members "
               "in general position (§5.1)");
}

/* A rigid group holds at most 64 members (the loader's shape check has
 * room for that many): 64 along a helix, no four coplanar, load as one
 * group, and a 65th is refused at the member list. */
static void a_group_of_64_loads_and_65_is_refused(void **state) {
  (void)state;
  char text[8192];
  for (int members = 64; members <= 65; members++) {
    size_t n = (size_t)snprintf(text, sizeof text,
                                "physics:\n  effects: [gravity, constraints]\n  particles:\n");
    for (int i = 0; i < members; i++)
      n += (size_t)snprintf(text + n, sizeof text - n,
                            "    - {name: p%d, position: [%.6f, %.6f, %.2f], mass: 1}\n", i,
                            cos(2.0 * i), sin(2.0 * i), 0.25 * i);
    n += (size_t)snprintf(text + n, sizeof text - n, "  groups:\n    - {name: g, particles: [");
    for (int i = 0; i < members; i++)
      n += (size_t)snprintf(text + n, sizeof text - n, "%sp%d", i ? ", " : "", i);
    n += (size_t)snprintf(text + n, sizeof text - n, "]}\n");
    assert_true(n < sizeof text);
    if (members == 64) {
      mr_scene s;
      mr_scene_error e;
      if (mr_scene_load_text("t.yaml", text, n, &s, &e) != MR_SCENE_OK) fail_msg("%s", e.text);
      assert_int_equal(s.n_groups, 1);
      assert_int_equal(s.groups[0].def.count, 64);
      mr_scene_free(&s);
    } else {
      expect_error(text, MR_SCENE_ERR_VALUE,
                   "t.yaml:70:28: expected 2 to 64 particles in group 'g', got 65");
    }
  }
}

/* Where two step settings may meet: dt_floor may equal dt_min (the
 * floor is the step's last resort below it), but the divergence bound
 * must lie strictly above threshold_max, or a step the controller would
 * keep counts as diverged. */
static void step_settings_where_they_meet(void **state) {
  (void)state;
  const char *ok = BASE "  ats: {dt_min: 0.001, dt_floor: 0.001, threshold_max: 0.1, "
                        "divergence: 0.2}\n";
  mr_scene s;
  mr_scene_error e;
  if (mr_scene_load_text("t.yaml", ok, strlen(ok), &s, &e) != MR_SCENE_OK) fail_msg("%s", e.text);
  assert_true(s.world.dt_floor == 0.001 && s.world.dt_min == 0.001);
  mr_scene_free(&s);
  expect_error(BASE "  ats: {threshold_max: 0.1, divergence: 0.1}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:41: expected divergence above threshold_max (0.1), got 0.1");
}

/* sim.max_steps counts steps a run may take; none is no run at all. */
static void max_steps_of_zero_is_refused(void **state) {
  (void)state;
  expect_error(BASE "sim: {max_steps: 0}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:18: expected max_steps between 1 and 1000000000, got 0");
  const char *ok = BASE "sim: {max_steps: 1}\n";
  mr_scene s;
  mr_scene_error e;
  if (mr_scene_load_text("t.yaml", ok, strlen(ok), &s, &e) != MR_SCENE_OK) fail_msg("%s", e.text);
  assert_int_equal(s.max_steps, 1);
  mr_scene_free(&s);
}

/* A puppet standing on the floor is the common start: a particle whose
 * bottom (y - radius) is at the floor's height loads, as does one a hair
 * (under MR_SCENE_COINCIDENT_M) below it from rounding; one a millimetre
 * below is refused at the particle. */
static void a_particle_resting_on_the_floor_loads(void **state) {
  (void)state;
  static const char *const fmt = "physics:\n  effects: [gravity, floor]\n  particles:\n"
                                 "    - {name: a, position: [0, %s, 0], mass: 1, radius: 0.1}\n"
                                 "  floor: {height: 0.5}\n";
  static const char *const fine[] = { "0.6", "0.5999995" };
  char text[256];
  for (size_t i = 0; i < sizeof fine / sizeof fine[0]; i++) {
    snprintf(text, sizeof text, fmt, fine[i]);
    mr_scene s;
    mr_scene_error e;
    if (mr_scene_load_text("t.yaml", text, strlen(text), &s, &e) != MR_SCENE_OK)
      fail_msg("%s: %s", fine[i], e.text);
    mr_scene_free(&s);
  }
  snprintf(text, sizeof text, fmt, "0.599");
  expect_error(text, MR_SCENE_ERR_VALUE,
               "t.yaml:4:7: particle 'a' starts below the floor (y - radius = 0.499 < 0.5); "
               "expected it on or above the floor");
}

/* A part's restitution and friction (Coulomb μ against other parts) are
 * read; a negative friction names its place. */
/* Four bytes that hang libfyaml ('%x', a lone 0xC3, a newline) never reach
 * it: malformed UTF-8 is refused at its place. */
static void malformed_utf8_is_refused_before_the_parser(void **state) {
  (void)state;
  expect_error("%x\xc3\n", MR_SCENE_ERR_SYNTAX,
               "t.yaml:1:3: expected UTF-8 text, found the byte 0xC3");
  expect_error("name: \xed\xa0\x80\n", MR_SCENE_ERR_SYNTAX,
               "t.yaml:1:7: expected UTF-8 text, found the byte 0xED"); /* a surrogate */
  expect_error("name: \xc0\xaf\n", MR_SCENE_ERR_SYNTAX,
               "t.yaml:1:7: expected UTF-8 text, found the byte 0xC0"); /* overlong */
}

/* Flow nesting is measured before libfyaml reads ahead (a megabyte of '['
 * took it a gigabyte). */
static void deep_nesting_is_refused(void **state) {
  (void)state;
  char text[2100];
  memset(text, '[', 2000);
  text[2000] = '\0';
  expect_error(text, MR_SCENE_ERR_SYNTAX, "t.yaml:1:65: expected at most 64 levels of nesting");
}

/* A key holding a newline and a terminal escape is shown escaped: the
 * error stays one line. */
static void control_bytes_in_errors_are_escaped(void **state) {
  (void)state;
  expect_error("physics:\n  effects: [gravity]\n  \"a\\nb\\e[31m\": 1\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:3:3: unknown key 'a\\nb\\x1b[31m' in physics; expected one of: effects, "
               "gravity, drag, ats, solver, contact, particles, control, constraints, groups, "
               "springs, strings, sine_springs, antigravity, triggered, floor, parts, "
               "string_correction, puppets");
}

/* DEL (0x7f) is a control byte too: a terminal may act on it, so an
 * error shows it as \x7f. */
static void delete_in_errors_is_escaped(void **state) {
  (void)state;
  expect_error("physics:\n  effects: [gravity]\n  \"a\\x7fb\": 1\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:3:3: unknown key 'a\\x7fb' in physics; expected one of: effects, "
               "gravity, drag, ats, solver, contact, particles, control, constraints, groups, "
               "springs, strings, sine_springs, antigravity, triggered, floor, parts, "
               "string_correction, puppets");
}

/* A long value is quoted in an error by its first 39 characters and
 * "...", so the message stays one readable line; "..." says that some
 * was left out, so a value of 39 characters is shown whole without it,
 * and one of 40 loses its last. */
static void a_long_value_is_shown_cut(void **state) {
  (void)state;
  static const char *const cases[][2] = {
    { "abcdefghijklmnopqrstuvwxyz0123456789ABCDEFGHIJ",
      "'abcdefghijklmnopqrstuvwxyz0123456789ABC...'" },
    { "abcdefghijklmnopqrstuvwxyz0123456789ABC", "'abcdefghijklmnopqrstuvwxyz0123456789ABC'" },
    { "abcdefghijklmnopqrstuvwxyz0123456789ABCD", "'abcdefghijklmnopqrstuvwxyz0123456789ABC...'" },
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char text[256], want[160];
    snprintf(text, sizeof text,
             "physics:\n  effects: [gravity]\n  particles:\n"
             "    - {name: a, position: [0, 1, 0], mass: %s}\n",
             cases[i][0]);
    snprintf(want, sizeof want, "t.yaml:4:44: expected a number for mass, got %s", cases[i][1]);
    expect_error(text, MR_SCENE_ERR_SCHEMA, want);
  }
}

static void part_friction_is_read_and_checked(void **state) {
  (void)state;
  const char *fx = "physics:\n"
                   "  effects: [gravity, constraints, self_collision]\n"
                   "  particles:\n"
                   "    - {name: a, position: [0, 1, 0], mass: 1}\n"
                   "    - {name: b, position: [1, 1, 0], mass: 2}\n"
                   "  parts:\n";
  char text[512];
  snprintf(text, sizeof text,
           "%s    - {particles: [a], restitution: 0.2, friction: 0.7}\n"
           "    - {particles: [b]}\n",
           fx);
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load_text("t.yaml", text, strlen(text), &s, &e), MR_SCENE_OK);
  assert_int_equal(s.n_parts, 2);
  assert_true(s.parts[0].def.friction == 0.7 && s.parts[0].def.restitution == 0.2);
  /* left out: the library's default */
  assert_true(s.parts[1].def.friction == mr_default_part_def().friction);
  mr_scene_free(&s);
  snprintf(text, sizeof text, "%s    - {particles: [a], friction: -0.1}\n", fx);
  mr_scene_status st = mr_scene_load_text("t.yaml", text, strlen(text), &s, &e);
  if (st == MR_SCENE_OK) mr_scene_free(&s);
  assert_int_equal(st, MR_SCENE_ERR_VALUE);
  assert_non_null(strstr(e.text, "t.yaml:7:"));
  assert_non_null(strstr(e.text, "friction"));
}

static void syntax_errors_name_the_place(void **state) {
  (void)state;
  expect_error("physics:\n  effects: [gravity\n  particles: []\n", MR_SCENE_ERR_SYNTAX,
               "t.yaml:4:1: expected valid YAML: flow sequence without a closing bracket");
  expect_error("physics:\n\t- 1\n", MR_SCENE_ERR_SYNTAX,
               "t.yaml:2:1: expected valid YAML: tab character may not be used as indentation");
}

static void not_yaml_is_refused(void **state) {
  (void)state;
  static const char binary[] = "\x7f"
                               "ELF\x02\x01\x01\x00\x00\x00";
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load_text("t.yaml", binary, sizeof binary - 1, &s, &e),
                   MR_SCENE_ERR_SYNTAX);
  assert_string_equal(e.text, "t.yaml:1:8: expected a YAML text file, found a NUL byte");
  expect_error("just some words\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:1:1: expected a mapping with a 'physics' section at the top level, got a "
               "scalar");
  expect_error("", MR_SCENE_ERR_SCHEMA,
               "t.yaml:1:1: expected a mapping with a 'physics' section, the file is empty");
}

static void missing_file_is_an_io_error(void **state) {
  (void)state;
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load("/nonexistent/dir/scene.yaml", &s, &e), MR_SCENE_ERR_IO);
  assert_string_equal(e.text, "/nonexistent/dir/scene.yaml: expected a readable scene file: "
                              "No such file or directory");
  assert_int_equal(e.line, 0);
}

static void file_errors_carry_the_path(void **state) {
  (void)state;
  const char text[] = BASE "    - {name: c, position: [2, 1, 0], mass: -3}\n";
  const char *path = tt_tmp_file("load_negative.yaml", text, sizeof text - 1);
  assert_non_null(path);
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load(path, &s, &e), MR_SCENE_ERR_VALUE);
  char expected[4200];
  snprintf(expected, sizeof expected,
           "%s:6:44: expected a positive mass in kg for particle 'c', got -3", path);
  assert_string_equal(e.text, expected);
  assert_int_equal(e.line, 6);
  assert_int_equal(e.column, 44);
}

static void expected_load_error_is_readable_from_a_broken_scene(void **state) {
  (void)state;
  const char text[] = "expect: {load_error: \"coincides with\"}\n" BASE
                      "    - {name: c, position: [1, 1, 0], mass: 1}\n";
  const char *path = tt_tmp_file("load_expect.yaml", text, sizeof text - 1);
  char out[64];
  assert_int_equal(mr_scene_expected_load_error(path, out, sizeof out), 0);
  assert_string_equal(out, "coincides with");
}

/* The glove mappings: named, listed axes only, the frame's start pose as
 * neutral, filter settings; without the section, none (the theater then
 * takes the default). Each reads into a definition the control library
 * accepts, and errors keep their place. */
static void glove_mappings_are_read(void **state) {
  (void)state;
  static const char *const head = "physics:\n"
                                  "  effects: [control]\n"
                                  "  particles: [{name: a, position: [0, 0, 0], mass: 1}]\n"
                                  "  control:\n"
                                  "    pose: {position: [0, 1.25, 0]}\n"
                                  "    points: [{name: bar, offset: [0, 0, 0]}]\n";
  char text[1024];
  snprintf(text, sizeof text,
           "%smapping:\n"
           "  - name: walk\n"
           "    filter: {min_cutoff: 2, beta: 0.3}\n"
           "    stuck_after: 1.5\n"
           "    axes:\n"
           "      move_z: {channel: 4, range: [-0.3, 0.3], invert: true, dead_zone: 0.05}\n"
           "      turn_y: {channel: 2, range: [-60, 60]}\n"
           "  - name: head-only\n",
           head);
  mr_scene s;
  mr_scene_error e;
  if (mr_scene_load_text("t.yaml", text, strlen(text), &s, &e) != MR_SCENE_OK)
    fail_msg("%s", e.text);
  assert_int_equal(s.n_mappings, 2);
  const mr_mapping_def *w = &s.mappings[0].def;
  assert_string_equal(w->name, "walk");
  assert_true(w->min_cutoff == 2 && w->beta == 0.3 && w->stuck_after == 1.5);
  assert_int_equal(w->axes[MR_DOF_MOVE_Z].channel, 4);
  assert_true(w->axes[MR_DOF_MOVE_Z].invert && w->axes[MR_DOF_MOVE_Z].dead_zone == 0.05);
  assert_true(w->axes[MR_DOF_MOVE_Z].low == -0.3 && w->axes[MR_DOF_MOVE_Z].high == 0.3);
  assert_int_equal(w->axes[MR_DOF_TURN_X].channel, -1); /* not listed: not driven */
  assert_true(w->neutral.position[1] == 1.25);
  /* A mapping that lists no axes keeps the paper's five. */
  assert_int_equal(s.mappings[1].def.axes[MR_DOF_MOVE_Y].channel, 3);
  const mr_mapping_def defs[2] = { s.mappings[0].def, s.mappings[1].def };
  mr_control *c = NULL;
  assert_int_equal(mr_control_create(defs, 2, &c, NULL, 0), MR_CONTROL_OK);
  mr_control_destroy(c);
  mr_scene_free(&s);

  /* The frame's turn limit is read in degrees per second, kept in radians;
   * its speed limit, not given, stays at the default. */
  snprintf(text, sizeof text, "%s    max_turn_rate: 90\n", head);
  if (mr_scene_load_text("t.yaml", text, strlen(text), &s, &e) != MR_SCENE_OK)
    fail_msg("%s", e.text);
  assert_true(fabs(s.frames[0].max_turn - 3.14159265358979323846 / 2) < 1e-15);
  assert_true(s.frames[0].max_speed == MR_SCENE_CONTROL_MAX_SPEED);
  assert_true(s.frames[0].max_accel == MR_SCENE_CONTROL_MAX_ACCEL);
  assert_true(fabs(s.frames[0].max_turn_accel -
                   MR_SCENE_CONTROL_MAX_TURN_ACCEL_DEG * 3.14159265358979323846 / 180) < 1e-12);
  mr_scene_free(&s);

  /* A glove's acceleration limits: m/s², and degrees per second squared
   * kept in radians; a negative one is refused at its place. */
  snprintf(text, sizeof text, "%s    max_accel: 4.5\n    max_turn_accel: 180\n", head);
  if (mr_scene_load_text("t.yaml", text, strlen(text), &s, &e) != MR_SCENE_OK)
    fail_msg("%s", e.text);
  assert_true(s.frames[0].max_accel == 4.5);
  assert_true(fabs(s.frames[0].max_turn_accel - 3.14159265358979323846) < 1e-15);
  mr_scene_free(&s);
  snprintf(text, sizeof text, "%s    max_turn_accel: -3\n", head);
  expect_error(text, MR_SCENE_ERR_VALUE,
               "t.yaml:7:21: expected a positive number for max_turn_accel, got -3");

  snprintf(text, sizeof text, "%smapping:\n  - name: m\n    axes:\n      fly: {channel: 1}\n",
           head);
  expect_error(text, MR_SCENE_ERR_SCHEMA,
               "t.yaml:10:7: unknown axis 'fly'; expected one of: turn_x, turn_y, turn_z, "
               "move_x, move_y, move_z");
  snprintf(text, sizeof text, "%smapping:\n  - name: m\n    axes:\n      turn_x: {channel: 5}\n",
           head);
  expect_error(text, MR_SCENE_ERR_VALUE, "t.yaml:10:25: expected channel between 0 and 4, got 5");
  expect_error("physics:\n  effects: [gravity]\n  particles: [{name: a, position: [0, 0, 0], "
               "mass: 1}]\nmapping: [{name: m}]\n",
               MR_SCENE_ERR_SCHEMA,
               "t.yaml:4:10: a glove mapping is declared but effect 'control' is not listed in "
               "physics.effects");
}

/* host/scenes/FORMAT.md, read once. */
static const char *format_md(void) {
  static char doc[131072];
  if (doc[0] != '\0') return doc;
  FILE *f = fopen(MR_SOURCE_DIR "/host/scenes/FORMAT.md", "r");
  assert_non_null(f);
  size_t n = fread(doc, 1, sizeof doc - 1, f);
  fclose(f);
  doc[n] = '\0';
  return doc;
}

/* Legal YAML, absurd numbers: each is refused with its place and its
 * range, before a run could try 1e300 steps. Empty values and explicit
 * tags keep their place too. */
static void absurd_values_empty_values_and_tags(void **state) {
  (void)state;
  static const char *const head = "physics:\n  effects: [gravity]\n";
  static const char *const one = "  particles: [{name: a, position: [0, 1, 0], mass: 1}]\n";
  static const struct {
    const char *before, *after, *error;
  } cases[] = {
    { "", "  ats: {dt_min: 1e-300}\n",
      "t.yaml:4:17: expected dt_min between 1e-09 and 1000 s, got 1e-300" },
    { "sim: {fps: 1e308}\n", "", "t.yaml:1:12: expected fps between 1 and 10000 Hz, got 1e+308" },
    { "sim: {duration: 1e308}\n", "",
      "t.yaml:1:17: expected duration between 1e-06 and 1e+06 s, got 1e+308" },
    { "sim: {duration: 0}\n", "", "t.yaml:1:17: expected a positive number for duration, got 0" },
    { "", "  drag: 1e12\n", "t.yaml:4:9: expected drag between 0 and 1e+06 N s/m, got 1e+12" },
  };
  char text[512];
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    snprintf(text, sizeof text, "%s%s%s%s", cases[i].before, head, one, cases[i].after);
    if (strstr(cases[i].after, "drag")) {
      snprintf(text, sizeof text, "physics:\n  effects: [gravity, drag]\n%s%s", one,
               cases[i].after);
    }
    expect_error(text, MR_SCENE_ERR_VALUE, cases[i].error);
  }
  expect_error("physics:\n  effects: [gravity]\n  particles:\n"
               "    - {name: a, position: [0, 1, 0], mass: }\n",
               MR_SCENE_ERR_SCHEMA, "t.yaml:4:42: expected a number for mass, got nothing");
  expect_error("physics:\n  effects: [gravity]\n  particles:\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:3:12: expected a sequence (- item or [a, b]) for physics.particles, got "
               "nothing");
  expect_error("physics:\n  effects:\n  particles: []\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:2:10: expected a sequence (- item or [a, b]) for physics.effects, got "
               "nothing");
  expect_error("physics:\n  effects: [gravity]\n  particles:\n"
               "    - {name: a, position: [0, 1, 0], mass: !!str 0.2}\n",
               MR_SCENE_ERR_SCHEMA, "t.yaml:4:50: expected a number for mass, got '0.2'");
  expect_error("physics:\n  effects: [gravity]\n  particles:\n"
               "    - {name: a, position: [0, 1, 0], mass: !kg 0.2}\n",
               MR_SCENE_ERR_SYNTAX,
               "t.yaml:4:48: unsupported tag '!kg'; expected no tag, or one of !!str, !!int, "
               "!!float, !!bool, !!null, !!map, !!seq");
  /* The core schema's own tags on the right kind of value are fine. */
  const char *ok = "physics:\n  effects: [gravity]\n  particles:\n"
                   "    - {name: !!str a, position: [0, 1, 0], mass: !!float 0.2}\n";
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load_text("t.yaml", ok, strlen(ok), &s, &e), MR_SCENE_OK);
  assert_true(s.particles[0].def.mass == 0.2);
  mr_scene_free(&s);
}

/* The name field holds MR_SCENE_NAME_MAX bytes with its NUL: the longest
 * name that fits loads whole, one character more is refused rather than
 * written past the end. */
static void names_at_the_length_bound(void **state) {
  (void)state;
  char name[MR_SCENE_NAME_MAX + 1], text[512];
  memset(name, 'n', sizeof name - 1);
  name[sizeof name - 1] = '\0';
  for (size_t len = MR_SCENE_NAME_MAX - 1; len <= MR_SCENE_NAME_MAX; len++) {
    snprintf(text, sizeof text,
             "physics:\n  effects: [gravity]\n"
             "  particles: [{name: %.*s, position: [0, 1, 0], mass: 1}]\n",
             (int)len, name);
    if (len == MR_SCENE_NAME_MAX) {
      expect_error(text, MR_SCENE_ERR_VALUE,
                   "t.yaml:3:22: expected a name of at most 47 characters for particle name");
      break;
    }
    mr_scene s;
    mr_scene_error e;
    assert_int_equal(mr_scene_load_text("t.yaml", text, strlen(text), &s, &e), MR_SCENE_OK);
    assert_int_equal(strlen(s.particles[0].name), len);
    mr_scene_free(&s);
  }
}

/* A fourth coordinate is a typo to show, not a number to drop. */
static void a_point_of_four_numbers_is_refused(void **state) {
  (void)state;
  expect_error("physics:\n  effects: [gravity]\n"
               "  particles: [{name: a, position: [0, 1, 0, 5], mass: 1}]\n",
               MR_SCENE_ERR_SCHEMA,
               "t.yaml:3:35: expected [x, y, z] (three numbers) for position, got a sequence of "
               "4 items");
}

/* Two keyframes at one time would ask the frame to jump between poses in
 * no time. */
static void keyframes_at_the_same_time_are_refused(void **state) {
  (void)state;
  expect_error(KEYFRAMED "        - {t: 1, position: [0, 2, 0]}\n"
                         "        - {t: 1, position: [2, 2, 0]}\n",
               MR_SCENE_ERR_VALUE,
               "t.yaml:10:15: expected keyframe times in increasing order, got 1 after 1");
}

/* A count of resets below zero can never be met, and one too large for a
 * long is not a number the check could compare. */
static void resets_out_of_range_are_refused(void **state) {
  (void)state;
  expect_error(BASE "expect: {resets: {min: -1}}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:24: expected min >= 0");
  expect_error(BASE "expect: {resets: {max: -1}}\n", MR_SCENE_ERR_VALUE,
               "t.yaml:6:24: expected max >= 0");
  expect_error(BASE "expect: {resets: 99999999999999999999}\n", MR_SCENE_ERR_SCHEMA,
               "t.yaml:6:18: expected an integer for resets, got '99999999999999999999'");
}

/* An empty value has no place of its own and is shown where its key
 * ends; a quoted key ends after its closing quote. */
static void an_empty_value_after_a_quoted_key_is_placed_at_its_colon(void **state) {
  (void)state;
  expect_error("physics:\n  effects: [gravity]\n  particles:\n"
               "    - {name: a, position: [0, 1, 0], \"mass\": }\n",
               MR_SCENE_ERR_SCHEMA, "t.yaml:4:44: expected a number for mass, got nothing");
}

/* FORMAT.md's table of ranges is the loader's, row for row. */
static void format_md_lists_every_range(void **state) {
  (void)state;
  const char *doc = format_md();
  int rows = 0;
  for (const mr_scene_range *g; (g = mr_scene_range_at(rows)) != NULL; rows++) {
    char row[160];
    snprintf(row, sizeof row, "| `%s` | %g | %g | %s |", g->key, g->lo, g->hi, g->unit);
    if (strstr(doc, row) == NULL) fail_msg("FORMAT.md has no row %s", row);
  }
  assert_true(rows > 50);
}

/* The commented example in FORMAT.md is a scene that loads. */
static void format_md_example_loads(void **state) {
  (void)state;
  const char *doc = format_md();
  char *start = strstr(doc, "```yaml\n");
  assert_non_null(start);
  start += strlen("```yaml\n");
  char *end = strstr(start, "```");
  assert_non_null(end);
  mr_scene s;
  mr_scene_error e;
  mr_scene_status st = mr_scene_load_text("FORMAT.md", start, (size_t)(end - start), &s, &e);
  if (st != MR_SCENE_OK) fail_msg("%s", e.text);
  assert_int_equal(s.n_particles, 3);
  assert_int_equal(s.n_forces, 1);
  assert_int_equal(s.forces[0].kind, MR_EFFECT_STRINGS);
  assert_true(s.expect.present);
  mr_scene_free(&s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(good_scene_loads_with_paper_defaults),
    cmocka_unit_test(unframed_load_leaves_only_the_framing_out),
    cmocka_unit_test(settings_and_anchors_are_read),
    cmocka_unit_test(keyframes_ease_and_hold),
    cmocka_unit_test(oscillation_follows_the_sine),
    cmocka_unit_test(unknown_top_level_key),
    cmocka_unit_test(theater_section_is_reserved),
    cmocka_unit_test(unknown_particle_key),
    cmocka_unit_test(nan_is_refused),
    cmocka_unit_test(negative_and_zero_mass_are_refused),
    cmocka_unit_test(coincident_particles_are_refused),
    cmocka_unit_test(zero_length_constraints_are_refused),
    cmocka_unit_test(undeclared_effect_is_refused),
    cmocka_unit_test(unknown_names_and_shapes),
    cmocka_unit_test(duplicate_keys_are_refused),
    cmocka_unit_test(unknown_alias_is_refused),
    cmocka_unit_test(every_physics_force_kind_has_a_scene_section),
    cmocka_unit_test(integrator_and_method_come_from_the_libraries_tables),
    cmocka_unit_test(degenerate_groups_are_refused),
    cmocka_unit_test(a_group_of_64_loads_and_65_is_refused),
    cmocka_unit_test(step_settings_where_they_meet),
    cmocka_unit_test(max_steps_of_zero_is_refused),
    cmocka_unit_test(a_particle_resting_on_the_floor_loads),
    cmocka_unit_test(part_friction_is_read_and_checked),
    cmocka_unit_test(malformed_utf8_is_refused_before_the_parser),
    cmocka_unit_test(deep_nesting_is_refused),
    cmocka_unit_test(control_bytes_in_errors_are_escaped),
    cmocka_unit_test(delete_in_errors_is_escaped),
    cmocka_unit_test(a_long_value_is_shown_cut),
    cmocka_unit_test(syntax_errors_name_the_place),
    cmocka_unit_test(not_yaml_is_refused),
    cmocka_unit_test(missing_file_is_an_io_error),
    cmocka_unit_test(file_errors_carry_the_path),
    cmocka_unit_test(expected_load_error_is_readable_from_a_broken_scene),
    cmocka_unit_test(format_md_example_loads),
    cmocka_unit_test(absurd_values_empty_values_and_tags),
    cmocka_unit_test(format_md_lists_every_range),
    cmocka_unit_test(glove_mappings_are_read),
    cmocka_unit_test(names_at_the_length_bound),
    cmocka_unit_test(a_point_of_four_numbers_is_refused),
    cmocka_unit_test(keyframes_at_the_same_time_are_refused),
    cmocka_unit_test(resets_out_of_range_are_refused),
    cmocka_unit_test(an_empty_value_after_a_quoted_key_is_placed_at_its_colon),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* A scene built into a physics world: ids, effects, the control frame's
 * pose, pins. */
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
#include "mr_scene_world.h"
#include "mr_sim.h"

static void load(const char *text, mr_scene *s) {
  mr_scene_error e;
  mr_scene_status st = mr_scene_load_text("t.yaml", text, strlen(text), s, &e);
  if (st != MR_SCENE_OK) fail_msg("%s", e.text);
}

/* Every word a scene file may list in physics.effects declares its own
 * physics bit: the physics' name table, and the file's words for two. */
static void every_scene_effect_maps_to_its_own_physics_bit(void **state) {
  (void)state;
  static const char *const words[] = {
    "gravity",     "drag",           "springs",          "strings",
    "antigravity", "triggered",      "sine_springs",     "constraints",
    "floor",       "self_collision", "puppet_collision", "string_correction",
    "control"
  };
  uint32_t seen = 0;
  for (size_t i = 0; i < sizeof words / sizeof words[0]; i++) {
    char text[256];
    snprintf(text, sizeof text,
             "physics:\n  effects: [%s]\n%s  particles: [{name: a, position: [0, 1, 0], "
             "mass: 1}]\n",
             words[i], strcmp(words[i], "drag") == 0 ? "  drag: 0.1\n" : "");
    mr_scene s;
    load(text, &s);
    uint32_t b = s.world.effects;
    assert_int_equal(b & (b - 1), 0); /* one bit */
    assert_int_not_equal(b, 0);
    assert_int_equal(seen & b, 0); /* not shared */
    seen |= b;
    mr_scene_free(&s);
  }
  assert_int_equal(seen, MR_EFFECT_ALL);
  const char *text = "physics:\n  effects: [drag, floor, control]\n  drag: 0.1\n"
                     "  particles: [{name: a, position: [0, 1, 0], mass: 1}]\n";
  mr_scene s;
  load(text, &s);
  assert_int_equal(s.world.effects, MR_EFFECT_DRAG | MR_EFFECT_PLANES | MR_EFFECT_FRAMES);
  mr_scene_free(&s);
  load("physics:\n  effects: []\n  particles: [{name: a, position: [0, 1, 0], mass: 1}]\n", &s);
  assert_int_equal(s.world.effects, 0);
  mr_scene_free(&s);
}

/* The control frame's pose reaches the physics as the file means it:
 * rotations in degrees, x applied first, then y, then z, about the
 * frame's origin, then moved to its position. Expected places are worked
 * out by hand, not by the code under test, so a doubled angle, radians,
 * a swapped order or a lost axis each move a point. */
static void control_points_sit_where_the_file_means(void **state) {
  (void)state;
  static const struct {
    const char *rotation;
    double off[3], want[3];
  } cases[] = {
    /* y by 90°: (x, y, z) -> (z, y, −x) */
    { "[0, 90, 0]", { 0.3, 0.1, -0.2 }, { 0.5 - 0.2, 2.1, -1.0 - 0.3 } },
    /* x by 90° then z by 90°: (0, 1, 0) -> (0, 0, 1) -> (0, 0, 1) */
    { "[90, 0, 90]", { 0, 1, 0 }, { 0.5, 2.0, 0.0 } },
    /* x by 90° then z by 90°: (1, 0, 0) -> (1, 0, 0) -> (0, 1, 0) */
    { "[90, 0, 90]", { 1, 0, 0 }, { 0.5, 3.0, -1.0 } },
    /* z by 30°: (1, 0, 0) -> (cos 30°, sin 30°, 0) */
    { "[0, 0, 30]", { 1, 0, 0 }, { 0.5 + 0.86602540378443865, 2.5, -1.0 } },
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    char text[512];
    snprintf(text, sizeof text,
             "physics:\n"
             "  effects: [control]\n"
             "  particles: [{name: a, position: [0, 0, 0], mass: 1}]\n"
             "  control:\n"
             "    pose: {position: [0.5, 2, -1], rotation: %s}\n"
             "    points: [{name: p, offset: [%g, %g, %g]}]\n",
             cases[c].rotation, cases[c].off[0], cases[c].off[1], cases[c].off[2]);
    mr_scene s;
    load(text, &s);
    mr_scene_world sw;
    mr_scene_error e;
    assert_int_equal(mr_scene_build(&s, &sw, &e), MR_SCENE_OK);
    double got[3];
    assert_int_equal(mr_world_particle_state(sw.world, sw.control_ids[0], got, NULL), MR_OK);
    for (int k = 0; k < 3; k++)
      if (!(fabs(got[k] - cases[c].want[k]) < 1e-12))
        fail_msg("rotation %s, offset (%g, %g, %g): point at (%.6f, %.6f, %.6f), expected "
                 "(%.6f, %.6f, %.6f)",
                 cases[c].rotation, cases[c].off[0], cases[c].off[1], cases[c].off[2], got[0],
                 got[1], got[2], cases[c].want[0], cases[c].want[1], cases[c].want[2]);
    mr_scene_world_free(&sw);
    mr_scene_free(&s);
  }
}

/* The start positions the stage takes its rest frames from: the scene's
 * particles where the file puts them, then its control points where the
 * frame's start pose puts their offsets (y by 90°: (x, y, z) -> (z, y, -x)). */
static void start_positions_are_particles_then_control_points(void **state) {
  (void)state;
  mr_scene s;
  load("physics:\n"
       "  effects: [control]\n"
       "  particles: [{name: a, position: [1, 2, 3], mass: 1},\n"
       "              {name: b, position: [-1, 0.5, 0], mass: 1}]\n"
       "  control:\n"
       "    pose: {position: [0.5, 2, -1], rotation: [0, 90, 0]}\n"
       "    points: [{name: p, offset: [0.3, 0.1, -0.2]}]\n",
       &s);
  size_t n = 0;
  mr_scene_error e;
  double *xyz = mr_scene_start_positions(&s, &n, &e);
  assert_non_null(xyz);
  assert_int_equal(n, 3);
  const double want[9] = { 1, 2, 3, -1, 0.5, 0, 0.5 - 0.2, 2.1, -1.0 - 0.3 };
  for (int k = 0; k < 9; k++)
    if (!(fabs(xyz[k] - want[k]) < 1e-12))
      fail_msg("xyz[%d] = %.9f, want %.9f", k, xyz[k], want[k]);
  free(xyz);
  mr_scene_free(&s);
}

/* A control point on a frame swaying 0.2 m in x at f Hz, from phase (°). */
static void load_oscillation(double f, double phase, mr_scene *s) {
  char text[512];
  snprintf(text, sizeof text,
           "physics:\n"
           "  effects: [control]\n"
           "  particles: [{name: a, position: [0, 0, 0], mass: 1}]\n"
           "  control:\n"
           "    pose: {position: [0, 1, 0]}\n"
           "    points: [{name: p, offset: [0, 0, 0]}]\n"
           "    track:\n"
           "      oscillate: {amplitude: [0.2, 0, 0], frequency: %g, phase: %g}\n",
           f, phase);
  load(text, s);
}

/* A track's rotation reaches the physics as the frame moves: keyframes
 * turning the frame 90° about y in 1 s, run through mr_scene_run, leave
 * the point where the turn puts it; an oscillation's phase is read in
 * degrees (90° starts it at its crest). */
static void track_rotation_and_phase_reach_the_world(void **state) {
  (void)state;
  const char *text = "physics:\n"
                     "  effects: [control]\n"
                     "  particles: [{name: a, position: [0, 0, 0], mass: 1}]\n"
                     "  control:\n"
                     "    pose: {position: [0, 1, 0]}\n"
                     "    points: [{name: p, offset: [1, 0, 0]}]\n"
                     "    track:\n"
                     "      keyframes:\n"
                     "        - {t: 0, rotation: [0, 0, 0]}\n"
                     "        - {t: 1, rotation: [0, 90, 0]}\n";
  mr_scene s;
  load(text, &s);
  mr_scene_world sw;
  mr_scene_error e;
  assert_int_equal(mr_scene_build(&s, &sw, &e), MR_SCENE_OK);
  mr_pose at;
  mr_scene_frame_pose_at(&s, 0, 1.0, &at);
  assert_int_equal(mr_world_set_frame_target(sw.world, sw.frames[0], &at, 1.0), MR_OK);
  assert_true(mr_world_step_to(sw.world, 1.0, NULL) >= 0);
  double got[3];
  mr_world_particle_state(sw.world, sw.control_ids[0], got, NULL);
  /* (1, 0, 0) turned 90° about y is (0, 0, −1). */
  assert_true(fabs(got[0]) < 1e-12 && fabs(got[1] - 1.0) < 1e-12 && fabs(got[2] + 1.0) < 1e-12);
  mr_scene_world_free(&sw);
  mr_scene_free(&s);

  load_oscillation(1, 90, &s);
  mr_pose p;
  mr_scene_frame_pose_at(&s, 0, 1e-9, &p);
  assert_true(fabs(p.position[0] - 0.2) < 1e-9); /* sin(0 + 90°) = 1 */
  mr_scene_frame_pose_at(&s, 0, 0.25, &p);
  assert_true(fabs(p.position[0]) < 1e-12); /* sin(90° + 90°) = 0 */
  mr_scene_frame_pose_at(&s, 0, 0.5, &p);
  assert_true(fabs(p.position[0] + 0.2) < 1e-12);
  mr_scene_free(&s);
}

/* A show left running for days: an oscillation at 8 Hz, 8 days in, is past
 * the 2²³ rad that the sine takes (a phase of 36 090°, 90° plus a hundred
 * turns, rides along; the reader bounds a phase to 10⁶°, 17 453 rad). The
 * track is taken in whole cycles first, so the pose is the one a cycle
 * after the start gives, and finite. */
static void oscillation_is_the_same_after_days_and_whole_turns_of_phase(void **state) {
  (void)state;
  mr_scene s;
  load_oscillation(8, 36090, &s);
  mr_pose near, far;
  double later = 8.0 * 86400.0; /* 8 days: 5.5 million cycles, 3.5e7 rad */
  for (int k = 1; k < 8; k++) {
    double dt = k / 64.0;
    mr_scene_frame_pose_at(&s, 0, dt, &near);
    mr_scene_frame_pose_at(&s, 0, later + dt, &far);
    assert_true(isfinite(far.position[0]));
    assert_true(fabs(far.position[0] - near.position[0]) < 1e-9);
  }
  mr_scene_frame_pose_at(&s, 0, later + 1.0 / 32.0, &far); /* a quarter cycle: sin(180°) */
  assert_true(fabs(far.position[0]) < 1e-9);
  mr_scene_free(&s);
}

/* Every setting a scene gives reaches the world it builds, each in its
 * own field: distinct values, read back from the world, not the parse. */
static void settings_reach_the_built_world(void **state) {
  (void)state;
  const char *text = "physics:\n"
                     "  effects: [gravity, drag, constraints, floor, string_correction]\n"
                     "  gravity: [0.1, -9.2, 0.3]\n"
                     "  drag: 0.37\n"
                     "  ats: {dt_initial: 0.021, dt_min: 0.011, dt_max: 0.047, "
                     "threshold_min: 0.00021, threshold_max: 0.0093, divergence: 0.41, "
                     "deviation_length: 0.013, max_steps: 77, error_length: 1.7, "
                     "error_speed: 2.9, max_speed: 123, dt_floor: 0.0003}\n"
                     "  solver: {integrator: midpoint, method: cg, ks: 31, kd: 17, "
                     "tolerance: 1e-9, max_iterations: 321}\n"
                     "  contact: {slop: 0.00031, rest_speed: 0.071}\n"
                     "  string_correction: {max_stretch: 0.023, iterations: 13}\n"
                     "  particles: [{name: a, position: [0, 1, 0], mass: 1}]\n"
                     "  floor: {height: 0}\n";
  mr_scene s;
  load(text, &s);
  mr_scene_world sw;
  mr_scene_error e;
  assert_int_equal(mr_scene_build(&s, &sw, &e), MR_SCENE_OK);
  mr_world_def d;
  assert_int_equal(mr_world_get_def(sw.world, &d), MR_OK);
  assert_true(d.gravity[0] == 0.1 && d.gravity[1] == -9.2 && d.gravity[2] == 0.3);
  assert_true(d.drag == 0.37);
  assert_true(d.dt_initial == 0.021 && d.dt_min == 0.011 && d.dt_max == 0.047);
  assert_true(d.deviation_low == 0.00021 && d.deviation_high == 0.0093);
  assert_true(d.divergence_bound == 0.41 && d.deviation_length == 0.013);
  assert_int_equal(d.max_steps_per_call, 77);
  assert_true(d.error_length == 1.7 && d.error_speed == 2.9 && d.max_speed == 123);
  assert_true(d.dt_floor == 0.0003);
  assert_int_equal(d.integrator, MR_INTEGRATOR_MIDPOINT);
  assert_int_equal(d.solver, MR_SOLVE_CG);
  assert_true(d.ks == 31 && d.kd == 17);
  assert_true(d.solver_tolerance == 1e-9);
  assert_int_equal(d.solver_max_iterations, 321);
  assert_true(d.contact_slop == 0.00031 && d.rest_speed == 0.071);
  assert_true(d.string_max_stretch == 0.023);
  assert_int_equal(d.string_correction_iterations, 13);
  mr_scene_world_free(&sw);
  mr_scene_free(&s);
}

/* A rigid group whose fourth member lies h above the plane of the first
 * three: the loader and the physics measure flatness the same way, so
 * for every h the file loads exactly when the world accepts the group, and
 * a refusal names the particles and the line. */
static void loader_and_physics_agree_on_flat_groups(void **state) {
  (void)state;
  /* d sits far from a, so a measure taken from d reads the same height as
   * 40 times flatter than one taken from a: they disagree from 0.7 to 29 mm. */
  const double heights[] = { 1e-4, 5e-4, 6e-4, 8e-4, 1e-3, 5e-3, 1e-2, 5e-2 };
  int refused = 0, accepted = 0;
  for (size_t i = 0; i < sizeof heights / sizeof heights[0]; i++) {
    char text[512];
    snprintf(text, sizeof text,
             "physics:\n"
             "  effects: [constraints]\n"
             "  particles:\n"
             "    - {name: a, position: [0, 1, 0], mass: 1}\n"
             "    - {name: b, position: [0.1, 1, 0], mass: 1}\n"
             "    - {name: c, position: [0, 1, 0.1], mass: 1}\n"
             "    - {name: d, position: [0.5, %.9g, 0.5], mass: 1}\n"
             "  groups: [{name: g, particles: [a, b, c, d]}]\n",
             1.0 + heights[i]);
    /* The world's own verdict on the same points. */
    mr_world_def def = mr_default_world_def();
    def.effects = MR_EFFECT_CONSTRAINTS;
    mr_world *w = NULL;
    assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
    const double pts[4][3] = {
      { 0, 1, 0 }, { 0.1, 1, 0 }, { 0, 1, 0.1 }, { 0.5, 1 + heights[i], 0.5 }
    };
    int ids[4];
    for (int k = 0; k < 4; k++) {
      mr_particle_def p = mr_default_particle_def();
      for (int j = 0; j < 3; j++) p.position[j] = pts[k][j];
      assert_int_equal(mr_world_add_particle(w, &p, &ids[k]), MR_OK);
    }
    mr_rigid_group_def g = mr_default_rigid_group_def();
    g.particles = ids;
    g.count = 4;
    int world_ok = mr_world_add_rigid_group(w, &g, NULL) == MR_OK;
    mr_world_destroy(w);

    mr_scene s;
    mr_scene_error e;
    int loads = mr_scene_load_text("t.yaml", text, strlen(text), &s, &e) == MR_SCENE_OK;
    if (loads) {
      mr_scene_world sw;
      assert_int_equal(mr_scene_build(&s, &sw, &e), MR_SCENE_OK);
      mr_scene_world_free(&sw);
      mr_scene_free(&s);
    } else {
      assert_string_equal(e.text, "t.yaml:8:43: group 'g': 'a', 'b', 'c' and 'd' are coplanar; a "
                                  "group starts with four members in general position (§5.1)");
    }
    assert_int_equal(loads, world_ok);
    refused += !loads;
    accepted += loads;
  }
  assert_true(refused > 0 && accepted > 0); /* the sweep crosses the line */
}

static void pinned_particle_stays_and_free_one_falls(void **state) {
  (void)state;
  const char *text = "physics:\n"
                     "  effects: [gravity, constraints]\n"
                     "  particles:\n"
                     "    - {name: a, position: [0, 2, 0], mass: 1, pinned: true}\n"
                     "    - {name: b, position: [0.5, 2, 0], mass: 1}\n"
                     "    - {name: c, position: [3, 2, 0], mass: 1}\n"
                     "  constraints: [{between: [a, b]}]\n";
  mr_scene s;
  load(text, &s);
  mr_scene_world sw;
  mr_scene_error e;
  assert_int_equal(mr_scene_build(&s, &sw, &e), MR_SCENE_OK);
  assert_int_equal(mr_world_particle_count(sw.world), 3);
  assert_int_equal(mr_world_constraint_rows(sw.world), 4); /* pin (3) + distance (1) */
  assert_true(mr_world_step_to(sw.world, 1.0, NULL) >= 0);
  double pa[3], pb[3], pc[3];
  mr_world_particle_state(sw.world, sw.particle_ids[0], pa, NULL);
  mr_world_particle_state(sw.world, sw.particle_ids[1], pb, NULL);
  mr_world_particle_state(sw.world, sw.particle_ids[2], pc, NULL);
  assert_true(fabs(pa[1] - 2.0) < 1e-6 && fabs(pa[0]) < 1e-6);
  /* b swings on its 0.5 m link; c falls freely: 2 - g/2 after 1 s */
  double d = sqrt((pb[0] - pa[0]) * (pb[0] - pa[0]) + (pb[1] - pa[1]) * (pb[1] - pa[1]));
  assert_true(fabs(d - 0.5) < 0.005);
  assert_true(fabs(pc[1] - (2.0 - 9.81 / 2)) < 1e-6);
  mr_scene_world_free(&sw);
  mr_scene_free(&s);
}

typedef struct tally {
  uint64_t accepted;
  double dt_sum;
  double last_t;
  int ordered;
} tally;

static void count_step(void *user, const mr_sim_step *step) {
  tally *t = user;
  t->accepted += (uint64_t)step->accepted;
  t->dt_sum += step->dt * step->accepted;
  if (!(step->t > t->last_t)) t->ordered = 0;
  t->last_t = step->t;
}

static void run_reports_every_step_to_the_callback(void **state) {
  (void)state;
  const char *text = "sim: {duration: 2}\n"
                     "physics:\n"
                     "  effects: [gravity, constraints]\n"
                     "  particles:\n"
                     "    - {name: a, position: [0, 2, 0], mass: 1, pinned: true}\n"
                     "    - {name: b, position: [0.5, 2, 0], mass: 1}\n"
                     "  constraints: [{between: [a, b]}]\n";
  mr_scene s;
  load(text, &s);
  tally t = { 0, 0, 0, 1 };
  mr_sim_def o = mr_default_sim_def();
  o.on_step = count_step;
  o.user = &t;
  mr_sim_result r;
  mr_scene_error e;
  assert_int_equal(mr_sim_run(&s, &o, &r, &e), MR_SCENE_OK);
  assert_true(r.sim_time == 2.0);
  assert_true(r.finite);
  assert_int_equal(t.accepted, r.steps);
  assert_true(t.ordered);
  assert_true(t.last_t == 2.0);
  assert_true(r.dt_max <= 0.05 + 1e-12);
  assert_true(fabs(r.dt_mean - t.dt_sum / (double)t.accepted) < 1e-12);
  assert_int_equal(r.resets, 0);
  mr_scene_free(&s);
}

/* A scene that sets nothing runs with the paper's settings (§7): the
 * loader starts from the physics' default world and changes nothing. */
static void unset_settings_are_the_papers(void **state) {
  (void)state;
  const char *text = "physics:\n"
                     "  effects: [gravity]\n"
                     "  particles: [{name: a, position: [0, 1, 0], mass: 1}]\n";
  mr_scene s;
  load(text, &s);
  mr_world_def d = mr_default_world_def();
  assert_true(s.world.dt_min == d.dt_min && s.world.dt_max == d.dt_max);
  assert_true(s.world.deviation_low == d.deviation_low &&
              s.world.deviation_high == d.deviation_high);
  assert_int_equal(s.world.integrator, d.integrator);
  assert_true(d.dt_min == 0.01 && d.dt_max == 0.05);
  assert_true(d.deviation_low == 1e-4 && d.deviation_high == 1e-2);
  assert_int_equal(d.integrator, MR_INTEGRATOR_RK4);
  /* The run's steps stay inside those bounds. */
  mr_sim_def o = mr_default_sim_def();
  o.duration = 1.0;
  mr_sim_result r;
  mr_scene_error e;
  assert_int_equal(mr_sim_run(&s, &o, &r, &e), MR_SCENE_OK);
  assert_true(r.dt_max <= 0.05 + 1e-12);
  assert_true(r.steps >= 20); /* 1 s at no more than 0.05 s a step */
  mr_scene_free(&s);
}

typedef struct frames {
  double fps, last_t;
  int crossed;
  uint64_t rows;
} frames;

static void check_frame_landing(void *user, const mr_sim_step *step) {
  frames *f = user;
  /* No frame time k/fps lies strictly inside a step. */
  double k_prev = floor(f->last_t * f->fps + 1e-9);
  double k_now = ceil(step->t * f->fps - 1e-9);
  if (k_now - k_prev > 1) f->crossed = 1;
  f->last_t = step->t;
  f->rows++;
}

/* With sim.fps the steps land on every frame time, as in the theater: the
 * run is paced by the theater's scheduler, which counts the frames (0 to
 * 3 s at 30 fps: 91). */
static void steps_land_on_frame_times_with_fps(void **state) {
  (void)state;
  const char *text = "sim: {duration: 3, fps: 30}\n"
                     "physics:\n"
                     "  effects: [gravity, constraints, strings, control]\n"
                     "  particles:\n"
                     "    - {name: a, position: [0, 1, 0], mass: 0.5}\n"
                     "    - {name: b, position: [0.2, 1, 0], mass: 0.5}\n"
                     "  constraints: [{between: [a, b]}]\n"
                     "  control:\n"
                     "    pose: {position: [0, 1.5, 0]}\n"
                     "    points: [{name: bar, offset: [0, 0, 0]}]\n"
                     "    track: {oscillate: {amplitude: [0.1, 0, 0], frequency: 1}}\n"
                     "  strings: [{from: bar, to: a, stiffness: 50, damping: 1}]\n";
  mr_scene s;
  load(text, &s);
  frames f = { 30.0, 0.0, 0, 0 };
  mr_sim_def o = mr_default_sim_def();
  o.on_step = check_frame_landing;
  o.user = &f;
  mr_sim_result r;
  mr_scene_error e;
  assert_int_equal(mr_sim_run(&s, &o, &r, &e), MR_SCENE_OK);
  assert_false(f.crossed);
  assert_true(f.rows >= 90); /* at least one step per frame */
  assert_true(r.dt_max <= 1.0 / 30.0 + 1e-12);
  assert_true(r.pass_calls[MR_PASS_STRINGS] > 0);
  assert_int_equal(r.frames, 91);
  mr_scene_free(&s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(every_scene_effect_maps_to_its_own_physics_bit),
    cmocka_unit_test(control_points_sit_where_the_file_means),
    cmocka_unit_test(start_positions_are_particles_then_control_points),
    cmocka_unit_test(track_rotation_and_phase_reach_the_world),
    cmocka_unit_test(oscillation_is_the_same_after_days_and_whole_turns_of_phase),
    cmocka_unit_test(settings_reach_the_built_world),
    cmocka_unit_test(loader_and_physics_agree_on_flat_groups),
    cmocka_unit_test(pinned_particle_stays_and_free_one_falls),
    cmocka_unit_test(run_reports_every_step_to_the_callback),
    cmocka_unit_test(steps_land_on_frame_times_with_fps),
    cmocka_unit_test(unset_settings_are_the_papers),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

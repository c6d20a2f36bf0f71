/* `marionette sim` as a user meets it: a real process, its exit status and
 * what it prints. The program's path comes as the first argument. */
#include <inttypes.h>
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
#include "proc.h"

static char *marionette;

#define SCENES MR_SOURCE_DIR "/host/scenes"

/* Runs marionette with the arguments up to a NULL. */
static void run(tt_output *p, ...) {
  char *argv[16] = { marionette };
  int n = 1;
  va_list ap;
  va_start(ap, p);
  const char *a;
  while ((a = va_arg(ap, const char *)) != NULL && n < 15) argv[n++] = (char *)a;
  va_end(ap);
  argv[n] = NULL;
  assert_int_equal(tt_capture(argv, p), 0);
}

static uint64_t field_u64(const char *text, const char *key) {
  char v[64];
  assert_int_equal(tt_field(text, key, v, sizeof v), 0);
  return strtoull(v, NULL, 10);
}

static void help_lists_subcommands_and_flags(void **state) {
  (void)state;
  tt_output p;
  run(&p, "--help", NULL);
  assert_int_equal(p.status, 0);
  assert_non_null(strstr(p.out, "  sim SCENE "));
  assert_non_null(strstr(p.out, "  export "));
  tt_output_free(&p);
  run(&p, "sim", "--help", NULL);
  assert_int_equal(p.status, 0);
  const char *flags[] = { "--time SECONDS", "--csv FILE", "--check",       "--quiet",
                          "--help",         "--fps HZ",   "--present MODE" };
  for (size_t i = 0; i < sizeof flags / sizeof flags[0]; i++)
    assert_non_null(strstr(p.out, flags[i]));
  tt_output_free(&p);
  run(&p, "dance", NULL);
  assert_int_equal(p.status, 2);
  assert_string_equal(p.err,
                      "marionette: unknown command 'dance'; expected one of: sim, run, render, "
                      "watch, export, take, list-ports, calibrate (see --help)\n");
  tt_output_free(&p);
}

static void load_errors_are_one_line_with_the_place(void **state) {
  (void)state;
  const char text[] = "physics:\n"
                      "  effects: [gravity]\n"
                      "  particles:\n"
                      "    - {name: a, position: [0, 1, 0], mass: -2}\n";
  const char *path = tt_tmp_file("sim_negative.yaml", text, sizeof text - 1);
  char expected[4300];
  snprintf(expected, sizeof expected,
           "marionette: %s:4:44: expected a positive mass in kg for particle 'a', got -2\n", path);
  tt_output p;
  run(&p, "sim", path, NULL);
  assert_int_equal(p.status, 1);
  assert_string_equal(p.err, expected);
  assert_string_equal(p.out, "");
  tt_output_free(&p);

  run(&p, "sim", "/nonexistent/scene.yaml", NULL);
  assert_int_equal(p.status, 1);
  assert_string_equal(p.err, "marionette: /nonexistent/scene.yaml: expected a readable scene "
                             "file: No such file or directory\n");
  tt_output_free(&p);

  const char binary[] = "\x7f"
                        "ELF\x02\x01\x01";
  path = tt_tmp_file("sim_binary.yaml", binary, sizeof binary); /* with its NUL */
  snprintf(expected, sizeof expected,
           "marionette: %s:1:8: expected a YAML text file, found a NUL byte\n", path);
  run(&p, "sim", path, NULL);
  assert_int_equal(p.status, 1);
  assert_string_equal(p.err, expected);
  tt_output_free(&p);
}

static void bad_usage_exits_2(void **state) {
  (void)state;
  tt_output p;
  run(&p, "sim", NULL);
  assert_int_equal(p.status, 2);
  tt_output_free(&p);
  run(&p, "sim", "--time", "-3", SCENES "/puppet.yaml", NULL);
  assert_int_equal(p.status, 2);
  assert_string_equal(p.err, "marionette: sim: --time expects a positive number of seconds\n");
  tt_output_free(&p);
  run(&p, "sim", "--bogus", SCENES "/puppet.yaml", NULL);
  assert_int_equal(p.status, 2);
  tt_output_free(&p);
}

/* DESIGN.md, Determinism: the same scene twice gives the same state, bit for bit,
 * and the program prints the hash the library computes in-process. */
static void same_scene_same_state_hash(void **state) {
  (void)state;
  const char *scene_path = SCENES "/puppet.yaml";
  tt_output a, b;
  run(&a, "sim", "--time", "4", scene_path, NULL);
  run(&b, "sim", "--time", "4", scene_path, NULL);
  assert_int_equal(a.status, 0);
  assert_int_equal(b.status, 0);
  char ha[64], hb[64];
  assert_int_equal(tt_field(a.out, "state hash", ha, sizeof ha), 0);
  assert_int_equal(tt_field(b.out, "state hash", hb, sizeof hb), 0);
  assert_int_equal(strlen(ha), 16);
  assert_string_equal(ha, hb);
  assert_int_equal(field_u64(a.out, "steps"), field_u64(b.out, "steps"));

  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load(scene_path, &s, &e), MR_SCENE_OK);
  mr_sim_def opts = mr_default_sim_def();
  opts.duration = 4.0;
  mr_sim_result r;
  assert_int_equal(mr_sim_run(&s, &opts, &r, &e), MR_SCENE_OK);
  char lib[64];
  snprintf(lib, sizeof lib, "%016" PRIx64, r.hash);
  assert_string_equal(ha, lib);
  assert_int_equal(field_u64(a.out, "steps"), r.steps);

  /* A different run length is a different state: the hash is not constant. */
  opts.duration = 3.0;
  mr_sim_result r3;
  assert_int_equal(mr_sim_run(&s, &opts, &r3, &e), MR_SCENE_OK);
  assert_true(r3.hash != r.hash);
  mr_scene_free(&s);
  tt_output_free(&a);
  tt_output_free(&b);
}

/* A sim def filled by hand (no cookie from mr_default_sim_def) is refused
 * with a line that names the maker, and no step runs; the same def from
 * the maker, with a non-default duration, runs. */
static void a_sim_def_not_from_its_maker_is_refused(void **state) {
  (void)state;
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load(SCENES "/puppet.yaml", &s, &e), MR_SCENE_OK);
  mr_sim_def hand;
  memset(&hand, 0, sizeof hand);
  hand.duration = 0.5;
  mr_sim_result r;
  assert_int_equal(mr_sim_run(&s, &hand, &r, &e), MR_SCENE_ERR_VALUE);
  assert_non_null(strstr(e.text, "mr_default_sim_def"));
  assert_int_equal(r.steps, 0);
  mr_sim_def opts = mr_default_sim_def();
  opts.duration = 0.5;
  assert_int_equal(mr_sim_run(&s, &opts, &r, &e), MR_SCENE_OK);
  assert_true(r.steps > 0 && r.sim_time > 0.5 - 1e-9 && r.sim_time < 0.5 + 1e-9);
  mr_scene_free(&s);
}

/* A pinned particle and a free one on a link: gravity and constraints
 * alone. */
static const char ONE_LINK[] = "physics:\n"
                               "  effects: [gravity, constraints]\n"
                               "  particles:\n"
                               "    - {name: a, position: [0, 2, 0], mass: 1, pinned: true}\n"
                               "    - {name: b, position: [0.5, 2, 0], mass: 1}\n"
                               "  constraints:\n"
                               "    - {between: [a, b]}\n";

/* The result keeps the last step call's status: a link written twice is
 * a dependent row at every step (reported, not a failure), one link
 * alone is none. */
static void the_last_step_status_is_kept(void **state) {
  (void)state;
  const char twice[] = "    - {between: [b, a]}\n";
  char text[sizeof ONE_LINK + sizeof twice];
  for (int dup = 0; dup < 2; dup++) {
    snprintf(text, sizeof text, "%s%s", ONE_LINK, dup ? twice : "");
    const char *path = tt_tmp_file("sim_status.yaml", text, strlen(text));
    mr_scene s;
    mr_scene_error e;
    assert_int_equal(mr_scene_load(path, &s, &e), MR_SCENE_OK);
    mr_sim_def opts = mr_default_sim_def();
    opts.duration = 0.5;
    mr_sim_result r;
    assert_int_equal(mr_sim_run(&s, &opts, &r, &e), MR_SCENE_OK);
    assert_true(r.steps > 0);
    assert_int_equal(r.last_status, dup ? MR_DEPENDENT : MR_OK);
    mr_scene_free(&s);
  }
}

/* The rest checks measure: the free end of ONE_LINK swings from its
 * start (a pendulum from horizontal), so after `settle` it travels about
 * a metre and reaches about 3 m/s, and a bound under either fails the
 * check with a line naming what was expected and what came. */
static void rest_checks_measure_creep_and_jitter(void **state) {
  (void)state;
  const struct {
    const char *bounds, *said;
  } cases[] = {
    { "creep: 0.01, jitter: 100", "check failed: expected creep <= 0.01 m after 0.2 s, got 0.9" },
    { "creep: 100, jitter: 0.5",
      "check failed: expected speeds <= 0.5 m/s after 0.2 s (no jitter), got 3.1" },
    { "creep: 100, jitter: 100", NULL },
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char text[sizeof ONE_LINK + 200];
    snprintf(text, sizeof text, "%sexpect: {rest: {particles: [b], settle: 0.2, %s}}\n", ONE_LINK,
             cases[i].bounds);
    const char *path = tt_tmp_file("sim_rest.yaml", text, strlen(text));
    tt_output p;
    run(&p, "sim", "--check", "-q", "--time", "1", path, NULL);
    if (cases[i].said == NULL) {
      assert_int_equal(p.status, 0);
    } else {
      assert_int_equal(p.status, 1);
      if (strstr(p.err, cases[i].said) == NULL)
        fail_msg("expected '%s' in: %s", cases[i].said, p.err);
    }
    tt_output_free(&p);
  }
}

/* --fps paces the run in frames at any rate, 1 Hz too (the start and one
 * a second); without it the run steps straight to its end and counts no
 * frames. */
static void fps_paces_the_run_even_at_one_hertz(void **state) {
  (void)state;
  const char *path = tt_tmp_file("sim_fps.yaml", ONE_LINK, sizeof ONE_LINK - 1);
  tt_output p;
  run(&p, "sim", "--fps", "1", "--time", "3", path, NULL);
  assert_int_equal(p.status, 0);
  if (strstr(p.out, "\nframes: 4 at 1 fps\n") == NULL) fail_msg("%s", p.out);
  tt_output_free(&p);
  run(&p, "sim", "--time", "3", path, NULL);
  assert_int_equal(p.status, 0);
  assert_null(strstr(p.out, "\nframes: "));
  tt_output_free(&p);
}

/* "Simulate only the effects a scene calls for": passes of effects the
 * scene does not declare never run. */
static void undeclared_effects_have_zero_pass_calls(void **state) {
  (void)state;
  const char *path = tt_tmp_file("sim_effects.yaml", ONE_LINK, sizeof ONE_LINK - 1);
  tt_output p;
  run(&p, "sim", "--time", "2", path, NULL);
  assert_int_equal(p.status, 0);
  uint64_t steps = field_u64(p.out, "steps");
  assert_true(steps > 0);
  assert_true(field_u64(p.out, "pass gravity") >= steps);
  assert_true(field_u64(p.out, "pass constraints") >= steps);
  assert_true(field_u64(p.out, "pass solve") >= steps);
  const char *off[] = { "pass drag",
                        "pass springs",
                        "pass strings",
                        "pass antigravity",
                        "pass triggered",
                        "pass sine-springs",
                        "pass planes",
                        "pass self-collision",
                        "pass puppet-collision",
                        "pass string-correction",
                        "pass frames" };
  for (size_t i = 0; i < sizeof off / sizeof off[0]; i++) {
    char v[32];
    assert_int_equal(tt_field(p.out, off[i], v, sizeof v), 0);
    assert_string_equal(v, "0");
  }
  tt_output_free(&p);
}

static void csv_has_one_row_per_step_call(void **state) {
  (void)state;
  char csv[4200];
  snprintf(csv, sizeof csv, "%s", tt_tmp_file("sim_trace.csv", "", 0));
  tt_output p;
  run(&p, "sim", "--time", "2", "--csv", csv, SCENES "/puppet.yaml", NULL);
  assert_int_equal(p.status, 0);
  uint64_t steps = field_u64(p.out, "steps");
  FILE *f = fopen(csv, "r");
  assert_non_null(f);
  char line[512];
  assert_non_null(fgets(line, sizeof line, f));
  assert_string_equal(line, "t,dt,error,accepted,rejected,reset,max_speed\n");
  uint64_t accepted = 0;
  double t = 0, last_t = -1;
  int rows = 0;
  while (fgets(line, sizeof line, f)) {
    double dt, err, speed;
    int acc, rej, reset;
    assert_int_equal(
        sscanf(line, "%lf,%lf,%lf,%d,%d,%d,%lf", &t, &dt, &err, &acc, &rej, &reset, &speed), 7);
    assert_true(t > last_t);
    assert_true(dt > 0 && dt <= 0.05 + 1e-12);
    last_t = t;
    accepted += (uint64_t)acc;
    rows++;
  }
  fclose(f);
  assert_true(rows > 0);
  assert_int_equal(accepted, steps);
  assert_true(t == 2.0);
  tt_output_free(&p);
}

/* A scene whose every step diverges (a speed bound no fall can meet),
 * sampled at a frame rate so one step call holds several resets: the CSV's
 * reset column counts them, so its sum is the summary's figure. */
static void csv_resets_add_up_to_the_summary(void **state) {
  (void)state;
  static const char scene[] = "sim: {duration: 0.5, fps: 10}\n"
                              "physics:\n"
                              "  effects: [gravity]\n"
                              "  ats: {max_speed: 0.001, dt_min: 0.01, dt_max: 0.02}\n"
                              "  particles: [{name: a, position: [0, 1, 0], mass: 1}]\n";
  char path[4200], csv[4200];
  snprintf(path, sizeof path, "%s", tt_tmp_file("resets.yaml", scene, sizeof scene - 1));
  snprintf(csv, sizeof csv, "%s", tt_tmp_file("resets.csv", "", 0));
  tt_output p;
  run(&p, "sim", "--csv", csv, path, NULL);
  assert_int_equal(p.status, 0);
  uint64_t resets = field_u64(p.out, "resets");
  FILE *f = fopen(csv, "r");
  assert_non_null(f);
  char line[512];
  assert_non_null(fgets(line, sizeof line, f));
  uint64_t sum = 0;
  int most = 0;
  while (fgets(line, sizeof line, f)) {
    double t, dt, err, speed;
    int acc, rej, reset;
    assert_int_equal(
        sscanf(line, "%lf,%lf,%lf,%d,%d,%d,%lf", &t, &dt, &err, &acc, &rej, &reset, &speed), 7);
    sum += (uint64_t)reset;
    if (reset > most) most = reset;
  }
  fclose(f);
  printf("%" PRIu64 " resets, %d in one call at most\n", resets, most);
  assert_true(resets >= 10);
  assert_true(most > 1);
  assert_int_equal(sum, resets);
  tt_output_free(&p);
}

/* sim.max_steps stops a run whose settings ask for too many steps, with one
 * clear line and a failure status, instead of running on for hours. */
static void run_past_the_step_guard_stops_clearly(void **state) {
  (void)state;
  /* 10 s at steps of up to 1 s may fit in 50 steps; a stiff string's
   * stability limit (2.5 ms) makes the run need thousands, and the guard
   * stops it on the way. */
  static const char scene[] = "sim: {duration: 10, max_steps: 50}\n"
                              "physics:\n"
                              "  effects: [gravity, strings, control]\n"
                              "  ats: {dt_max: 1}\n"
                              "  particles: [{name: a, position: [0, 1, 0], mass: 1}]\n"
                              "  control: {points: [{name: bar, offset: [0, 2, 0]}]}\n"
                              "  strings: [{from: bar, to: a, mode: spring, stiffness: 1000000}]\n";
  char path[4200];
  snprintf(path, sizeof path, "%s", tt_tmp_file("guard.yaml", scene, sizeof scene - 1));
  tt_output p;
  run(&p, "sim", path, NULL);
  assert_int_not_equal(p.status, 0);
  assert_non_null(strstr(p.err, "stopped after 51 step tries, past sim.max_steps (50)"));
  assert_ptr_equal(strchr(p.err, '\n'), p.err + strlen(p.err) - 1); /* one line */
  tt_output_free(&p);
  /* Settings that cannot finish within the guard are refused at once:
   * 10 s at steps of at most 1e-9 s needs 1e10 steps. */
  static const char tiny[] = "sim: {duration: 10}\n"
                             "physics:\n"
                             "  effects: [gravity]\n"
                             "  ats: {dt_min: 1e-9, dt_initial: 1e-9, dt_max: 1e-9}\n"
                             "  particles: [{name: a, position: [0, 1, 0], mass: 1}]\n";
  snprintf(path, sizeof path, "%s", tt_tmp_file("tiny.yaml", tiny, sizeof tiny - 1));
  run(&p, "sim", path, NULL);
  assert_int_not_equal(p.status, 0);
  assert_non_null(strstr(p.err, "needs at least 1e+10 steps, past sim.max_steps (2000000)"));
  assert_non_null(strstr(p.err, "at t = 0.000000 s"));
  tt_output_free(&p);
}

static void check_fails_with_a_clear_line(void **state) {
  (void)state;
  /* A swinging pendulum cannot meet a deviation bound of 1e-30. */
  const char text[] = "physics:\n"
                      "  effects: [gravity, constraints]\n"
                      "  particles:\n"
                      "    - {name: a, position: [0, 2, 0], mass: 1, pinned: true}\n"
                      "    - {name: b, position: [0.5, 2, 0], mass: 1}\n"
                      "  constraints:\n"
                      "    - {between: [a, b]}\n"
                      "expect: {max_deviation: 1e-30}\n";
  const char *path = tt_tmp_file("sim_check.yaml", text, sizeof text - 1);
  tt_output p;
  run(&p, "sim", "--check", "--quiet", "--time", "1", path, NULL);
  assert_int_equal(p.status, 1);
  char prefix[4300];
  snprintf(prefix, sizeof prefix,
           "marionette: %s: check failed: expected max deviation <= 1e-30, got ", path);
  assert_memory_equal(p.err, prefix, strlen(prefix));
  /* one line */
  assert_ptr_equal(strchr(p.err, '\n'), p.err + strlen(p.err) - 1);
  tt_output_free(&p);
}

/* A world with nothing stiff in it (no spring, drag, string or
 * constraint) has no step limit, and the summary says none rather than a
 * limit of 0 s. */
static void a_world_without_a_step_limit_reports_none(void **state) {
  (void)state;
  const char text[] = "physics:\n"
                      "  effects: [gravity]\n"
                      "  particles:\n"
                      "    - {name: a, position: [0, 2, 0], mass: 1}\n";
  const char *path = tt_tmp_file("sim_no_limit.yaml", text, sizeof text - 1);
  tt_output p;
  run(&p, "sim", "--time", "0.5", path, NULL);
  assert_int_equal(p.status, 0);
  assert_true(field_u64(p.out, "steps") > 0);
  char v[32];
  assert_int_not_equal(tt_field(p.out, "stable dt", v, sizeof v), 0);
  tt_output_free(&p);
}

/* A 1 kg weight on a stiff spring string, checked by `expect` (a flow
 * map), run for 2 s with --check into p. */
static void hanging_spring(tt_output *p, const char *name, const char *expect) {
  char text[512];
  int n =
      snprintf(text, sizeof text,
               "physics:\n"
               "  effects: [gravity, strings, control]\n"
               "  particles:\n"
               "    - {name: w, position: [0, 1, 0], mass: 1}\n"
               "  control:\n"
               "    pose: {position: [0, 1.5, 0]}\n"
               "    points: [{name: bar, offset: [0, 0, 0]}]\n"
               "  strings:\n"
               "    - {from: bar, to: w, mode: spring, stiffness: 1000, damping: 10, rest: 0.5}\n"
               "expect: %s\n",
               expect);
  const char *path = tt_tmp_file(name, text, (size_t)n);
  run(p, "sim", "--check", "--time", "2", path, NULL);
}

/* The stretch a failed check against `max` reports, from its message. */
static double stretch_failed(const char *max) {
  char expect[64];
  snprintf(expect, sizeof expect, "{max_string_stretch: %s}", max);
  tt_output p;
  hanging_spring(&p, "sim_stretch_max.yaml", expect);
  assert_int_equal(p.status, 1);
  const char *got = strstr(p.err, "its rest length, got ");
  assert_non_null(got);
  double g = strtod(got + strlen("its rest length, got "), NULL);
  tt_output_free(&p);
  return g;
}

/* A check that fails by a hair says by how much: the stretch it reports
 * is past the limit it names, also when the two agree to six digits (a
 * string 3.5e-6 over 1.01 was reported as "got 1.01"). */
static void a_failed_stretch_check_names_a_stretch_past_its_limit(void **state) {
  (void)state;
  const double stretch = stretch_failed("1.0");
  assert_true(stretch > 1.0 && stretch < 1.1);
  char limit[32];
  snprintf(limit, sizeof limit, "%.5f", floor(stretch * 1e5) / 1e5); /* six digits, below it */
  const double again = stretch_failed(limit);
  printf("stretch %.9g; against a limit of %s the check reports %.9g\n", stretch, limit, again);
  assert_true(again > strtod(limit, NULL));
  assert_true(again == stretch);
}

/* A string that never leaves its rest length cannot meet a stretch
 * expectation, and the summary reports the stretch it did reach. */
static void string_stretch_is_measured_and_checked(void **state) {
  (void)state;
  tt_output p;
  hanging_spring(&p, "sim_stretch.yaml", "{min_string_stretch: 3}");
  assert_int_equal(p.status, 1);
  char v[64];
  assert_int_equal(tt_field(p.out, "string stretch max", v, sizeof v), 0);
  double stretch = strtod(v, NULL);
  /* 1 kg on 1000 N/m sags 9.8 mm below its 0.5 m rest: about 1.02 x. */
  assert_true(stretch > 1.0 && stretch < 1.1);
  /* The spring limits the step (forces.c): RK4's reach over ω = √1000,
   * about 0.08 s, reported. */
  assert_int_equal(tt_field(p.out, "stable dt", v, sizeof v), 0);
  const double stable = strtod(v, NULL);
  assert_true(stable > 0.05 && stable < 0.1);
  assert_non_null(strstr(p.err, "check failed: expected a string stretched to >= 3 x its rest "
                                "length, got "));
  tt_output_free(&p);
}

/* A pinned hash is checked: --print-hash gives the line that pins the run,
 * that line passes --check, and one changed digit fails it with both
 * hashes named. Under --time the run is another length and the pin does
 * not apply. */
static void pinned_state_hash_is_checked(void **state) {
  (void)state;
  const char base[] = "sim: {duration: 1}\n"
                      "physics:\n"
                      "  effects: [gravity, constraints]\n"
                      "  particles:\n"
                      "    - {name: a, position: [0, 2, 0], mass: 1, pinned: true}\n"
                      "    - {name: b, position: [0.5, 2, 0], mass: 1}\n"
                      "  constraints: [{between: [a, b]}]\n";
  const char *path = tt_tmp_file("sim_hash.yaml", base, sizeof base - 1);
  tt_output p;
  run(&p, "sim", "--print-hash", path, NULL);
  assert_int_equal(p.status, 0);
  char pin[64];
  assert_int_equal(tt_field(p.out, "state_hash", pin, sizeof pin), 0);
  assert_int_equal(strlen(pin), 18);
  assert_memory_equal(pin, "0x", 2);
  tt_output_free(&p);

  char text[1024];
  snprintf(text, sizeof text, "%sexpect:\n  state_hash: %s\n", base, pin);
  path = tt_tmp_file("sim_hash.yaml", text, strlen(text));
  run(&p, "sim", "--check", "-q", path, NULL);
  assert_int_equal(p.status, 0);
  assert_string_equal(p.out, "check: passed\n");
  tt_output_free(&p);

  char wrong[64];
  snprintf(wrong, sizeof wrong, "%s", pin);
  wrong[17] = wrong[17] == '0' ? '1' : '0';
  snprintf(text, sizeof text, "%sexpect:\n  state_hash: %s\n", base, wrong);
  path = tt_tmp_file("sim_hash.yaml", text, strlen(text));
  run(&p, "sim", "--check", "-q", path, NULL);
  assert_int_equal(p.status, 1);
  char want[4400];
  snprintf(want, sizeof want, "marionette: %s: check failed: expected state hash %s, got %s\n",
           path, wrong, pin);
  assert_string_equal(p.err, want);
  tt_output_free(&p);
  run(&p, "sim", "--check", "-q", "--time", "0.5", path, NULL);
  assert_int_equal(p.status, 0);
  tt_output_free(&p);
}

static void example_puppet_runs_cleanly(void **state) {
  (void)state;
  tt_output p;
  run(&p, "sim", "--check", SCENES "/puppet.yaml", NULL);
  assert_int_equal(p.status, 0);
  assert_int_equal(field_u64(p.out, "resets"), 0);
  assert_true(field_u64(p.out, "pass strings") > 0);
  assert_true(field_u64(p.out, "pass antigravity") > 0);
  assert_true(field_u64(p.out, "pass planes") > 0);
  assert_non_null(strstr(p.out, "check: passed\n"));
  tt_output_free(&p);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s PATH-TO-marionette\n", argv[0]);
    return 2;
  }
  marionette = argv[1];
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(help_lists_subcommands_and_flags),
    cmocka_unit_test(load_errors_are_one_line_with_the_place),
    cmocka_unit_test(bad_usage_exits_2),
    cmocka_unit_test(same_scene_same_state_hash),
    cmocka_unit_test(a_sim_def_not_from_its_maker_is_refused),
    cmocka_unit_test(the_last_step_status_is_kept),
    cmocka_unit_test(rest_checks_measure_creep_and_jitter),
    cmocka_unit_test(fps_paces_the_run_even_at_one_hertz),
    cmocka_unit_test(undeclared_effects_have_zero_pass_calls),
    cmocka_unit_test(csv_has_one_row_per_step_call),
    cmocka_unit_test(csv_resets_add_up_to_the_summary),
    cmocka_unit_test(run_past_the_step_guard_stops_clearly),
    cmocka_unit_test(check_fails_with_a_clear_line),
    cmocka_unit_test(a_world_without_a_step_limit_reports_none),
    cmocka_unit_test(string_stretch_is_measured_and_checked),
    cmocka_unit_test(a_failed_stretch_check_names_a_stretch_past_its_limit),
    cmocka_unit_test(pinned_state_hash_is_checked),
    cmocka_unit_test(example_puppet_runs_cleanly),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

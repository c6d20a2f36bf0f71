/* The show on its physics thread (mr_show_runner): commands from the
 * drawing thread reach it, in order, none lost; paused it publishes
 * nothing, and a single step publishes one frame; the caller's pump runs
 * at every tick on one thread and never on a thread of its own. Run under
 * ThreadSanitizer by make test-tsan. The glove is a pty path that never
 * opens: the show runs on, its puppet hanging at rest. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>
#include <time.h>

#include "mr_scene.h"
#include "mr_show_runner.h"

#define PUPPET MR_SOURCE_DIR "/host/scenes/puppet.yaml"

typedef struct notes {
  int resets, mappings; /* the physics thread's, read after it ended */
} notes;

static void note(void *user, const char *line) {
  notes *n = user;
  if (strncmp(line, "reset:", 6) == 0) n->resets++;
  if (strncmp(line, "mapping '", 9) == 0) n->mappings++;
}

static void nap(double s) {
  struct timespec ts = { 0, (long)(s * 1e9) };
  nanosleep(&ts, NULL);
}

static void load_puppet(mr_scene *scene) {
  mr_scene_error serr;
  assert_int_equal(mr_scene_load(PUPPET, scene, &serr), MR_SCENE_OK);
}

static mr_show_runner *start_with(const mr_scene *scene, mr_virtual_clock *vc,
                                  const mr_show_hooks *h, const mr_show_runner_def *rd) {
  mr_show_def d = mr_default_show_def();
  d.gloves[0] = "pty:/nonexistent/marionette-test";
  d.n_gloves = 1;
  d.fps = 60;
  mr_clock base = mr_clock_virtual(vc);
  mr_show_runner *r = NULL;
  mr_show_error err;
  mr_show_status st = mr_show_runner_start(scene, &d, &base, h, rd, &r, &err);
  if (st != MR_SHOW_OK) fail_msg("start: %s", err.text);
  return r;
}

static mr_show_runner *start(const mr_scene *scene, mr_virtual_clock *vc, notes *n) {
  mr_show_hooks h = { NULL, NULL, NULL, note, n };
  mr_show_runner_def rd = mr_default_show_runner_def();
  return start_with(scene, vc, &h, &rd);
}

static uint64_t frames_of(mr_show_runner *r) {
  const mr_show_frame *f = NULL;
  mr_show_runner_latest(r, &f);
  return f != NULL ? f->stats.frames_simulated : 0;
}

/* 10 000 frames under a hail of random pauses, single steps, slow
 * motions, resets and mapping changes from this thread: the show never
 * locks up (ctest's timeout), every command sent is done, and each reset
 * and mapping change is told once. */
static void random_commands_for_10000_frames_are_all_done(void **state) {
  (void)state;
  mr_scene scene;
  load_puppet(&scene);
  mr_virtual_clock vc = { 0.0 };
  notes n = { 0, 0 };
  mr_show_runner *r = start(&scene, &vc, &n);
  static const mr_show_cmd pick[] = {
    MR_SHOW_CMD_PAUSE, MR_SHOW_CMD_STEP,  MR_SHOW_CMD_STEP,
    MR_SHOW_CMD_SLOW,  MR_SHOW_CMD_RESET, MR_SHOW_CMD_NEXT_MAPPING
  };
  uint32_t rng = 12345;
  uint64_t commands = 0;
  while (frames_of(r) < 10000) {
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    mr_show_runner_send(r, pick[rng % (sizeof pick / sizeof pick[0])]);
    commands++;
    if (rng % 4 == 0) nap(1e-5);
  }
  mr_show_runner_send(r, MR_SHOW_CMD_QUIT);
  while (!mr_show_runner_done(r)) nap(1e-3);
  uint64_t sent[MR_SHOW_CMD_COUNT], done[MR_SHOW_CMD_COUNT];
  mr_show_runner_counts(r, sent, done);
  for (int c = 0; c < MR_SHOW_CMD_COUNT; c++) {
    print_message("command %d: %llu sent, %llu done\n", c, (unsigned long long)sent[c],
                  (unsigned long long)done[c]);
    assert_int_equal(done[c], sent[c]);
  }
  for (int c = 0; c < MR_SHOW_CMD_QUIT; c++) assert_true(sent[c] > 100);
  mr_show_result res;
  mr_show_error err;
  assert_int_equal(mr_show_runner_finish(r, &res, &err), MR_SHOW_OK);
  assert_true(res.frames.frames_simulated >= 10000);
  assert_int_equal(n.resets, (int)sent[MR_SHOW_CMD_RESET]);
  assert_int_equal(n.mappings, (int)sent[MR_SHOW_CMD_NEXT_MAPPING]);
  mr_show_result_free(&res);
  print_message("%llu commands over %llu frames\n", (unsigned long long)commands,
                (unsigned long long)res.frames.frames_simulated);
  mr_scene_free(&scene);
}

/* Paused, the physics publishes nothing however long the drawing thread
 * waits; each single step publishes exactly one frame more. */
static void paused_nothing_comes_and_a_step_brings_one_frame(void **state) {
  (void)state;
  mr_scene scene;
  load_puppet(&scene);
  mr_virtual_clock vc = { 0.0 };
  notes n = { 0, 0 };
  mr_show_runner *r = start(&scene, &vc, &n);
  while (frames_of(r) < 30) nap(1e-3);
  mr_show_runner_send(r, MR_SHOW_CMD_PAUSE);
  uint64_t done[MR_SHOW_CMD_COUNT];
  do {
    nap(1e-3);
    mr_show_runner_counts(r, NULL, done);
  } while (done[MR_SHOW_CMD_PAUSE] == 0);
  nap(0.02); /* the frame in hand when the pause came */
  uint64_t paused_at = frames_of(r);
  nap(0.1);
  assert_int_equal(frames_of(r), paused_at);
  for (int k = 1; k <= 3; k++) {
    mr_show_runner_send(r, MR_SHOW_CMD_STEP);
    for (int i = 0; i < 5000 && frames_of(r) < paused_at + (uint64_t)k; i++) nap(1e-3);
    nap(0.05);
    assert_int_equal(frames_of(r), paused_at + (uint64_t)k);
  }
  mr_show_runner_send(r, MR_SHOW_CMD_QUIT);
  mr_show_result res;
  assert_int_equal(mr_show_runner_finish(r, &res, NULL), MR_SHOW_OK);
  mr_show_result_free(&res);
  mr_scene_free(&scene);
}

/* The caller's pump, counted; each frame the show simulates spends two
 * frame periods of the virtual clock, so a show on one thread is always
 * behind and never waits: only its ticks can pump. */
typedef struct pumped {
  mr_virtual_clock *vc;
  int calls;
} pumped;

static void pump(void *user) {
  ((pumped *)user)->calls++;
}

static void slow_frame(void *user, const mr_show_frame *f) {
  (void)f;
  mr_virtual_clock_spend(((pumped *)user)->vc, 2.0 / 60);
}

/* On one thread the pump runs at every tick, not only while the show
 * waits: a show that has fallen behind still takes the caller's inputs. */
static void on_one_thread_every_tick_pumps(void **state) {
  (void)state;
  mr_scene scene;
  load_puppet(&scene);
  mr_virtual_clock vc = { 0.0 };
  pumped p = { &vc, 0 };
  mr_show_hooks h = { NULL, NULL, slow_frame, NULL, &p };
  mr_show_runner_def rd = mr_default_show_runner_def();
  rd.threaded = false;
  rd.pump = pump;
  rd.user = &p;
  mr_show_runner *r = start_with(&scene, &vc, &h, &rd);
  for (int tick = 0; tick < 100; tick++) {
    int before = p.calls;
    assert_int_equal(mr_show_runner_tick(r), MR_SHOW_OK);
    if (p.calls == before) fail_msg("tick %d did not pump", tick);
  }
  mr_show_result res;
  assert_int_equal(mr_show_runner_finish(r, &res, NULL), MR_SHOW_OK);
  mr_show_result_free(&res);
  mr_scene_free(&scene);
}

/* The pump is for a runner on one thread: on a thread of its own, the
 * runner never calls it (the caller's inputs come as commands, and the
 * pump would run off the caller's thread). */
static void on_its_own_thread_the_runner_never_pumps(void **state) {
  (void)state;
  mr_scene scene;
  load_puppet(&scene);
  mr_virtual_clock vc = { 0.0 };
  pumped p = { &vc, 0 };
  mr_show_hooks h = { NULL, NULL, NULL, NULL, NULL };
  mr_show_runner_def rd = mr_default_show_runner_def();
  rd.pump = pump;
  rd.user = &p;
  mr_show_runner *r = start_with(&scene, &vc, &h, &rd);
  while (frames_of(r) < 100) nap(1e-3);
  mr_show_runner_send(r, MR_SHOW_CMD_QUIT);
  mr_show_result res;
  assert_int_equal(mr_show_runner_finish(r, &res, NULL), MR_SHOW_OK);
  mr_show_result_free(&res);
  /* Read once the thread has been joined. */
  assert_int_equal(p.calls, 0);
  mr_scene_free(&scene);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(random_commands_for_10000_frames_are_all_done),
    cmocka_unit_test(paused_nothing_comes_and_a_step_brings_one_frame),
    cmocka_unit_test(on_one_thread_every_tick_pumps),
    cmocka_unit_test(on_its_own_thread_the_runner_never_pumps),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

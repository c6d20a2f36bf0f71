/* The show and out of memory. A show allocates when it starts, never
 * while it plays: a box that runs for hours must not fail in the middle
 * of a performance for want of memory it could have taken at the start.
 * And when an allocation at the start fails, the show says so and leaves
 * nothing behind (the sanitizers' leak check runs over this test).
 *
 * Allocations are counted, and one of them made to fail, by
 * tests/common/alloc.h. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mr_io.h"
#include "mr_scene.h"
#include "mr_show.h"
#include "mr_show_runner.h"
#include "alloc.h"
#include "proc.h"

/* --- a take and the puppet ------------------------------------------------ */

static void put(mr_rec_writer *w, double t, const gp_msg *m) {
  uint8_t wire[GP_MAX_WIRE + 2];
  size_t n = gp_encode(m, GP_SPEC_HASH, wire, sizeof wire);
  assert_true(n > 0);
  mr_io_error err;
  if (mr_rec_writer_add(w, (uint64_t)llround(t * 1e9), wire, n, &err) != 0) fail_msg("%s", err.msg);
}

/* A right glove calibrated so that a raw r reads r / 4000, its fingers
 * waving for `seconds`, a sample every 10 ms. */
static void write_take(const char *path, double seconds) {
  mr_rec_writer w;
  mr_io_error err;
  if (mr_rec_writer_open(&w, path, GP_SPEC_HASH, 0, &err) != 0) fail_msg("%s", err.msg);
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_INFO;
  m.u.info.proto_major = 1;
  m.u.info.spec_hash = GP_SPEC_HASH;
  m.u.info.uid[0] = 0x00c0ffeeu;
  m.u.info.hand = GP_HAND_RIGHT;
  m.u.info.n_channels = 5;
  m.u.info.adc_bits = 12;
  m.u.info.frame_rate_hz = 100;
  m.u.info.cal_state = GP_CAL_VALID;
  for (int k = 0; k < 5; k++) m.u.info.cal_max[k] = 4000;
  put(&w, 0.0, &m);
  for (int i = 1; i * 0.01 < seconds; i++) {
    const double t = i * 0.01;
    memset(&m, 0, sizeof m);
    m.type = GP_SAMPLE;
    m.u.sample.seq = (uint16_t)i;
    m.u.sample.t_us = (uint32_t)llround(t * 1e6);
    for (int k = 0; k < 5; k++)
      m.u.sample.ch[k] = (uint16_t)llround(4000 * (0.5 + 0.4 * sin(2.0 * 3.14159 * t + k)));
    put(&w, t, &m);
  }
  if (mr_rec_writer_close(&w, &err) != 0) fail_msg("%s", err.msg);
}

#define PUPPET MR_SOURCE_DIR "/host/scenes/puppet.yaml"

typedef struct rig {
  char *dir;
  char source[400];
  mr_scene scene;
  mr_virtual_clock vc;
  int frames;
  uint64_t last_hash; /* of the last frame simulated */
} rig;

static void frame_done(void *user, const mr_show_frame *f) {
  rig *r = user;
  r->frames++;
  r->last_hash = f->hash;
}

static void rig_make(rig *r, double seconds) {
  memset(r, 0, sizeof *r);
  r->dir = tt_tmpdir();
  assert_non_null(r->dir);
  const char *take = tt_path(r->dir, "wave.mrec");
  write_take(take, seconds);
  snprintf(r->source, sizeof r->source, "take:%s", take);
  mr_scene_error err;
  if (mr_scene_load(PUPPET, &r->scene, &err) != MR_SCENE_OK) fail_msg("%s", err.text);
}

static void rig_free(rig *r) {
  mr_scene_free(&r->scene);
  tt_rmdir(r->dir);
  free(r->dir);
}

static mr_show_def show_def(rig *r, double duration) {
  mr_show_def d = mr_default_show_def();
  d.fps = 60;
  d.duration = duration;
  d.present = MR_PRESENT_LAND;
  d.gloves[0] = r->source;
  d.n_gloves = 1;
  return d;
}

static mr_show_status show_start(rig *r, double duration, mr_show **out, mr_show_error *err) {
  mr_show_def d = show_def(r, duration);
  r->vc.t = 0.0;
  mr_clock c = mr_clock_virtual(&r->vc);
  mr_show_hooks h = { NULL, NULL, frame_done, NULL, r };
  *out = NULL;
  return mr_show_create(&r->scene, &d, &c, &h, out, err);
}

static void show_finish(mr_show *show) {
  mr_show_result res;
  mr_show_error err;
  if (mr_show_destroy(show, &res, &err) != MR_SHOW_OK) fail_msg("%s", err.text);
  mr_show_result_free(&res);
}

/* --- a show plays without allocating -------------------------------------- */

/* Past its first second (the physics' first steps and the glove's first
 * samples size what they keep), two seconds of a waving glove moving the
 * project's puppet, its strings taut and its feet on the floor, allocate
 * nothing. */
static void a_playing_show_allocates_nothing(void **state) {
  (void)state;
  rig r;
  rig_make(&r, 3.5);
  mr_show *show = NULL;
  mr_show_error err;
  if (show_start(&r, 3.0, &show, &err) != MR_SHOW_OK) fail_msg("%s", err.text);
  while (r.frames < 60) assert_int_equal(mr_show_tick(show), MR_SHOW_OK);
  const int before = r.frames;
  const uint64_t warm = r.last_hash;
  tt_alloc_count(0);
  mr_show_status st;
  while ((st = mr_show_tick(show)) == MR_SHOW_OK) {
  }
  const long allocations = tt_alloc_stop();
  assert_int_equal(st, MR_SHOW_ENDED);
  print_message("%d frames played after the first second, %ld allocations\n", r.frames - before,
                allocations);
  /* The show ran its course, and the puppet moved in it. */
  assert_true(r.frames - before >= 110);
  assert_true(r.last_hash != warm);
  assert_int_equal(allocations, 0);
  show_finish(show);
  rig_free(&r);
}

/* --- out of memory at the start ------------------------------------------- */

/* A start of the show over r's take, for 0.5 s: its status (and what it
 * told in err), and when it started, the frames it then played to its
 * end (in r->frames). */
typedef mr_show_status (*starter)(rig *r, mr_show_error *err);

static mr_show_status show_play(rig *r, mr_show_error *err) {
  mr_show *show = NULL;
  mr_show_status st = show_start(r, 0.5, &show, err);
  if (st != MR_SHOW_OK) {
    assert_null(show);
    return st;
  }
  tt_alloc_stop();
  while ((st = mr_show_tick(show)) == MR_SHOW_OK) {
  }
  assert_int_equal(st, MR_SHOW_ENDED);
  show_finish(show);
  return MR_SHOW_OK;
}

/* The runner adds its queue and the three frames it hands to the
 * drawing side. */
static mr_show_status runner_play(rig *r, mr_show_error *err) {
  mr_show_def d = show_def(r, 0.5);
  r->vc.t = 0.0;
  mr_clock base = mr_clock_virtual(&r->vc);
  mr_show_runner_def rd = mr_default_show_runner_def();
  rd.threaded = false;
  mr_show_hooks h = { NULL, NULL, frame_done, NULL, r };
  mr_show_runner *runner = NULL;
  mr_show_status st = mr_show_runner_start(&r->scene, &d, &base, &h, &rd, &runner, err);
  if (st != MR_SHOW_OK) {
    assert_null(runner);
    return st;
  }
  tt_alloc_stop();
  while (mr_show_runner_tick(runner) == MR_SHOW_OK) {
  }
  const mr_show_frame *latest = NULL;
  assert_true(mr_show_runner_latest(runner, &latest));
  assert_true(latest->t > 0.45);
  mr_show_result res;
  if (mr_show_runner_finish(runner, &res, err) != MR_SHOW_OK) fail_msg("%s", err->text);
  mr_show_result_free(&res);
  return MR_SHOW_OK;
}

/* The start with its k-th allocation failing, for every k up to the
 * first start that needs no more: each fails with "out of memory" and no
 * show, or, where the world can do without what it asked for (the room
 * to keep a control point's placement, grown again at the first step),
 * starts and plays to its end. Returns how many allocations the start
 * makes; refusals: how many of them, failing, refused it. */
static long each_allocation_failing(starter start, const char *what, long *refusals) {
  rig r;
  rig_make(&r, 1.0);
  long k = 1;
  *refusals = 0;
  for (;; k++) {
    mr_show_error err;
    memset(&err, 0, sizeof err);
    const int before = r.frames;
    tt_alloc_count(k);
    mr_show_status st = start(&r, &err);
    tt_alloc_stop();
    const int failed_one = tt_allocations() >= k;
    if (st == MR_SHOW_OK) {
      if (r.frames - before < 30)
        fail_msg("%s, allocation %ld failing: %d frames played", what, k, r.frames - before);
      if (!failed_one) break;
      continue;
    }
    assert_true(failed_one);
    if (strstr(err.text, "out of memory") == NULL)
      fail_msg("%s, allocation %ld failing: \"%s\", expected out of memory", what, k, err.text);
    ++*refusals;
    assert_true(k < 100000);
  }
  rig_free(&r);
  print_message("%s: %ld allocations; %ld refused it when they failed\n", what, k - 1, *refusals);
  return k - 1;
}

static void every_allocation_of_a_shows_start_may_fail(void **state) {
  (void)state;
  long refusals, n = each_allocation_failing(show_play, "the show's start", &refusals);
  assert_true(refusals > 20);
  assert_true(refusals >= n - 5); /* all but the few the world can do without */
}

static void every_allocation_of_a_runners_start_may_fail(void **state) {
  (void)state;
  long refusals, n = each_allocation_failing(runner_play, "the runner's start", &refusals);
  long show_refusals,
      show_n = each_allocation_failing(show_play, "the show's start", &show_refusals);
  /* The runner's own: its queue and the three frames it hands over. */
  assert_true(n >= show_n + 4);
  assert_true(refusals >= show_refusals + 4);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_playing_show_allocates_nothing),
    cmocka_unit_test(every_allocation_of_a_shows_start_may_fail),
    cmocka_unit_test(every_allocation_of_a_runners_start_may_fail),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

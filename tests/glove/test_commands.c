/* Commands to a glove over a real pty, answered by glove-gen as the
 * firmware answers them: each command is matched to its answer by tag,
 * sent again until answered, given up after its tries; a refusal comes
 * back with its reason; STREAM_OFF stops the samples without the glove
 * being taken for lost, STREAM_ON brings them back; GET_STATUS brings a
 * STATUS; a calibration saved from the motion seen is the glove's new
 * range; a new baud is followed. Time is the wall clock here: the glove
 * answers in real time. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mr_glove.h"
#include "mr_io.h"
#include "proc.h"

static const char *glove_gen;

typedef struct live {
  pid_t gen;
  char *dir;
  mr_glove *g;
  double t0;
} live;

static double now_s(const live *l) {
  return (double)mr_io_monotonic_ns() * 1e-9 - l->t0;
}

/* glove-gen on a new pty for 20 s (extra arguments after), and a glove on
 * it, live. */
static void start(live *l, const char *extra) {
  memset(l, 0, sizeof *l);
  l->dir = tt_tmpdir();
  char pf[300], err[300];
  snprintf(pf, sizeof pf, "%s", tt_path(l->dir, "pty.path"));
  snprintf(err, sizeof err, "%s", tt_path(l->dir, "gen.err"));
  /* With extra NULL the list ends before it. */
  const char *argv[] = { glove_gen,    "-o", "pty", "--path-file", pf,
                         "--duration", "20", "-q",  extra,         NULL };
  l->gen = tt_spawn(argv, NULL, err);
  assert_true(l->gen > 0);
  assert_int_equal(tt_await_file(l->gen, pf, err, 30), 0);
  char *path = tt_read_file(pf, NULL);
  assert_non_null(path);
  path[strcspn(path, "\n")] = '\0';
  mr_glove_def d = mr_default_glove_def();
  snprintf(d.source, sizeof d.source, "pty:%s", path);
  free(path);
  d.cmd_timeout = 0.2;
  char msg[200];
  assert_int_equal(mr_glove_create(&d, &l->g, msg, sizeof msg), MR_GLOVE_OK);
  l->t0 = (double)mr_io_monotonic_ns() * 1e-9;
  while (mr_glove_get_state(l->g) != MR_GLOVE_LIVE && now_s(l) < 5)
    mr_glove_poll(l->g, now_s(l), 20);
  assert_int_equal(mr_glove_get_state(l->g), MR_GLOVE_LIVE);
}

static void stop(live *l) {
  mr_glove_destroy(l->g);
  kill(l->gen, SIGTERM);
  tt_wait(l->gen, 10);
  tt_rmdir(l->dir);
  free(l->dir);
}

/* Polls for `secs` of wall time. */
static void run_for(live *l, double secs) {
  double end = now_s(l) + secs;
  while (now_s(l) < end) mr_glove_poll(l->g, now_s(l), 10);
}

/* Sends cmd and polls until it is answered or given up. */
static mr_glove_cmd_result send_and_wait(live *l, mr_glove_cmd cmd) {
  char msg[200];
  int tag = mr_glove_command(l->g, &cmd, now_s(l), msg, sizeof msg);
  if (tag < 0) fail_msg("%s", msg);
  mr_glove_cmd_result r = mr_glove_command_result(l->g, tag);
  double end = now_s(l) + 5;
  while (r.state == MR_GLOVE_CMD_PENDING && now_s(l) < end) {
    mr_glove_poll(l->g, now_s(l), 10);
    r = mr_glove_command_result(l->g, tag);
  }
  assert_int_equal(r.tag, tag);
  return r;
}

static mr_glove_cmd command(uint8_t type) {
  mr_glove_cmd c = { type, 0, 0 };
  return c;
}

static void commands_are_answered_by_tag(void **state) {
  (void)state;
  live l;
  start(&l, NULL);
  mr_glove_cmd_result r = send_and_wait(&l, command(GP_PING));
  assert_int_equal(r.state, MR_GLOVE_CMD_ACKED);
  assert_int_equal(r.sends, 1);
  mr_glove_cmd_result r2 = send_and_wait(&l, command(GP_GET_INFO));
  assert_int_equal(r2.state, MR_GLOVE_CMD_ACKED);
  assert_int_not_equal(r2.tag, r.tag);
  assert_non_null(mr_glove_info(l.g));
  assert_null(mr_glove_status_frame(l.g));
  assert_int_equal(send_and_wait(&l, command(GP_GET_STATUS)).state, MR_GLOVE_CMD_ACKED);
  run_for(&l, 0.1);
  const gp_status *st = mr_glove_status_frame(l.g);
  assert_non_null(st);
  assert_true(st->frames_sent > 0);
  stop(&l);
}

/* The glove leaves the first two unanswered: the third send is answered. */
static void an_unanswered_command_is_sent_again(void **state) {
  (void)state;
  live l;
  start(&l, "--ignore-commands=2");
  mr_glove_cmd_result r = send_and_wait(&l, command(GP_PING));
  assert_int_equal(r.state, MR_GLOVE_CMD_ACKED);
  assert_int_equal(r.sends, 3);
  stop(&l);
}

static void a_command_never_answered_is_given_up(void **state) {
  (void)state;
  live l;
  start(&l, "--ignore-commands=1000");
  double t = now_s(&l);
  mr_glove_cmd_result r = send_and_wait(&l, command(GP_PING));
  assert_int_equal(r.state, MR_GLOVE_CMD_TIMED_OUT);
  assert_int_equal(r.sends, 5);
  assert_true(now_s(&l) - t >= 5 * 0.2 - 0.05); /* five tries, 0.2 s apart */
  stop(&l);
}

static void a_refusal_comes_back_with_its_reason(void **state) {
  (void)state;
  live l;
  start(&l, NULL);
  mr_glove_cmd rate = { GP_SET_RATE, 1000, 0 }; /* glove-gen keeps its 250 Hz */
  mr_glove_cmd_result r = send_and_wait(&l, rate);
  assert_int_equal(r.state, MR_GLOVE_CMD_NACKED);
  assert_int_equal(r.nack_reason, GP_NACK_BAD_ARGUMENT);
  assert_string_equal(mr_glove_nack_reason_name(r.nack_reason), "BAD_ARGUMENT");
  /* CAL_SAVE without CAL_START: the wrong state. */
  r = send_and_wait(&l, command(GP_CAL_SAVE));
  assert_int_equal(r.state, MR_GLOVE_CMD_NACKED);
  assert_int_equal(r.nack_reason, GP_NACK_BAD_STATE);
  stop(&l);
}

static uint64_t samples(const live *l) {
  mr_glove_reading r;
  mr_glove_latest(l->g, &r);
  return r.samples;
}

/* Off: no samples for 1.5 s, and the glove, still sending INFO, is not
 * taken for lost. On: samples again. */
static void the_stream_stops_and_starts_on_command(void **state) {
  (void)state;
  live l;
  start(&l, NULL);
  assert_int_equal(send_and_wait(&l, command(GP_STREAM_OFF)).state, MR_GLOVE_CMD_ACKED);
  run_for(&l, 0.1); /* what was on the way */
  uint64_t before = samples(&l);
  run_for(&l, 1.5);
  assert_int_equal(samples(&l), before);
  assert_int_equal(mr_glove_get_state(l.g), MR_GLOVE_LIVE);
  assert_int_equal(send_and_wait(&l, command(GP_STREAM_ON)).state, MR_GLOVE_CMD_ACKED);
  run_for(&l, 0.5);
  assert_true(samples(&l) >= before + 100); /* 250 Hz */
  stop(&l);
}

/* CAL_START, the default motion for 1.5 s, CAL_SAVE: the INFO that follows
 * has the range seen; CAL_CLEAR goes back to the defaults. */
static void a_saved_calibration_is_the_new_range(void **state) {
  (void)state;
  live l;
  start(&l, NULL);
  assert_int_equal(send_and_wait(&l, command(GP_CAL_START)).state, MR_GLOVE_CMD_ACKED);
  run_for(&l, 0.1);
  assert_int_equal(mr_glove_info(l.g)->cal_state, GP_CAL_RUNNING);
  run_for(&l, 1.5);
  assert_int_equal(send_and_wait(&l, command(GP_CAL_SAVE)).state, MR_GLOVE_CMD_ACKED);
  run_for(&l, 0.1);
  const gp_info *info = mr_glove_info(l.g);
  assert_int_equal(info->cal_state, GP_CAL_VALID);
  for (int k = 0; k < 5; k++) {
    assert_true(info->cal_min[k] < info->cal_max[k]);
    assert_true(info->cal_max[k] - info->cal_min[k] < 4095);
  }
  assert_int_equal(send_and_wait(&l, command(GP_CAL_CLEAR)).state, MR_GLOVE_CMD_ACKED);
  run_for(&l, 0.1);
  assert_int_equal(mr_glove_info(l.g)->cal_state, GP_CAL_DEFAULTS);
  stop(&l);
}

/* SET_RATE with a new baud: ACKed at the old speed, then the port is
 * reopened at the new one, and the glove, which announces it, reads on. */
static void a_new_baud_is_followed(void **state) {
  (void)state;
  live l;
  start(&l, NULL);
  mr_glove_counters c0;
  mr_glove_get_counters(l.g, &c0);
  mr_glove_cmd rate = { GP_SET_RATE, 250, 921600 };
  assert_int_equal(send_and_wait(&l, rate).state, MR_GLOVE_CMD_ACKED);
  uint64_t before = samples(&l);
  run_for(&l, 0.5);
  mr_glove_counters c1;
  mr_glove_get_counters(l.g, &c1);
  assert_int_equal(c1.opens, c0.opens + 1);
  assert_int_equal(mr_glove_info(l.g)->baud, 921600);
  assert_true(samples(&l) >= before + 80);
  assert_int_equal(mr_glove_get_state(l.g), MR_GLOVE_LIVE);
  stop(&l);
}

static void a_take_carries_no_commands(void **state) {
  (void)state;
  const char *take = tt_tmp_file("t.mrec", "", 0);
  assert_non_null(take);
  mr_io_error err;
  mr_rec_writer w;
  assert_int_equal(mr_rec_writer_open(&w, take, GP_SPEC_HASH, 0, &err), 0);
  assert_int_equal(mr_rec_writer_close(&w, &err), 0);
  mr_glove_def d = mr_default_glove_def();
  snprintf(d.source, sizeof d.source, "file:%s", take);
  mr_glove *g = NULL;
  assert_int_equal(mr_glove_create(&d, &g, NULL, 0), MR_GLOVE_OK);
  char msg[300];
  mr_glove_cmd c = command(GP_PING);
  assert_int_equal(mr_glove_command(g, &c, 0.0, msg, sizeof msg), -1);
  char want[400];
  snprintf(want, sizeof want,
           "glove file:%s: PING cannot be sent: a take, a file or stdin carries no commands", take);
  assert_string_equal(msg, want);
  c.type = GP_SAMPLE;
  assert_int_equal(mr_glove_command(g, &c, 0.0, msg, sizeof msg), -1);
  /* With no message buffer, or one of no room, the refusal is the same and
   * nothing is written: not past a size given without a buffer, not into
   * a buffer given without room. */
  char one = 'x';
  const uint8_t frame[1] = { 0 };
  c.type = GP_PING;
  assert_int_equal(mr_glove_command(g, &c, 0.0, NULL, sizeof msg), -1);
  assert_int_equal(mr_glove_command(g, &c, 0.0, &one, 0), -1);
  assert_int_equal(mr_glove_send_raw(g, frame, sizeof frame, NULL, sizeof msg), -1);
  assert_int_equal(mr_glove_send_raw(g, frame, sizeof frame, &one, 0), -1);
  assert_true(one == 'x');
  mr_glove_destroy(g);
}

int main(int argc, char **argv) {
  signal(SIGPIPE, SIG_IGN);
  glove_gen = argc > 1 ? argv[1] : "glove-gen";
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(commands_are_answered_by_tag),
    cmocka_unit_test(an_unanswered_command_is_sent_again),
    cmocka_unit_test(a_command_never_answered_is_given_up),
    cmocka_unit_test(a_refusal_comes_back_with_its_reason),
    cmocka_unit_test(the_stream_stops_and_starts_on_command),
    cmocka_unit_test(a_saved_calibration_is_the_new_range),
    cmocka_unit_test(a_new_baud_is_followed),
    cmocka_unit_test(a_take_carries_no_commands),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

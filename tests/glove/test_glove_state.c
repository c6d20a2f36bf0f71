/* A glove's state from the bytes of a real pty, on a virtual clock: the
 * calibrated range used only when the glove says it is valid, the device
 * clock unwrapped at 2^32 us and started afresh (never taken for a wrap)
 * when the glove restarts, the clock offset the smallest seen since then,
 * a loss counted once however long it lasts, the port tried again after
 * retry_every and not sooner, and a frame cut by a hang-up one error whose
 * bytes are only the glove's; a take sent down the port is a glove's
 * bytes, not a take. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glove_wire.h"

static mr_glove_reading latest(const mr_glove *g) {
  mr_glove_reading r;
  mr_glove_latest(g, &r);
  return r;
}

static mr_glove_counters counters(const mr_glove *g) {
  mr_glove_counters c;
  mr_glove_get_counters(g, &c);
  return c;
}

/* Sends m and a SAMPLE, and polls at `now` until the SAMPLE is taken. */
static void send_and_take(gw_port *p, mr_glove *g, const gp_msg *m, gp_msg s, double now) {
  if (m != NULL) gw_port_send(p, m);
  gw_port_send(p, &s);
  if (gw_poll_for_samples(g, now) == 0) fail_msg("seq %u not taken", (unsigned)s.u.sample.seq);
}

static void sample_at(gw_port *p, mr_glove *g, uint16_t seq, uint32_t t_us, uint16_t flags,
                      double now) {
  send_and_take(p, g, NULL, gw_sample(seq, t_us, flags, 2000), now);
}

static void expect_values(const mr_glove *g, double v0, double step, const char *what) {
  mr_glove_reading r = latest(g);
  for (int k = 0; k < 5; k++)
    if (!(fabs(r.values[k] - (v0 + step * k)) < 1e-12))
      fail_msg("%s: channel %d reads %.9f, expected %.9f", what, k, r.values[k], v0 + step * k);
}

/* The range 1000..3000 is in every INFO; only a VALID one is used. Raw
 * 2000 + 100 k on channel k. */
static void the_calibrated_range_is_used_only_when_the_glove_says_it_is_valid(void **state) {
  (void)state;
  gw_port p;
  gw_port_make(&p);
  mr_glove *g = gw_glove(p.source, 0.5, 0.5);
  mr_glove_poll(g, 1.0, 0);
  static const struct {
    uint8_t cal_state, adc_bits;
    uint16_t lo, hi;
    double v0, step;
  } cases[] = {
    { GP_CAL_DEFAULTS, 12, 1000, 3000, 2000.0 / 4095, 100.0 / 4095 },
    { GP_CAL_VALID, 12, 1000, 3000, 0.5, 0.05 },
    { GP_CAL_RUNNING, 12, 1000, 3000, 2000.0 / 4095, 100.0 / 4095 },
    { 3 /* CORRUPT */, 12, 1000, 3000, 2000.0 / 4095, 100.0 / 4095 },
    { GP_CAL_VALID, 12, 1500, 2500, 0.5, 0.1 },
    { GP_CAL_DEFAULTS, 14, 1000, 3000, 2000.0 / 16383, 100.0 / 16383 },
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    gp_msg info = gw_info(0xCA1, cases[i].cal_state, cases[i].lo, cases[i].hi, cases[i].adc_bits);
    send_and_take(&p, g, &info, gw_sample((uint16_t)(i + 1), 1000u * (uint32_t)(i + 1), 0, 2000),
                  1.0 + 0.01 * (double)i);
    char what[64];
    snprintf(what, sizeof what, "case %zu (cal_state %u)", i, (unsigned)cases[i].cal_state);
    expect_values(g, cases[i].v0, cases[i].step, what);
  }
  mr_glove_destroy(g);
  gw_port_remove(&p);
}

static void expect_device_t(const mr_glove *g, double want, const char *what) {
  double t = latest(g).device_t;
  if (!(fabs(t - want) < 1e-7)) fail_msg("%s: device time %.6f s, expected %.6f s", what, t, want);
}

/* The 32-bit us counter wraps twice and is counted on; a step back of
 * 0.5 ms is a step back, not a wrap. */
static void a_device_clock_that_wraps_is_counted_on(void **state) {
  (void)state;
  gw_port p;
  gw_port_make(&p);
  mr_glove *g = gw_glove(p.source, 0.5, 0.5);
  mr_glove_poll(g, 1.0, 0);
  const double wrap = 4294.967296;
  sample_at(&p, g, 1, 4294957296u, 0, 1.0);
  expect_device_t(g, 4294.957296, "before the wrap");
  sample_at(&p, g, 2, 10000u, 0, 1.02);
  expect_device_t(g, wrap + 0.01, "after the wrap");
  sample_at(&p, g, 3, 9500u, 0, 1.03);
  expect_device_t(g, wrap + 0.0095, "0.5 ms back");
  sample_at(&p, g, 4, 2147483648u, 0, 1.04); /* half way round, in steps */
  sample_at(&p, g, 5, 4294900000u, 0, 1.05);
  sample_at(&p, g, 6, 5000u, 0, 1.06);
  expect_device_t(g, 2 * wrap + 0.005, "after the second wrap");
  mr_glove_destroy(g);
  gw_port_remove(&p);
}

/* A glove that restarts: by a START flag after its clock wrapped, and
 * with its clock moved back by more than 2^31 us (from 3000 s to 2 ms) by
 * its sequence counting again with no START, and by a replug with the
 * sequence carried on. Each time the device time is the new clock's, not
 * a wrap's 4294 s ahead. */
static void a_restart_that_moves_the_clock_back_far_is_no_wrap(void **state) {
  (void)state;
  gw_port p;
  gw_port_make(&p);
  mr_glove *g = gw_glove(p.source, 0.5, 0.5);
  double now = 1.0;
  mr_glove_poll(g, now, 0);
  sample_at(&p, g, 998, 4294957296u, 0, now); /* a wrap first: its 4294 s go too */
  sample_at(&p, g, 999, 10000u, 0, now += 0.01);
  sample_at(&p, g, 1000, 2000000000u, 0, now += 0.01);
  sample_at(&p, g, 0, 1000u, GP_SAMPLE_F_START, now += 0.01);
  expect_device_t(g, 0.001, "after a START");
  sample_at(&p, g, 1000, 3000000000u, 0, now += 0.01);
  sample_at(&p, g, 5, 2000u, 0, now += 0.01); /* 995 back, no START */
  expect_device_t(g, 0.002, "after the sequence started again");
  sample_at(&p, g, 6, 3000000000u, 0, now += 0.01);
  gw_port_unplug(&p);
  for (int i = 0; i < 100 && mr_glove_get_state(g) != MR_GLOVE_LOST; i++) mr_glove_poll(g, now, 10);
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LOST);
  gw_port_plug(&p);
  mr_glove_poll(g, now += 0.5, 0);
  sample_at(&p, g, 7, 3000u, 0, now);
  expect_device_t(g, 0.003, "after a replug");
  assert_true(fabs(gw_lateness(g)) < 1e-9);
  mr_glove_destroy(g);
  gw_port_remove(&p);
}

/* Host times with up to 7 ms of jitter over device times: the offset is
 * the smallest host − device seen, whichever sample brought it. */
static double jittered(gw_port *p, mr_glove *g, double host0, uint32_t t0_us, uint16_t *seq,
                       uint16_t first_flags) {
  static const double jitter[] = { 0.004, 0.002, 0.007, 0.0005, 0.003, 0.006 };
  for (int i = 0; i < 6; i++)
    sample_at(p, g, (*seq)++, t0_us + 10000u * (uint32_t)i, i == 0 ? first_flags : 0,
              host0 + 0.01 * i + jitter[i]);
  return host0 - t0_us * 1e-6 + 0.0005; /* the offset these samples give */
}

static void expect_offset(const mr_glove *g, double want, const char *what) {
  double off = mr_glove_clock_offset(g);
  if (!(fabs(off - want) < 1e-9)) fail_msg("%s: offset %.6f s, expected %.6f s", what, off, want);
}

/* And started afresh when the device clock does: after a START flag, a
 * new INFO uid and a replug, each time 10 ms above the old, so that only a
 * fresh start finds it; the same uid again starts nothing. */
static void the_clock_offset_is_the_smallest_seen_since_the_clock_started_afresh(void **state) {
  (void)state;
  gw_port p;
  gw_port_make(&p);
  mr_glove *g = gw_glove(p.source, 0.5, 0.5);
  uint16_t seq = 1;
  mr_glove_poll(g, 10.0, 0);
  assert_true(isnan(mr_glove_clock_offset(g)));
  gp_msg info = gw_info(0x111, GP_CAL_VALID, 1000, 3000, 12);
  gw_port_send(&p, &info);
  expect_offset(g, jittered(&p, g, 10.0, 5000000u, &seq, 0), "first");
  assert_true(fabs(gw_lateness(g) - 0.0055) < 1e-9); /* the last jitter less the least */

  expect_offset(g, jittered(&p, g, 11.0, 5990000u, &seq, GP_SAMPLE_F_START), "after a START");
  info.u.info.uid[0] = 0x222;
  gw_port_send(&p, &info);
  expect_offset(g, jittered(&p, g, 12.0, 6980000u, &seq, 0), "after a new uid");
  info.u.info.uid[0] = 0x222; /* the same glove again: nothing starts afresh */
  gw_port_send(&p, &info);
  jittered(&p, g, 13.0, 7970000u, &seq, 0);
  expect_offset(g, 12.0 - 6.98 + 0.0005, "the same uid again");

  gw_port_unplug(&p);
  for (int i = 0; i < 100 && mr_glove_get_state(g) != MR_GLOVE_LOST; i++)
    mr_glove_poll(g, 13.1, 10);
  gw_port_plug(&p);
  mr_glove_poll(g, 14.0, 0);
  expect_offset(g, jittered(&p, g, 14.0, 8960000u, &seq, 0), "after a replug");
  mr_glove_destroy(g);
  gw_port_remove(&p);
}

/* Silent on an open port for lost_after (0.2 s and 1 s): lost at once
 * after it, not before; silent on for 5 s more, polled all along, still
 * one loss, dated from its start. Back, and silent again: two. */
static void a_silent_glove_is_lost_after_lost_after_and_counted_once(void **state) {
  (void)state;
  static const double lost_after[] = { 0.2, 1.0 };
  for (int c = 0; c < 2; c++) {
    gw_port p;
    gw_port_make(&p);
    mr_glove *g = gw_glove(p.source, lost_after[c], 0.5);
    double now = 1.0;
    mr_glove_poll(g, now, 0);
    sample_at(&p, g, 1, 1000u, 0, now);
    mr_glove_poll(g, now + lost_after[c] - 0.01, 0);
    assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LIVE);
    mr_glove_poll(g, now + lost_after[c] + 0.01, 0);
    assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LOST);
    for (int i = 1; i <= 100; i++) mr_glove_poll(g, now + lost_after[c] + 0.01 + 0.05 * i, 0);
    now += lost_after[c] + 5.01;
    assert_int_equal(counters(g).losses, 1);
    char line[300], want[64];
    mr_glove_describe(g, now, line, sizeof line);
    snprintf(want, sizeof want, ": lost 5.0 s ago");
    if (strstr(line, want) == NULL) fail_msg("'%s' does not say '%s'", line, want);

    /* The silent port was closed and is opened again every retry_every. */
    for (int i = 0; i < 100 && mr_glove_io_path(g)[0] == '\0'; i++)
      mr_glove_poll(g, now += 0.01, 0);
    sample_at(&p, g, 2, 2000u, 0, now);
    assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LIVE);
    for (int i = 1; i <= 40; i++) mr_glove_poll(g, now + 0.05 * i, 0);
    assert_int_equal(counters(g).losses, 2);
    mr_glove_destroy(g);
    gw_port_remove(&p);
  }
}

/* Unplugged at `now` and plugged in again at once: the port is opened
 * again at now + retry_every (0.25 s and 0.75 s), not a step sooner; while
 * nothing is there, it is tried once every retry_every. Times are steps of
 * 1/128 s, which add up exactly. */
static void a_lost_port_is_tried_again_after_retry_every_and_not_sooner(void **state) {
  (void)state;
  static const double retry[] = { 0.25, 0.75 }, step = 1.0 / 128;
  for (int c = 0; c < 2; c++) {
    gw_port p;
    gw_port_make(&p);
    mr_glove *g = gw_glove(p.source, 0.5, retry[c]);
    double now = 1.0;
    mr_glove_poll(g, now, 0);
    sample_at(&p, g, 1, 1000u, 0, now);
    gw_port_unplug(&p);
    for (int i = 0; i < 100 && mr_glove_get_state(g) != MR_GLOVE_LOST; i++)
      mr_glove_poll(g, now, 10);
    assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LOST);
    mr_glove_counters c0 = counters(g);
    /* Nothing there: one try per retry_every, over 4 s. */
    for (int i = 1; i <= 512; i++) mr_glove_poll(g, now + step * i, 0);
    now += 4.0;
    mr_glove_counters c1 = counters(g);
    int tries = (int)(c1.open_failures - c0.open_failures);
    if (tries != (int)floor(4.0 / retry[c] + 1e-9))
      fail_msg("%d tries in 4 s, retry_every %.1f s", tries, retry[c]);
    /* Back at once after a fresh loss of the reopened port. */
    gw_port_plug(&p);
    for (int i = 0; i < 200 && counters(g).opens == c1.opens; i++) mr_glove_poll(g, now += step, 0);
    sample_at(&p, g, 2, 2000u, 0, now);
    gw_port_unplug(&p);
    for (int i = 0; i < 100 && mr_glove_get_state(g) != MR_GLOVE_LOST; i++)
      mr_glove_poll(g, now, 10);
    gw_port_plug(&p);
    uint64_t opens = counters(g).opens;
    mr_glove_poll(g, now + retry[c] - step, 0);
    assert_int_equal(counters(g).opens, opens);
    mr_glove_poll(g, now + retry[c], 0);
    assert_int_equal(counters(g).opens, opens + 1);
    mr_glove_destroy(g);
    gw_port_remove(&p);
  }
}

/* An INFO, then the first 1 byte and then half of a SAMPLE, each cut by
 * an unplug: each cut frame is one framing error, no frame fuses with
 * the next port's bytes, and the bytes counted are those the glove sent,
 * without the delimiter the host puts after a cut frame. */
static void a_frame_cut_by_a_hang_up_is_one_error_and_its_delimiter_is_not_counted(void **state) {
  (void)state;
  gw_port p;
  gw_port_make(&p);
  mr_glove *g = gw_glove(p.source, 0.5, 0.1);
  double now = 1.0;
  mr_glove_poll(g, now, 0);
  gp_msg info = gw_info(0xB17E5, GP_CAL_VALID, 1000, 3000, 12);
  uint64_t sent = gw_port_send(&p, &info);
  static const size_t cut_at[] = { 1, 0 }; /* 0: half */
  for (int c = 0; c < 2; c++) {
    gp_msg s = gw_sample((uint16_t)(c + 1), 1000u, 0, 2000);
    sent += gw_port_send(&p, &s);
    assert_true(gw_poll_for_samples(g, now) > 0);
    uint8_t wire[GP_MAX_WIRE];
    size_t n = gw_encode(&s, wire), cut = cut_at[c] ? cut_at[c] : n / 2;
    assert_int_equal(gw_write(p.master.fd, wire, cut), 0);
    sent += cut;
    for (int i = 0; i < 100 && mr_glove_unfinished(g) != cut; i++) mr_glove_poll(g, now, 10);
    assert_int_equal(mr_glove_unfinished(g), cut);
    gw_port_unplug(&p);
    for (int i = 0; i < 100 && mr_glove_get_state(g) != MR_GLOVE_LOST; i++)
      mr_glove_poll(g, now, 10);
    assert_int_equal(mr_glove_unfinished(g), 0);
    gw_port_plug(&p);
    mr_glove_poll(g, now += 0.1, 0);
  }
  gp_msg s = gw_sample(9, 2000u, 0, 2400);
  sent += gw_port_send(&p, &s);
  assert_true(gw_poll_for_samples(g, now) > 0);
  assert_true(fabs(latest(g).values[0] - 0.7) < 1e-12);
  mr_glove_counters c = counters(g);
  assert_int_equal(c.decoder.framing_errors, 2);
  assert_int_equal(c.decoder.crc_errors + c.decoder.oversize, 0);
  assert_int_equal(c.decoder.frames, 4);
  assert_int_equal(c.decoder.bytes, sent);
  mr_glove_destroy(g);
  gw_port_remove(&p);
}

/* Only a file, a FIFO or stdin may carry a take. A take's bytes sent down
 * a glove's port are the glove's bytes, every one of them, the take's
 * own header too: the SAMPLE frames inside its chunks are read as they
 * come, and the port stays a glove, which takes commands. */
static void a_take_sent_down_a_port_is_read_as_a_glove(void **state) {
  (void)state;
  size_t len = 0;
  char *bytes = gw_take(5, 0.001, &len);
  gw_port p;
  gw_port_make(&p);
  mr_glove *g = gw_glove(p.source, 0.5, 0.5);
  double now = 1.0;
  mr_glove_poll(g, now, 0);
  assert_int_equal(gw_write(p.master.fd, bytes, len), 0);
  free(bytes);
  for (int i = 0; i < 100 && counters(g).decoder.frames < 5; i++) mr_glove_poll(g, now, 10);
  mr_glove_counters n = counters(g);
  assert_int_equal(n.decoder.frames, 5);
  assert_int_equal(n.decoder.bytes, len);
  assert_int_equal(latest(g).seq, 5);
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LIVE);
  mr_glove_cmd c = { .type = GP_PING };
  char msg[300];
  if (mr_glove_command(g, &c, now, msg, sizeof msg) < 0) fail_msg("PING refused: %s", msg);
  mr_glove_destroy(g);
  gw_port_remove(&p);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_calibrated_range_is_used_only_when_the_glove_says_it_is_valid),
    cmocka_unit_test(a_device_clock_that_wraps_is_counted_on),
    cmocka_unit_test(a_restart_that_moves_the_clock_back_far_is_no_wrap),
    cmocka_unit_test(the_clock_offset_is_the_smallest_seen_since_the_clock_started_afresh),
    cmocka_unit_test(a_silent_glove_is_lost_after_lost_after_and_counted_once),
    cmocka_unit_test(a_lost_port_is_tried_again_after_retry_every_and_not_sooner),
    cmocka_unit_test(a_frame_cut_by_a_hang_up_is_one_error_and_its_delimiter_is_not_counted),
    cmocka_unit_test(a_take_sent_down_a_port_is_read_as_a_glove),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

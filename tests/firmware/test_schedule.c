/* The sampling schedule: SAMPLE timestamps come from the timer's tick, so a
 * main loop that runs late, in bursts, or misses a tick moves no frame off
 * the 4 ms grid by more than one tick. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "fake_hal.h"
#include "fw_hal.h"

static fw_core core;

static int setup(void **state) {
  (void)state;
  fake_reset();
  fw_core_init(&core);
  return 0;
}

static void firmware_schedule_timestamps_follow_the_timer(void **state) {
  (void)state;
  /* Polls per tick cycle through "late" patterns: the loop sometimes skips
   * up to three ticks (the block queue holds four) and then catches up. */
  static const unsigned polls[] = { 1, 0, 0, 1, 2, 0, 0, 0, 1, 1, 3, 0, 1 };
  for (unsigned t = 0; t < 4000; t++) fake_step(&core, 0, polls[t % 13]);
  fake_step(&core, 0, 1);
  fake_run(&core, 100); /* drain the line */
  fake_decode();
  assert_int_equal(fake.tx_overflow, 0);
  assert_int_equal(frames.c.crc_errors + frames.c.framing_errors + frames.c.lost, 0);

  size_t n = 0;
  uint32_t prev_t = 0;
  uint16_t prev_seq = 0;
  for (size_t i = fake_find(0, GP_SAMPLE); i < frames.n; i = fake_find(i + 1, GP_SAMPLE)) {
    const gp_sample *s = &frames.msg[i].u.sample;
    /* On the grid exactly: nothing was missed, only delayed. */
    assert_int_equal(s->t_us % 4000u, 0);
    assert_int_equal(s->flags & GP_SAMPLE_F_OVERRUN, 0);
    if (n > 0) {
      assert_int_equal((uint16_t)(s->seq - prev_seq), 1);
      assert_int_equal(s->t_us - prev_t, 4000u);
    }
    prev_t = s->t_us;
    prev_seq = s->seq;
    n++;
  }
  assert_true(n >= 1000);
}

static void firmware_schedule_missed_ticks_cost_at_most_one_tick(void **state) {
  (void)state;
  unsigned skipped = 0;
  for (unsigned t = 0; t < 3000; t++) {
    /* Every 37th tick's sampling never happens (an overrun). */
    int skip = t % 37 == 36;
    skipped += (unsigned)skip;
    fake_step(&core, skip, 1);
  }
  fake_run(&core, 50);
  fake_decode();
  size_t n = 0, flagged = 0;
  uint32_t prev_t = 0;
  for (size_t i = fake_find(0, GP_SAMPLE); i < frames.n; i = fake_find(i + 1, GP_SAMPLE)) {
    const gp_sample *s = &frames.msg[i].u.sample;
    uint32_t ticks = s->t_us / 1000u;
    /* Jitter: at most one tick after the nominal 4-tick grid. */
    assert_in_range(ticks % 4u, 0, 1);
    if (n > 0) assert_in_range(s->t_us - prev_t, 3000u, 5000u);
    if (s->flags & GP_SAMPLE_F_OVERRUN) flagged++;
    prev_t = s->t_us;
    n++;
  }
  assert_true(n >= 750);
  /* Every skipped tick shows in the frame that follows it. */
  assert_int_equal(flagged, skipped);
  assert_int_equal(core.overruns, skipped);
}

/* INFO goes out on ticks 0, 1000, 2000, ...: at a 1000 Hz frame rate every
 * tick has a SAMPLE, and an INFO is queued just before the SAMPLE of its
 * own tick, so the SAMPLE after each INFO names the tick it went out on.
 * Ticks 2000 and 2001 are never sampled: that INFO is late, the next is
 * back on the grid. */
static void firmware_schedule_info_goes_out_every_1000_ticks(void **state) {
  (void)state;
  core.frame_rate_hz = 1000;
  core.baud = 921600;
  fake.baud = 921600;
  for (unsigned t = 0; t < 10500; t++) fake_step(&core, t == 2000 || t == 2001, 1);
  fake_run(&core, 20);
  fake_decode();
  assert_int_equal(frames.c.crc_errors + frames.c.framing_errors + frames.c.lost, 0);
  assert_int_equal(core.dropped_frames, 0);
  unsigned k = 0;
  for (size_t i = fake_find(0, GP_INFO); i < frames.n; i = fake_find(i + 1, GP_INFO), k++) {
    size_t s = fake_find(i + 1, GP_SAMPLE);
    assert_true(s < frames.n);
    uint32_t tick = frames.msg[s].u.sample.t_us / FW_TICK_US;
    uint32_t want = k == 2 ? 2002u : 1000u * k;
    if (tick != want) fail_msg("INFO %u went out on tick %u, not %u", k, tick, want);
  }
  assert_int_equal(k, 11);
}

/* A block handed over twice with the same tick number is taken once: the
 * copy moves neither the filter, nor the calibration capture, nor the
 * button's debounce, nor the schedule. */
static void firmware_schedule_a_repeated_tick_is_processed_once(void **state) {
  (void)state;
  fake_run(&core, 100);
  fw_cal_start(&core.cal);
  fake.button = 1;
  fake_run(&core, FW_BUTTON_DEBOUNCE_TICKS - 1);
  fake_decode();
  size_t samples_before = 0;
  for (size_t i = fake_find(0, GP_SAMPLE); i < frames.n; i = fake_find(i + 1, GP_SAMPLE))
    samples_before++;
  uint16_t seq = core.seq;
  uint32_t sent = core.frames_sent;

  /* The copy of the last tick carries levels no real tick had. */
  for (unsigned c = 0; c < FW_N_CH; c++) fake.level[c] = 4000;
  fake_sample_at(fake.tick - 1u);
  fw_core_poll(&core);
  for (unsigned c = 0; c < FW_N_CH; c++) {
    assert_int_equal(core.ch[c], 2048);
    assert_int_equal(core.cal.run_max[c], 2048);
  }
  assert_int_equal(core.seq, seq);
  assert_int_equal(core.frames_sent, sent);
  assert_int_equal(core.cal.state, GP_CAL_RUNNING);
  assert_int_equal(core.button, 0);
  assert_int_equal(core.overruns, 0);

  /* The next real tick is the debounce's twentieth read; the stream goes on
   * with one SAMPLE per four ticks, none flagged. */
  for (unsigned c = 0; c < FW_N_CH; c++) fake.level[c] = 2048;
  fake_run(&core, 1);
  assert_int_equal(core.button, 1);
  fake_run(&core, 100);
  fake_decode();
  size_t samples = 0;
  uint32_t prev_t = 0;
  for (size_t i = fake_find(0, GP_SAMPLE); i < frames.n; i = fake_find(i + 1, GP_SAMPLE)) {
    const gp_sample *smp = &frames.msg[i].u.sample;
    if (samples > 0) assert_int_equal(smp->t_us - prev_t, 4000u);
    assert_int_equal(smp->flags & (GP_SAMPLE_F_OVERRUN | GP_SAMPLE_F_CLIPPED), 0);
    prev_t = smp->t_us;
    samples++;
  }
  assert_true(samples > samples_before);
  assert_int_equal(core.overruns, 0);
}

/* A main loop that falls further behind than the block queue holds loses the
 * blocks that found it full; nothing counts them at the queue, and nothing
 * needs to: the gap they leave in the tick numbers is counted as overruns
 * and flagged in the next SAMPLE. */
static void firmware_schedule_blocks_the_queue_cannot_hold_count_as_overruns(void **state) {
  (void)state;
  fake_run(&core, 10);
  for (unsigned t = 0; t < FW_BLOCKQ_DEPTH + 3u; t++) fake_step(&core, 0, 0);
  assert_int_equal(core.overruns, 0);
  /* The first tick after the stall is sampled before the loop runs, into a
   * queue that is still full: four blocks lost in all. */
  fake_run(&core, 20);
  assert_int_equal(fake.blocks_lost, 4);
  assert_int_equal(core.overruns, 4);
  fake_decode();
  size_t flagged = 0;
  for (size_t i = fake_find(0, GP_SAMPLE); i < frames.n; i = fake_find(i + 1, GP_SAMPLE))
    if (frames.msg[i].u.sample.flags & GP_SAMPLE_F_OVERRUN) flagged++;
  assert_int_equal(flagged, 1);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test_setup(firmware_schedule_timestamps_follow_the_timer, setup),
    cmocka_unit_test_setup(firmware_schedule_missed_ticks_cost_at_most_one_tick, setup),
    cmocka_unit_test_setup(firmware_schedule_info_goes_out_every_1000_ticks, setup),
    cmocka_unit_test_setup(firmware_schedule_a_repeated_tick_is_processed_once, setup),
    cmocka_unit_test_setup(firmware_schedule_blocks_the_queue_cannot_hold_count_as_overruns, setup),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

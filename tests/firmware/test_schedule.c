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
  static const unsigned polls[] = {1, 0, 0, 1, 2, 0, 0, 0, 1, 1, 3, 0, 1};
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

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(firmware_schedule_timestamps_follow_the_timer, setup),
      cmocka_unit_test_setup(firmware_schedule_missed_ticks_cost_at_most_one_tick, setup),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

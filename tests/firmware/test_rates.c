/* Frame rates against the link: bytes that leave the simulated line per
 * second of simulated time, against the baud rate's budget (10 bits a byte
 * at 8N1). 250 Hz fits in half of 115200; 1000 Hz needs the 921600 link,
 * where it takes under a quarter. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fake_hal.h"
#include "fw_hal.h"
#include "fw_frame.h"
#include "fw_link.h"

static fw_core core;

static int setup(void **state) {
  (void)state;
  fake_reset();
  fw_core_init(&core);
  return 0;
}

/* Runs seconds of simulated time; returns the most bytes any one second put
 * on the wire and the SAMPLE count of the last second. */
static size_t busiest_second(unsigned seconds, size_t *samples_last) {
  size_t most = 0;
  for (unsigned s = 0; s < seconds; s++) {
    size_t before = fake.wire_len;
    fake_run(&core, FW_TICK_HZ);
    size_t bytes = fake.wire_len - before;
    if (bytes > most) most = bytes;
    if (s + 1 == seconds) {
      fake_decode();
      *samples_last = 0;
      for (size_t i = 0; i < frames.n; i++)
        if (frames.end[i] > before && frames.msg[i].type == GP_SAMPLE) (*samples_last)++;
    }
  }
  return most;
}

static void firmware_rates_sample_wire_size(void **state) {
  (void)state;
  uint8_t w[GP_MAX_WIRE];
  uint16_t ch[FW_N_CH] = { 1, 2, 3, 4, 5 };
  assert_int_equal(FW_SAMPLE_WIRE_BYTES, 22);
  assert_int_equal(fw_frame_sample(1, 4000, ch, 0, w, sizeof w), 22);
  assert_int_equal(fw_link_load_permille(250, 115200), 477);
  assert_int_equal(fw_link_load_permille(1000, 921600), 238);
  assert_true(fw_link_rate_ok(250, 115200));
  assert_true(fw_link_rate_ok(1000, 921600));
  assert_false(fw_link_rate_ok(1000, 115200));
  assert_false(fw_link_rate_ok(500, 115200)); /* 91 % */
}

static void firmware_rates_250hz_at_115200_under_half(void **state) {
  (void)state;
  size_t samples = 0;
  size_t most = busiest_second(10, &samples);
  /* 250 * 22 bytes of SAMPLE + one INFO; a 115200 line carries 11520 a
   * second, half of it 5760. */
  assert_true(most * 10u * 2u <= 115200u);
  assert_true(most >= 250u * 22u);
  assert_int_equal(samples, 250);
  fake_decode();
  assert_int_equal(frames.c.lost, 0);
  assert_int_equal(core.dropped_frames, 0);
  assert_int_equal(fake.tx_overflow, 0);
}

static void firmware_rates_1000hz_at_921600(void **state) {
  (void)state;
  fake_run(&core, 10);
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SET_RATE;
  m.u.set_rate.tag = 1;
  m.u.set_rate.frame_rate_hz = 1000;
  m.u.set_rate.baud = 921600;
  fake_send(&m);
  /* The ACK goes out at 115200, then the line switches. */
  fake_run(&core, 10);
  fake_decode();
  size_t ack = fake_find(0, GP_ACK);
  assert_true(ack < frames.n);
  assert_int_equal(frames.msg[ack].u.ack.cmd, GP_SET_RATE);
  assert_int_equal(fake.baud, 921600);
  assert_int_equal(fake.baud_changes, 1);
  assert_int_equal(core.baud, 921600);

  size_t samples = 0;
  size_t most = busiest_second(5, &samples);
  assert_int_equal(samples, 1000);
  /* 1000 * 22 bytes + INFO: under a quarter of 92160 bytes a second. */
  assert_true(most >= 1000u * 22u);
  assert_true(most * 10u * 4u <= 921600u);
  size_t dropped = core.dropped_frames;
  fake_decode();
  /* Frames due while the ACK drained were not queued: the host sees them
   * as lost, and STATUS says why. */
  assert_int_equal(frames.c.lost, dropped);
  assert_true(dropped <= 2);
  assert_int_equal(fake.tx_overflow, 0);
}

static void firmware_rates_1000hz_refused_at_115200(void **state) {
  (void)state;
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SET_RATE;
  m.u.set_rate.tag = 2;
  m.u.set_rate.frame_rate_hz = 1000;
  fake_send(&m);
  fake_run(&core, 10);
  fake_decode();
  size_t i = fake_find(0, GP_NACK);
  assert_true(i < frames.n);
  assert_int_equal(frames.msg[i].u.nack.reason, GP_NACK_BAD_ARGUMENT);
  assert_int_equal(core.frame_rate_hz, 250);
}

static void firmware_rates_full_queue_drops_and_counts(void **state) {
  (void)state;
  /* A line far slower than the stream (as if the host stopped reading):
   * the transmit queue fills, frames are dropped whole and counted, and
   * the sequence numbers still count every frame due. */
  fake.baud = 9600;
  fake_run(&core, 2000);
  assert_true(core.dropped_frames > 0);
  assert_int_equal(fake.tx_overflow, 0);
  fake_decode();
  assert_int_equal(frames.c.crc_errors + frames.c.framing_errors, 0);
  assert_true(frames.c.lost > 0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test_setup(firmware_rates_sample_wire_size, setup),
    cmocka_unit_test_setup(firmware_rates_250hz_at_115200_under_half, setup),
    cmocka_unit_test_setup(firmware_rates_1000hz_at_921600, setup),
    cmocka_unit_test_setup(firmware_rates_1000hz_refused_at_115200, setup),
    cmocka_unit_test_setup(firmware_rates_full_queue_drops_and_counts, setup),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

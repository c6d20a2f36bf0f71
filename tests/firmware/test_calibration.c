/* Calibration: captured between CAL_START and CAL_SAVE (or between pressing
 * and releasing the button), stored with a version and a CRC, restored after
 * a reset; a corrupt record falls back to the defaults and INFO says
 * CORRUPT. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fake_hal.h"
#include "fw_hal.h"

static fw_core core;

static int setup(void **state) {
  (void)state;
  fake_reset();
  fw_core_init(&core);
  fake_run(&core, 5);
  return 0;
}

static void cmd(uint8_t type, uint8_t tag) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = type;
  m.u.ping.tag = tag;
  fake_send(&m);
  fake_run(&core, 20); /* long enough for the reply and an INFO to leave the line */
}

/* The reply to the newest command: 1 ACK, or the NACK reason + 100. */
static int last_reply(void) {
  fake_decode();
  for (size_t i = frames.n; i-- > 0;) {
    if (frames.msg[i].type == GP_ACK) return 1;
    if (frames.msg[i].type == GP_NACK) return 100 + frames.msg[i].u.nack.reason;
  }
  return 0;
}

static const gp_info *last_info(void) {
  cmd(GP_GET_INFO, 99);
  fake_decode();
  for (size_t i = frames.n; i-- > 0;)
    if (frames.msg[i].type == GP_INFO) return &frames.msg[i].u.info;
  fail_msg("no INFO");
  return NULL;
}

/* Holds every string at lo, moves it to hi, holds it there, and back. */
static void sweep(uint16_t lo, uint16_t hi) {
  for (unsigned t = 0; t < 800; t++) {
    unsigned v = t < 100   ? lo
                 : t < 300 ? lo + (hi - lo) * (t - 100) / 199u
                 : t < 500 ? hi
                           : hi - (hi - lo) * (t - 500) / 299u;
    for (unsigned c = 0; c < FW_N_CH; c++) fake.level[c] = (uint16_t)(v + 10 * c);
    fake_run(&core, 1);
  }
}

static void firmware_calibration_save_survives_reset(void **state) {
  (void)state;
  cmd(GP_CAL_START, 1);
  assert_int_equal(last_reply(), 1);
  assert_int_equal(last_info()->cal_state, GP_CAL_RUNNING);
  sweep(500, 3500);
  cmd(GP_CAL_SAVE, 2);
  assert_int_equal(last_reply(), 1);
  assert_int_equal(fake.flash_writes, 1);
  const gp_info *info = last_info();
  assert_int_equal(info->cal_state, GP_CAL_VALID);
  for (unsigned c = 0; c < FW_N_CH; c++) {
    /* Held long enough for the filter to settle on both extremes; a
     * first-order filter never overshoots them. */
    assert_int_equal(info->cal_min[c], 500 + 10 * c);
    assert_int_equal(info->cal_max[c], 3500 + 10 * c);
  }
  uint16_t min0 = info->cal_min[0], max4 = info->cal_max[4];
  fake_run(&core, 10);
  fake_decode();
  size_t s = frames.n;
  while (s-- > 0 && frames.msg[s].type != GP_SAMPLE) {
  }
  assert_true(frames.msg[s].u.sample.flags & GP_SAMPLE_F_CALIBRATED);

  /* Reset: a fresh core over the same flash. */
  fake.wire_len = 0;
  fake.txq_len = 0;
  fw_core_init(&core);
  fake_run(&core, 5);
  info = last_info();
  assert_int_equal(info->cal_state, GP_CAL_VALID);
  assert_int_equal(info->cal_min[0], min0);
  assert_int_equal(info->cal_max[4], max4);
}

static void firmware_calibration_corrupt_record_falls_back(void **state) {
  (void)state;
  uint16_t lo[FW_N_CH] = { 300, 310, 320, 330, 340 },
           hi[FW_N_CH] = { 3000, 3010, 3020, 3030, 3040 };
  uint8_t rec[FW_CAL_RECORD_LEN], copy[FW_CAL_RECORD_LEN];
  uint16_t a[FW_N_CH], b[FW_N_CH];
  fw_cal_record_write(lo, hi, rec);
  assert_int_equal(fw_cal_record_read(rec, a, b), GP_CAL_VALID);
  assert_int_equal(a[3], 330);
  assert_int_equal(b[4], 3040);
  /* Every single-bit error anywhere in the record is caught. */
  for (unsigned i = 0; i < FW_CAL_RECORD_LEN * 8u; i++) {
    memcpy(copy, rec, sizeof rec);
    copy[i / 8] ^= (uint8_t)(1u << (i % 8));
    assert_int_equal(fw_cal_record_read(copy, a, b), GP_CAL_CORRUPT);
  }
  /* Erased flash is "never calibrated", not corrupt. */
  memset(copy, 0xFF, sizeof copy);
  assert_int_equal(fw_cal_record_read(copy, a, b), GP_CAL_DEFAULTS);
  /* A good CRC over an impossible range is still refused. */
  uint16_t bad_hi[FW_N_CH] = { 3000, 3010, 320, 3030, 3040 };
  fw_cal_record_write(lo, bad_hi, copy);
  assert_int_equal(fw_cal_record_read(copy, a, b), GP_CAL_CORRUPT);

  /* Through the core: a corrupt page boots with defaults and says so. */
  memcpy(fake.flash, rec, sizeof rec);
  fake.flash[9] ^= 0x04;
  fw_core_init(&core);
  fake_run(&core, 5);
  const gp_info *info = last_info();
  assert_int_equal(info->cal_state, GP_CAL_CORRUPT);
  assert_int_equal(info->cal_min[2], 0);
  assert_int_equal(info->cal_max[2], FW_ADC_MAX);
  fake_decode();
  size_t s = fake_find(0, GP_SAMPLE);
  assert_true(s < frames.n);
  assert_int_equal(frames.msg[s].u.sample.flags & GP_SAMPLE_F_CALIBRATED, 0);

  /* And the intact record loads. */
  memcpy(fake.flash, rec, sizeof rec);
  fw_core_init(&core);
  fake_run(&core, 5);
  info = last_info();
  assert_int_equal(info->cal_state, GP_CAL_VALID);
  assert_int_equal(info->cal_min[1], 310);
}

static void firmware_calibration_refusals(void **state) {
  (void)state;
  cmd(GP_CAL_SAVE, 1);
  assert_int_equal(last_reply(), 100 + GP_NACK_BAD_STATE);
  cmd(GP_CAL_START, 2);
  fake_run(&core, 50); /* the strings never move */
  cmd(GP_CAL_SAVE, 3);
  assert_int_equal(last_reply(), 100 + GP_NACK_BAD_ARGUMENT);
  assert_int_equal(last_info()->cal_state, GP_CAL_RUNNING);
  sweep(1000, 2000);
  fake.flash_fail_write = 1;
  cmd(GP_CAL_SAVE, 4);
  assert_int_equal(last_reply(), 100 + GP_NACK_FLASH_ERROR);
  cmd(GP_CAL_CLEAR, 5);
  assert_int_equal(last_reply(), 100 + GP_NACK_FLASH_ERROR);
  fake.flash_fail_write = 0;
  cmd(GP_CAL_START, 6);
  sweep(1000, 2000);
  cmd(GP_CAL_SAVE, 7);
  assert_int_equal(last_reply(), 1);
  cmd(GP_CAL_CLEAR, 8);
  assert_int_equal(last_reply(), 1);
  assert_int_equal(last_info()->cal_state, GP_CAL_DEFAULTS);
  for (unsigned i = 0; i < FW_CAL_RECORD_LEN; i++) assert_int_equal(fake.flash[i], 0xFF);
  assert_int_equal(core.cmd_errors, 4);
}

/* A refused CAL_CLEAR changes nothing: the stored range stays in use. */
static void firmware_calibration_failed_clear_keeps_the_calibration(void **state) {
  (void)state;
  cmd(GP_CAL_START, 1);
  sweep(700, 3300);
  cmd(GP_CAL_SAVE, 2);
  assert_int_equal(last_reply(), 1);
  fake.flash_fail_write = 1;
  cmd(GP_CAL_CLEAR, 3);
  assert_int_equal(last_reply(), 100 + GP_NACK_FLASH_ERROR);
  const gp_info *info = last_info();
  assert_int_equal(info->cal_state, GP_CAL_VALID);
  assert_int_equal(info->cal_min[0], 700);
  assert_int_equal(info->cal_max[4], 3340);
  fake_decode();
  size_t s = frames.n;
  while (s-- > 0 && frames.msg[s].type != GP_SAMPLE) {
  }
  assert_true(frames.msg[s].u.sample.flags & GP_SAMPLE_F_CALIBRATED);
  /* The record is still in flash, and a retry that works clears it. */
  fake.flash_fail_write = 0;
  cmd(GP_CAL_CLEAR, 4);
  assert_int_equal(last_reply(), 1);
  assert_int_equal(last_info()->cal_state, GP_CAL_DEFAULTS);
}

static void firmware_calibration_board_without_storage(void **state) {
  (void)state;
  fake.flash_absent = 1;
  fw_core_init(&core);
  fake_run(&core, 5);
  assert_int_equal(last_info()->cal_state, GP_CAL_DEFAULTS);
  cmd(GP_CAL_START, 1);
  sweep(1000, 3000);
  cmd(GP_CAL_SAVE, 2);
  assert_int_equal(last_reply(), 100 + GP_NACK_FLASH_ERROR);
}

static void firmware_calibration_by_button(void **state) {
  (void)state;
  /* Press: the capture starts (after the debounce time). */
  fake.button = 1;
  fake_run(&core, FW_BUTTON_DEBOUNCE_TICKS - 2);
  assert_int_equal(core.cal.state, GP_CAL_DEFAULTS);
  fake_run(&core, 5);
  assert_int_equal(core.cal.state, GP_CAL_RUNNING);
  /* Fast blink while capturing: the LED changes every 100 ticks. */
  int led0 = fake.led;
  fake_run(&core, 100);
  assert_int_not_equal(fake.led, led0);
  sweep(800, 3200);
  /* A bounce shorter than the debounce time does nothing. */
  fake.button = 0;
  fake_run(&core, FW_BUTTON_DEBOUNCE_TICKS / 2);
  fake.button = 1;
  fake_run(&core, FW_BUTTON_DEBOUNCE_TICKS + 5);
  assert_int_equal(core.cal.state, GP_CAL_RUNNING);
  assert_int_equal(fake.flash_writes, 0);
  /* Release: the capture is saved. */
  fake.button = 0;
  fake_run(&core, FW_BUTTON_DEBOUNCE_TICKS + 5);
  assert_int_equal(core.cal.state, GP_CAL_VALID);
  assert_int_equal(fake.flash_writes, 1);
  assert_int_equal(core.cal.min[0], 800);
  assert_int_equal(core.cal.max[4], 3240);
  /* The release sent an INFO announcing it. */
  fake_run(&core, 20);
  fake_decode();
  size_t i = frames.n;
  while (i-- > 0 && frames.msg[i].type != GP_INFO) {
  }
  assert_int_equal(frames.msg[i].u.info.cal_state, GP_CAL_VALID);
  assert_int_equal(frames.msg[i].u.info.cal_min[0], 800);
}

/* The button counts once it has read the same for FW_BUTTON_DEBOUNCE_TICKS
 * (20) ticks in a row, the first of them included: a press of 19 ticks is a
 * bounce, the 20th tick of a press starts the capture, and the 20th tick of
 * the release saves it. */
static void firmware_calibration_button_debounce_is_20_ticks(void **state) {
  (void)state;
  assert_int_equal(FW_BUTTON_DEBOUNCE_TICKS, 20);
  fake.button = 1;
  fake_run(&core, 19);
  fake.button = 0;
  fake_run(&core, 50);
  assert_int_equal(core.cal.state, GP_CAL_DEFAULTS);

  fake.button = 1;
  fake_run(&core, 19);
  assert_int_equal(core.cal.state, GP_CAL_DEFAULTS);
  fake_run(&core, 1);
  assert_int_equal(core.cal.state, GP_CAL_RUNNING);
  sweep(800, 3200);

  fake.button = 0;
  fake_run(&core, 19);
  assert_int_equal(core.cal.state, GP_CAL_RUNNING);
  assert_int_equal(fake.flash_writes, 0);
  fake_run(&core, 1);
  assert_int_equal(core.cal.state, GP_CAL_VALID);
  assert_int_equal(fake.flash_writes, 1);
}

/* A string that moved by exactly FW_CAL_MIN_SPAN counts is enough; one count
 * less is refused. Directly, and through CAL_SAVE with the filter between. */
static void firmware_calibration_accepts_a_span_of_exactly_the_minimum(void **state) {
  (void)state;
  fw_cal cal;
  fw_cal_load(&cal);
  for (unsigned short_ch = 0; short_ch < FW_N_CH; short_ch++) {
    uint16_t lo[FW_N_CH], hi[FW_N_CH];
    for (unsigned c = 0; c < FW_N_CH; c++) {
      lo[c] = (uint16_t)(1000 + 100 * c);
      hi[c] = (uint16_t)(lo[c] + FW_CAL_MIN_SPAN - (c == short_ch ? 1u : 0u));
    }
    fw_cal_start(&cal);
    fw_cal_feed(&cal, lo);
    fw_cal_feed(&cal, hi);
    assert_int_equal(fw_cal_save(&cal), FW_CAL_ERR_SPAN);
    assert_int_equal(cal.state, GP_CAL_RUNNING);
  }
  uint16_t lo[FW_N_CH], hi[FW_N_CH];
  for (unsigned c = 0; c < FW_N_CH; c++) {
    lo[c] = (uint16_t)(1000 + 100 * c);
    hi[c] = (uint16_t)(lo[c] + FW_CAL_MIN_SPAN);
  }
  fw_cal_start(&cal);
  fw_cal_feed(&cal, lo);
  fw_cal_feed(&cal, hi);
  assert_int_equal(fw_cal_save(&cal), FW_CAL_OK);
  assert_int_equal(cal.state, GP_CAL_VALID);
  assert_int_equal(cal.min[2], 1200);
  assert_int_equal(cal.max[2], 1200 + FW_CAL_MIN_SPAN);

  cmd(GP_CAL_START, 1);
  sweep(2000, (uint16_t)(2000 + FW_CAL_MIN_SPAN));
  cmd(GP_CAL_SAVE, 2);
  assert_int_equal(last_reply(), 1);
  const gp_info *info = last_info();
  assert_int_equal(info->cal_state, GP_CAL_VALID);
  for (unsigned c = 0; c < FW_N_CH; c++)
    assert_int_equal(info->cal_max[c] - info->cal_min[c], FW_CAL_MIN_SPAN);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test_setup(firmware_calibration_save_survives_reset, setup),
    cmocka_unit_test_setup(firmware_calibration_corrupt_record_falls_back, setup),
    cmocka_unit_test_setup(firmware_calibration_refusals, setup),
    cmocka_unit_test_setup(firmware_calibration_failed_clear_keeps_the_calibration, setup),
    cmocka_unit_test_setup(firmware_calibration_board_without_storage, setup),
    cmocka_unit_test_setup(firmware_calibration_by_button, setup),
    cmocka_unit_test_setup(firmware_calibration_button_debounce_is_20_ticks, setup),
    cmocka_unit_test_setup(firmware_calibration_accepts_a_span_of_exactly_the_minimum, setup),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

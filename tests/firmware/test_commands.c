/* Every command in messages.def gets its ACK or NACK; garbage, unknown,
 * oversize, wrong-spec and broken commands get a NACK or silence, and the
 * SAMPLE stream runs on through all of it without losing a frame. */
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
  fake_run(&core, 10);
  return 0;
}

static void send_cmd(uint8_t type, uint8_t tag) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = type;
  m.u.ping.tag = tag;
  fake_send(&m);
}

/* The reply frames (ACK/NACK) after wire offset from. */
static size_t reply_after(size_t from_wire, uint8_t type) {
  fake_decode();
  for (size_t i = 0; i < frames.n; i++)
    if (frames.end[i] > from_wire && frames.ev[i] == GP_EV_FRAME && frames.msg[i].type == type)
      return i;
  return frames.n;
}

static void expect_ack(uint8_t type, uint8_t tag, size_t *idx) {
  size_t from = fake.wire_len;
  send_cmd(type, tag);
  fake_run(&core, 20);
  size_t i = reply_after(from, GP_ACK);
  assert_true(i < frames.n);
  assert_int_equal(frames.msg[i].u.ack.tag, tag);
  assert_int_equal(frames.msg[i].u.ack.cmd, type);
  assert_int_equal(reply_after(from, GP_NACK), frames.n);
  if (idx) *idx = i;
}

static void expect_nack_raw(const uint8_t *wire, size_t n, uint8_t tag, uint8_t cmd,
                            uint8_t reason) {
  size_t from = fake.wire_len;
  fake_rx(wire, n);
  fake_run(&core, 20);
  size_t i = reply_after(from, GP_NACK);
  assert_true(i < frames.n);
  assert_int_equal(frames.msg[i].u.nack.tag, tag);
  assert_int_equal(frames.msg[i].u.nack.cmd, cmd);
  assert_int_equal(frames.msg[i].u.nack.reason, reason);
}

static void set_rate(uint8_t tag, uint16_t rate, uint32_t baud) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SET_RATE;
  m.u.set_rate.tag = tag;
  m.u.set_rate.frame_rate_hz = rate;
  m.u.set_rate.baud = baud;
  fake_send(&m);
}

/* A frame with a good CRC under our spec: type, payload bytes. */
static size_t raw_frame(uint8_t type, const uint8_t *payload, size_t len, uint32_t hash,
                        uint8_t *wire) {
  uint8_t raw[64];
  raw[0] = type;
  memcpy(raw + 1, payload, len);
  uint32_t crc = gp_frame_crc(hash, raw, 1 + len);
  for (int k = 0; k < 4; k++) raw[1 + len + k] = (uint8_t)(crc >> (8 * k));
  size_t n = gp_cobs_encode(raw, 1 + len + 4, wire, 80);
  wire[n] = 0;
  return n + 1;
}

static void firmware_commands_ping_and_info(void **state) {
  (void)state;
  size_t i;
  expect_ack(GP_PING, 7, NULL);
  expect_ack(GP_GET_INFO, 8, &i);
  size_t j = fake_find(i + 1, GP_INFO);
  assert_true(j < frames.n);
  const gp_info *info = &frames.msg[j].u.info;
  assert_int_equal(info->spec_hash, GP_SPEC_HASH);
  assert_int_equal(info->proto_major, GP_PROTO_MAJOR);
  assert_int_equal(info->frame_rate_hz, 250);
  assert_int_equal(info->baud, 115200);
  assert_int_equal(info->n_channels, 5);
  assert_int_equal(info->adc_bits, 12);
  assert_int_equal(info->sample_rate_hz, FW_TICK_HZ * FW_OVERSAMPLE);
  assert_int_equal(info->uid[2], 0x8899AABBu);
  assert_int_equal(info->cal_state, GP_CAL_DEFAULTS);
}

static void firmware_commands_set_rate(void **state) {
  (void)state;
  size_t i;
  uint8_t w[80];
  expect_ack(GP_PING, 1, NULL); /* line up */
  size_t from = fake.wire_len;
  set_rate(2, 100, 0);
  fake_run(&core, 100);
  i = reply_after(from, GP_ACK);
  assert_true(i < frames.n);
  assert_int_equal(frames.msg[i].u.ack.cmd, GP_SET_RATE);
  /* After the ACK the frames come every 10 ms. */
  size_t a = fake_find(i + 1, GP_SAMPLE), b = fake_find(a + 1, GP_SAMPLE);
  assert_true(b < frames.n);
  assert_int_equal(frames.msg[b].u.sample.t_us - frames.msg[a].u.sample.t_us, 10000u);

  /* Refused: not a divisor of 1000, zero, above the tick rate, more than
   * the link carries, and a baud rate the board does not offer. */
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SET_RATE;
  const struct {
    uint16_t rate;
    uint32_t baud;
  } bad[] = {
    { 3, 0 },        { 0, 0 },       { 2000, 921600 }, { 1000, 0 },
    { 500, 115200 }, { 250, 12345 }, { 250, 57600 },
  };
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    m.u.set_rate.tag = (uint8_t)(30 + k);
    m.u.set_rate.frame_rate_hz = bad[k].rate;
    m.u.set_rate.baud = bad[k].baud;
    size_t n = gp_encode(&m, GP_SPEC_HASH, w, sizeof w);
    expect_nack_raw(w, n, (uint8_t)(30 + k), GP_SET_RATE, GP_NACK_BAD_ARGUMENT);
  }
  assert_int_equal(core.frame_rate_hz, 100);
  assert_int_equal(fake.baud_changes, 0);
}

static void firmware_commands_stream_off_and_on(void **state) {
  (void)state;
  expect_ack(GP_STREAM_OFF, 3, NULL);
  size_t from = fake.wire_len;
  fake_run(&core, 2100);
  fake_decode();
  size_t samples = 0, infos = 0;
  for (size_t i = 0; i < frames.n; i++) {
    if (frames.end[i] <= from) continue;
    samples += frames.msg[i].type == GP_SAMPLE;
    infos += frames.msg[i].type == GP_INFO;
  }
  assert_int_equal(samples, 0);
  assert_int_equal(infos, 2);    /* INFO keeps its 1 Hz */
  assert_int_equal(fake.led, 1); /* steady on while not streaming */
  size_t ack;
  expect_ack(GP_STREAM_ON, 4, &ack);
  fake_run(&core, 100);
  fake_decode();
  /* An INFO goes first, then the SAMPLEs resume. */
  size_t first_info = fake_find(ack + 1, GP_INFO), first_sample = fake_find(ack + 1, GP_SAMPLE);
  assert_true(first_info < first_sample);
  assert_true(first_sample < frames.n);
  samples = 0;
  for (size_t i = ack; i < frames.n; i++) samples += frames.msg[i].type == GP_SAMPLE;
  assert_in_range(samples, 28, 31);
}

static void firmware_commands_get_status_counts(void **state) {
  (void)state;
  uint8_t w[80];
  /* The leading 0x00 puts the glove in step: a tail before it is no error. */
  const uint8_t junk[] = { 0x00, 0x55, 0x66, 0x77, 0x00 };
  fake_rx(junk, sizeof junk); /* one corrupt frame */
  uint8_t tag = 5;
  size_t n = raw_frame(0x7E, &tag, 1, GP_SPEC_HASH, w); /* one NACK */
  fake_rx(w, n);
  fake_run(&core, 10);
  size_t i;
  expect_ack(GP_GET_STATUS, 9, &i);
  size_t j = fake_find(i + 1, GP_STATUS);
  assert_true(j < frames.n);
  const gp_status *s = &frames.msg[j].u.status;
  assert_int_equal(s->cmd_errors, 2);
  assert_int_equal(s->overruns, 0);
  assert_int_equal(s->dropped_frames, 0);
  /* Every frame before the STATUS was queued before it. */
  assert_int_equal(s->frames_sent, j);
  assert_int_equal(s->t_us % 1000u, 0);
  assert_true(s->t_us > 0);
}

static void firmware_commands_bad_input_keeps_streaming(void **state) {
  (void)state;
  uint8_t w[600];
  size_t n;
  uint8_t p[GP_MAX_PAYLOAD] = { 0x42 };

  /* Answered with NACK: a valid frame of an unknown type, and a known
   * command of the wrong length. */
  n = raw_frame(0x7F, p, 1, GP_SPEC_HASH, w);
  expect_nack_raw(w, n, 0x42, 0x7F, GP_NACK_UNKNOWN_COMMAND);
  n = raw_frame(GP_PING, p, 2, GP_SPEC_HASH, w);
  expect_nack_raw(w, n, 0x42, GP_PING, GP_NACK_BAD_LENGTH);
  n = raw_frame(GP_SET_RATE, p, 3, GP_SPEC_HASH, w);
  expect_nack_raw(w, n, 0x42, GP_SET_RATE, GP_NACK_BAD_LENGTH);

  /* Silence: a glove-to-host frame, garbage, an oversize run, a foreign
   * spec, a bad CRC, a truncated frame, idle delimiters. */
  size_t from = fake.wire_len;
  n = raw_frame(GP_SAMPLE, p, GP_SAMPLE_LEN, GP_SPEC_HASH, w);
  fake_rx(w, n);
  uint32_t seed = 12345;
  for (size_t k = 0; k < 100; k++) {
    seed = seed * 1103515245u + 12345u;
    w[k] = (uint8_t)(1u + (seed >> 16) % 255u);
  }
  w[100] = 0;
  fake_rx(w, 101);
  memset(w, 0xAB, 500);
  w[500] = 0;
  fake_rx(w, 501);
  fake_run(&core, 40);
  n = raw_frame(GP_PING, p, 1, 0xDEADBEEFu, w);
  fake_rx(w, n);
  n = raw_frame(GP_PING, p, 1, GP_SPEC_HASH, w);
  w[2] ^= 0x10;
  fake_rx(w, n);
  n = raw_frame(GP_GET_INFO, p, 1, GP_SPEC_HASH, w);
  w[n - 3] = 0;
  fake_rx(w, n - 2);
  const uint8_t zeros[] = { 0, 0, 0 };
  fake_rx(zeros, sizeof zeros);
  fake_run(&core, 60);
  size_t stray = reply_after(from, GP_NACK);
  if (stray < frames.n)
    fail_msg("unexpected NACK cmd 0x%02x reason %u", frames.msg[stray].u.nack.cmd,
             frames.msg[stray].u.nack.reason);
  size_t stray_ack = reply_after(from, GP_ACK);
  assert_int_equal(stray_ack, frames.n);

  /* Then a good command is still understood. */
  expect_ack(GP_PING, 0x43, NULL);
  assert_int_equal(core.cmd_errors, 4 + 5);

  /* The stream never noticed: every SAMPLE present, 4 ms apart. */
  fake_decode();
  assert_int_equal(frames.c.lost + frames.c.crc_errors + frames.c.framing_errors, 0);
  size_t samples = 0;
  uint32_t prev = 0;
  for (size_t i = fake_find(0, GP_SAMPLE); i < frames.n; i = fake_find(i + 1, GP_SAMPLE)) {
    if (samples) assert_int_equal(frames.msg[i].u.sample.t_us - prev, 4000u);
    prev = frames.msg[i].u.sample.t_us;
    samples++;
  }
  assert_true(samples > 45);
  assert_int_equal(samples, core.seq);
}

/* TX wired to RX by mistake: the glove hears its own SAMPLE and INFO
 * frames. It must drop them quietly; a NACK for each would be heard too
 * and answered again, until replies crowd out the samples. */
static void firmware_commands_own_output_looped_back_is_ignored(void **state) {
  (void)state;
  fake_run(&core, 1200); /* SAMPLEs and an INFO or more */
  size_t echoed_from = 0, echoed_to = fake.wire_len;
  fake_decode();
  size_t echoed_frames = frames.n;
  assert_true(echoed_frames > 250);
  assert_true(fake_find(0, GP_INFO) < frames.n);
  uint32_t errors_before = core.cmd_errors;
  size_t from = fake.wire_len;
  /* Feed it back in pieces, as a line would, while the glove keeps running. */
  for (size_t off = echoed_from; off < echoed_to; off += 64) {
    size_t n = echoed_to - off < 64 ? echoed_to - off : 64;
    fake_rx(fake.wire + off, n);
    fake_run(&core, 2);
  }
  fake_run(&core, 200);
  /* reply_after decodes afresh: take its answer before reading frames.n. */
  size_t nack = reply_after(from, GP_NACK), ack = reply_after(from, GP_ACK);
  assert_int_equal(nack, frames.n);
  assert_int_equal(ack, frames.n);
  assert_int_equal(core.cmd_errors - errors_before, echoed_frames);
  fake_decode();
  assert_int_equal(frames.c.lost + frames.c.crc_errors + frames.c.framing_errors, 0);
}

/* The INFO sent after wire offset from, or frames.n. */
static size_t info_after(size_t from_wire) {
  return reply_after(from_wire, GP_INFO);
}

static void firmware_commands_a_command_without_payload_is_nacked_with_tag_0(void **state) {
  (void)state;
  uint8_t w[80];
  const uint8_t none[1] = { 0 };
  expect_nack_raw(w, raw_frame(GP_PING, none, 0, GP_SPEC_HASH, w), 0, GP_PING, GP_NACK_BAD_LENGTH);
  expect_nack_raw(w, raw_frame(0x7F, none, 0, GP_SPEC_HASH, w), 0, 0x7F, GP_NACK_UNKNOWN_COMMAND);
}

static void firmware_commands_an_undefined_glove_to_host_type_gets_silence(void **state) {
  (void)state;
  uint8_t w[80];
  const uint8_t p[1] = { 0x42 };
  uint32_t errors = core.cmd_errors;
  size_t from = fake.wire_len;
  /* 0x06..0x0F are glove to host, though undefined: never a NACK. */
  for (uint8_t type = GP_NACK + 1u; type < 0x10u; type++)
    fake_rx(w, raw_frame(type, p, 1, GP_SPEC_HASH, w));
  fake_run(&core, 40);
  size_t stray = reply_after(from, GP_NACK);
  if (stray < frames.n) fail_msg("NACK for type 0x%02x", frames.msg[stray].u.nack.cmd);
  assert_int_equal(reply_after(from, GP_ACK), frames.n);
  assert_int_equal(core.cmd_errors - errors, 0x10u - (GP_NACK + 1u));
}

static void firmware_commands_set_rate_keeping_the_baud_is_followed_by_info(void **state) {
  (void)state;
  const uint32_t bauds[] = { 0, FW_BAUD };
  for (size_t k = 0; k < 2; k++) {
    size_t from = fake.wire_len;
    set_rate((uint8_t)(20 + k), (uint16_t)(k ? 100 : 125), bauds[k]);
    fake_run(&core, 20); /* well before the periodic INFO */
    size_t ack = reply_after(from, GP_ACK), info = info_after(from);
    assert_true(ack < frames.n);
    assert_true(info < frames.n);
    assert_true(info > ack);
    assert_int_equal(frames.msg[info].u.info.frame_rate_hz, k ? 100 : 125);
    assert_int_equal(frames.msg[info].u.info.baud, FW_BAUD);
    assert_int_equal(fake.baud_changes, 0);
  }
}

static void firmware_commands_cal_start_save_and_clear_send_info_at_once(void **state) {
  (void)state;
  const struct {
    uint8_t cmd, state;
  } steps[] = { { GP_CAL_START, GP_CAL_RUNNING }, { GP_CAL_CLEAR, GP_CAL_DEFAULTS } };
  for (size_t k = 0; k < 2; k++) {
    size_t from = fake.wire_len;
    send_cmd(steps[k].cmd, (uint8_t)(30 + k));
    fake_run(&core, 20);
    size_t ack = reply_after(from, GP_ACK), info = info_after(from);
    assert_true(ack < frames.n);
    assert_int_equal(frames.msg[ack].u.ack.cmd, steps[k].cmd);
    assert_true(info < frames.n && info > ack);
    assert_int_equal(frames.msg[info].u.info.cal_state, steps[k].state);
  }
  /* A refused CAL_SAVE (no capture running) changed nothing: no INFO. */
  size_t from = fake.wire_len;
  send_cmd(GP_CAL_SAVE, 40);
  fake_run(&core, 3);
  assert_true(reply_after(from, GP_NACK) < frames.n);
  assert_int_equal(info_after(from), frames.n);
}

static void firmware_commands_cmd_errors_counts_each_refused_frame_once(void **state) {
  (void)state;
  uint8_t w[600];
  const uint8_t p[GP_MAX_PAYLOAD] = { 0x42 };
  uint32_t before = core.cmd_errors;
  fake_rx(w, raw_frame(0x7F, p, 1, GP_SPEC_HASH, w));                  /* NACK unknown */
  fake_rx(w, raw_frame(GP_PING, p, 2, GP_SPEC_HASH, w));               /* NACK length */
  fake_rx(w, raw_frame(GP_PING, p, 1, 0xDEADBEEFu, w));                /* foreign spec */
  fake_rx(w, raw_frame(GP_SAMPLE, p, GP_SAMPLE_LEN, GP_SPEC_HASH, w)); /* echo */
  size_t n = raw_frame(GP_PING, p, 1, GP_SPEC_HASH, w);
  w[2] ^= 0x10;
  fake_rx(w, n); /* bad CRC */
  memset(w, 0xAB, 500);
  w[500] = 0;
  fake_rx(w, 501); /* oversize */
  const uint8_t zeros[] = { 0, 0, 0 };
  fake_rx(zeros, sizeof zeros);                          /* empty frames: not counted */
  fake_rx(w, raw_frame(GP_PING, p, 1, GP_SPEC_HASH, w)); /* carried out */
  fake_run(&core, 80);
  assert_int_equal(core.cmd_errors - before, 6);
}

static void firmware_commands_a_reset_glove_is_one_restart_with_nothing_lost(void **state) {
  (void)state;
  /* About 25 frames: without the START flag, the new 0 would look like a
   * frame from 25 back, a duplicate. */
  fake_run(&core, 100);
  fake_decode();
  size_t first = fake_find(0, GP_SAMPLE);
  assert_true(first < frames.n);
  assert_true(frames.msg[first].u.sample.flags & GP_SAMPLE_F_START);
  for (size_t i = first + 1; i < frames.n; i++)
    if (frames.msg[i].type == GP_SAMPLE)
      assert_int_equal(frames.msg[i].u.sample.flags & GP_SAMPLE_F_START, 0);
  assert_int_equal(frames.c.duplicates + frames.c.seq_restarts, 0);
  /* A reset: the core starts again, the line and the host stay. */
  fw_core_init(&core);
  fake_run(&core, 100);
  fake_decode();
  assert_int_equal(frames.c.seq_restarts, 1);
  assert_int_equal(frames.c.lost, 0);
  assert_int_equal(frames.c.reordered + frames.c.duplicates, 0);
}

static void firmware_commands_a_tail_before_the_first_delimiter_is_no_error(void **state) {
  (void)state;
  /* The tail of a command the glove woke in the middle of. */
  const uint8_t tail[] = { 0x37, 0x42, 0x99, 0x05, 0x00 };
  uint32_t before = core.cmd_errors;
  fake_rx(tail, sizeof tail);
  expect_ack(GP_PING, 0x51, NULL);
  assert_int_equal(core.cmd_errors, before);
  /* The same bytes once the glove is in step are a corrupt frame. */
  fake_rx(tail, sizeof tail);
  fake_run(&core, 20);
  assert_int_equal(core.cmd_errors, before + 1);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test_setup(firmware_commands_ping_and_info, setup),
    cmocka_unit_test_setup(firmware_commands_own_output_looped_back_is_ignored, setup),
    cmocka_unit_test_setup(firmware_commands_set_rate, setup),
    cmocka_unit_test_setup(firmware_commands_stream_off_and_on, setup),
    cmocka_unit_test_setup(firmware_commands_get_status_counts, setup),
    cmocka_unit_test_setup(firmware_commands_bad_input_keeps_streaming, setup),
    cmocka_unit_test_setup(firmware_commands_a_command_without_payload_is_nacked_with_tag_0, setup),
    cmocka_unit_test_setup(firmware_commands_an_undefined_glove_to_host_type_gets_silence, setup),
    cmocka_unit_test_setup(firmware_commands_set_rate_keeping_the_baud_is_followed_by_info, setup),
    cmocka_unit_test_setup(firmware_commands_cal_start_save_and_clear_send_info_at_once, setup),
    cmocka_unit_test_setup(firmware_commands_cmd_errors_counts_each_refused_frame_once, setup),
    cmocka_unit_test_setup(firmware_commands_a_reset_glove_is_one_restart_with_nothing_lost, setup),
    cmocka_unit_test_setup(firmware_commands_a_tail_before_the_first_delimiter_is_no_error, setup),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

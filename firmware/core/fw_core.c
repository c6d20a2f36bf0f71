#include "fw_core.h"

#include "fw_frame.h"
#include "fw_hal.h"
#include "fw_link.h"

/* Received bytes handled per pass, so a flood of input cannot starve the
 * sampling schedule. */
#define FW_RX_BYTES_PER_POLL 32u

void fw_core_init(fw_core *c) {
  fw_filter_init(&c->filter);
  fw_cal_load(&c->cal);
  fw_rx_init(&c->rx);
  fw_hal_uid(c->uid);
  c->frame_rate_hz = FW_FRAME_RATE_HZ;
  c->baud = FW_BAUD;
  c->pending_baud = 0;
  c->streaming = 1;
  c->have_tick = 0;
  c->last_tick = 0;
  c->frame_phase = 0;
  c->info_phase = 0;
  c->seq = 0;
  c->seq_started = 0;
  for (unsigned i = 0; i < FW_N_CH; i++) c->ch[i] = 0;
  c->pending_flags = 0;
  c->button = 0;
  c->button_raw = 0;
  c->button_count = 0;
  c->frames_sent = 0;
  c->overruns = 0;
  c->dropped_frames = 0;
  c->cmd_errors = 0;
}

/* Queues a whole frame or none of it. While a baud change waits for the line
 * to drain, nothing new is queued: those frames would go out at the wrong
 * speed. */
static void send(fw_core *c, const uint8_t *wire, size_t n) {
  if (n == 0 || c->pending_baud != 0 || fw_hal_uart_tx_free() < n) {
    c->dropped_frames++;
    return;
  }
  fw_hal_uart_write(wire, n);
  c->frames_sent++;
}

static void send_info(fw_core *c) {
  fw_info_state s;
  s.fw_major = FW_VERSION_MAJOR;
  s.fw_minor = FW_VERSION_MINOR;
  s.fw_patch = FW_VERSION_PATCH;
  s.hand = FW_HAND;
  s.n_channels = FW_N_CH;
  s.adc_bits = FW_ADC_BITS;
  /* Conversions per channel per second, as INFO defines the field: the
   * tick rate times the oversampling. */
  s.sample_rate_hz = FW_TICK_HZ * FW_OVERSAMPLE;
  for (unsigned k = 0; k < 3; k++) s.uid[k] = c->uid[k];
  s.frame_rate_hz = c->frame_rate_hz;
  s.baud = c->baud;
  s.cal_state = c->cal.state;
  for (unsigned i = 0; i < FW_N_CH; i++) {
    s.cal_min[i] = c->cal.min[i];
    s.cal_max[i] = c->cal.max[i];
  }
  uint8_t wire[GP_MAX_WIRE];
  send(c, wire, fw_frame_info(&s, wire, sizeof wire));
}

static void send_status(fw_core *c) {
  fw_status_state s = {
    .t_us = c->last_tick * FW_TICK_US,
    .frames_sent = c->frames_sent,
    .overruns = c->overruns,
    .dropped_frames = c->dropped_frames,
    .cmd_errors = c->cmd_errors,
    .adc_timeouts = fw_hal_adc_timeouts(),
  };
  uint8_t wire[GP_MAX_WIRE];
  send(c, wire, fw_frame_status(&s, wire, sizeof wire));
}

static void send_ack(fw_core *c, uint8_t tag, uint8_t cmd) {
  uint8_t wire[GP_MAX_WIRE];
  send(c, wire, fw_frame_ack(tag, cmd, wire, sizeof wire));
}

static void send_nack(fw_core *c, uint8_t tag, uint8_t cmd, uint8_t reason) {
  uint8_t wire[GP_MAX_WIRE];
  c->cmd_errors++;
  send(c, wire, fw_frame_nack(tag, cmd, reason, wire, sizeof wire));
}

static void send_sample(fw_core *c) {
  uint8_t flags = c->pending_flags;
  if (c->cal.state == GP_CAL_VALID) flags |= GP_SAMPLE_F_CALIBRATED;
  if (c->button) flags |= GP_SAMPLE_F_BUTTON;
  /* The host tells a reset from loss or reordering by this flag, whatever
   * number the old sequence had reached (SPEC.md, "Sequence check"). */
  if (!c->seq_started) flags |= GP_SAMPLE_F_START;
  c->seq_started = 1;
  uint8_t wire[GP_MAX_WIRE];
  /* The device timestamp is the sampling tick's, not the time the main loop
   * got to it: loop latency never shows as jitter. */
  size_t n = fw_frame_sample(c->seq, c->last_tick * FW_TICK_US, c->ch, flags, wire, sizeof wire);
  /* The sequence number counts frames due, sent or not, so the host sees
   * every frame the link could not carry as lost. */
  c->seq++;
  c->pending_flags = 0;
  send(c, wire, n);
}

/* The reply to a calibration command, from what the calibration did. A
 * change of calibration is announced at once by an INFO, as the button's is
 * (SPEC.md, CAL_START to CAL_CLEAR); a refusal changed nothing. */
static void reply_cal(fw_core *c, uint8_t tag, uint8_t cmd, fw_cal_result r) {
  switch (r) {
  case FW_CAL_OK:
    send_ack(c, tag, cmd);
    send_info(c);
    break;
  case FW_CAL_ERR_STATE:
    send_nack(c, tag, cmd, GP_NACK_BAD_STATE);
    break;
  case FW_CAL_ERR_SPAN:
    send_nack(c, tag, cmd, GP_NACK_BAD_ARGUMENT);
    break;
  default:
    send_nack(c, tag, cmd, GP_NACK_FLASH_ERROR);
    break;
  }
}

static void set_rate(fw_core *c, const gp_set_rate *r) {
  uint32_t baud = r->baud != 0 ? r->baud : c->baud;
  if ((r->baud != 0 && !fw_link_baud_ok(r->baud)) || !fw_link_rate_ok(r->frame_rate_hz, baud)) {
    send_nack(c, r->tag, GP_SET_RATE, GP_NACK_BAD_ARGUMENT);
    return;
  }
  send_ack(c, r->tag, GP_SET_RATE);
  c->frame_rate_hz = r->frame_rate_hz;
  /* INFO follows every accepted SET_RATE: at once when the baud stays, as
   * the first frame at the new speed otherwise (fw_core_poll). */
  if (baud != c->baud)
    c->pending_baud = baud;
  else
    send_info(c);
}

static void command(fw_core *c, const gp_msg *m) {
  /* Every command's first field is its tag; PING's layout stands for all. */
  uint8_t tag = m->u.ping.tag;
  switch (m->type) {
  case GP_PING:
    send_ack(c, tag, GP_PING);
    break;
  case GP_GET_INFO:
    send_ack(c, tag, GP_GET_INFO);
    send_info(c);
    break;
  case GP_SET_RATE:
    set_rate(c, &m->u.set_rate);
    break;
  case GP_STREAM_ON:
    c->streaming = 1;
    send_ack(c, tag, GP_STREAM_ON);
    send_info(c); /* SPEC.md: an INFO goes first */
    break;
  case GP_STREAM_OFF:
    c->streaming = 0;
    send_ack(c, tag, GP_STREAM_OFF);
    break;
  case GP_CAL_START:
    fw_cal_start(&c->cal);
    reply_cal(c, tag, GP_CAL_START, FW_CAL_OK);
    break;
  case GP_CAL_SAVE:
    reply_cal(c, tag, GP_CAL_SAVE, fw_cal_save(&c->cal));
    break;
  case GP_CAL_CLEAR:
    reply_cal(c, tag, GP_CAL_CLEAR, fw_cal_clear(&c->cal));
    break;
  case GP_GET_STATUS:
    send_ack(c, tag, GP_GET_STATUS);
    send_status(c);
    break;
  default:
    /* fw_rx only passes host-direction types; a new one lands here until
     * this switch learns it. */
    send_nack(c, tag, m->type, GP_NACK_UNKNOWN_COMMAND);
    break;
  }
}

/* The button (SPEC.md, CAL_SAVE): pressing it starts a calibration capture,
 * releasing it saves the capture. Each change is announced by an INFO sent at
 * once (a refused save keeps capturing, and the INFO says RUNNING). */
static void button_tick(fw_core *c) {
  uint8_t raw = fw_hal_button() ? 1 : 0;
  /* button_count counts the ticks in a row that read raw, this one
   * included: the change is taken on the FW_BUTTON_DEBOUNCE_TICKS-th. */
  if (raw != c->button_raw) {
    c->button_raw = raw;
    c->button_count = 1;
  } else if (c->button_count < FW_BUTTON_DEBOUNCE_TICKS) {
    c->button_count++;
  }
  if (raw == c->button || c->button_count < FW_BUTTON_DEBOUNCE_TICKS) return;
  c->button = raw;
  if (raw)
    fw_cal_start(&c->cal);
  else if (c->cal.state == GP_CAL_RUNNING)
    (void)fw_cal_save(&c->cal);
  else
    return;
  send_info(c);
}

/* What the LED says (firmware/README.md): fast blink while calibrating, slow
 * blink while streaming, steady on while the stream is off. */
static void led_tick(fw_core *c) {
  uint32_t ms = c->last_tick * (1000u / FW_TICK_HZ);
  int on;
  if (c->cal.state == GP_CAL_RUNNING)
    on = (ms / 100u) % 2u == 0;
  else if (c->streaming)
    on = (ms / 500u) % 2u == 0;
  else
    on = 1;
  fw_hal_led(on);
}

static void tick(fw_core *c, const uint16_t block[FW_BLOCK_LEN], uint32_t t) {
  uint32_t elapsed = 1;
  int first = !c->have_tick;
  if (!first) {
    elapsed = t - c->last_tick;
    /* A block from before the last one cannot happen with a working queue;
     * ignore it rather than run time backwards. */
    if (elapsed == 0 || elapsed > 0x80000000u) return;
    if (elapsed > 1) {
      c->overruns += elapsed - 1u;
      c->pending_flags |= GP_SAMPLE_F_OVERRUN;
    }
  }
  c->have_tick = 1;
  c->last_tick = t;
  if (fw_filter_block(&c->filter, block, c->ch)) c->pending_flags |= GP_SAMPLE_F_CLIPPED;
  fw_cal_feed(&c->cal, c->ch);
  button_tick(c);
  led_tick(c);

  /* Each schedule counts ticks since its last nominal boundary, so a missed
   * tick delays one frame by at most the ticks missed and the next frames
   * are back on the grid. INFO goes first: a host that starts listening
   * learns the spec at once. */
  uint32_t period = FW_TICK_HZ / c->frame_rate_hz;
  int info_due = first, frame_due = first;
  if (!first) {
    c->info_phase += elapsed;
    if (c->info_phase >= FW_INFO_PERIOD_TICKS) {
      info_due = 1;
      c->info_phase %= FW_INFO_PERIOD_TICKS;
    }
    c->frame_phase += elapsed;
    if (c->frame_phase >= period) {
      frame_due = 1;
      c->frame_phase %= period;
    }
  }
  if (info_due) send_info(c);
  if (frame_due && c->streaming) send_sample(c);
}

void fw_core_poll(fw_core *c) {
  uint16_t block[FW_BLOCK_LEN];
  uint32_t t;
  for (unsigned i = 0; i < FW_BLOCKQ_DEPTH && fw_hal_adc_take(block, &t); i++) tick(c, block, t);

  uint8_t byte;
  for (unsigned i = 0; i < FW_RX_BYTES_PER_POLL && fw_hal_uart_read(&byte); i++) {
    fw_rx_frame fr;
    switch (fw_rx_byte(&c->rx, byte, &fr)) {
    case FW_RX_COMMAND:
      command(c, &fr.msg);
      break;
    case FW_RX_NACK:
      send_nack(c, fr.tag, fr.cmd, fr.reason);
      break;
    case FW_RX_CORRUPT:
    case FW_RX_ECHO:
      c->cmd_errors++;
      break;
    default:
      break;
    }
  }

  if (c->pending_baud != 0 && fw_hal_uart_tx_idle()) {
    fw_hal_uart_set_baud(c->pending_baud);
    c->baud = c->pending_baud;
    c->pending_baud = 0;
    send_info(c); /* the first frame at the new speed says what it is */
  }
  fw_hal_watchdog_kick();
}

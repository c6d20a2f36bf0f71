#include "fake_hal.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fw_hal.h"

fake_hal fake;

void fake_reset(void) {
  memset(&fake, 0, sizeof fake);
  fw_blockq_init(&fake.q);
  for (unsigned c = 0; c < FW_N_CH; c++) fake.level[c] = 2048;
  fake.baud = FW_BAUD;
  memset(fake.flash, 0xFF, sizeof fake.flash);
  fake.uid[0] = 0x00112233u;
  fake.uid[1] = 0x44556677u;
  fake.uid[2] = 0x8899AABBu;
}

void fake_sample_at(uint32_t tick) {
  uint16_t *slot = fw_blockq_slot(&fake.q);
  if (slot == NULL) { /* lost, as on a board: the tick gap tells the core */
    fake.blocks_lost++;
    return;
  }
  for (unsigned s = 0; s < FW_OVERSAMPLE; s++)
    for (unsigned c = 0; c < FW_N_CH; c++) slot[s * FW_N_CH + c] = fake.level[c];
  fw_blockq_commit(&fake.q, tick);
}

static void sample(void) {
  fake_sample_at(fake.tick);
  fake.tick++;
}

/* The line carries baud / 10 bytes a second at 8N1. */
static void line(void) {
  fake.line_bits += (uint64_t)fake.baud * 1000u / FW_TICK_HZ;
  while (fake.txq_len > 0 && fake.line_bits >= 10u * 1000u) {
    fake.line_bits -= 10u * 1000u;
    if (fake.wire_len < FAKE_WIRE_CAP) fake.wire[fake.wire_len++] = fake.txq[0];
    memmove(fake.txq, fake.txq + 1, --fake.txq_len);
  }
  if (fake.txq_len == 0) fake.line_bits = 0; /* an idle line saves nothing up */
}

void fake_step(fw_core *c, int skip_sample, unsigned polls) {
  if (skip_sample)
    fake.tick++;
  else
    sample();
  for (unsigned i = 0; i < polls; i++) fw_core_poll(c);
  line();
}

void fake_run(fw_core *c, unsigned ticks) {
  for (unsigned i = 0; i < ticks; i++) fake_step(c, 0, 1);
}

void fake_rx(const uint8_t *data, size_t n) {
  /* Keep the unread bytes, drop the read ones; a test that queues more than
   * the line can hold is wrong, and says so rather than overrunning. */
  memmove(fake.rx, fake.rx + fake.rx_pos, fake.rx_len - fake.rx_pos);
  fake.rx_len -= fake.rx_pos;
  fake.rx_pos = 0;
  if (n > sizeof fake.rx - fake.rx_len)
    fail_msg("fake_rx: %zu bytes queued on top of %zu unread overflow the %zu-byte line", n,
             fake.rx_len, sizeof fake.rx);
  memcpy(fake.rx + fake.rx_len, data, n);
  fake.rx_len += n;
}

fake_frames frames;

void fake_decode(void) {
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  frames.n = 0;
  size_t off = 0;
  while (off < fake.wire_len && frames.n < FAKE_MAX_FRAMES) {
    gp_event ev = GP_EV_NONE;
    gp_msg m;
    memset(&m, 0, sizeof m);
    off += gp_decoder_feed(&d, fake.wire + off, fake.wire_len - off, &m, &ev);
    if (ev == GP_EV_NONE) continue;
    frames.msg[frames.n] = m;
    frames.ev[frames.n] = ev;
    frames.end[frames.n] = off;
    frames.n++;
  }
  frames.c = d.c;
}

size_t fake_find(size_t from, uint8_t type) {
  for (size_t i = from; i < frames.n; i++)
    if (frames.ev[i] == GP_EV_FRAME && frames.msg[i].type == type) return i;
  return frames.n;
}

void fake_send(const gp_msg *m) {
  uint8_t wire[GP_MAX_WIRE];
  size_t n = gp_encode(m, GP_SPEC_HASH, wire, sizeof wire);
  fake_rx(wire, n);
}

/* --- fw_hal.h ------------------------------------------------------------- */

int fw_hal_adc_take(uint16_t block[FW_BLOCK_LEN], uint32_t *tick) {
  return fw_blockq_take(&fake.q, block, tick);
}

uint32_t fw_hal_adc_timeouts(void) {
  return fake.adc_timeouts;
}

size_t fw_hal_uart_tx_free(void) {
  return FW_TXQ_BYTES - fake.txq_len;
}

void fw_hal_uart_write(const uint8_t *data, size_t n) {
  /* The core promised to respect tx_free; overflowing here is a core bug. */
  if (n > FW_TXQ_BYTES - fake.txq_len) {
    fake.tx_overflow = 1;
    return;
  }
  memcpy(fake.txq + fake.txq_len, data, n);
  fake.txq_len += n;
}

int fw_hal_uart_tx_idle(void) {
  return fake.txq_len == 0;
}

int fw_hal_uart_read(uint8_t *byte) {
  if (fake.rx_pos >= fake.rx_len) return 0;
  *byte = fake.rx[fake.rx_pos++];
  return 1;
}

void fw_hal_uart_set_baud(uint32_t baud) {
  fake.baud = baud;
  fake.baud_changes++;
}

int fw_hal_flash_read(void *data, size_t len) {
  if (fake.flash_absent || len > sizeof fake.flash) return -1;
  memcpy(data, fake.flash, len);
  return 0;
}

int fw_hal_flash_write(const void *data, size_t len) {
  if (fake.flash_absent || fake.flash_fail_write || len > sizeof fake.flash) return -1;
  memset(fake.flash, 0xFF, sizeof fake.flash);
  memcpy(fake.flash, data, len);
  fake.flash_writes++;
  return 0;
}

int fw_hal_flash_erase(void) {
  if (fake.flash_absent) return 0;
  if (fake.flash_fail_write) return -1;
  memset(fake.flash, 0xFF, sizeof fake.flash);
  return 0;
}

void fw_hal_led(int on) {
  fake.led = on;
}
int fw_hal_button(void) {
  return fake.button;
}
void fw_hal_watchdog_kick(void) {}
void fw_hal_uid(uint32_t uid[3]) {
  memcpy(uid, fake.uid, sizeof fake.uid);
}

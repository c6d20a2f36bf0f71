/* libFuzzer target for the firmware's command path: the input is what a
 * host sends to the glove, fed through fw_rx and the core's command
 * handling while the glove samples and streams, on a simulated board of
 * its own (below): a ramp on the ADC, a line that drains at the glove's
 * baud rate, a flash page in memory.
 *
 * Each input runs twice on a fresh glove: as the bytes on the line, and as
 * a list of frames the target completes with the right CRC and framing
 * (frame_input), so that mutations get past the CRC to the commands.
 *
 * Besides the sanitizers, it holds the glove to what firmware/README.md
 * promises whatever arrives:
 *   - everything it sends decodes as valid frames of its own spec, of
 *     glove-to-host types only, and every frame it counts as sent arrives;
 *   - it never queues more than the transmit queue has room for, and the
 *     line drains;
 *   - it answers at most one ACK or NACK per frame the host ended with a
 *     0x00, counts at most one cmd_error per frame, ACKs only host
 *     commands, and never NACKs a glove-to-host frame (its own frames
 *     echoed back get silence);
 *   - time goes on: every tick of the run is processed, none lost.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fw_blockq.h"
#include "fw_core.h"
#include "fw_hal.h"
#include "gp.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check(int cond) {
  if (!cond) abort();
}

/* --- the simulated board -------------------------------------------------- */

static struct {
  fw_blockq q;
  uint32_t tick;
  const uint8_t *rx;
  size_t rx_len, rx_pos;
  uint8_t txq[FW_TXQ_BYTES];
  size_t txq_len;
  uint32_t baud;
  uint64_t line_bits; /* bit times the line may still carry, x1000 */
  uint8_t flash[FW_CAL_RECORD_LEN];
  gp_decoder dec;
  uint32_t frames_out, replies_out;
} board;

static void board_reset(const uint8_t *data, size_t size) {
  memset(&board, 0, sizeof board);
  fw_blockq_init(&board.q);
  board.rx = data;
  board.rx_len = size;
  board.baud = FW_BAUD;
  memset(board.flash, 0xFF, sizeof board.flash);
  gp_decoder_init(&board.dec, GP_SPEC_HASH);
}

/* One tick's block: every channel on a ramp that sweeps the ADC range, so a
 * calibration can succeed. */
static void board_sample(void) {
  uint16_t *slot = fw_blockq_slot(&board.q);
  if (slot != NULL) {
    for (unsigned s = 0; s < FW_OVERSAMPLE; s++)
      for (unsigned c = 0; c < FW_N_CH; c++)
        slot[s * FW_N_CH + c] = (uint16_t)((board.tick * 97u + c * 400u + s) % 4096u);
    fw_blockq_commit(&board.q, board.tick);
  }
  board.tick++;
}

/* A byte leaves the line: the host's decoder takes it. */
static void board_wire(uint8_t byte) {
  gp_msg m;
  gp_event ev = GP_EV_NONE;
  check(gp_decoder_feed(&board.dec, &byte, 1, &m, &ev) == 1);
  if (ev == GP_EV_NONE) return;
  check(ev == GP_EV_FRAME);
  const gp_msg_desc *d = gp_msg_find(m.type);
  check(d != NULL && d->dir == GP_DIR_DEVICE);
  board.frames_out++;
  if (m.type == GP_ACK) {
    const gp_msg_desc *cmd = gp_msg_find(m.u.ack.cmd);
    check(cmd != NULL && cmd->dir == GP_DIR_HOST);
    board.replies_out++;
  } else if (m.type == GP_NACK) {
    const gp_msg_desc *cmd = gp_msg_find(m.u.nack.cmd);
    check(cmd == NULL || cmd->dir == GP_DIR_HOST);
    board.replies_out++;
  }
}

/* The line carries baud / 10 bytes a second at 8N1. */
static void board_line(void) {
  board.line_bits += (uint64_t)board.baud * 1000u / FW_TICK_HZ;
  while (board.txq_len > 0 && board.line_bits >= 10u * 1000u) {
    board.line_bits -= 10u * 1000u;
    board_wire(board.txq[0]);
    memmove(board.txq, board.txq + 1, --board.txq_len);
  }
  if (board.txq_len == 0) board.line_bits = 0;
}

int fw_hal_adc_take(uint16_t block[FW_BLOCK_LEN], uint32_t *tick) {
  return fw_blockq_take(&board.q, block, tick);
}

uint32_t fw_hal_adc_timeouts(void) {
  return 0;
}

size_t fw_hal_uart_tx_free(void) {
  return FW_TXQ_BYTES - board.txq_len;
}

void fw_hal_uart_write(const uint8_t *data, size_t n) {
  check(n <= FW_TXQ_BYTES - board.txq_len);
  memcpy(board.txq + board.txq_len, data, n);
  board.txq_len += n;
}

int fw_hal_uart_tx_idle(void) {
  return board.txq_len == 0;
}

int fw_hal_uart_read(uint8_t *byte) {
  if (board.rx_pos >= board.rx_len) return 0;
  *byte = board.rx[board.rx_pos++];
  return 1;
}

void fw_hal_uart_set_baud(uint32_t baud) {
  check(board.txq_len == 0); /* the core switches only on an idle line */
  board.baud = baud;
}

int fw_hal_flash_read(void *data, size_t len) {
  if (len > sizeof board.flash) return -1;
  memcpy(data, board.flash, len);
  return 0;
}

int fw_hal_flash_write(const void *data, size_t len) {
  if (len > sizeof board.flash) return -1;
  memset(board.flash, 0xFF, sizeof board.flash);
  memcpy(board.flash, data, len);
  return 0;
}

int fw_hal_flash_erase(void) {
  memset(board.flash, 0xFF, sizeof board.flash);
  return 0;
}

void fw_hal_led(int on) {
  (void)on;
}
int fw_hal_button(void) {
  return 0;
}
void fw_hal_watchdog_kick(void) {}

void fw_hal_uid(uint32_t uid[3]) {
  uid[0] = 0x00112233u;
  uid[1] = 0x44556677u;
  uid[2] = 0x8899AABBu;
}

/* --- the target ----------------------------------------------------------- */

/* A bound on the ticks the line needs, once the input is read, to carry a
 * full transmit queue at the slowest baud, then the INFO of a baud switch:
 * SAMPLEs may take half the line (FW_LINK_MAX_PERCENT) and INFO another 6 %
 * at 9600 baud, so the backlog shrinks at more than a third of the line's
 * rate; four times the bare drain time covers it. */
#define DRAIN_TICKS (4u * (FW_TXQ_BYTES + GP_MAX_WIRE) * 10u * FW_TICK_HZ / 9600u)

/* Runs a fresh glove on stream, frames_in being the most frames it can hold. */
static void run(const uint8_t *stream, size_t size, size_t frames_in) {
  static fw_core core;
  board_reset(stream, size);
  fw_core_init(&core);

  /* Sample, poll, let the line carry a tick's bytes: until every input
   * byte is read (each poll reads at least one) and every reply has left
   * the line, at whatever baud the input switched to. */
  uint32_t ticks = 0;
  do {
    board_sample();
    fw_core_poll(&core);
    board_line();
    ticks++;
    check(ticks <= size + DRAIN_TICKS);
  } while (board.rx_pos < board.rx_len || board.txq_len > 0 || core.pending_baud != 0);

  check(board.frames_out == core.frames_sent);
  check(board.replies_out <= frames_in);
  check(core.cmd_errors <= frames_in);
  check(core.overruns == 0);
  check(core.last_tick == ticks - 1u);
}

/* The input read as frames: [n][n bytes of type and payload] again and
 * again, each sent with its CRC under our spec hash, COBS and a 0x00, so
 * that mutations reach the command handling behind the CRC. */
static uint8_t framed[1u << 16];

static size_t frame_input(const uint8_t *data, size_t size, size_t *frames) {
  size_t out = 0;
  *frames = 0;
  for (size_t i = 0; i < size && out + GP_MAX_WIRE <= sizeof framed;) {
    size_t n = data[i++] % (GP_MAX_FRAME - GP_CRC_LEN + 1u);
    if (n > size - i) n = size - i;
    uint8_t raw[GP_MAX_FRAME];
    memcpy(raw, data + i, n);
    i += n;
    uint32_t crc = gp_frame_crc(GP_SPEC_HASH, raw, n);
    for (unsigned k = 0; k < GP_CRC_LEN; k++) raw[n + k] = (uint8_t)(crc >> (8u * k));
    size_t w = gp_cobs_encode(raw, n + GP_CRC_LEN, framed + out, sizeof framed - out - 1u);
    check(w > 0);
    out += w;
    framed[out++] = 0;
    (*frames)++;
  }
  return out;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  size_t delimiters = 0;
  for (size_t i = 0; i < size; i++) delimiters += data[i] == 0;
  run(data, size, delimiters);

  size_t frames;
  size_t n = frame_input(data, size, &frames);
  run(framed, n, frames);
  return 0;
}

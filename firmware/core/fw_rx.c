#include "fw_rx.h"

void fw_rx_init(fw_rx *rx) {
  rx->len = 0;
  rx->overflow = 0;
  rx->in_step = 0;
}

static fw_rx_result frame_end(fw_rx *rx, fw_rx_frame *out) {
  uint8_t raw[GP_MAX_FRAME];
  int n = gp_cobs_decode(rx->buf, rx->len, raw, sizeof raw);
  if (n < (int)(1u + GP_CRC_LEN)) return FW_RX_CORRUPT;
  size_t body = (size_t)n - GP_CRC_LEN;
  uint32_t crc = (uint32_t)raw[body] | ((uint32_t)raw[body + 1] << 8) |
                 ((uint32_t)raw[body + 2] << 16) | ((uint32_t)raw[body + 3] << 24);
  /* A foreign spec hash fails here too: its CRC was seeded differently. */
  if (crc != gp_frame_crc(GP_SPEC_HASH, raw, body)) return FW_RX_CORRUPT;
  out->cmd = raw[0];
  /* Every command starts with its tag; one sent without a payload has none,
   * and SPEC.md says its NACK carries 0. */
  out->tag = body > 1 ? raw[1] : 0;
  const gp_msg_desc *d = gp_msg_find(raw[0]);
  /* The glove-to-host range, defined or not, is never answered: it is our
   * own output looped back, or another glove's (SPEC.md, section 9). */
  if ((d != 0 && d->dir == GP_DIR_DEVICE) || raw[0] < FW_RX_FIRST_HOST_TYPE) return FW_RX_ECHO;
  if (d == 0) {
    out->reason = GP_NACK_UNKNOWN_COMMAND;
    return FW_RX_NACK;
  }
  if (body - 1u != d->len || gp_payload_unpack(raw[0], raw + 1, body - 1u, &out->msg) != 0) {
    out->reason = GP_NACK_BAD_LENGTH;
    return FW_RX_NACK;
  }
  return FW_RX_COMMAND;
}

fw_rx_result fw_rx_byte(fw_rx *rx, uint8_t byte, fw_rx_frame *out) {
  if (byte != 0) {
    if (rx->len < sizeof rx->buf)
      rx->buf[rx->len++] = byte;
    else
      rx->overflow = 1;
    return FW_RX_NONE;
  }
  fw_rx_result r;
  if (rx->overflow)
    r = FW_RX_CORRUPT;
  else if (rx->len == 0)
    r = FW_RX_NONE; /* an idle delimiter: the host resynchronising */
  else
    r = frame_end(rx, out);
  /* Before the first 0x00 the glove may have woken in the middle of a
   * frame: a tail that is no frame is not an error (SPEC.md, rule 1). */
  if (!rx->in_step && r == FW_RX_CORRUPT && !rx->overflow) r = FW_RX_NONE;
  rx->in_step = 1;
  rx->len = 0;
  rx->overflow = 0;
  return r;
}

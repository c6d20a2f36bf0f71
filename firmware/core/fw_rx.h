/* The command receiver: turns the bytes the host sends into checked command
 * frames, one byte at a time, never blocking.
 *
 * It uses the codec's COBS, CRC and unpacking directly rather than the
 * host-side stream decoder, because a device must answer a frame it can
 * attribute (right CRC, wrong type or length) with a NACK naming its tag,
 * and stay silent on anything it cannot (bad CRC, a foreign spec hash,
 * broken framing, oversize): those only count in STATUS.cmd_errors.
 */
#ifndef FW_RX_H
#define FW_RX_H

#include <stddef.h>
#include <stdint.h>

#include "gp.h"

/* Type ids below this are glove to host (SPEC.md, "Messages"). */
#define FW_RX_FIRST_HOST_TYPE 0x10u

typedef enum fw_rx_result {
  FW_RX_NONE = 0, /* byte consumed, no frame ended */
  FW_RX_COMMAND,  /* a valid command: msg filled */
  FW_RX_NACK,     /* a frame with a good CRC to refuse: tag, cmd, reason filled */
  FW_RX_CORRUPT,  /* a frame to drop silently (bad CRC, framing, oversize) */
  FW_RX_ECHO,     /* a frame of a glove-to-host type (0x01..0x0F, defined
                      * or not), such as our own output looped back to RX:
                      * dropped silently, since a NACK would be echoed too
                      * and feed itself */
} fw_rx_result;

typedef struct fw_rx_frame {
  gp_msg msg;
  uint8_t tag;
  uint8_t cmd;
  uint8_t reason; /* GP_NACK_* */
} fw_rx_frame;

typedef struct fw_rx {
  size_t len;
  uint8_t overflow;
  uint8_t in_step; /* a 0x00 has been seen: frames start where they should */
  uint8_t buf[GP_MAX_WIRE];
} fw_rx;

void fw_rx_init(fw_rx *rx);
fw_rx_result fw_rx_byte(fw_rx *rx, uint8_t byte, fw_rx_frame *out);

#endif

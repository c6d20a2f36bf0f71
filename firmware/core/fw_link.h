/* What the serial link can carry: the rate arithmetic behind SET_RATE.
 *
 * A SAMPLE costs FW_SAMPLE_WIRE_BYTES on the wire (type, 15-byte payload and
 * CRC make a 20-byte raw frame; COBS adds one byte at these lengths, the
 * delimiter one more: 22), and each byte 10 bit times at 8N1. So a stream
 * of R frames per second at B baud fills 22 * 10 * R / B of the link:
 * 250 Hz at 115200 is 47.7 %, 1000 Hz at 921600 is 23.9 %.
 */
#ifndef FW_LINK_H
#define FW_LINK_H

#include <stdint.h>

#include "gp.h"

/* Bytes a SAMPLE takes on the wire: COBS adds one code byte per 254 data
 * bytes (one here), then the 0x00 delimiter. */
#define FW_SAMPLE_WIRE_BYTES (1u + GP_SAMPLE_LEN + GP_CRC_LEN + 1u + 1u)
#define FW_BITS_PER_BYTE     10u /* 8N1: start, 8 data, stop */

/* 1 if baud is one the board supports (FW_BAUDS). */
int fw_link_baud_ok(uint32_t baud);
/* 1 if frame_rate_hz divides the tick rate and its SAMPLE stream stays
 * within FW_LINK_MAX_PERCENT of baud. */
int fw_link_rate_ok(uint32_t frame_rate_hz, uint32_t baud);
/* The SAMPLE stream's share of the link, in tenths of a percent. */
uint32_t fw_link_load_permille(uint32_t frame_rate_hz, uint32_t baud);

#endif

/* Consistent Overhead Byte Stuffing (Cheshire & Baker, 1999): removes every
 * 0x00 from a block so that 0x00 can delimit frames. Each code byte c says
 * "c-1 data bytes follow, then a zero", except 0xFF ("254 bytes, no zero")
 * and the implied zero at the end of the block, which is dropped. */
#include "gp.h"

size_t gp_cobs_encode(const uint8_t *in, size_t len, uint8_t *out, size_t cap) {
  size_t code_at = 0, o = 1;
  uint8_t code = 1;
  if (cap == 0) return 0;
  for (size_t i = 0; i < len; i++) {
    if (in[i] == 0) {
      out[code_at] = code;
      code_at = o++;
      code = 1;
    } else {
      if (o >= cap) return 0;
      out[o++] = in[i];
      if (++code == 0xFF) {
        out[code_at] = code;
        code_at = o++;
        code = 1;
      }
    }
    if (o > cap) return 0;
  }
  if (code_at >= cap) return 0;
  out[code_at] = code;
  return o;
}

int gp_cobs_decode(const uint8_t *in, size_t len, uint8_t *out, size_t cap) {
  size_t i = 0, o = 0;
  while (i < len) {
    uint8_t code = in[i++];
    if (code == 0) return -1;
    for (uint8_t k = 1; k < code; k++) {
      if (i >= len || in[i] == 0 || o >= cap) return -1;
      out[o++] = in[i++];
    }
    if (code != 0xFF && i < len) {
      if (o >= cap) return -1;
      out[o++] = 0;
    }
  }
  return (int)o;
}

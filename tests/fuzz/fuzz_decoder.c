/* libFuzzer target for the streaming decoder. The input is split at a byte
 * chosen by the input itself and fed in two pieces, so that frames cut
 * across feed calls are exercised too. Besides the sanitizers, it checks
 * the decoder's promises: every byte consumed and counted, and no frame
 * delivered whose re-encoding differs from a frame that passes the CRC. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "gp.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check(int cond) {
  if (!cond) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  gp_decoder d;
  gp_decoder_init(&d, GP_SPEC_HASH);
  size_t split = size ? data[0] % (size + 1) : 0;
  const uint8_t *parts[2] = { data, data + split };
  size_t lens[2] = { split, size - split };
  uint32_t events = 0;
  for (int k = 0; k < 2; k++) {
    const uint8_t *p = parts[k];
    size_t n = lens[k];
    while (n) {
      gp_msg out;
      gp_event ev;
      size_t used = gp_decoder_feed(&d, p, n, &out, &ev);
      check(used >= 1 && used <= n);
      if (ev == GP_EV_FRAME || ev == GP_EV_FRAME_LATE || ev == GP_EV_DUPLICATE) {
        /* A delivered frame re-encodes to a frame the decoder accepts. */
        uint8_t wire[GP_MAX_WIRE];
        size_t w = gp_encode(&out, GP_SPEC_HASH, wire, sizeof wire);
        check(w > 0 && w <= GP_MAX_WIRE);
        gp_decoder again;
        gp_decoder_init(&again, GP_SPEC_HASH);
        gp_msg back;
        gp_event ev2;
        check(gp_decoder_feed(&again, wire, w, &back, &ev2) == w);
        check(ev2 == GP_EV_FRAME);
      }
      if (ev != GP_EV_NONE) events++;
      p += used;
      n -= used;
    }
  }
  check(d.c.bytes == size);
  const gp_counters *c = &d.c;
  check(c->frames + c->crc_errors + c->framing_errors + c->oversize + c->unknown_type +
            c->spec_mismatch + c->duplicates ==
        events);
  return 0;
}

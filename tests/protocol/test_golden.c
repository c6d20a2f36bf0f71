/* The C codec against the golden vectors written by an independent
 * implementation of SPEC.md (protocol/vectors/make_golden.py), and every
 * 1-, 2- and 3-bit error in every golden frame. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "golden.h"

#define MAX_VECTORS 64
static golden_vec vecs[MAX_VECTORS];
static int n_vecs;

static int load(void **state) {
  (void)state;
  char err[256];
  n_vecs =
      golden_load(MR_SOURCE_DIR "/protocol/vectors/golden.txt", vecs, MAX_VECTORS, err, sizeof err);
  if (n_vecs < 0) {
    fprintf(stderr, "%s\n", err);
    return -1;
  }
  return n_vecs >= 15 ? 0 : -1;
}

static void golden_vectors_cover_every_message_type(void **state) {
  (void)state;
  for (size_t t = 0; t < gp_msg_desc_count; t++) {
    int found = 0;
    for (int i = 0; i < n_vecs; i++)
      found |= vecs[i].msg.type == gp_msg_descs[t].type && vecs[i].hash == GP_SPEC_HASH;
    assert_true(found);
  }
}

static void encoder_produces_every_golden_vector_bit_for_bit(void **state) {
  (void)state;
  for (int i = 0; i < n_vecs; i++) {
    uint8_t wire[GP_MAX_WIRE];
    size_t n = gp_encode(&vecs[i].msg, vecs[i].hash, wire, sizeof wire);
    assert_int_equal(n, vecs[i].wire_len);
    assert_memory_equal(wire, vecs[i].wire, n);
  }
}

static void decoder_reads_every_golden_vector_as_its_meaning(void **state) {
  (void)state;
  for (int i = 0; i < n_vecs; i++) {
    gp_decoder d;
    gp_decoder_init(&d, GP_SPEC_HASH);
    gp_msg out;
    memset(&out, 0, sizeof out);
    gp_event ev;
    int mismatch = strncmp(vecs[i].name, "mismatch_", 9) == 0;
    if (mismatch && vecs[i].msg.type != GP_INFO) {
      /* A foreign frame is recognised once its INFO has announced the hash. */
      for (int j = 0; j < n_vecs; j++)
        if (strcmp(vecs[j].name, "mismatch_info") == 0)
          gp_decoder_feed(&d, vecs[j].wire, vecs[j].wire_len, &out, &ev);
      assert_int_equal(ev, GP_EV_SPEC_MISMATCH);
      assert_int_equal(d.peer_hash, vecs[i].hash);
    }
    memset(&out, 0, sizeof out);
    size_t used = gp_decoder_feed(&d, vecs[i].wire, vecs[i].wire_len, &out, &ev);
    assert_int_equal(used, vecs[i].wire_len);
    if (mismatch) {
      assert_int_equal(ev, GP_EV_SPEC_MISMATCH);
      if (vecs[i].msg.type == GP_INFO) assert_memory_equal(&out, &vecs[i].msg, sizeof out);
    } else {
      assert_int_equal(ev, GP_EV_FRAME);
      assert_memory_equal(&out, &vecs[i].msg, sizeof out);
    }
  }
}

/* Feeds a corrupted frame plus a delimiter (in case the error removed the
 * frame's own) and reports whether any valid frame came out. */
static int accepted(const uint8_t *wire, size_t n, gp_decoder *d) {
  static const uint8_t delim = 0;
  gp_msg out;
  gp_event ev;
  for (int pass = 0; pass < 2; pass++) {
    const uint8_t *p = pass ? &delim : wire;
    size_t left = pass ? 1 : n;
    while (left) {
      size_t used = gp_decoder_feed(d, p, left, &out, &ev);
      if (ev == GP_EV_FRAME || ev == GP_EV_FRAME_LATE || ev == GP_EV_DUPLICATE) return 1;
      p += used;
      left -= used;
    }
  }
  return 0;
}

static void every_one_two_and_three_bit_error_in_every_golden_frame_is_detected(void **state) {
  (void)state;
  unsigned long long trials = 0;
  for (int v = 0; v < n_vecs; v++) {
    uint8_t w[2 * GP_MAX_WIRE];
    size_t n = vecs[v].wire_len;
    size_t bits = n * 8;
    gp_decoder base;
    gp_decoder_init(&base, GP_SPEC_HASH);
    if (vecs[v].hash != GP_SPEC_HASH) {
      /* Let the decoder know the foreign hash, so that a corrupted foreign
       * frame could only pass as foreign, never as ours. */
      base.peer_hash = vecs[v].hash;
      base.peer_known = 1;
    }
    for (size_t a = 0; a < bits; a++) {
      for (size_t b = a; b < bits; b++) {
        for (size_t c = b; c < bits; c++) {
          /* a == b == c: one bit; b == c: two bits (a, b); else three. */
          if ((a == b) != (b == c) && a == b) continue;
          memcpy(w, vecs[v].wire, n);
          w[a / 8] ^= (uint8_t)(1u << (a % 8));
          if (b != a) w[b / 8] ^= (uint8_t)(1u << (b % 8));
          if (c != b) w[c / 8] ^= (uint8_t)(1u << (c % 8));
          gp_decoder d = base;
          if (accepted(w, n, &d))
            fail_msg("%s: bits %zu %zu %zu flipped, frame accepted", vecs[v].name, a, b, c);
          trials++;
        }
      }
    }
  }
  print_message("%llu corrupted frames, none accepted\n", trials);
  assert_true(trials > 1000000ull);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(golden_vectors_cover_every_message_type),
    cmocka_unit_test(encoder_produces_every_golden_vector_bit_for_bit),
    cmocka_unit_test(decoder_reads_every_golden_vector_as_its_meaning),
    cmocka_unit_test(every_one_two_and_three_bit_error_in_every_golden_frame_is_detected),
  };
  return cmocka_run_group_tests(tests, load, NULL);
}

/* The show-state codec (host/net/state.def, STATE.md): the golden vectors
 * written by an implementation apart from the C one, round trips, the
 * quantisation's bound, and every way a message can be wrong. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mr_state.h"

#define GOLDEN MR_SOURCE_DIR "/host/net/vectors/state_golden.txt"

static size_t unhex(const char *hex, uint8_t *out, size_t cap) {
  size_t n = strlen(hex) / 2;
  assert_true(n <= cap);
  for (size_t i = 0; i < n; i++) {
    unsigned v = 0;
    assert_int_equal(sscanf(hex + 2 * i, "%2x", &v), 1);
    out[i] = (uint8_t)v;
  }
  return n;
}

/* field=VALUE of a golden line, as a number (the first of a list). */
static unsigned long long field(const char *line, const char *name) {
  char key[64];
  snprintf(key, sizeof key, " %s=", name);
  const char *at = strstr(line, key);
  assert_non_null(at);
  return strtoull(at + strlen(key), NULL, 10);
}

static void check_frame(const char *line, const uint8_t *wire, size_t n) {
  float pose[7 * 4];
  uint16_t q[3 * 8];
  mr_state_frame m = { .pose = pose, .pose_cap = 28, .q = q, .q_cap = 24 };
  assert_int_equal(mr_state_frame_decode(wire, n, &m), MR_STATE_OK);
  assert_int_equal(m.scene_id, field(line, "scene_id"));
  assert_int_equal(m.seq, field(line, "seq"));
  assert_int_equal(m.t_us, field(line, "t_us"));
  assert_int_equal(m.sent_us, field(line, "sent_us"));
  assert_int_equal(m.n_frames, field(line, "n_frames"));
  assert_int_equal(m.n_points, field(line, "n_points"));
  const char *qs = strstr(line, " q=");
  for (size_t i = 0; qs != NULL && i < (size_t)m.n_points * 3; i++) {
    qs += i == 0 ? 3 : 1;
    assert_int_equal(m.q[i], strtoul(qs, (char **)&qs, 10));
  }
  uint8_t again[512];
  assert_int_equal(mr_state_frame_encode(&m, again, sizeof again), n);
  assert_memory_equal(again, wire, n);
}

static void check_scene(const char *line, const uint8_t *wire, size_t n) {
  mr_state_scene s;
  assert_int_equal(mr_state_scene_decode(wire, n, &s), MR_STATE_OK);
  assert_true(s.scene_hash == field(line, "scene_hash"));
  assert_true(s.scene_hash == mr_state_bundle_hash(s.files, s.size));
  assert_int_equal(s.n_files, field(line, "n_files"));
  assert_int_equal(s.n_points, field(line, "n_points"));
  uint8_t again[512];
  assert_int_equal(mr_state_scene_encode(&s, again, sizeof again), n);
  assert_memory_equal(again, wire, n);
}

/* Every vector of our definition decodes to its fields and encodes back
 * to the same bytes; the foreign one is refused by its hash. */
static void golden_vectors_decode_to_their_fields_and_encode_back_byte_for_byte(void **state) {
  (void)state;
  FILE *f = fopen(GOLDEN, "r");
  assert_non_null(f);
  char line[4096], name[64], type[16], hex[2048];
  unsigned hash = 0;
  int seen = 0, foreign = 0;
  while (fgets(line, sizeof line, f) != NULL) {
    if (line[0] == '#') continue;
    assert_int_equal(sscanf(line, "%63s %15s 0x%x %2047s", name, type, &hash, hex), 4);
    uint8_t wire[1024];
    size_t n = unhex(hex, wire, sizeof wire);
    if (hash != MR_STATE_SPEC_HASH) {
      uint8_t t = 0;
      uint32_t h = 0;
      assert_int_equal(mr_state_peek(wire, n, &t, &h), MR_STATE_ERR_HASH);
      assert_int_equal(h, hash);
      foreign++;
    } else if (strcmp(type, "FRAME") == 0) {
      check_frame(line, wire, n);
    } else {
      check_scene(line, wire, n);
    }
    seen++;
  }
  fclose(f);
  assert_int_equal(seen, 4);
  assert_int_equal(foreign, 1);
}

static double rnd(unsigned *s) {
  *s = *s * 1103515245u + 12345u;
  return (double)((*s >> 8) & 0xFFFFFF) / (double)0xFFFFFF;
}

/* Quantised and back, every particle is within half the message's step
 * of where it was, on boxes of several sizes and places, a flat axis
 * among them. */
static void a_frame_round_trips_with_every_particle_within_half_a_step(void **state) {
  (void)state;
  enum { N = 300 };
  static double xyz[3 * N], back[3];
  static uint16_t q[3 * N], q2[3 * N];
  const double spans[] = { 2.0, 0.001, 150.0 }, offsets[] = { 0.3, -7.1, 1000.0 };
  unsigned seed = 17;
  for (int k = 0; k < 3; k++) {
    for (size_t i = 0; i < 3 * N; i++)
      xyz[i] = i % 3 == 2 && k == 1 ? 0.5 : offsets[k] + spans[k] * (rnd(&seed) - 0.5);
    mr_state_frame m = { .seq = 9, .n_points = N, .q = q };
    mr_state_quantise(xyz, N, m.origin, m.step, q);
    uint8_t wire[4096];
    size_t len = mr_state_frame_encode(&m, wire, sizeof wire);
    assert_int_equal(len, mr_state_frame_size(&m));
    mr_state_frame d = { .q = q2, .q_cap = 3 * N };
    assert_int_equal(mr_state_frame_decode(wire, len, &d), MR_STATE_OK);
    for (size_t i = 0; i < N; i++) {
      mr_state_point(&d, i, back);
      for (int a = 0; a < 3; a++) {
        double err = fabs(back[a] - xyz[3 * i + (size_t)a]);
        if (!(err <= 0.5 * (double)d.step[a] + 1e-12))
          fail_msg("box %d particle %zu axis %d off by %g, step %g", k, i, a, err,
                   (double)d.step[a]);
      }
    }
  }
}

/* Each single bit flipped anywhere in a frame is caught (a CRC or a
 * hash), never decoded as another frame. */
static void every_single_bit_flip_of_a_frame_is_caught(void **state) {
  (void)state;
  float pose[7] = { 0.1f, 0.2f, 0.3f, 1, 0, 0, 0 };
  uint16_t q[6] = { 1, 2, 3, 4, 5, 6 }, q2[6];
  float p2[7];
  mr_state_frame m = { .seq = 3, .n_frames = 1, .n_points = 2, .pose = pose, .q = q };
  uint8_t wire[256];
  size_t len = mr_state_frame_encode(&m, wire, sizeof wire);
  assert_true(len > 0);
  for (size_t bit = 0; bit < 8 * len; bit++) {
    wire[bit / 8] ^= (uint8_t)(1u << (bit % 8));
    mr_state_frame d = { .pose = p2, .pose_cap = 7, .q = q2, .q_cap = 6 };
    assert_int_not_equal(mr_state_frame_decode(wire, len, &d), MR_STATE_OK);
    wire[bit / 8] ^= (uint8_t)(1u << (bit % 8));
  }
}

/* Lengths its fields do not make are refused even with a good CRC, and
 * a frame larger than the caller's arrays is refused, not written past
 * them. */
static void short_long_and_too_large_frames_are_refused(void **state) {
  (void)state;
  uint16_t q[9] = { 0 }, q2[9];
  mr_state_frame m = { .n_points = 3, .q = q };
  uint8_t wire[256];
  size_t len = mr_state_frame_encode(&m, wire, sizeof wire);
  for (size_t cut = 9; cut <= len + 6; cut++) {
    if (cut == len) continue;
    uint8_t w[256];
    memcpy(w, wire, len < cut ? len : cut);
    if (cut > len) memset(w + len, 0, cut - len);
    uint32_t crc = mr_state_crc32c(w, cut - 4);
    for (int i = 0; i < 4; i++) w[cut - 4 + (size_t)i] = (uint8_t)(crc >> (8 * i));
    mr_state_frame d = { .q = q2, .q_cap = 9 };
    assert_int_not_equal(mr_state_frame_decode(w, cut, &d), MR_STATE_OK);
  }
  mr_state_frame small = { .q = q2, .q_cap = 8 };
  assert_int_equal(mr_state_frame_decode(wire, len, &small), MR_STATE_ERR_ROOM);
}

/* The scene's files come back as they went, and a name that would write
 * outside the watcher's folder is refused when added and when read. */
static void scene_files_round_trip_and_unsafe_names_are_refused(void **state) {
  (void)state;
  mr_state_bundle b;
  memset(&b, 0, sizeof b);
  assert_int_equal(mr_state_bundle_add(&b, "show.yaml", "a: 1\n", 5), 0);
  assert_int_equal(mr_state_bundle_add(&b, "models/x..y.obj", "v 0 0 0\n", 8), 0);
  assert_int_equal(mr_state_bundle_add(&b, "one", "!", 1), 0); /* one byte is data too */
  const char *bad[] = { "", "/etc/passwd", "../up", "models/../../up", "a/..", "a\\b" };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
    assert_int_equal(mr_state_bundle_add(&b, bad[i], "x", 1), -1);
  assert_int_equal(b.n_files, 3);
  size_t off = 0;
  mr_state_file f;
  assert_int_equal(mr_state_bundle_next(b.data, b.size, &off, &f), 1);
  assert_string_equal(f.name, "show.yaml");
  assert_int_equal(f.len, 5);
  assert_memory_equal(f.data, "a: 1\n", 5);
  assert_int_equal(mr_state_bundle_next(b.data, b.size, &off, &f), 1);
  assert_string_equal(f.name, "models/x..y.obj");
  assert_memory_equal(f.data, "v 0 0 0\n", 8);
  assert_int_equal(mr_state_bundle_next(b.data, b.size, &off, &f), 1);
  assert_string_equal(f.name, "one");
  assert_int_equal(f.len, 1);
  assert_int_equal(f.data[0], '!');
  assert_int_equal(mr_state_bundle_next(b.data, b.size, &off, &f), 0);
  /* The last record cut short: refused. */
  off = 0;
  assert_int_equal(mr_state_bundle_next(b.data, b.size - 1, &off, &f), 1);
  assert_int_equal(mr_state_bundle_next(b.data, b.size - 1, &off, &f), 1);
  assert_int_equal(mr_state_bundle_next(b.data, b.size - 1, &off, &f), -1);
  /* A record renamed on the wire to climb out: refused when read. */
  memcpy(b.data + 2, "../s", 4);
  off = 0;
  assert_int_equal(mr_state_bundle_next(b.data, b.size, &off, &f), -1);
  mr_state_bundle_free(&b);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(golden_vectors_decode_to_their_fields_and_encode_back_byte_for_byte),
    cmocka_unit_test(a_frame_round_trips_with_every_particle_within_half_a_step),
    cmocka_unit_test(every_single_bit_flip_of_a_frame_is_caught),
    cmocka_unit_test(short_long_and_too_large_frames_are_refused),
    cmocka_unit_test(scene_files_round_trip_and_unsafe_names_are_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

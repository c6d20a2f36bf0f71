/* The golden vectors (protocol/vectors/golden.txt) of every frame type the
 * glove sends, rebuilt bit for bit through the firmware's frame assembly
 * (fw_frame.c). Vectors of host commands and of foreign specs are frames
 * this firmware never sends. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fw_frame.h"

#define MAX_VALUES 16

typedef struct field {
  char name[32];
  unsigned long v[MAX_VALUES];
  int n;
} field;

static field fields[32];
static int n_fields;

static const unsigned long *get(const char *name, int count) {
  for (int i = 0; i < n_fields; i++)
    if (strcmp(fields[i].name, name) == 0) {
      assert_int_equal(fields[i].n, count);
      return fields[i].v;
    }
  fail_msg("field %s missing", name);
  return NULL;
}

static void parse_fields(char *rest) {
  n_fields = 0;
  for (char *tok = strtok(rest, " \t\n"); tok; tok = strtok(NULL, " \t\n")) {
    char *eq = strchr(tok, '=');
    assert_non_null(eq);
    assert_true(n_fields < 32);
    field *f = &fields[n_fields++];
    *eq = 0;
    snprintf(f->name, sizeof f->name, "%s", tok);
    f->n = 0;
    for (char *p = eq + 1; *p && f->n < MAX_VALUES;) {
      f->v[f->n++] = strtoul(p, &p, 10);
      if (*p == ',') p++;
    }
  }
}

static size_t build(const char *type, uint8_t *w, size_t cap) {
  if (strcmp(type, "SAMPLE") == 0) {
    uint16_t ch[FW_N_CH];
    const unsigned long *c = get("ch", FW_N_CH);
    for (unsigned i = 0; i < FW_N_CH; i++) ch[i] = (uint16_t)c[i];
    return fw_frame_sample((uint16_t)get("seq", 1)[0], (uint32_t)get("t_us", 1)[0], ch,
                           (uint8_t)get("flags", 1)[0], w, cap);
  }
  if (strcmp(type, "INFO") == 0) {
    /* proto_major and spec_hash are the build's own. */
    assert_int_equal(get("proto_major", 1)[0], GP_PROTO_MAJOR);
    assert_int_equal(get("spec_hash", 1)[0], GP_SPEC_HASH);
    fw_info_state s;
    s.fw_major = (uint8_t)get("fw_major", 1)[0];
    s.fw_minor = (uint8_t)get("fw_minor", 1)[0];
    s.fw_patch = (uint8_t)get("fw_patch", 1)[0];
    const unsigned long *uid = get("uid", 3);
    for (int i = 0; i < 3; i++) s.uid[i] = (uint32_t)uid[i];
    s.hand = (uint8_t)get("hand", 1)[0];
    s.n_channels = (uint8_t)get("n_channels", 1)[0];
    s.adc_bits = (uint8_t)get("adc_bits", 1)[0];
    s.sample_rate_hz = (uint32_t)get("sample_rate_hz", 1)[0];
    s.frame_rate_hz = (uint32_t)get("frame_rate_hz", 1)[0];
    s.baud = (uint32_t)get("baud", 1)[0];
    s.cal_state = (uint8_t)get("cal_state", 1)[0];
    const unsigned long *lo = get("cal_min", FW_N_CH), *hi = get("cal_max", FW_N_CH);
    for (unsigned i = 0; i < FW_N_CH; i++) {
      s.cal_min[i] = (uint16_t)lo[i];
      s.cal_max[i] = (uint16_t)hi[i];
    }
    return fw_frame_info(&s, w, cap);
  }
  if (strcmp(type, "STATUS") == 0) {
    fw_status_state s = {
      .t_us = (uint32_t)get("t_us", 1)[0],
      .frames_sent = (uint32_t)get("frames_sent", 1)[0],
      .overruns = (uint32_t)get("overruns", 1)[0],
      .dropped_frames = (uint32_t)get("dropped_frames", 1)[0],
      .cmd_errors = (uint32_t)get("cmd_errors", 1)[0],
      .adc_timeouts = (uint32_t)get("adc_timeouts", 1)[0],
    };
    return fw_frame_status(&s, w, cap);
  }
  if (strcmp(type, "ACK") == 0)
    return fw_frame_ack((uint8_t)get("tag", 1)[0], (uint8_t)get("cmd", 1)[0], w, cap);
  if (strcmp(type, "NACK") == 0)
    return fw_frame_nack((uint8_t)get("tag", 1)[0], (uint8_t)get("cmd", 1)[0],
                         (uint8_t)get("reason", 1)[0], w, cap);
  return 0;
}

static void firmware_golden_vectors_match_bit_for_bit(void **state) {
  (void)state;
  const char *path = MR_SOURCE_DIR "/protocol/vectors/golden.txt";
  FILE *f = fopen(path, "r");
  if (f == NULL) fail_msg("cannot open %s", path);
  char line[2048];
  int lineno = 0, built = 0, seen_types = 0;
  const char *types[] = { "SAMPLE", "INFO", "STATUS", "ACK", "NACK" };
  while (fgets(line, sizeof line, f)) {
    lineno++;
    char name[64], type[32], hash[32], hex[512];
    int off = 0;
    if (line[0] == '#' || sscanf(line, "%63s %31s %31s %511s %n", name, type, hash, hex, &off) < 4)
      continue;
    int sendable = 0;
    for (int t = 0; t < 5; t++)
      if (strcmp(type, types[t]) == 0) sendable = 1 << t;
    if (!sendable || strtoul(hash, NULL, 16) != GP_SPEC_HASH) continue;
    seen_types |= sendable;
    parse_fields(line + off);
    uint8_t w[GP_MAX_WIRE];
    size_t n = build(type, w, sizeof w);
    char got[2 * GP_MAX_WIRE + 1];
    for (size_t i = 0; i < n; i++) snprintf(got + 2 * i, 3, "%02x", w[i]);
    got[2 * n] = 0;
    if (strcmp(got, hex) != 0)
      fail_msg("%s:%d: %s: firmware built %s, vector is %s", path, lineno, name, got, hex);
    built++;
  }
  fclose(f);
  /* Every type the glove sends has a vector, and all were rebuilt. */
  assert_int_equal(seen_types, 0x1F);
  assert_true(built >= 5);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(firmware_golden_vectors_match_bit_for_bit),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

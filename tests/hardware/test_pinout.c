/* hardware/pinout.csv (for makers) and firmware/boards/blackpill_f411/
 * board_pins.h (for the firmware) must state the same pin map. These tests
 * check the real files, then feed the checker deliberately altered copies
 * to show that a changed pin on either side is caught and named. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "hwpin.h"

#define HEADER_PATH MR_SOURCE_DIR "/firmware/boards/blackpill_f411/board_pins.h"
#define CSV_PATH    MR_SOURCE_DIR "/hardware/pinout.csv"

typedef struct {
  char *header_text, *csv_text;
  hwpin_map header, csv;
  char err[512];
  char report[4096];
} fixture;

static char *read_text(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t cap = 4096, n = 0;
  char *buf = malloc(cap);
  size_t got;
  while (buf && (got = fread(buf + n, 1, cap - n - 1, f)) > 0) {
    n += got;
    if (n + 1 == cap) {
      char *bigger = realloc(buf, cap * 2);
      if (!bigger) {
        free(buf);
        buf = NULL;
        break;
      }
      buf = bigger;
      cap *= 2;
    }
  }
  fclose(f);
  if (buf) buf[n] = '\0';
  return buf;
}

/* text with [from, from+len) replaced by repl; caller frees. */
static char *splice(const char *text, size_t from, size_t len, const char *repl) {
  size_t n = strlen(text), r = strlen(repl);
  char *out = malloc(n - len + r + 1);
  assert_non_null(out);
  memcpy(out, text, from);
  memcpy(out + from, repl, r);
  memcpy(out + from + r, text + from + len, n - from - len + 1);
  return out;
}

/* Finds "#define NAME" followed by a blank, asserting exactly one. */
static const char *find_define(const char *text, const char *name) {
  char key[96];
  snprintf(key, sizeof key, "#define %s", name);
  const char *hit = NULL;
  for (const char *p = strstr(text, key); p; p = strstr(p + 1, key)) {
    char next = p[strlen(key)];
    if (next == ' ' || next == '\t') {
      assert_null(hit);
      hit = p;
    }
  }
  assert_non_null(hit);
  return hit;
}

/* A copy of board_pins.h with NAME's BOARD_PIN(...) set to port/num. */
static char *header_move_pin(const char *text, const char *name, char port, int num) {
  const char *def = find_define(text, name);
  const char *open = strstr(def, "BOARD_PIN(");
  assert_non_null(open);
  const char *close = strchr(open, ')');
  assert_non_null(close);
  char repl[32];
  snprintf(repl, sizeof repl, "BOARD_PIN('%c', %d)", port, num);
  return splice(text, (size_t)(open - text), (size_t)(close + 1 - open), repl);
}

/* A copy of board_pins.h with ADC channel NAME set to value. */
static char *header_set_adc(const char *text, const char *name, int value) {
  const char *def = find_define(text, name);
  const char *v = def + strlen("#define ") + strlen(name);
  while (*v == ' ' || *v == '\t') v++;
  size_t len = strspn(v, "0123456789");
  assert_true(len > 0);
  char repl[16];
  snprintf(repl, sizeof repl, "%d", value);
  return splice(text, (size_t)(v - text), len, repl);
}

/* Start of the CSV line whose first field is signal. */
static const char *csv_row(const char *text, const char *signal) {
  size_t n = strlen(signal);
  for (const char *p = text; p && *p;) {
    if (strncmp(p, signal, n) == 0 && p[n] == ',') return p;
    p = strchr(p, '\n');
    if (p) p++;
  }
  fail_msg("no row %s in pinout.csv", signal);
  return NULL;
}

/* A copy of pinout.csv with signal's pin field set to pin. */
static char *csv_move_pin(const char *text, const char *signal, const char *pin) {
  const char *field = csv_row(text, signal) + strlen(signal) + 1;
  size_t len = strcspn(field, ",\n");
  return splice(text, (size_t)(field - text), len, pin);
}

/* A copy of pinout.csv without signal's row. */
static char *csv_drop_row(const char *text, const char *signal) {
  const char *row = csv_row(text, signal);
  const char *end = strchr(row, '\n');
  size_t len = end ? (size_t)(end + 1 - row) : strlen(row);
  return splice(text, (size_t)(row - text), len, "");
}

static int setup(void **state) {
  fixture *fx = calloc(1, sizeof *fx);
  if (!fx) return -1;
  fx->header_text = read_text(HEADER_PATH);
  fx->csv_text = read_text(CSV_PATH);
  *state = fx;
  return (fx->header_text && fx->csv_text) ? 0 : -1;
}

static int teardown(void **state) {
  fixture *fx = *state;
  free(fx->header_text);
  free(fx->csv_text);
  free(fx);
  return 0;
}

/* Parses both texts (either may be an altered copy) and compares them. */
static int check(fixture *fx, const char *header_text, const char *csv_text) {
  int rc = hwpin_parse_header(header_text, "board_pins.h", &fx->header, fx->err, sizeof fx->err);
  if (rc != 0) fail_msg("%s", fx->err);
  rc = hwpin_parse_csv(csv_text, "pinout.csv", &fx->csv, fx->err, sizeof fx->err);
  if (rc != 0) fail_msg("%s", fx->err);
  return hwpin_compare(&fx->header, &fx->csv, fx->report, sizeof fx->report);
}

static void expect_in_report(const fixture *fx, const char *needle) {
  if (!strstr(fx->report, needle)) fail_msg("report lacks \"%s\":\n%s", needle, fx->report);
}

static void hardware_pinout_files_agree(void **state) {
  fixture *fx = *state;
  int problems = check(fx, fx->header_text, fx->csv_text);
  if (problems != 0) fail_msg("%d problem(s):\n%s", problems, fx->report);
  /* five sensors, UART TX/RX, LED, button; five ADC channels */
  assert_int_equal(fx->header.n_pins, 9);
  assert_int_equal(fx->csv.n_pins, 9);
  assert_int_equal(fx->header.n_adcs, 5);
  assert_int_equal(fx->csv.n_adcs, 5);
}

static void hardware_pinout_catches_pin_moved_in_header(void **state) {
  fixture *fx = *state;
  char *altered = header_move_pin(fx->header_text, "PIN_CH_RING", 'A', 6);
  int problems = check(fx, altered, fx->csv_text);
  free(altered);
  /* the mismatch, and PA6 being ADC1_IN6 while ADC_CH_RING stays 4 */
  assert_int_equal(problems, 2);
  expect_in_report(fx, "PIN_CH_RING: board_pins.h:");
  expect_in_report(fx, "says PA6, pinout.csv:");
  expect_in_report(fx, "says PA4");
  expect_in_report(fx, "which is ADC1_IN6, but ADC_CH_RING is 4");
}

static void hardware_pinout_catches_pin_moved_in_csv(void **state) {
  fixture *fx = *state;
  char *altered = csv_move_pin(fx->csv_text, "PIN_UART_TX", "PA15");
  int problems = check(fx, fx->header_text, altered);
  free(altered);
  assert_int_equal(problems, 1);
  expect_in_report(fx, "PIN_UART_TX: board_pins.h:");
  expect_in_report(fx, "says PA9, pinout.csv:");
  expect_in_report(fx, "says PA15");
}

static void hardware_pinout_catches_adc_channel_change(void **state) {
  fixture *fx = *state;
  char *altered = header_set_adc(fx->header_text, "ADC_CH_INDEX", 7);
  int problems = check(fx, altered, fx->csv_text);
  free(altered);
  assert_int_equal(problems, 2);
  expect_in_report(fx, "ADC_CH_INDEX: board_pins.h:");
  expect_in_report(fx, "says 7, pinout.csv:");
  expect_in_report(fx, "which is ADC1_IN2, but ADC_CH_INDEX is 7");
}

static void hardware_pinout_rejects_usb_pins(void **state) {
  fixture *fx = *state;
  char *h = header_move_pin(fx->header_text, "PIN_UART_RX", 'A', 12);
  char *c = csv_move_pin(fx->csv_text, "PIN_UART_RX", "PA12");
  int problems = check(fx, h, c);
  free(h);
  free(c);
  /* the two files agree, but each puts RX on USB D+ */
  assert_int_equal(problems, 2);
  expect_in_report(fx, "board_pins.h:");
  expect_in_report(fx, "PIN_UART_RX on PA12 collides with USB D+");
}

static void hardware_pinout_rejects_swd_pins(void **state) {
  fixture *fx = *state;
  char *h = header_move_pin(fx->header_text, "PIN_LED", 'A', 13);
  char *c = csv_move_pin(fx->csv_text, "PIN_LED", "PA13");
  int problems = check(fx, h, c);
  free(h);
  free(c);
  assert_int_equal(problems, 2);
  expect_in_report(fx, "PIN_LED on PA13 collides with SWDIO");
}

static void hardware_pinout_rejects_pin_used_twice(void **state) {
  fixture *fx = *state;
  char *h = header_move_pin(fx->header_text, "PIN_BUTTON", 'A', 1);
  char *c = csv_move_pin(fx->csv_text, "PIN_BUTTON", "PA1");
  int problems = check(fx, h, c);
  free(h);
  free(c);
  assert_int_equal(problems, 2);
  expect_in_report(fx, "board_pins.h: PA1 used twice: PIN_CH_THUMB");
  expect_in_report(fx, "pinout.csv: PA1 used twice: PIN_CH_THUMB");
}

static void hardware_pinout_catches_missing_row(void **state) {
  fixture *fx = *state;
  char *c = csv_drop_row(fx->csv_text, "PIN_LED");
  int problems = check(fx, fx->header_text, c);
  free(c);
  assert_int_equal(problems, 1);
  expect_in_report(fx, "PIN_LED: board_pins.h:");
  expect_in_report(fx, "says PC13, pinout.csv does not list it");
}

static void hardware_pinout_csv_errors_name_line_and_column(void **state) {
  fixture *fx = *state;
  /* PIN_CH_INDEX is on line 3; its pin field starts at column 14 */
  char *c = csv_move_pin(fx->csv_text, "PIN_CH_INDEX", "PZ2");
  int rc = hwpin_parse_csv(c, "pinout.csv", &fx->csv, fx->err, sizeof fx->err);
  free(c);
  assert_int_equal(rc, -1);
  if (!strstr(fx->err, "pinout.csv:3:14: PIN_CH_INDEX: expected a pin like PA1"))
    fail_msg("unexpected message: %s", fx->err);

  const char *unterminated = "signal,pin,adc_signal,adc_channel\n"
                             "PIN_LED,\"PC13,,\n";
  rc = hwpin_parse_csv(unterminated, "pinout.csv", &fx->csv, fx->err, sizeof fx->err);
  assert_int_equal(rc, -1);
  if (!strstr(fx->err, "pinout.csv:2:16: malformed field"))
    fail_msg("unexpected message: %s", fx->err);

  const char *no_column = "signal,pin,adc_channel\nPIN_LED,PC13,\n";
  rc = hwpin_parse_csv(no_column, "pinout.csv", &fx->csv, fx->err, sizeof fx->err);
  assert_int_equal(rc, -1);
  if (!strstr(fx->err, "lacks the column 'adc_signal'"))
    fail_msg("unexpected message: %s", fx->err);
}

static void hardware_pinout_header_errors_name_line_and_column(void **state) {
  fixture *fx = *state;
  const char *bad = "/* pins */\n#define PIN_LED BOARD_PIN('C', 13)\n"
                    "#define PIN_BUTTON PA0\n";
  int rc = hwpin_parse_header(bad, "board_pins.h", &fx->header, fx->err, sizeof fx->err);
  assert_int_equal(rc, -1);
  if (!strstr(fx->err, "board_pins.h:3:20: PIN_BUTTON: expected BOARD_PIN("))
    fail_msg("unexpected message: %s", fx->err);

  /* a define inside a comment is not a pin */
  const char *commented = "/* #define PIN_LED BOARD_PIN('C', 13)\n*/\n"
                          "#define ADC_CH_THUMB 1 // thumb\n";
  rc = hwpin_parse_header(commented, "board_pins.h", &fx->header, fx->err, sizeof fx->err);
  assert_int_equal(rc, 0);
  assert_int_equal(fx->header.n_pins, 0);
  assert_int_equal(fx->header.n_adcs, 1);
  assert_int_equal(fx->header.adcs[0].line, 3);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(hardware_pinout_files_agree),
    cmocka_unit_test(hardware_pinout_catches_pin_moved_in_header),
    cmocka_unit_test(hardware_pinout_catches_pin_moved_in_csv),
    cmocka_unit_test(hardware_pinout_catches_adc_channel_change),
    cmocka_unit_test(hardware_pinout_rejects_usb_pins),
    cmocka_unit_test(hardware_pinout_rejects_swd_pins),
    cmocka_unit_test(hardware_pinout_rejects_pin_used_twice),
    cmocka_unit_test(hardware_pinout_catches_missing_row),
    cmocka_unit_test(hardware_pinout_csv_errors_name_line_and_column),
    cmocka_unit_test(hardware_pinout_header_errors_name_line_and_column),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}

/* Pin-map checker: reads the firmware's board_pins.h and the makers'
 * hardware/pinout.csv into one shape and reports every way they disagree.
 *
 * Both parsers return 0 on success, or -1 with a message in err naming
 * file:line:column and what was expected. hwpin_compare never fails; it
 * returns the number of problems and lists them, one per line, in report.
 */
#ifndef HWPIN_H
#define HWPIN_H

#include <stddef.h>

#define HWPIN_MAX      32
#define HWPIN_NAME_MAX 48

/* One named pin: PIN_CH_THUMB -> port 'A' (0), pin 1. */
typedef struct {
  char name[HWPIN_NAME_MAX];
  int port; /* 0 = A, 1 = B, ... */
  int num;  /* 0..15 */
  int line; /* where it was stated */
} hwpin_pin;

/* One named ADC channel: ADC_CH_THUMB -> 1. */
typedef struct {
  char name[HWPIN_NAME_MAX];
  int channel;
  int line;
} hwpin_adc;

/* A whole pin map as one file states it. */
typedef struct {
  const char *path; /* for messages; not owned */
  hwpin_pin pins[HWPIN_MAX];
  int n_pins;
  hwpin_adc adcs[HWPIN_MAX];
  int n_adcs;
} hwpin_map;

int hwpin_parse_header(const char *text, const char *path, hwpin_map *out, char *err,
                       size_t err_len);
int hwpin_parse_csv(const char *text, const char *path, hwpin_map *out, char *err, size_t err_len);
int hwpin_compare(const hwpin_map *header, const hwpin_map *csv, char *report, size_t report_len);

/* "PA1" for port 0, pin 1; buf needs 5 bytes. */
void hwpin_format(int port, int num, char *buf, size_t len);

/* The STM32F411 ADC1 input a pin carries, or -1 if it has none. */
int hwpin_adc1_input(int port, int num);

#endif

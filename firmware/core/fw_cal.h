/* Per-channel calibration: the smallest and largest filtered count each
 * string reached between CAL_START and CAL_SAVE (or two button presses),
 * kept in one flash page so it survives a reset.
 *
 * Record in flash, little-endian, FW_CAL_RECORD_LEN bytes:
 *   magic u32 "MRCL" | version u16 | n_channels u16 | min u16[5] | max u16[5]
 *   | CRC-32C u32 over everything before it
 * Erased flash (all 0xFF) means "never calibrated" (GP_CAL_DEFAULTS); any
 * other record that fails a check means GP_CAL_CORRUPT, and the defaults
 * (the full ADC range) are used until the next CAL_SAVE or CAL_CLEAR.
 */
#ifndef FW_CAL_H
#define FW_CAL_H

#include <stdint.h>

#include "fw_config.h"

#define FW_CAL_MAGIC      0x4C434D52u /* "MRCL" in memory order */
#define FW_CAL_VERSION    1u
#define FW_CAL_RECORD_LEN (4u + 2u + 2u + 4u * FW_N_CH + 4u)

typedef struct fw_cal {
  uint8_t state; /* GP_CAL_* */
  uint16_t min[FW_N_CH];
  uint16_t max[FW_N_CH];
  uint16_t run_min[FW_N_CH]; /* the extremes of the run in progress */
  uint16_t run_max[FW_N_CH];
} fw_cal;

typedef enum fw_cal_result {
  FW_CAL_OK = 0,
  FW_CAL_ERR_STATE, /* CAL_SAVE without CAL_START */
  FW_CAL_ERR_SPAN,  /* a string moved less than FW_CAL_MIN_SPAN */
  FW_CAL_ERR_FLASH, /* the page could not be written or erased */
} fw_cal_result;

/* Loads the record from flash: VALID, DEFAULTS or CORRUPT. */
void fw_cal_load(fw_cal *cal);
/* Starts (or restarts) a capture. */
void fw_cal_start(fw_cal *cal);
/* Feeds one filtered sample to a running capture. */
void fw_cal_feed(fw_cal *cal, const uint16_t ch[FW_N_CH]);
/* Ends the capture and stores it. On failure the previous calibration stays
 * in use and the capture keeps running (except for FW_CAL_ERR_STATE). */
fw_cal_result fw_cal_save(fw_cal *cal);
/* Forgets the calibration: the page erased, then defaults in use. If the
 * erase fails, FW_CAL_ERR_FLASH and the calibration is left as it was. */
fw_cal_result fw_cal_clear(fw_cal *cal);

/* Record (de)serialisation, public for the tests that corrupt it. */
void fw_cal_record_write(const uint16_t min[FW_N_CH], const uint16_t max[FW_N_CH],
                         uint8_t rec[FW_CAL_RECORD_LEN]);
/* Returns GP_CAL_VALID (min/max filled), GP_CAL_DEFAULTS (erased) or
 * GP_CAL_CORRUPT. */
uint8_t fw_cal_record_read(const uint8_t rec[FW_CAL_RECORD_LEN], uint16_t min[FW_N_CH],
                           uint16_t max[FW_N_CH]);

#endif

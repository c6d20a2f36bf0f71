#include "fw_cal.h"

#include "fw_hal.h"
#include "gp.h"

static void put16(uint8_t *p, uint16_t v) {
  p[0] = (uint8_t)v;
  p[1] = (uint8_t)(v >> 8);
}

static void put32(uint8_t *p, uint32_t v) {
  for (unsigned i = 0; i < 4; i++) p[i] = (uint8_t)(v >> (8u * i));
}

static uint16_t get16(const uint8_t *p) {
  return (uint16_t)(p[0] | (p[1] << 8));
}

static uint32_t get32(const uint8_t *p) {
  return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static void set_defaults(fw_cal *cal) {
  for (unsigned c = 0; c < FW_N_CH; c++) {
    cal->min[c] = 0;
    cal->max[c] = FW_ADC_MAX;
  }
}

void fw_cal_record_write(const uint16_t min[FW_N_CH], const uint16_t max[FW_N_CH],
                         uint8_t rec[FW_CAL_RECORD_LEN]) {
  put32(rec, FW_CAL_MAGIC);
  put16(rec + 4, FW_CAL_VERSION);
  put16(rec + 6, FW_N_CH);
  for (unsigned c = 0; c < FW_N_CH; c++) {
    put16(rec + 8 + 2 * c, min[c]);
    put16(rec + 8 + 2 * FW_N_CH + 2 * c, max[c]);
  }
  put32(rec + FW_CAL_RECORD_LEN - 4, gp_crc32c(0, rec, FW_CAL_RECORD_LEN - 4));
}

uint8_t fw_cal_record_read(const uint8_t rec[FW_CAL_RECORD_LEN], uint16_t min[FW_N_CH],
                           uint16_t max[FW_N_CH]) {
  unsigned erased = 1;
  for (unsigned i = 0; i < FW_CAL_RECORD_LEN; i++) erased &= rec[i] == 0xFFu;
  if (erased) return GP_CAL_DEFAULTS;
  if (get32(rec) != FW_CAL_MAGIC || get16(rec + 4) != FW_CAL_VERSION || get16(rec + 6) != FW_N_CH ||
      get32(rec + FW_CAL_RECORD_LEN - 4) != gp_crc32c(0, rec, FW_CAL_RECORD_LEN - 4))
    return GP_CAL_CORRUPT;
  uint16_t lo[FW_N_CH], hi[FW_N_CH];
  for (unsigned c = 0; c < FW_N_CH; c++) {
    lo[c] = get16(rec + 8 + 2 * c);
    hi[c] = get16(rec + 8 + 2 * FW_N_CH + 2 * c);
    /* A record with a good CRC but an impossible range was written by
     * something else: still not ours to trust. */
    if (hi[c] > FW_ADC_MAX || lo[c] >= hi[c]) return GP_CAL_CORRUPT;
  }
  for (unsigned c = 0; c < FW_N_CH; c++) {
    min[c] = lo[c];
    max[c] = hi[c];
  }
  return GP_CAL_VALID;
}

void fw_cal_load(fw_cal *cal) {
  uint8_t rec[FW_CAL_RECORD_LEN];
  set_defaults(cal);
  if (fw_hal_flash_read(rec, sizeof rec) != 0)
    cal->state = GP_CAL_DEFAULTS;
  else
    cal->state = fw_cal_record_read(rec, cal->min, cal->max);
  if (cal->state != GP_CAL_VALID) set_defaults(cal);
}

void fw_cal_start(fw_cal *cal) {
  for (unsigned c = 0; c < FW_N_CH; c++) {
    cal->run_min[c] = (uint16_t)FW_ADC_MAX;
    cal->run_max[c] = 0;
  }
  cal->state = GP_CAL_RUNNING;
}

void fw_cal_feed(fw_cal *cal, const uint16_t ch[FW_N_CH]) {
  if (cal->state != GP_CAL_RUNNING) return;
  for (unsigned c = 0; c < FW_N_CH; c++) {
    if (ch[c] < cal->run_min[c]) cal->run_min[c] = ch[c];
    if (ch[c] > cal->run_max[c]) cal->run_max[c] = ch[c];
  }
}

fw_cal_result fw_cal_save(fw_cal *cal) {
  if (cal->state != GP_CAL_RUNNING) return FW_CAL_ERR_STATE;
  for (unsigned c = 0; c < FW_N_CH; c++)
    if (cal->run_max[c] < cal->run_min[c] ||
        (uint32_t)(cal->run_max[c] - cal->run_min[c]) < FW_CAL_MIN_SPAN)
      return FW_CAL_ERR_SPAN;
  uint8_t rec[FW_CAL_RECORD_LEN];
  fw_cal_record_write(cal->run_min, cal->run_max, rec);
  if (fw_hal_flash_write(rec, sizeof rec) != 0) return FW_CAL_ERR_FLASH;
  /* Trust only what reads back. */
  uint8_t back[FW_CAL_RECORD_LEN];
  uint16_t lo[FW_N_CH], hi[FW_N_CH];
  if (fw_hal_flash_read(back, sizeof back) != 0 || fw_cal_record_read(back, lo, hi) != GP_CAL_VALID)
    return FW_CAL_ERR_FLASH;
  for (unsigned c = 0; c < FW_N_CH; c++) {
    cal->min[c] = lo[c];
    cal->max[c] = hi[c];
  }
  cal->state = GP_CAL_VALID;
  return FW_CAL_OK;
}

fw_cal_result fw_cal_clear(fw_cal *cal) {
  /* A NACK means nothing changed (SPEC.md, NACK): a failed erase keeps the
   * calibration in use, so the host can retry instead of seeing DEFAULTS
   * that the next reset would undo. */
  if (fw_hal_flash_erase() != 0) return FW_CAL_ERR_FLASH;
  set_defaults(cal);
  cal->state = GP_CAL_DEFAULTS;
  return FW_CAL_OK;
}

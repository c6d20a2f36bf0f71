#include "fw_filter.h"

void fw_filter_init(fw_filter *f) {
  for (unsigned c = 0; c < FW_N_CH; c++) f->y[c] = 0;
  f->primed = 0;
}

int fw_filter_block(fw_filter *f, const uint16_t block[FW_BLOCK_LEN], uint16_t out[FW_N_CH]) {
  int clipped = 0;
  for (unsigned c = 0; c < FW_N_CH; c++) {
    uint32_t sum = 0;
    for (unsigned s = 0; s < FW_OVERSAMPLE; s++) {
      uint32_t v = block[s * FW_N_CH + c] & FW_ADC_MAX;
      if (v == 0 || v == FW_ADC_MAX) clipped = 1;
      sum += v;
    }
    /* Mean of the oversamples, rounded, in filter fixed point. */
    int32_t x = (int32_t)(((sum << FW_FILTER_FRAC_BITS) + FW_OVERSAMPLE / 2u) / FW_OVERSAMPLE);
    if (!f->primed) {
      f->y[c] = x;
    } else {
      int32_t d = x - f->y[c];
      /* Symmetric rounding toward zero, so rising and falling steps settle
       * alike (>> of a negative value is implementation-defined in C). */
      int32_t step = d >= 0 ? (d >> FW_FILTER_SHIFT) : -((-d) >> FW_FILTER_SHIFT);
      if (step == 0 && d != 0) step = d > 0 ? 1 : -1;
      f->y[c] += step;
    }
    /* Nearest count; a tie goes the way the filter is moving (down only when
     * the input is below the state), so a falling step rounds exactly as the
     * mirror image of a rising one. At rest a tie rounds up, as the mean
     * above does. */
    uint32_t half = (1u << (FW_FILTER_FRAC_BITS - 1u)) - (x < f->y[c] ? 1u : 0u);
    uint32_t y = ((uint32_t)f->y[c] + half) >> FW_FILTER_FRAC_BITS;
    out[c] = (uint16_t)(y > FW_ADC_MAX ? FW_ADC_MAX : y);
  }
  f->primed = 1;
  return clipped;
}

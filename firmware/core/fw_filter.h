/* Oversampling and low-pass filtering of the five string sensors.
 *
 * Each tick's block holds FW_OVERSAMPLE conversions per channel; their mean
 * is one 1 kHz sample (a boxcar over the tick: lag (FW_OVERSAMPLE-1)/2
 * conversion periods, 0.375 ms on the Black Pill). The samples then pass a
 * first-order low-pass, an exponential moving average
 *
 *   y[n] = y[n-1] + (x[n] - y[n-1]) / 2^k,        alpha = 2^-k
 *
 * kept in fixed point with FW_FILTER_FRAC_BITS fractional bits. Its step
 * response is 1 - (1 - alpha)^n after n ticks; its lag at low frequencies
 * (group delay at DC) is (1 - alpha) / alpha ticks; its -3 dB corner is
 * about -ln(1 - alpha) * FW_TICK_HZ / (2 pi). For the default k = 3:
 * lag 7 ticks (7 ms), 50 % of a step after 6 ticks, 90 % after 18, 99 %
 * after 35, corner 21 Hz: well under the 125 Hz Nyquist limit of the 250 Hz
 * default frame rate, and above the few hertz a finger moves at.
 */
#ifndef FW_FILTER_H
#define FW_FILTER_H

#include <stdint.h>

#include "fw_config.h"

typedef struct fw_filter {
  int32_t y[FW_N_CH]; /* filter state, counts << FW_FILTER_FRAC_BITS */
  uint8_t primed;     /* the first sample sets the state (no start-up ramp) */
} fw_filter;

void fw_filter_init(fw_filter *f);
/* Feeds one tick's block. Writes the filtered counts to out and returns 1 if
 * any conversion sat at 0 or full scale (the CLIPPED flag). */
int fw_filter_block(fw_filter *f, const uint16_t block[FW_BLOCK_LEN], uint16_t out[FW_N_CH]);

#endif

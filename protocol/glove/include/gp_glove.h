/* A glove's own frames, INFO and SAMPLE, built from what a glove knows: a
 * description, channel values 0..1 and seconds of device time.
 *
 * One encoder for every glove that the host or the tools make up: the
 * keyboard's glove (host/app) and glove-gen's synthetic glove (tools/libgg)
 * both send their frames through it, so they announce and round alike. The
 * firmware builds its frames freestanding, in firmware/core/fw_frame.c.
 * This library is hosted C11 (it rounds with libm); the codec it encodes
 * with, gp, stays freestanding.
 *
 *   gp_info info = gp_default_glove_info();
 *   gp_glove_info_set_rate(&info, 100);
 *   n = gp_glove_info_encode(&info, wire, sizeof wire);
 *   gp_sample s = gp_glove_sample(seq, gp_glove_time_us(t_s), counts);
 *   n = gp_glove_sample_encode(&s, GP_SPEC_HASH, wire, sizeof wire);
 */
#ifndef GP_GLOVE_H
#define GP_GLOVE_H

#include <stddef.h>
#include <stdint.h>

#include "gp.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a made-up glove announces unless told otherwise: this build's
 * protocol and spec hash, firmware 0.1.0, the right hand, uid 0, five
 * channels of GP_SAMPLE_CH_BITS bits, frame and sample rate 0 (set them
 * with gp_glove_info_set_rate), 115200 baud, and the factory calibration
 * (GP_CAL_DEFAULTS, each channel 0..GP_SAMPLE_CH_MAX). */
gp_info gp_default_glove_info(void);

/* Sets the frame rate and the sample rate (a made-up glove takes one value
 * per frame) to rate_hz, rounded; at most 65535, 0 for no positive rate. */
void gp_glove_info_set_rate(gp_info *info, double rate_hz);

/* Encodes INFO as a glove built from info->spec_hash sends it (announced
 * and encoded with that hash). The wire length (at most GP_MAX_WIRE), or 0
 * when cap is too small. */
size_t gp_glove_info_encode(const gp_info *info, uint8_t *wire, size_t cap);

/* A channel value 0..1 as ADC counts 0..GP_SAMPLE_CH_MAX, rounded; values
 * beyond the ends are clamped and NaN reads as 0. */
uint16_t gp_glove_value_count(double value);

/* Seconds of device time as a SAMPLE's t_us: rounded to the microsecond,
 * wrapping at 2^32 as a device clock does. */
uint32_t gp_glove_time_us(double t_s);

/* A SAMPLE with no flags set: sequence number, device time, and the
 * GP_SAMPLE_CH_COUNT channels in counts. */
gp_sample gp_glove_sample(uint16_t seq, uint32_t t_us, const uint16_t ch[GP_SAMPLE_CH_COUNT]);

/* Encodes a SAMPLE with spec_hash: the wire length (at most GP_MAX_WIRE),
 * or 0 when cap is too small. */
size_t gp_glove_sample_encode(const gp_sample *s, uint32_t spec_hash, uint8_t *wire, size_t cap);

#ifdef __cplusplus
}
#endif

#endif

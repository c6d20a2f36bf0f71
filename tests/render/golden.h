/* Frames compared with committed PNGs (golden images), and with each
 * other, at one tolerance: per channel within MR_GOLDEN_TOLERANCE of 255
 * on at least MR_GOLDEN_FRACTION of the pixels. Any test of pictures may
 * use it. With MR_UPDATE_GOLDEN=1 in the environment the frame is written
 * as the golden instead (then commit the PNG). */
#ifndef MR_TEST_GOLDEN_H
#define MR_TEST_GOLDEN_H

#include <stddef.h>
#include <stdint.h>

#define MR_GOLDEN_TOLERANCE 5
#define MR_GOLDEN_FRACTION  0.999

/* The fraction of pixels of two w x h RGB frames whose every channel is
 * within tolerance; *worst (may be NULL) gets the largest difference. */
double mr_frames_agreement(const uint8_t *a, const uint8_t *b, int w, int h, int tolerance,
                           int *worst);

/* 0 when rgb (w x h, top row first) agrees with the PNG at png_path;
 * else -1, msg saying why, and the frame written beside the test binary
 * as NAME.actual.png to look at. Updates the PNG when MR_UPDATE_GOLDEN=1. */
int mr_golden_compare(const char *png_path, const uint8_t *rgb, int w, int h, char *msg,
                      size_t msg_size);

/* Writes rgb as a PNG; 0 or -1. */
int mr_png_write(const char *path, const uint8_t *rgb, int w, int h);

#endif

/* Golden images through stb_image and stb_image_write (Debian's libstb
 * ships them compiled). */
#include "golden.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>
#include <stb_image_write.h>

double mr_frames_agreement(const uint8_t *a, const uint8_t *b, int w, int h, int tolerance,
                           int *worst) {
  size_t n = (size_t)w * (size_t)h, ok = 0;
  int max = 0;
  for (size_t i = 0; i < n; i++) {
    int far = 0;
    for (int c = 0; c < 3; c++) {
      int d = abs((int)a[3 * i + (size_t)c] - (int)b[3 * i + (size_t)c]);
      if (d > max) max = d;
      if (d > tolerance) far = 1;
    }
    ok += !far;
  }
  if (worst) *worst = max;
  return n ? (double)ok / (double)n : 1.0;
}

int mr_png_write(const char *path, const uint8_t *rgb, int w, int h) {
  return stbi_write_png(path, w, h, 3, rgb, w * 3) ? 0 : -1;
}

static void write_actual(const char *png_path, const uint8_t *rgb, int w, int h, char *where,
                         size_t where_size) {
  const char *base = strrchr(png_path, '/');
  base = base ? base + 1 : png_path;
  char stem[256];
  snprintf(stem, sizeof stem, "%s", base);
  char *dot = strrchr(stem, '.');
  if (dot) *dot = '\0';
#ifdef MR_BINARY_DIR
  snprintf(where, where_size, "%s/tests/render/%s.actual.png", MR_BINARY_DIR, stem);
#else
  snprintf(where, where_size, "%s.actual.png", stem);
#endif
  if (mr_png_write(where, rgb, w, h) != 0) snprintf(where, where_size, "(not written)");
}

int mr_golden_compare(const char *png_path, const uint8_t *rgb, int w, int h, char *msg,
                      size_t msg_size) {
  const char *update = getenv("MR_UPDATE_GOLDEN");
  if (update && strcmp(update, "1") == 0) {
    if (mr_png_write(png_path, rgb, w, h) == 0) return 0;
    snprintf(msg, msg_size, "%s: cannot write the golden", png_path);
    return -1;
  }
  int gw = 0, gh = 0, n = 0;
  unsigned char *g = stbi_load(png_path, &gw, &gh, &n, 3);
  char where[512] = "";
  if (!g) {
    write_actual(png_path, rgb, w, h, where, sizeof where);
    snprintf(msg, msg_size,
             "%s: cannot read (%s); the frame is in %s (MR_UPDATE_GOLDEN=1 makes it)", png_path,
             stbi_failure_reason(), where);
    return -1;
  }
  int rc = 0;
  if (gw != w || gh != h) {
    snprintf(msg, msg_size, "%s: %dx%d, the frame is %dx%d", png_path, gw, gh, w, h);
    rc = -1;
  } else {
    int worst = 0;
    double agree = mr_frames_agreement(rgb, g, w, h, MR_GOLDEN_TOLERANCE, &worst);
    if (agree < MR_GOLDEN_FRACTION) {
      write_actual(png_path, rgb, w, h, where, sizeof where);
      snprintf(msg, msg_size,
               "%s: only %.4f%% of pixels within %d/255 (worst %d); the frame is in %s", png_path,
               agree * 100, MR_GOLDEN_TOLERANCE, worst, where);
      rc = -1;
    }
  }
  stbi_image_free(g);
  return rc;
}

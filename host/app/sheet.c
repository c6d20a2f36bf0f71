/* The contact sheet. Frames come one at a time and the count is not known
 * ahead (a live show ends when it is stopped), so the sheet keeps every
 * stride-th frame and, when twice the cells are held, drops every other
 * one and doubles the stride: what is held stays evenly spread over the
 * show, in bounded memory. At the end, cells of them are picked evenly. */
#include "sheet.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>
#include <stb_truetype.h>

#define FONT_PATH "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf"
#define THUMB_W   320
#define GAP       4

typedef struct thumb {
  uint8_t *rgb;
  double t;
} thumb;

struct mr_sheet {
  int width, height, tw, th, cells;
  thumb *held; /* up to 2 cells */
  int n_held;
  uint64_t offered, stride;
};

mr_sheet *mr_sheet_create(int width, int height, int cells) {
  mr_sheet *sh = calloc(1, sizeof *sh);
  if (sh == NULL) return NULL;
  sh->width = width;
  sh->height = height;
  sh->cells = cells > 0 ? cells : 24;
  sh->tw = width < THUMB_W ? width : THUMB_W;
  sh->th = (int)lround((double)height * sh->tw / width);
  if (sh->th < 1) sh->th = 1;
  sh->stride = 1;
  sh->held = calloc((size_t)sh->cells * 2, sizeof *sh->held);
  if (sh->held == NULL) {
    free(sh);
    return NULL;
  }
  return sh;
}

void mr_sheet_destroy(mr_sheet *sh) {
  if (sh == NULL) return;
  for (int i = 0; i < sh->n_held; i++) free(sh->held[i].rgb);
  free(sh->held);
  free(sh);
}

/* A box filter from the frame to the thumbnail: each thumbnail pixel is
 * the mean of the frame pixels under it. */
static void shrink(const mr_sheet *sh, const uint8_t *rgb, uint8_t *out) {
  for (int y = 0; y < sh->th; y++) {
    int y0 = y * sh->height / sh->th, y1 = (y + 1) * sh->height / sh->th;
    if (y1 <= y0) y1 = y0 + 1;
    for (int x = 0; x < sh->tw; x++) {
      int x0 = x * sh->width / sh->tw, x1 = (x + 1) * sh->width / sh->tw;
      if (x1 <= x0) x1 = x0 + 1;
      unsigned sum[3] = { 0, 0, 0 }, n = 0;
      for (int yy = y0; yy < y1; yy++)
        for (int xx = x0; xx < x1; xx++, n++)
          for (int c = 0; c < 3; c++) sum[c] += rgb[((size_t)yy * sh->width + xx) * 3 + c];
      for (int c = 0; c < 3; c++) out[((size_t)y * sh->tw + x) * 3 + c] = (uint8_t)(sum[c] / n);
    }
  }
}

void mr_sheet_offer(mr_sheet *sh, const uint8_t *rgb, double t) {
  uint64_t i = sh->offered++;
  if (i % sh->stride != 0) return;
  if (sh->n_held == 2 * sh->cells) {
    int k = 0;
    for (int j = 0; j < sh->n_held; j++) {
      if (j % 2 == 0)
        sh->held[k++] = sh->held[j];
      else
        free(sh->held[j].rgb);
    }
    sh->n_held = k;
    sh->stride *= 2;
    if (i % sh->stride != 0) return;
  }
  uint8_t *small = malloc((size_t)sh->tw * sh->th * 3);
  if (small == NULL) return; /* a sheet with a thumbnail fewer */
  shrink(sh, rgb, small);
  sh->held[sh->n_held].rgb = small;
  sh->held[sh->n_held].t = t;
  sh->n_held++;
}

int mr_sheet_cells(const mr_sheet *sh) {
  return sh->n_held < sh->cells ? sh->n_held : sh->cells;
}

/* The font, read once; NULL when the system has none. */
static const stbtt_fontinfo *font(void) {
  static stbtt_fontinfo info;
  static unsigned char *data;
  static int tried;
  if (tried) return data != NULL ? &info : NULL;
  tried = 1;
  FILE *f = fopen(FONT_PATH, "rb");
  if (f == NULL) return NULL;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  data = n > 0 ? malloc((size_t)n) : NULL;
  if (data == NULL || fread(data, 1, (size_t)n, f) != (size_t)n ||
      !stbtt_InitFont(&info, data, stbtt_GetFontOffsetForIndex(data, 0))) {
    free(data);
    data = NULL;
  }
  fclose(f);
  return data != NULL ? &info : NULL;
}

/* Darkens a box under the text so it reads on any picture. */
static void dark_box(uint8_t *rgb, int width, int height, int x, int y, int w, int h) {
  for (int yy = y; yy < y + h && yy < height; yy++)
    for (int xx = x; xx < x + w && xx < width; xx++)
      for (int c = 0; c < 3; c++) {
        if (xx < 0 || yy < 0) continue;
        uint8_t *p = &rgb[((size_t)yy * width + xx) * 3 + c];
        *p = (uint8_t)(*p / 3);
      }
}

void mr_sheet_text(uint8_t *rgb, int width, int height, int x, int y, int px, const char *text) {
  const stbtt_fontinfo *f = font();
  if (f == NULL) return;
  float scale = stbtt_ScaleForPixelHeight(f, (float)px);
  int ascent, descent, gap, adv, lsb;
  stbtt_GetFontVMetrics(f, &ascent, &descent, &gap);
  stbtt_GetCodepointHMetrics(f, 'M', &adv, &lsb);
  int cw = (int)ceilf(adv * scale), baseline = y + 2 + (int)lroundf(ascent * scale);
  dark_box(rgb, width, height, x, y, cw * (int)strlen(text) + 6, px + 4);
  int pen = x + 3;
  for (const char *s = text; *s != '\0'; s++, pen += cw) {
    int w, h, xo, yo;
    unsigned char *g = stbtt_GetCodepointBitmap(f, 0, scale, (unsigned char)*s, &w, &h, &xo, &yo);
    for (int j = 0; g != NULL && j < h; j++)
      for (int i = 0; i < w; i++) {
        int xx = pen + xo + i, yy = baseline + yo + j;
        if (xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
        unsigned a = g[j * w + i];
        for (int c = 0; c < 3; c++) {
          uint8_t *p = &rgb[((size_t)yy * width + xx) * 3 + c];
          *p = (uint8_t)((*p * (255 - a) + 255 * a) / 255);
        }
      }
    stbtt_FreeBitmap(g, NULL);
  }
}

int mr_sheet_write(const mr_sheet *sh, const char *path) {
  int n = mr_sheet_cells(sh);
  int cols = n < 6 ? (n > 0 ? n : 1) : 6, rows = n > 0 ? (n + cols - 1) / cols : 1;
  int w = cols * (sh->tw + GAP) + GAP, h = rows * (sh->th + GAP) + GAP;
  uint8_t *img = malloc((size_t)w * h * 3);
  if (img == NULL) return -1;
  memset(img, 24, (size_t)w * h * 3);
  for (int k = 0; k < n; k++) {
    /* Evenly over what is held, first and last included. */
    int j = n > 1 ? (int)lround((double)k * (sh->n_held - 1) / (n - 1)) : 0;
    const thumb *th = &sh->held[j];
    int x0 = GAP + (k % cols) * (sh->tw + GAP), y0 = GAP + (k / cols) * (sh->th + GAP);
    for (int y = 0; y < sh->th; y++)
      memcpy(&img[((size_t)(y0 + y) * w + x0) * 3], &th->rgb[(size_t)y * sh->tw * 3],
             (size_t)sh->tw * 3);
    char label[32];
    snprintf(label, sizeof label, "%.2f s", th->t);
    mr_sheet_text(img, w, h, x0 + 2, y0 + 2, 14, label);
  }
  int ok = stbi_write_png(path, w, h, 3, img, w * 3);
  free(img);
  return ok ? 0 : -1;
}

/* The contact sheet. Frames come one at a time and neither their count
 * nor the show's length is known ahead (a live show ends when it is
 * stopped), and show time may fall unevenly on them (renders skipped
 * under load). So the sheet holds frames at least a step of show time
 * apart: every frame at first; when twice the cells are held, the step
 * grows to the time held over one and a half times the cells and the
 * held are thinned to it, so what is held stays spread evenly over show
 * time, in bounded memory. The frame offered last is
 * kept too, held or not, so that the sheet ends where the show ended (a
 * curtain closing). At the end, cells of them are picked at even steps of
 * show time, the first and the last frame always among them. */
#include "sheet.h"

#include <math.h>
#include <stdbool.h>
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
  thumb last;  /* the frame offered last when it is not held, else rgb NULL */
  double step; /* the least show time between two held frames, s */
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
  free(sh->last.rgb);
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

/* Thins the held frames to a grown step: each kept one at least a step
 * after the one kept before, the first always kept; every other one when
 * that keeps them all (show time standing still). */
static void thin(mr_sheet *sh) {
  double span = sh->held[sh->n_held - 1].t - sh->held[0].t;
  /* About one and a half cells' worth kept: enough for every cell, and
   * room for as many again before the next thinning. */
  sh->step = fmax(sh->step, span / (1.5 * sh->cells));
  int k = 1;
  for (int j = 1; j < sh->n_held; j++) {
    if (sh->held[j].t >= sh->held[k - 1].t + sh->step && sh->step > 0)
      sh->held[k++] = sh->held[j];
    else
      free(sh->held[j].rgb);
  }
  if (sh->step > 0) {
    sh->n_held = k;
    return;
  }
  for (int j = 1; j < sh->n_held; j++) sh->held[j].rgb = NULL; /* freed above */
  sh->n_held = 1;
}

/* Whether a frame at t is held: a step after the last held, room made. */
static bool holds(mr_sheet *sh, double t) {
  if (sh->n_held > 0 && t < sh->held[sh->n_held - 1].t + sh->step) return false;
  if (sh->n_held < 2 * sh->cells) return true;
  thin(sh);
  return sh->n_held < 2 * sh->cells && t >= sh->held[sh->n_held - 1].t + sh->step;
}

void mr_sheet_offer(mr_sheet *sh, const uint8_t *rgb, double t) {
  size_t bytes = (size_t)sh->tw * sh->th * 3;
  if (holds(sh, t)) {
    uint8_t *small = malloc(bytes);
    if (small == NULL) return; /* a sheet with a thumbnail fewer */
    shrink(sh, rgb, small);
    sh->held[sh->n_held].rgb = small;
    sh->held[sh->n_held].t = t;
    sh->n_held++;
    free(sh->last.rgb); /* the last frame is a held one now */
    sh->last.rgb = NULL;
    return;
  }
  /* Not held: it becomes the last frame, in the room of the one before. */
  if (sh->last.rgb == NULL && (sh->last.rgb = malloc(bytes)) == NULL) return;
  shrink(sh, rgb, sh->last.rgb);
  sh->last.t = t;
}

/* The frames to pick from, in show order: the held, then the last. */
static int candidates(const mr_sheet *sh) {
  return sh->n_held + (sh->last.rgb != NULL ? 1 : 0);
}

static const thumb *candidate(const mr_sheet *sh, int j) {
  return j < sh->n_held ? &sh->held[j] : &sh->last;
}

int mr_sheet_cells(const mr_sheet *sh) {
  int n = candidates(sh);
  return n < sh->cells ? n : sh->cells;
}

int mr_sheet_pick(const mr_sheet *sh, int *picks, int n) {
  int total = candidates(sh), cells = mr_sheet_cells(sh);
  if (n > cells) n = cells;
  if (n <= 0) return 0;
  double t0 = candidate(sh, 0)->t, t1 = candidate(sh, total - 1)->t;
  int prev = -1;
  for (int k = 0; k < n; k++) {
    /* The frame nearest to its even step of time, after the one before
     * and leaving one for each cell still to come. */
    double goal = n > 1 ? t0 + (t1 - t0) * k / (n - 1) : t0;
    int lo = prev + 1, hi = total - (n - k), best = lo;
    for (int j = lo + 1; j <= hi; j++)
      if (fabs(candidate(sh, j)->t - goal) < fabs(candidate(sh, best)->t - goal)) best = j;
    picks[k] = prev = best;
  }
  return n;
}

double mr_sheet_time(const mr_sheet *sh, int pick) {
  return candidate(sh, pick)->t;
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
  int *picks = malloc((size_t)sh->cells * sizeof *picks);
  if (picks == NULL) return -1;
  int n = mr_sheet_pick(sh, picks, sh->cells);
  int cols = n < 6 ? (n > 0 ? n : 1) : 6, rows = n > 0 ? (n + cols - 1) / cols : 1;
  int w = cols * (sh->tw + GAP) + GAP, h = rows * (sh->th + GAP) + GAP;
  uint8_t *img = malloc((size_t)w * h * 3);
  if (img == NULL) return free(picks), -1;
  memset(img, 24, (size_t)w * h * 3);
  for (int k = 0; k < n; k++) {
    const thumb *th = candidate(sh, picks[k]);
    int x0 = GAP + (k % cols) * (sh->tw + GAP), y0 = GAP + (k / cols) * (sh->th + GAP);
    for (int y = 0; y < sh->th; y++)
      memcpy(&img[((size_t)(y0 + y) * w + x0) * 3], &th->rgb[(size_t)y * sh->tw * 3],
             (size_t)sh->tw * 3);
    char label[32];
    snprintf(label, sizeof label, "%.2f s", mr_sheet_time(sh, picks[k]));
    mr_sheet_text(img, w, h, x0 + 2, y0 + 2, 14, label);
  }
  int ok = stbi_write_png(path, w, h, 3, img, w * 3);
  free(img);
  free(picks);
  return ok ? 0 : -1;
}

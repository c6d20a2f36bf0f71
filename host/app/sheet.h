/* A contact sheet: a grid of thumbnails of a show, each with its time.
 * Frames are offered one by one without knowing how many will come; the
 * sheet keeps them evenly spread over the whole show. */
#ifndef MR_SHEET_H
#define MR_SHEET_H

#include <stdint.h>

typedef struct mr_sheet mr_sheet;

/* For frames of width x height, at most cells thumbnails. NULL: no memory. */
mr_sheet *mr_sheet_create(int width, int height, int cells);
void mr_sheet_destroy(mr_sheet *sh);
void mr_sheet_offer(mr_sheet *sh, const uint8_t *rgb, double t);
/* The thumbnails that the sheet will show. */
int mr_sheet_cells(const mr_sheet *sh);
/* Which frames the sheet shows, in order, into picks (at most n): evenly
 * over show time, the first and the last frame offered always among them.
 * Returns how many; mr_sheet_time gives each one's time. */
int mr_sheet_pick(const mr_sheet *sh, int *picks, int n);
double mr_sheet_time(const mr_sheet *sh, int pick);
/* The sheet as a PNG; 0 or -1. */
int mr_sheet_write(const mr_sheet *sh, const char *path);

/* Text into an RGB image at x, y (top left), white on a dark box, in the
 * system's DejaVu Sans Mono at px pixels; nothing when the font is not
 * there. */
void mr_sheet_text(uint8_t *rgb, int width, int height, int x, int y, int px, const char *text);

#endif

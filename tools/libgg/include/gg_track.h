/* Recorded tracks for glove-gen's motion: five channels over time, read from
 * a CSV (glove-dump --csv writes one) or from a .mrec recording. */
#ifndef GG_TRACK_H
#define GG_TRACK_H

#include <stddef.h>

#include "gg_motion.h"

/* NULL with "FILE:LINE:COL: what" (CSV) or "FILE: byte N: what" in err. */
gg_track *gg_track_load_csv(const char *path, char *err, size_t errcap);
gg_track *gg_track_load_mrec(const char *path, char *err, size_t errcap);

gg_track *gg_track_retain(gg_track *t);
void gg_track_release(gg_track *t);

/* Channel `column` at t_s seconds from the track's start, 0..1, linearly
 * interpolated; past the end it holds the last value or starts over. */
double gg_track_eval(const gg_track *t, int column, double t_s, int loop);

#endif

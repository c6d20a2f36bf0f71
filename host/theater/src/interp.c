/* Frames presented between steps (§4.6, the alternative to landing): the
 * physics steps at the Δt the ATS chooses, and a frame whose time falls
 * inside a step shows the state interpolated linearly between the step's
 * two ends. Between two states h apart the chord strays at most h²a/8 from
 * the path: 3.1 mm for a 0.05 s step in free fall, a pixel or two on a
 * stage a metre and a half wide, and less for a puppet its strings hold.
 * Positions only: they are what the stage draws. */
#include "theater_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int mr_interp_open(mr_interp *ip, int n) {
  memset(ip, 0, sizeof *ip);
  ip->n = n > 0 ? n : 0;
  size_t len = (size_t)(ip->n > 0 ? 3 * ip->n : 1);
  ip->before = calloc(len, sizeof *ip->before);
  ip->after = calloc(len, sizeof *ip->after);
  ip->frame = calloc(len, sizeof *ip->frame);
  return ip->before && ip->after && ip->frame ? 0 : -1;
}

void mr_interp_close(mr_interp *ip) {
  free(ip->before);
  free(ip->after);
  free(ip->frame);
  memset(ip, 0, sizeof *ip);
}

void mr_interp_mark(mr_interp *ip, const mr_world *w) {
  mr_world_positions(w, ip->before, ip->n);
  ip->t_before = mr_world_time(w);
}

const double *mr_interp_at(mr_interp *ip, const mr_world *w, double t) {
  mr_world_positions(w, ip->after, ip->n);
  double t_after = mr_world_time(w), span = t_after - ip->t_before;
  double u = span > 0 ? (t - ip->t_before) / span : 1.0;
  u = fmin(1.0, fmax(0.0, u));
  for (int i = 0; i < 3 * ip->n; i++)
    ip->frame[i] = ip->before[i] + u * (ip->after[i] - ip->before[i]);
  ip->lead = t_after - t;
  return ip->frame;
}

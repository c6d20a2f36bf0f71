/* A control frame as a wooden control (the paper's Fig. 2, 3 and 8):
 * the bars that join its points, where the strings are tied. */
#include "mr_stage.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const style_names[] = { "solid", "wire" };

const char *mr_frame_style_name(mr_frame_style s) {
  return (int)s >= 0 && (size_t)s < sizeof style_names / sizeof style_names[0] ? style_names[s]
                                                                               : "unknown";
}

int mr_frame_style_parse(const char *name, mr_frame_style *out) {
  for (size_t i = 0; name != NULL && i < sizeof style_names / sizeof style_names[0]; i++)
    if (strcmp(name, style_names[i]) == 0) {
      *out = (mr_frame_style)i;
      return 0;
    }
  return -1;
}

static double dist2(const double *xyz, int a, int b) {
  double d = 0;
  for (int k = 0; k < 3; k++) {
    double e = xyz[3 * a + k] - xyz[3 * b + k];
    d += e * e;
  }
  return d;
}

/* Prim's tree, grown from point 0: each round the point outside the tree
 * nearest to it joins by its shortest bar, and the others' distances to
 * the tree shrink to their distance to it where that is nearer. Ties go to
 * the lower index, so a symmetric frame gets the same bars every time. */
int mr_frame_bars(const double *xyz, int n, int *pairs) {
  if (xyz == NULL || pairs == NULL || n < 2) return 0;
  double *near = malloc((size_t)n * sizeof *near);
  int *from = malloc((size_t)n * sizeof *from);
  if (near == NULL || from == NULL) {
    free(near);
    free(from);
    return -1;
  }
  for (int i = 0; i < n; i++) {
    near[i] = i == 0 ? -1 : dist2(xyz, 0, i); /* -1: in the tree */
    from[i] = 0;
  }
  int bars = 0;
  for (int round = 1; round < n; round++) {
    int next = -1;
    for (int i = 0; i < n; i++)
      if (near[i] >= 0 && (next < 0 || near[i] < near[next])) next = i;
    if (next < 0) break; /* NaN positions: the bars found so far */
    pairs[2 * bars] = from[next];
    pairs[2 * bars + 1] = next;
    bars++;
    near[next] = -1;
    for (int i = 0; i < n; i++) {
      double d = near[i] >= 0 ? dist2(xyz, next, i) : -1;
      if (d < near[i]) {
        near[i] = d;
        from[i] = next;
      }
    }
  }
  free(near);
  free(from);
  return bars;
}

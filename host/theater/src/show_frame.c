/* A show's frame as a value: its arrays its own, sized for the show; and
 * the names of the show's statuses. */
#include <stdlib.h>
#include <string.h>

#include "mr_show.h"
#include "theater_internal.h"

int mr_show_frame_alloc(mr_show_frame *f, size_t n_frames, int n_particles) {
  memset(f, 0, sizeof *f);
  size_t nf = n_frames > 0 ? n_frames : 1, np = n_particles > 0 ? (size_t)n_particles : 1;
  f->target = calloc(nf, sizeof *f->target);
  f->pose = calloc(nf, sizeof *f->pose);
  f->glove_of = calloc(nf, sizeof *f->glove_of);
  f->xyz = calloc(3 * np, sizeof *f->xyz);
  if (f->target == NULL || f->pose == NULL || f->glove_of == NULL || f->xyz == NULL) {
    mr_show_frame_free(f);
    return -1;
  }
  f->n_frames = n_frames;
  f->n_particles = n_particles;
  return 0;
}

void mr_show_frame_free(mr_show_frame *f) {
  if (f == NULL) return;
  free(f->target);
  free(f->pose);
  free(f->glove_of);
  free(f->xyz);
  memset(f, 0, sizeof *f);
}

int mr_show_frame_copy(mr_show_frame *dst, const mr_show_frame *src) {
  if (dst == NULL || src == NULL || dst->n_frames != src->n_frames ||
      dst->n_particles != src->n_particles || dst->xyz == NULL)
    return -1;
  mr_show_frame keep = *dst; /* dst's own arrays */
  *dst = *src;
  dst->target = keep.target;
  dst->pose = keep.pose;
  dst->glove_of = keep.glove_of;
  dst->xyz = keep.xyz;
  size_t n = src->n_frames;
  memcpy(dst->target, src->target, n * sizeof *dst->target);
  memcpy(dst->pose, src->pose, n * sizeof *dst->pose);
  memcpy(dst->glove_of, src->glove_of, n * sizeof *dst->glove_of);
  memcpy(dst->xyz, src->xyz, 3 * (size_t)src->n_particles * sizeof *dst->xyz);
  return 0;
}

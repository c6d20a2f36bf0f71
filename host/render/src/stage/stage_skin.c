/* §3.3 (4), freeform mode, "in process of being implemented" in the paper,
 * done here as linear blend skinning. Each vertex is bound once to its
 * nearest bones (particles) with weights (mr_stage_skin_bind); each frame
 * every bone gets a pose taking the world at rest to the world now, and
 * the renderer blends the poses by the weights on the GPU.
 *
 * A particle is a point: it has a place but no orientation. A bone's turn
 * is therefore read from its neighbourhood: the rotation that best takes
 * the offsets from the bone to its nearest bones at rest onto the same
 * offsets now (Horn's closed form, stage_math.c). Where those neighbours
 * lie on one line at rest the turn about that line is unknowable, and the
 * bone takes the shortest turn of the line; a bone with no neighbour (a
 * skin of one bone) only moves. Under a rigid motion of all the bones
 * every bone with a spanning neighbourhood gets exactly that motion, so
 * the skin moves rigidly too. */
#include "stage_internal.h"
#include "stage_math.h"

#include <math.h>
#include <string.h>

/* A vertex closer to a bone than this is on it. */
#define ON_BONE_M 1e-6

static double dist2(const double a[3], const double b[3]) {
  double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

static double norm2(const double a[3]) {
  return a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
}

/* The k nearest of n bones to p, nearest first, ties to the lower index;
 * returns how many (at most k). */
static int nearest(const double p[3], const double *bones, int n, int skip, int k, int *idx,
                   double *d2) {
  int have = 0;
  for (int b = 0; b < n; b++) {
    if (b == skip) continue;
    double d = dist2(p, &bones[3 * b]);
    int at = have < k ? have++ : k;
    if (at == k && !(d < d2[k - 1])) continue;
    if (at == k) at = k - 1;
    while (at > 0 && d < d2[at - 1]) {
      d2[at] = d2[at - 1];
      idx[at] = idx[at - 1];
      at--;
    }
    d2[at] = d;
    idx[at] = b;
  }
  return have;
}

mr_stage_status mr_stage_skin_bind(const float *vertices, size_t n_vertices,
                                   const double *bones_rest, int n_bones, int influences,
                                   int *index, float *weight) {
  if ((n_vertices > 0 && (vertices == NULL || index == NULL || weight == NULL)) ||
      bones_rest == NULL || n_bones < 1 || influences < 1 || influences > MR_SKIN_MAX_INFLUENCES)
    return MR_STAGE_ERR_ARG;
  for (size_t v = 0; v < n_vertices; v++) {
    double p[3] = { vertices[3 * v], vertices[3 * v + 1], vertices[3 * v + 2] };
    if (!mr_stage_finite3(p)) return MR_STAGE_ERR_VALUE;
    int idx[MR_SKIN_MAX_INFLUENCES];
    double d2[MR_SKIN_MAX_INFLUENCES];
    int k = nearest(p, bones_rest, n_bones, -1, influences, idx, d2);
    int *io = &index[(size_t)influences * v];
    float *wo = &weight[(size_t)influences * v];
    for (int j = 0; j < influences; j++) {
      io[j] = 0;
      wo[j] = 0;
    }
    if (d2[0] < ON_BONE_M * ON_BONE_M) { /* on a bone: that bone alone */
      io[0] = idx[0];
      wo[0] = 1;
      continue;
    }
    /* Inverse square distance, normalised to sum 1. */
    double w[MR_SKIN_MAX_INFLUENCES], sum = 0;
    for (int j = 0; j < k; j++) sum += (w[j] = 1 / d2[j]);
    for (int j = 0; j < k; j++) {
      io[j] = idx[j];
      wo[j] = (float)(w[j] / sum);
    }
  }
  return MR_STAGE_OK;
}

/* Whether the offsets u (n of them) span at least a plane: two of them
 * more than 5° from one line. */
static bool spans_plane(const double *u, int n) {
  const double sin5 = 0.0871557427;
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < n; j++) {
      const double *a = &u[3 * i], *b = &u[3 * j];
      double c[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                      a[0] * b[1] - a[1] * b[0] };
      if (norm2(c) > sin5 * sin5 * norm2(a) * norm2(b)) return true;
    }
  return false;
}

void mr_stage_bones_prepare(mr_stage *s, size_t m) {
  const mr_model_def *d = &s->models[m];
  const mr_stage_model *st = &s->state[m];
  const double *rest = st->bones_rest;
  for (int b = 0; b < d->n_bones; b++) {
    int *nb = &s->neighbours[(st->first_bone + (size_t)b) * MR_STAGE_BONE_NEIGHBOURS];
    double d2[MR_STAGE_BONE_NEIGHBOURS], u[3 * MR_STAGE_BONE_NEIGHBOURS];
    int k = nearest(&rest[3 * b], rest, d->n_bones, b, MR_STAGE_BONE_NEIGHBOURS, nb, d2);
    int used = 0;
    for (int j = 0; j < k; j++) /* a neighbour on the same spot gives no direction */
      if (d2[j] > MR_STAGE_TINY_M * MR_STAGE_TINY_M) nb[used++] = nb[j];
    for (int j = used; j < MR_STAGE_BONE_NEIGHBOURS; j++) nb[j] = -1;
    for (int j = 0; j < used; j++)
      for (int c = 0; c < 3; c++) u[3 * j + c] = rest[3 * nb[j] + c] - rest[3 * b + c];
    s->fit[st->first_bone + (size_t)b] = used == 0              ? MR_STAGE_FIT_NONE
                                         : spans_plane(u, used) ? MR_STAGE_FIT_FULL
                                                                : MR_STAGE_FIT_AXIS;
  }
}

/* Bone b's turn from its neighbours' offsets at rest (u) and now (v). */
static void bone_turn(int fit, const double *u, const double *v, int n, double q[4]) {
  q[0] = 1;
  q[1] = q[2] = q[3] = 0;
  if (fit == MR_STAGE_FIT_FULL) {
    mr_stage_fit_rotation(u, v, n, q);
    return;
  }
  if (fit != MR_STAGE_FIT_AXIS) return;
  /* One line: its direction at rest and now, each neighbour's offset
   * signed to point the way the first one does. */
  double wr[3] = { 0, 0, 0 }, wn[3] = { 0, 0, 0 };
  for (int j = 0; j < n; j++) {
    double sgn = u[3 * j] * u[0] + u[3 * j + 1] * u[1] + u[3 * j + 2] * u[2] >= 0 ? 1 : -1;
    for (int c = 0; c < 3; c++) {
      wr[c] += sgn * u[3 * j + c];
      wn[c] += sgn * v[3 * j + c];
    }
  }
  mr_stage_quat_arc(wr, wn, q); /* untouched when the line collapsed: no turn */
}

int mr_stage_bones_update(mr_stage *s, size_t m, const double *xyz) {
  const mr_model_def *d = &s->models[m];
  const mr_stage_model *st = &s->state[m];
  for (int b = 0; b < d->n_bones; b++)
    if (!mr_stage_finite3(&xyz[3 * (size_t)st->bones[b]])) return -1;
  for (int b = 0; b < d->n_bones; b++) {
    size_t g = st->first_bone + (size_t)b;
    const int *nb = &s->neighbours[g * MR_STAGE_BONE_NEIGHBOURS];
    const double *r0 = &st->bones_rest[3 * b], *p0 = &xyz[3 * (size_t)st->bones[b]];
    double u[3 * MR_STAGE_BONE_NEIGHBOURS], v[3 * MR_STAGE_BONE_NEIGHBOURS];
    int n = 0;
    for (; n < MR_STAGE_BONE_NEIGHBOURS && nb[n] >= 0; n++)
      for (int c = 0; c < 3; c++) {
        u[3 * n + c] = st->bones_rest[3 * nb[n] + c] - r0[c];
        v[3 * n + c] = xyz[3 * (size_t)st->bones[nb[n]] + c] - p0[c];
      }
    /* World at rest -> world now: x' = R (x - r0) + p0. */
    mr_pose *pose = &s->bone_poses[g];
    bone_turn(s->fit[g], u, v, n, pose->orientation);
    double rr[3];
    mr_pose_rotate(pose->orientation, r0, rr);
    for (int c = 0; c < 3; c++) pose->position[c] = p0[c] - rr[c];
  }
  return 0;
}

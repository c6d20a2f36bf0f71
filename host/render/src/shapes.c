/* The built-in shapes (mr_stage.h): unit-size meshes a scene names instead
 * of a model file. Round shapes are surfaces of revolution about y built
 * from a profile of rings, closed by flat discs where they have ends. */
#include "shapes.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The finest level: enough to look round at the sizes puppets are drawn
 * up close. Each coarser level halves all three (mr_shape_mesh_lod). */
enum { SEGMENTS = 32, RINGS = 16, CAP_RINGS = 8 };
#define MR_PI 3.14159265358979323846

/* One ring of a surface of revolution: its radius and height, its
 * normal's outward and up parts (need not be unit), and the texture's v. */
typedef struct ring {
  double r, y, nr, ny, v;
} ring;

/* The tessellation of one level: segments round, the sphere's rings pole
 * to pole, the capsule's rings per cap. */
typedef struct tess {
  int segments, rings, cap_rings;
} tess;

typedef struct builder {
  mr_mesh *m;
  size_t nv, ni;
} builder;

int mr_mesh_alloc(mr_mesh *m, size_t n_vertices, size_t n_triangles, int with_uvs) {
  memset(m, 0, sizeof *m);
  m->positions = malloc(3 * n_vertices * sizeof *m->positions);
  m->normals = malloc(3 * n_vertices * sizeof *m->normals);
  m->uvs = with_uvs ? malloc(2 * n_vertices * sizeof *m->uvs) : NULL;
  m->indices = malloc(3 * n_triangles * sizeof *m->indices);
  if (!m->positions || !m->normals || (with_uvs && !m->uvs) || !m->indices) {
    mr_mesh_release(m);
    return -1;
  }
  m->n_vertices = n_vertices;
  m->n_indices = 3 * n_triangles;
  return 0;
}

void mr_mesh_release(mr_mesh *m) {
  free(m->positions);
  free(m->normals);
  free(m->uvs);
  free(m->indices);
  free(m->texture);
  memset(m, 0, sizeof *m);
}

static uint32_t put_vertex(builder *b, const double p[3], const double n[3], double u, double v) {
  size_t k = b->nv++;
  double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int i = 0; i < 3; i++) {
    b->m->positions[3 * k + i] = (float)p[i];
    b->m->normals[3 * k + i] = (float)(n[i] / len);
  }
  b->m->uvs[2 * k] = (float)u;
  b->m->uvs[2 * k + 1] = (float)v;
  return (uint32_t)k;
}

static void put_triangle(builder *b, uint32_t i0, uint32_t i1, uint32_t i2) {
  b->m->indices[b->ni++] = i0;
  b->m->indices[b->ni++] = i1;
  b->m->indices[b->ni++] = i2;
}

/* Vertices and triangles of a surface of n rings: a ring of radius 0 (a
 * pole) makes the band beside it a fan, one triangle per segment. */
static void lathe_count(const ring *rings, int n, int segments, size_t *nv, size_t *nt) {
  *nv += (size_t)n * (size_t)(segments + 1);
  for (int i = 0; i + 1 < n; i++)
    *nt += (size_t)segments * (size_t)(2 - (rings[i].r == 0) - (rings[i + 1].r == 0));
}

/* Rings run bottom to top; column j sits at angle θ = 2π j / SEGMENTS from
 * +z towards +x, so seen from outside columns run left to right and rings
 * upwards, and (a, b, c), (a, c, d) below are counter-clockwise. The seam
 * repeats its column for the texture's u = 0 and 1. */
static void lathe(builder *b, const ring *rings, int n, int segments) {
  uint32_t first = (uint32_t)b->nv, seg = (uint32_t)segments;
  for (int i = 0; i < n; i++) {
    for (int j = 0; j <= segments; j++) {
      double t = 2 * MR_PI * j / segments, s = sin(t), c = cos(t);
      double p[3] = { rings[i].r * s, rings[i].y, rings[i].r * c };
      double nn[3] = { rings[i].nr * s, rings[i].ny, rings[i].nr * c };
      put_vertex(b, p, nn, (double)j / segments, rings[i].v);
    }
  }
  for (int i = 0; i + 1 < n; i++) {
    for (uint32_t j = 0; j < seg; j++) {
      uint32_t a = first + (uint32_t)i * (seg + 1) + j, d = a + seg + 1;
      if (rings[i].r != 0) put_triangle(b, a, a + 1, d + 1);
      if (rings[i + 1].r != 0) put_triangle(b, a, d + 1, d);
    }
  }
}

/* A flat disc of radius 0.5 at height y facing up (+1) or down (-1). */
static void disc(builder *b, double y, int facing, int segments) {
  double n[3] = { 0, facing, 0 }, centre[3] = { 0, y, 0 };
  uint32_t c = put_vertex(b, centre, n, 0.5, 0.5), seg = (uint32_t)segments;
  for (int j = 0; j < segments; j++) {
    double t = 2 * MR_PI * j / segments, p[3] = { 0.5 * sin(t), y, 0.5 * cos(t) };
    put_vertex(b, p, n, 0.5 + p[0], 0.5 - facing * p[2]);
  }
  for (uint32_t j = 0; j < seg; j++) {
    uint32_t r0 = c + 1 + j, r1 = c + 1 + (j + 1) % seg;
    if (facing > 0)
      put_triangle(b, c, r0, r1);
    else
      put_triangle(b, c, r1, r0);
  }
}

static int sphere_rings(ring *out, int rings) {
  for (int i = 0; i <= rings; i++) {
    double phi = MR_PI * i / rings;
    double r = (i == 0 || i == rings) ? 0 : sin(phi);
    out[i] = (ring){ 0.5 * r, -0.5 * cos(phi), r, -cos(phi), 1.0 - (double)i / rings };
  }
  return rings + 1;
}

/* A capsule of radius 0.5 whose ends stay inside y 0..1: hemispheres of
 * radius 0.5 would meet in the middle and leave a sphere, so the caps are
 * half-ellipsoids 0.25 tall and the middle half is straight. */
static int capsule_rings(ring *out, int cap_rings) {
  int n = 0;
  for (int k = 0; k <= cap_rings; k++) {
    double phi = 0.5 * MR_PI * k / cap_rings, r = k == 0 ? 0 : sin(phi), y = 0.25 - 0.25 * cos(phi);
    out[n++] = (ring){ 0.5 * r, y, 2 * r, -4 * cos(phi), 1.0 - y };
  }
  for (int k = cap_rings; k >= 0; k--) {
    double phi = 0.5 * MR_PI * k / cap_rings, r = k == 0 ? 0 : sin(phi), y = 0.75 + 0.25 * cos(phi);
    out[n++] = (ring){ 0.5 * r, y, 2 * r, 4 * cos(phi), 1.0 - y };
  }
  return n;
}

/* The box's faces: each an outward normal n and a unit u along the face;
 * v = n × u, so u × v = n and the corners below run counter-clockwise. */
static void box(builder *b) {
  static const double faces[6][2][3] = {
    { { 1, 0, 0 }, { 0, 0, -1 } }, { { -1, 0, 0 }, { 0, 0, 1 } }, { { 0, 1, 0 }, { 1, 0, 0 } },
    { { 0, -1, 0 }, { 1, 0, 0 } }, { { 0, 0, 1 }, { 1, 0, 0 } },  { { 0, 0, -1 }, { -1, 0, 0 } },
  };
  static const double corner[4][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
  for (int f = 0; f < 6; f++) {
    const double *n = faces[f][0], *u = faces[f][1];
    double v[3] = { n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2],
                    n[0] * u[1] - n[1] * u[0] };
    uint32_t first = (uint32_t)b->nv;
    for (int k = 0; k < 4; k++) {
      double p[3];
      for (int i = 0; i < 3; i++) p[i] = 0.5 * (n[i] + corner[k][0] * u[i] + corner[k][1] * v[i]);
      put_vertex(b, p, n, 0.5 + 0.5 * corner[k][0], 0.5 - 0.5 * corner[k][1]);
    }
    put_triangle(b, first, first + 1, first + 2);
    put_triangle(b, first, first + 2, first + 3);
  }
}

static int build(mr_shape s, tess ts, builder *b, size_t *nv, size_t *nt) {
  ring rings[2 * CAP_RINGS + RINGS + 2];
  int n = 0, discs = 0; /* discs: 1 bottom, 2 bottom and top */
  const double cone_n = 1 / sqrt(1.25);
  switch (s) {
  case MR_SHAPE_SPHERE:
    n = sphere_rings(rings, ts.rings);
    break;
  case MR_SHAPE_CAPSULE:
    n = capsule_rings(rings, ts.cap_rings);
    break;
  case MR_SHAPE_CYLINDER:
    rings[0] = (ring){ 0.5, 0, 1, 0, 1 };
    rings[1] = (ring){ 0.5, 1, 1, 0, 0 };
    n = 2, discs = 2;
    break;
  case MR_SHAPE_CONE: /* r = 0.5 (1 - y): the side's normal leans up by 0.5 */
    for (int i = 0; i <= 4; i++)
      rings[i] = (ring){ 0.5 * (4 - i) / 4.0, i / 4.0, cone_n, 0.5 * cone_n, 1 - i / 4.0 };
    n = 5, discs = 1;
    break;
  case MR_SHAPE_BOX:
    if (!b)
      *nv += 24, *nt += 12;
    else
      box(b);
    return 0;
  default:
    return -1;
  }
  if (!b) {
    lathe_count(rings, n, ts.segments, nv, nt);
    *nv += (size_t)discs * (size_t)(ts.segments + 1);
    *nt += (size_t)discs * (size_t)ts.segments;
    return 0;
  }
  lathe(b, rings, n, ts.segments);
  if (discs >= 1) disc(b, 0, -1, ts.segments);
  if (discs == 2) disc(b, 1, 1, ts.segments);
  return 0;
}

int mr_shape_mesh_lod(mr_shape s, int level, mr_mesh *out) {
  memset(out, 0, sizeof *out);
  if (level < 0 || level >= MR_SHAPE_LEVELS) return -1;
  tess ts = { SEGMENTS >> level, RINGS >> level, CAP_RINGS >> level };
  size_t nv = 0, nt = 0;
  if (build(s, ts, NULL, &nv, &nt) != 0 || mr_mesh_alloc(out, nv, nt, 1) != 0) return -1;
  builder b = { out, 0, 0 };
  build(s, ts, &b, NULL, NULL);
  return 0;
}

int mr_shape_mesh(mr_shape s, mr_mesh *out) {
  return mr_shape_mesh_lod(s, 0, out);
}

int mr_shape_segments(int level) {
  return level < 0 || level >= MR_SHAPE_LEVELS ? 0 : SEGMENTS >> level;
}

/* A vertex's position on a grid a millionth of the mesh's size (a seam's
 * sin 2 pi is not quite sin 0), and its index, sorted to weld them. */
typedef struct welded {
  long long p[3];
  uint32_t i;
} welded;

static int by_position(const void *a, const void *b) {
  const welded *x = a, *y = b;
  for (int k = 0; k < 3; k++)
    if (x->p[k] != y->p[k]) return x->p[k] < y->p[k] ? -1 : 1;
  return 0;
}

static bool weld(const mr_mesh *m, welded *w) {
  double size = 0;
  for (size_t v = 0; v < 3 * m->n_vertices; v++) size = fmax(size, fabs(m->positions[v]));
  double grid = size > 0 ? 1e-6 * size : 1;
  for (size_t v = 0; v < m->n_vertices; v++) {
    for (int k = 0; k < 3; k++) {
      double q = m->positions[3 * v + (size_t)k] / grid;
      if (!(fabs(q) < 1e15)) return false;
      w[v].p[k] = llround(q);
    }
    w[v].i = (uint32_t)v;
  }
  return true;
}

static int by_key(const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

static uint32_t root(uint32_t *up, uint32_t i) {
  while (up[i] != i) i = up[i] = up[up[i]];
  return i;
}

/* Each directed edge once and its reverse once: every edge is shared by
 * two triangles wound the same way round. */
static bool edges_pair(const mr_mesh *m, const uint32_t *id, uint64_t *e) {
  size_t n = m->n_indices;
  for (size_t t = 0; t < n; t += 3) {
    for (int k = 0; k < 3; k++) {
      uint32_t a = id[m->indices[t + (size_t)k]], b = id[m->indices[t + (size_t)(k + 1) % 3]];
      if (a == b) return false;
      e[t + (size_t)k] = (uint64_t)a << 32 | b;
    }
  }
  qsort(e, n, sizeof *e, by_key);
  for (size_t k = 0; k < n; k++) {
    uint64_t rev = e[k] << 32 | e[k] >> 32;
    if ((k + 1 < n && e[k + 1] == e[k]) || !bsearch(&rev, e, n, sizeof *e, by_key)) return false;
  }
  return true;
}

/* Each connected part encloses a positive volume (its triangles turn
 * counter-clockwise seen from outside). */
static bool parts_outward(const mr_mesh *m, const uint32_t *id, uint32_t *up, double *vol,
                          uint32_t n_ids) {
  for (uint32_t i = 0; i < n_ids; i++) up[i] = i, vol[i] = 0;
  for (size_t t = 0; t < m->n_indices; t += 3) {
    uint32_t a = root(up, id[m->indices[t]]);
    for (int k = 1; k < 3; k++) up[root(up, id[m->indices[t + (size_t)k]])] = a;
  }
  for (size_t t = 0; t < m->n_indices; t += 3) {
    const float *a = &m->positions[3 * m->indices[t]], *b = &m->positions[3 * m->indices[t + 1]],
                *c = &m->positions[3 * m->indices[t + 2]];
    double cx = (double)b[1] * c[2] - (double)b[2] * c[1];
    double cy = (double)b[2] * c[0] - (double)b[0] * c[2];
    double cz = (double)b[0] * c[1] - (double)b[1] * c[0];
    vol[root(up, id[m->indices[t]])] += a[0] * cx + a[1] * cy + a[2] * cz;
  }
  for (uint32_t i = 0; i < n_ids; i++)
    if (up[i] == i && vol[i] <= 0) return false;
  return true;
}

bool mr_mesh_is_closed_outward(const mr_mesh *m) {
  size_t n = m->n_vertices;
  if (n == 0 || m->n_indices == 0 || m->n_indices % 3 != 0 || n >= UINT32_MAX) return false;
  welded *w = malloc(n * sizeof *w);
  uint32_t *id = malloc(n * sizeof *id), *up = malloc(n * sizeof *up);
  uint64_t *e = malloc(m->n_indices * sizeof *e);
  double *vol = malloc(n * sizeof *vol);
  bool ok = w && id && up && e && vol && weld(m, w);
  if (ok) {
    qsort(w, n, sizeof *w, by_position);
    uint32_t n_ids = 0;
    for (size_t v = 0; v < n; v++) {
      if (v > 0 && by_position(&w[v - 1], &w[v]) != 0) n_ids++;
      id[w[v].i] = n_ids;
    }
    ok = edges_pair(m, id, e) && parts_outward(m, id, up, vol, n_ids + 1);
  }
  free(w);
  free(id);
  free(up);
  free(e);
  free(vol);
  return ok;
}

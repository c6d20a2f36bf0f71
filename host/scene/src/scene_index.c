/* Particles by name and by place. A scene of 100 000 particles must load
 * in well under a second, so neither the name lookups of every item nor
 * the checks for a repeated name or a shared place may compare all pairs:
 * names are sorted once per batch of particles and searched by bisection,
 * and places are bucketed in cells as wide as the coincidence distance, so
 * a point is compared only with points in its own and the 26 next cells. */
#define _GNU_SOURCE /* qsort_r: a comparison with a context, no global */
#include "scene_read.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* By name; equal names by file order, so the later of a pair follows. */
static int by_name(const void *a, const void *b, void *particles) {
  const mr_scene_particle *p = particles;
  size_t i = *(const size_t *)a, j = *(const size_t *)b;
  int c = strcmp(p[i].name, p[j].name);
  return c != 0 ? c : (i > j) - (i < j);
}

typedef struct cell {
  double c[3];
  size_t i;
} cell;

static int cell_cmp3(const double a[3], const double b[3]) {
  for (int k = 0; k < 3; k++)
    if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
  return 0;
}

static int by_cell(const void *a, const void *b) {
  const cell *x = a, *y = b;
  int c = cell_cmp3(x->c, y->c);
  return c != 0 ? c : (x->i > y->i) - (x->i < y->i);
}

/* The first cell entry at or after key, by bisection. */
static size_t lower_bound(const cell *cells, size_t n, const double key[3]) {
  size_t lo = 0, hi = n;
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (cell_cmp3(cells[mid].c, key) < 0)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

static double dist3(const double a[3], const double b[3]) {
  double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return sqrt(dx * dx + dy * dy + dz * dz);
}

/* The pair (i, j), i later in the file, of coincident particles with the
 * smallest i; 0 when there is none. */
static int find_coincident(const mr_scene *s, cell *cells, size_t *later, size_t *earlier) {
  size_t n = s->n_particles;
  for (size_t i = 0; i < n; i++) {
    for (int k = 0; k < 3; k++)
      cells[i].c[k] = floor(s->particles[i].def.position[k] / MR_SCENE_COINCIDENT_M);
    cells[i].i = i;
  }
  qsort(cells, n, sizeof *cells, by_cell);
  size_t best_i = n, best_j = n;
  for (size_t a = 0; a < n; a++) {
    const double *here = cells[a].c;
    for (int d = 0; d < 27; d++) {
      double key[3] = { here[0] + (d % 3 - 1), here[1] + (d / 3 % 3 - 1), here[2] + (d / 9 - 1) };
      for (size_t b = lower_bound(cells, n, key); b < n && cell_cmp3(cells[b].c, key) == 0; b++) {
        size_t i = cells[a].i, j = cells[b].i;
        if (j >= i) continue;
        if (dist3(s->particles[i].def.position, s->particles[j].def.position) <
                MR_SCENE_COINCIDENT_M &&
            (i < best_i || (i == best_i && j < best_j))) {
          best_i = i;
          best_j = j;
        }
      }
    }
  }
  *later = best_i;
  *earlier = best_j;
  return best_i < n;
}

static int check_names(mr_reader *r) {
  const mr_scene *s = r->scene;
  size_t later = s->n_particles;
  for (size_t k = 1; k < r->n_by_name; k++) {
    size_t i = r->by_name[k - 1], j = r->by_name[k];
    if (strcmp(s->particles[i].name, s->particles[j].name) == 0 && j < later) later = j;
  }
  if (later == s->n_particles) return 0;
  const mr_scene_particle *p = &s->particles[later];
  return mr_scene_read_fail_at(r, p->pos.line, p->pos.column, MR_SCENE_ERR_VALUE,
                               "expected a unique particle name, '%s' is already declared",
                               p->name);
}

int mr_scene_index_particles(mr_reader *r) {
  const mr_scene *s = r->scene;
  size_t n = s->n_particles;
  size_t *idx = realloc(r->by_name, (n ? n : 1) * sizeof *idx);
  cell *cells = malloc((n ? n : 1) * sizeof *cells);
  if (idx == NULL || cells == NULL) {
    free(cells);
    if (idx != NULL) r->by_name = idx;
    return mr_scene_read_fail_at(r, 0, 0, MR_SCENE_ERR_NOMEM, "out of memory");
  }
  r->by_name = idx;
  for (size_t i = 0; i < n; i++) idx[i] = i;
  qsort_r(idx, n, sizeof *idx, by_name, s->particles);
  r->n_by_name = n;
  size_t later, earlier;
  int found = find_coincident(s, cells, &later, &earlier);
  free(cells);
  if (check_names(r) != 0) return -1;
  if (!found) return 0;
  const mr_scene_particle *p = &s->particles[later], *q = &s->particles[earlier];
  return mr_scene_read_fail_at(r, p->pos.line, p->pos.column, MR_SCENE_ERR_VALUE,
                               "particle '%s' coincides with particle '%s' (line %d); "
                               "expected distinct positions",
                               p->name, q->name, q->pos.line);
}

size_t mr_scene_lookup_particle(const mr_reader *r, const char *name) {
  const mr_scene *s = r->scene;
  size_t lo = 0, hi = r->n_by_name;
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    int c = strcmp(s->particles[r->by_name[mid]].name, name);
    if (c == 0) return r->by_name[mid];
    if (c < 0)
      lo = mid + 1;
    else
      hi = mid;
  }
  return (size_t)-1;
}

int mr_scene_qualify(const mr_reader *r, const char *name, char out[MR_SCENE_NAME_MAX]) {
  if (r->puppet == NULL) {
    int n = snprintf(out, MR_SCENE_NAME_MAX, "%s", name);
    return n >= 0 && n < MR_SCENE_NAME_MAX ? 0 : -1;
  }
  int n = snprintf(out, MR_SCENE_NAME_MAX, "%s.%s", r->puppet, name);
  return n >= 0 && n < MR_SCENE_NAME_MAX ? 0 : -1;
}

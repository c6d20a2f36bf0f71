/* Particles by name and by place. A scene of 100 000 particles must load
 * in well under a second, so neither the name lookups of every item nor
 * the checks for a repeated name or a shared place may compare all pairs,
 * nor pay a bisection of string compares per lookup: names are hashed
 * (open addressing), and places are bucketed in cells four times as wide
 * as the coincidence distance, the cells hashed too, so a point is
 * compared only with points in the cells its neighbourhood overlaps: one
 * cell per axis unless it lies near a face, 3.4 cells on average where
 * cells as wide as the distance would take 27 (each a likely cache miss
 * in a table of 100 000 places). Particles closer than the distance are
 * refused, so a cell holds at most 125 of them. Each batch of particles
 * (the scene's, then each puppet's) is added to the tables as it is read;
 * the batches before it were checked already, so only pairs with a new
 * particle can fail. */
#include "scene_read.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A cell of the place grid: its coordinates in units of the coincidence
 * distance, and the last particle put in it (a list through next[]). */
typedef struct cell {
  double c[3];
  uint32_t last; /* particle index + 1; 0: the slot is empty */
} cell;

struct mr_scene_index {
  size_t n;        /* particles indexed */
  uint32_t *names; /* particle index + 1 per slot, 0 empty; cap slots */
  cell *cells;     /* cap slots */
  uint32_t *next;  /* the particle before it in its cell, + 1; 0 none */
  size_t cap;      /* a power of two, at least twice n */
};

/* FNV-1a (64 bit): short names, no need for more. */
static uint64_t hash_text(const char *s) {
  uint64_t h = 0xcbf29ce484222325u;
  for (; *s; s++) h = (h ^ (unsigned char)*s) * 0x100000001b3u;
  return h;
}

static uint64_t hash_cell(const double c[3]) {
  uint64_t h = 0xcbf29ce484222325u;
  for (int k = 0; k < 3; k++) {
    double v = c[k] + 0.0; /* -0 and +0 are one cell, as == says */
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    h = (h ^ bits) * 0x100000001b3u;
    h ^= h >> 29;
  }
  return h;
}

static bool same_cell(const double a[3], const double b[3]) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

/* The slot of name: where it is, or the empty slot where it would go. */
static size_t name_slot(const mr_scene_index *x, const mr_scene *s, const char *name) {
  size_t mask = x->cap - 1;
  for (size_t k = (size_t)hash_text(name) & mask;; k = (k + 1) & mask)
    if (x->names[k] == 0 || strcmp(s->particles[x->names[k] - 1].name, name) == 0) return k;
}

static size_t cell_slot(const mr_scene_index *x, const double c[3]) {
  size_t mask = x->cap - 1;
  for (size_t k = (size_t)hash_cell(c) & mask;; k = (k + 1) & mask)
    if (x->cells[k].last == 0 || same_cell(x->cells[k].c, c)) return k;
}

#define CELL_M (4 * MR_SCENE_COINCIDENT_M)

static void cell_of(const mr_scene_particle *p, double c[3]) {
  for (int k = 0; k < 3; k++) c[k] = floor(p->def.position[k] / CELL_M);
}

static void put_place(mr_scene_index *x, const mr_scene *s, size_t i) {
  double c[3];
  cell_of(&s->particles[i], c);
  cell *e = &x->cells[cell_slot(x, c)];
  if (e->last == 0) memcpy(e->c, c, sizeof e->c);
  x->next[i] = e->last;
  e->last = (uint32_t)i + 1;
}

/* Room for n particles; the tables grow by rehashing what they hold. */
static int reserve(mr_scene_index *x, const mr_scene *s, size_t n) {
  if (n >= UINT32_MAX / 2) return -1;
  uint32_t *next = realloc(x->next, (n ? n : 1) * sizeof *next);
  if (next == NULL) return -1;
  x->next = next;
  if (x->cap >= 2 * n) return 0;
  size_t cap = 64;
  while (cap < 2 * n) cap *= 2;
  uint32_t *names = calloc(cap, sizeof *names);
  cell *cells = calloc(cap, sizeof *cells);
  if (names == NULL || cells == NULL) {
    free(names);
    free(cells);
    return -1;
  }
  free(x->names);
  free(x->cells);
  x->names = names;
  x->cells = cells;
  x->cap = cap;
  for (size_t i = 0; i < x->n; i++) {
    x->names[name_slot(x, s, s->particles[i].name)] = (uint32_t)i + 1;
    put_place(x, s, i);
  }
  return 0;
}

/* Adds particles [x->n, n) by name; the first that repeats a name is the
 * later one of the pair that comes first in the file: (size_t)-1 if none. */
static size_t add_names(mr_scene_index *x, const mr_scene *s, size_t n) {
  for (size_t i = x->n; i < n; i++) {
    size_t k = name_slot(x, s, s->particles[i].name);
    if (x->names[k] != 0) return i;
    x->names[k] = (uint32_t)i + 1;
  }
  return (size_t)-1;
}

/* The earliest particle before i within the coincidence distance of it,
 * or (size_t)-1. */
static size_t earliest_near(const mr_scene_index *x, const mr_scene *s, size_t i) {
  const double *here = s->particles[i].def.position;
  double lo[3], hi[3];
  for (int k = 0; k < 3; k++) {
    lo[k] = floor((here[k] - MR_SCENE_COINCIDENT_M) / CELL_M);
    hi[k] = floor((here[k] + MR_SCENE_COINCIDENT_M) / CELL_M);
  }
  size_t best = (size_t)-1;
  double key[3];
  for (key[0] = lo[0]; key[0] <= hi[0]; key[0]++)
    for (key[1] = lo[1]; key[1] <= hi[1]; key[1]++)
      for (key[2] = lo[2]; key[2] <= hi[2]; key[2]++) {
        const cell *e = &x->cells[cell_slot(x, key)];
        for (uint32_t j = e->last; j != 0; j = x->next[j - 1]) {
          const double *there = s->particles[j - 1].def.position;
          double dx = here[0] - there[0], dy = here[1] - there[1], dz = here[2] - there[2];
          if (sqrt(dx * dx + dy * dy + dz * dz) < MR_SCENE_COINCIDENT_M && j - 1 < best)
            best = j - 1;
        }
      }
  return best;
}

int mr_scene_index_particles(mr_reader *r) {
  const mr_scene *s = r->scene;
  size_t n = s->n_particles;
  if (r->index == NULL && (r->index = calloc(1, sizeof *r->index)) == NULL)
    return mr_scene_read_fail_at(r, 0, 0, MR_SCENE_ERR_NOMEM, "out of memory");
  mr_scene_index *x = r->index;
  if (reserve(x, s, n) != 0)
    return mr_scene_read_fail_at(r, 0, 0, MR_SCENE_ERR_NOMEM, "out of memory");
  size_t later = add_names(x, s, n);
  if (later != (size_t)-1) {
    const mr_scene_particle *p = &s->particles[later];
    return mr_scene_read_fail_at(r, p->pos.line, p->pos.column, MR_SCENE_ERR_VALUE,
                                 "expected a unique particle name, '%s' is already declared",
                                 p->name);
  }
  for (size_t i = x->n; i < n; i++) {
    size_t j = earliest_near(x, s, i);
    if (j != (size_t)-1) {
      const mr_scene_particle *p = &s->particles[i], *q = &s->particles[j];
      return mr_scene_read_fail_at(r, p->pos.line, p->pos.column, MR_SCENE_ERR_VALUE,
                                   "particle '%s' coincides with particle '%s' (line %d); "
                                   "expected distinct positions",
                                   p->name, q->name, q->pos.line);
    }
    put_place(x, s, i);
  }
  x->n = n;
  return 0;
}

size_t mr_scene_lookup_particle(const mr_reader *r, const char *name) {
  const mr_scene_index *x = r->index;
  if (x == NULL || x->n == 0) return (size_t)-1;
  uint32_t i = x->names[name_slot(x, r->scene, name)];
  return i != 0 && i - 1 < x->n ? i - 1 : (size_t)-1;
}

void mr_scene_index_free(mr_reader *r) {
  if (r->index == NULL) return;
  free(r->index->names);
  free(r->index->cells);
  free(r->index->next);
  free(r->index);
  r->index = NULL;
}

int mr_scene_qualify(const mr_reader *r, const char *name, char out[MR_SCENE_NAME_MAX]) {
  size_t a = r->puppet ? strlen(r->puppet) + 1 : 0, b = strlen(name);
  if (a + b >= MR_SCENE_NAME_MAX) return -1;
  if (r->puppet != NULL) {
    memcpy(out, r->puppet, a - 1);
    out[a - 1] = '.';
  }
  memcpy(out + a, name, b + 1);
  return 0;
}

/* The library's storage: one growth rule for every array, and the copy of a
 * matrix pattern that tells cached work from stale. */
#include "solver_internal.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

int mr_grow_to(void *pp, size_t *cap, size_t count, size_t elem_size) {
  void **p = pp;
  if (count == 0) count = 1;
  if (count <= *cap && *p) return 0;
  size_t grown = *cap ? *cap : 16;
  while (grown < count) grown *= 2;
  void *q = realloc(*p, grown * elem_size);
  if (!q) return MR_SOLVE_ERR_NOMEM;
  *p = q;
  *cap = grown;
  return 0;
}

int mr_buf_reserve(mr_buf *b, size_t count, size_t elem_size) {
  return mr_grow(&b->p, &b->cap, count, elem_size);
}

void mr_bufs_free(mr_buf *const *bufs, size_t count) {
  for (size_t i = 0; i < count; i++) {
    free(bufs[i]->p);
    bufs[i]->p = NULL;
    bufs[i]->cap = 0;
  }
}

/* Comparing the arrays was 2.4 % of the Fig. 10 run's instructions: a
 * solve or two an evaluation, each on a pattern met the time before. */
int mr_pattern_same(mr_pattern *pat, const mr_csr *A) {
  if (!pat->valid) return 0;
  if (A->pattern_id != 0 && pat->id == A->pattern_id) return 1;
  if (pat->n != A->n || pat->nnz != A->row_ptr[A->n] ||
      memcmp(pat->rp.p, A->row_ptr, (size_t)(A->n + 1) * sizeof(int)) != 0 ||
      memcmp(pat->col.p, A->col, (size_t)pat->nnz * sizeof(int)) != 0)
    return 0;
  pat->id = A->pattern_id;
  return 1;
}

uint64_t mr_pattern_new_id(void) {
  /* Shared by every thread's solvers: an id must not be handed out twice. */
  static _Atomic uint64_t last = 0;
  return atomic_fetch_add(&last, 1) + 1;
}

uint64_t mr_hash_ints(uint64_t h, const int *v, size_t n) {
  size_t i = 0;
  for (; i + 1 < n; i += 2)
    h = (h ^ ((uint64_t)(unsigned)v[i] | (uint64_t)(unsigned)v[i + 1] << 32)) * 1099511628211u;
  if (i < n) h = (h ^ (uint64_t)(unsigned)v[i]) * 1099511628211u;
  return h;
}

/* The row starts are left out: with the size, the columns alone tell
 * the patterns a physics run meets apart, and a rare match is compared
 * whole anyway. */
uint64_t mr_pattern_hash(const mr_csr *A) {
  const int dims[2] = { A->n, A->row_ptr[A->n] };
  uint64_t h = mr_hash_ints(14695981039346656037u, dims, 2);
  return mr_hash_ints(h, A->col, (size_t)dims[1]);
}

int mr_pattern_reserve(mr_pattern *pat, size_t n, size_t nnz) {
  if (mr_buf_reserve(&pat->rp, n + 1, sizeof(int)) != 0 ||
      mr_buf_reserve(&pat->col, nnz, sizeof(int)) != 0)
    return MR_SOLVE_ERR_NOMEM;
  return 0;
}

int mr_pattern_keep(mr_pattern *pat, const mr_csr *A) {
  const int nnz = A->row_ptr[A->n];
  pat->valid = 0;
  if (mr_pattern_reserve(pat, (size_t)A->n, (size_t)nnz) != 0) return MR_SOLVE_ERR_NOMEM;
  memcpy(pat->rp.p, A->row_ptr, ((size_t)A->n + 1) * sizeof(int));
  memcpy(pat->col.p, A->col, (size_t)nnz * sizeof(int));
  pat->n = A->n;
  pat->nnz = nnz;
  pat->id = A->pattern_id;
  pat->valid = 1;
  return 0;
}

void mr_pattern_free(mr_pattern *pat) {
  mr_buf *const bufs[] = { &pat->rp, &pat->col };
  mr_bufs_free(bufs, 2);
  pat->valid = 0;
}

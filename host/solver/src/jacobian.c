/* The constraint Jacobian J = ∂C/∂q (§5.2), stored by rows in 3-wide
 * blocks: a distance or pin constraint touches one or two particles, so a
 * row holds a handful of (particle, ∂C_i/∂x_particle) pairs instead of 3n
 * numbers. */
#include "solver_internal.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* row_ptr holds rows + 1 entries. */
static int grow_rows(mr_jac *J, int rows) {
  return mr_grow(&J->row_ptr, &J->cap_rows, (size_t)rows + 1, sizeof *J->row_ptr);
}

/* particle and d share one count; each keeps its own copy of the
 * capacity until both have grown. */
static int grow_entries(mr_jac *J, int entries) {
  size_t cap_p = J->cap_entries, cap_d = J->cap_entries;
  if (mr_grow(&J->particle, &cap_p, (size_t)entries, sizeof *J->particle) != 0 ||
      mr_grow(&J->d, &cap_d, (size_t)entries, sizeof *J->d) != 0)
    return MR_SOLVE_ERR_NOMEM;
  J->cap_entries = cap_p;
  return 0;
}

mr_solve_status mr_jac_reset(mr_jac *J, int n_particles) {
  if (!J || n_particles < 0) return MR_SOLVE_ERR_ARG;
  J->rows = 0;
  J->n_particles = n_particles;
  if (grow_rows(J, 0) != 0) return MR_SOLVE_ERR_NOMEM;
  J->row_ptr[0] = 0;
  return MR_SOLVE_OK;
}

mr_solve_status mr_jac_reserve(mr_jac *J, int rows, int entries) {
  if (!J || rows < 0 || entries < 0) return MR_SOLVE_ERR_ARG;
  if (grow_rows(J, rows) != 0 || grow_entries(J, entries) != 0) return MR_SOLVE_ERR_NOMEM;
  return MR_SOLVE_OK;
}

int mr_jac_begin_row(mr_jac *J) {
  if (!J || !J->row_ptr) return -1;
  if (grow_rows(J, J->rows + 1) != 0) return -1;
  int end = J->row_ptr[J->rows];
  J->rows++;
  J->row_ptr[J->rows] = end;
  return J->rows - 1;
}

mr_solve_status mr_jac_add(mr_jac *J, int particle, const double d[3]) {
  if (!J || J->rows == 0 || particle < 0 || particle >= J->n_particles) return MR_SOLVE_ERR_ARG;
  int start = J->row_ptr[J->rows - 1];
  int end = J->row_ptr[J->rows];
  /* A constraint may name a particle twice (e.g. a term built from two
     * pieces); J must hold the sum, once, or JM⁻¹Jᵀ would miss the cross
     * terms' structure. Rows are short, so a linear scan is cheapest. */
  for (int e = start; e < end; e++) {
    if (J->particle[e] == particle) {
      J->d[e][0] += d[0];
      J->d[e][1] += d[1];
      J->d[e][2] += d[2];
      return MR_SOLVE_OK;
    }
  }
  if ((size_t)end + 1 > J->cap_entries && grow_entries(J, end + 1) != 0) return MR_SOLVE_ERR_NOMEM;
  J->particle[end] = particle;
  memcpy(J->d[end], d, sizeof J->d[end]);
  J->row_ptr[J->rows] = end + 1;
  return MR_SOLVE_OK;
}

int mr_jac_add_rows(mr_jac *J, int count, int width) {
  if (!J || !J->row_ptr || count < 0 || width < 1) return -1;
  const int first = J->row_ptr[J->rows];
  const long long end = (long long)first + (long long)count * width;
  if (end > INT_MAX || grow_rows(J, J->rows + count) != 0 ||
      ((size_t)end > J->cap_entries && grow_entries(J, (int)end) != 0))
    return -1;
  int *rp = J->row_ptr + J->rows;
  for (int r = 1; r <= count; r++) rp[r] = first + r * width;
  J->rows += count;
  return first;
}

void mr_jac_free(mr_jac *J) {
  if (!J) return;
  free(J->row_ptr);
  free(J->particle);
  free(J->d);
  memset(J, 0, sizeof *J);
}

/* The products read J through locals: the compiler cannot tell that the
 * stores into out leave J's arrays alone, and would load them again for
 * every entry (mr_jac_row_mul loads them once a row). */
void mr_jac_mul(const mr_jac *J, const double *v3n, double *out_k) {
  const int rows = J->rows;
  for (int i = 0; i < rows; i++) out_k[i] = mr_jac_row_mul(J, i, v3n);
}

void mr_jac_tmul(const mr_jac *J, const double *lam_k, double *out_3n) {
  const int rows = J->rows, *rp = J->row_ptr, *part = J->particle;
  const double(*d)[3] = (const double(*)[3])J->d;
  memset(out_3n, 0, (size_t)J->n_particles * 3 * sizeof *out_3n);
  for (int i = 0, e = 0; i < rows; i++) { /* row_ptr[0] is 0 */
    const double l = lam_k[i];
    const int end = rp[i + 1];
    if (end - e == 2) { /* a distance: the same sums, without the loop */
      double *oa = out_3n + 3 * part[e];
      oa[0] += d[e][0] * l;
      oa[1] += d[e][1] * l;
      oa[2] += d[e][2] * l;
      double *ob = out_3n + 3 * part[e + 1];
      ob[0] += d[e + 1][0] * l;
      ob[1] += d[e + 1][1] * l;
      ob[2] += d[e + 1][2] * l;
      e = end;
    }
    for (; e < end; e++) {
      double *o = out_3n + 3 * part[e];
      o[0] += d[e][0] * l;
      o[1] += d[e][1] * l;
      o[2] += d[e][2] * l;
    }
  }
}

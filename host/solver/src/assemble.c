/* A = J M⁻¹ Jᵀ, the matrix of §5.2 eq. 8 and §5.3 eq. 9.
 *
 * Entry (i, j) is Σ_p w_p (∂C_i/∂x_p · ∂C_j/∂x_p) over the particles p that
 * rows i and j share, with w_p = 1/m_p. Rows that share no movable particle
 * give a structural zero, so A is as sparse as the constraint graph: the
 * assembly walks particle → rows lists instead of forming 3n-wide products.
 * The diagonal is always stored (a zero row of J still gets A_ii = 0), so
 * every solver finds its pivot without a search and can flag such a row as
 * dependent.
 *
 * A's pattern depends only on which particles each row of J names and on
 * which particles are pinned (w_p = 0 adds nothing). The physics rebuilds J
 * every evaluation with the same rows, so the plan keeps that pattern, the
 * particle → rows lists and A's sorted columns, and a call that finds them
 * unchanged only recomputes the numbers. */
#include "solver_internal.h"

#include <stdlib.h>
#include <string.h>

struct mr_csr_plan {
  mr_buf rp, col, val; /* A's arrays: A->row_ptr, col and val point here */
  /* The pattern the plan was built for: J's rows, their particles, and
   * which particles were pinned. */
  int valid, rows, np, ne;
  mr_buf jrp, jpart, pinned;
  /* Particle → entries of J that name it (movable particles only): the
   * transpose of J's pattern. */
  mr_buf pstart, prow, pent;
  mr_buf mark, cursor, ucol; /* scratch of the pattern build and the symmetrising copy */
  mr_buf work;               /* one row of A, dense; zero between rows */
  unsigned long builds;
};

#define INTS(b) ((int *)(b).p)

static int pinned(const double *inv_mass, int p)
{
  return !inv_mass || inv_mass[p] == 0.0;
}

static int same_source(const struct mr_csr_plan *pl, const mr_jac *J, const double *inv_mass,
                       int ne)
{
  if (!pl->valid || pl->rows != J->rows || pl->np != J->n_particles || pl->ne != ne)
    return 0;
  if (J->rows > 0 && memcmp(pl->jrp.p, J->row_ptr, (size_t)(J->rows + 1) * sizeof(int)) != 0)
    return 0;
  if (ne > 0 && memcmp(pl->jpart.p, J->particle, (size_t)ne * sizeof(int)) != 0)
    return 0;
  const unsigned char *pin = pl->pinned.p;
  for (int p = 0; p < J->n_particles; p++)
    if (pin[p] != pinned(inv_mass, p))
      return 0;
  return 1;
}

/* The plan's arrays for k rows, np particles and ne entries of J. */
static int plan_reserve(struct mr_csr_plan *pl, size_t k, size_t np, size_t ne)
{
  if (mr_buf_reserve(&pl->rp, k + 1, sizeof(int)) || mr_buf_reserve(&pl->jrp, k + 1, sizeof(int)) ||
      mr_buf_reserve(&pl->jpart, ne, sizeof(int)) || mr_buf_reserve(&pl->pinned, np, 1) ||
      mr_buf_reserve(&pl->pstart, np + 1, sizeof(int)) || mr_buf_reserve(&pl->prow, ne, sizeof(int)) ||
      mr_buf_reserve(&pl->pent, ne, sizeof(int)) || mr_buf_reserve(&pl->mark, k, sizeof(int)) ||
      mr_buf_reserve(&pl->cursor, k + 1, sizeof(int)) || mr_buf_reserve(&pl->work, k, sizeof(double)))
    return MR_SOLVE_ENOMEM;
  return 0;
}

/* A's entries: nnz columns and values, and the unsorted columns. */
static int plan_reserve_entries(struct mr_csr_plan *pl, size_t nnz)
{
  if (mr_buf_reserve(&pl->ucol, nnz, sizeof(int)) || mr_buf_reserve(&pl->col, nnz, sizeof(int)) ||
      mr_buf_reserve(&pl->val, nnz, sizeof(double)))
    return MR_SOLVE_ENOMEM;
  return 0;
}

static void keep_source(struct mr_csr_plan *pl, const mr_jac *J, const double *inv_mass, int ne)
{
  const int k = J->rows, np = J->n_particles;
  if (k > 0)
    memcpy(pl->jrp.p, J->row_ptr, ((size_t)k + 1) * sizeof(int));
  if (ne > 0)
    memcpy(pl->jpart.p, J->particle, (size_t)ne * sizeof(int));
  unsigned char *pin = pl->pinned.p;
  for (int p = 0; p < np; p++)
    pin[p] = (unsigned char)pinned(inv_mass, p);
  pl->rows = k;
  pl->np = np;
  pl->ne = ne;
}

/* Particle → (row, entry) lists by a counting sort over J's entries; a
 * pinned particle gets an empty list. */
static void particle_lists(struct mr_csr_plan *pl, const mr_jac *J, const double *inv_mass, int ne)
{
  const int np = J->n_particles;
  int *pstart = INTS(pl->pstart), *prow = INTS(pl->prow), *pent = INTS(pl->pent);
  memset(pstart, 0, ((size_t)np + 1) * sizeof *pstart);
  for (int e = 0; e < ne; e++)
    if (!pinned(inv_mass, J->particle[e]))
      pstart[J->particle[e] + 1]++;
  for (int p = 0; p < np; p++)
    pstart[p + 1] += pstart[p];
  for (int i = 0; i < J->rows; i++) {
    for (int e = J->row_ptr[i]; e < J->row_ptr[i + 1]; e++) {
      int p = J->particle[e];
      if (pinned(inv_mass, p))
        continue;
      int at = pstart[p]++;
      prow[at] = i;
      pent[at] = e;
    }
  }
  for (int p = np; p > 0; p--)
    pstart[p] = pstart[p - 1];
  pstart[0] = 0;
}

/* The columns of row i of A (the diagonal first, then the rows sharing a
 * movable particle, unsorted) into out when out is not NULL. Returns the
 * count. mark[j] == i marks column j as seen for row i. */
static int row_columns(const struct mr_csr_plan *pl, const mr_jac *J, int i, int *mark, int *out)
{
  const int *pstart = INTS(pl->pstart), *prow = INTS(pl->prow), *part = J->particle;
  int c = 0;
  mark[i] = i;
  if (out)
    out[c] = i;
  c++;
  for (int e = J->row_ptr[i]; e < J->row_ptr[i + 1]; e++) {
    for (int q = pstart[part[e]]; q < pstart[part[e] + 1]; q++) {
      int j = prow[q];
      if (mark[j] != i) {
        mark[j] = i;
        if (out)
          out[c] = j;
        c++;
      }
    }
  }
  return c;
}

/* A's row_ptr and sorted columns. Each row's columns are listed unsorted
 * into ucol, then one counting transpose sorts them all: A is symmetric,
 * so the transpose of its pattern is the pattern itself. */
static int build_pattern(mr_csr *A, struct mr_csr_plan *pl, const mr_jac *J)
{
  const int k = J->rows;
  int *mark = INTS(pl->mark), *cnt = INTS(pl->cursor);
  for (int i = 0; i < k; i++)
    mark[i] = -1;
  int nnz = 0;
  for (int i = 0; i < k; i++)
    nnz += row_columns(pl, J, i, mark, NULL);
  if (plan_reserve_entries(pl, (size_t)nnz) != 0)
    return MR_SOLVE_ENOMEM;
  int *ucol = INTS(pl->ucol), *rp = INTS(pl->rp), *col = INTS(pl->col);
  memset(cnt, 0, ((size_t)k + 1) * sizeof *cnt);
  for (int i = 0; i < k; i++)
    mark[i] = -1;
  for (int i = 0, at = 0; i < k; i++) {
    int c = row_columns(pl, J, i, mark, ucol + at);
    for (int t = at; t < at + c; t++)
      cnt[ucol[t] + 1]++;
    at += c;
  }
  for (int i = 0; i < k; i++)
    cnt[i + 1] += cnt[i];
  memcpy(rp, cnt, ((size_t)k + 1) * sizeof *rp);
  /* Row i lists as many columns as column i has rows (A's pattern is
   * symmetric: rows i and j share a particle or they do not). */
  for (int i = 0, at = 0; i < k; i++) {
    for (int end = at + (rp[i + 1] - rp[i]); at < end; at++)
      col[cnt[ucol[at]]++] = i;
  }
  A->n = k;
  A->nnz = nnz;
  return 0;
}

static int replan(mr_csr *A, struct mr_csr_plan *pl, const mr_jac *J, const double *inv_mass, int ne)
{
  pl->valid = 0;
  if (plan_reserve(pl, (size_t)J->rows, (size_t)J->n_particles, (size_t)ne) != 0)
    return MR_SOLVE_ENOMEM;
  memset(pl->work.p, 0, (size_t)J->rows * sizeof(double));
  keep_source(pl, J, inv_mass, ne);
  particle_lists(pl, J, inv_mass, ne);
  if (build_pattern(A, pl, J) != 0)
    return MR_SOLVE_ENOMEM;
  pl->valid = 1;
  pl->builds++;
  return 0;
}

static double dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The numbers: row i's sums scattered into the dense work row, in J's
 * entry order, then gathered into A's sorted columns. Only the lower
 * triangle and the diagonal are summed (each particle's list is in row
 * order, so the rest of a list lies above): symmetrise() copies them up. */
static void numeric(mr_csr *A, struct mr_csr_plan *pl, const mr_jac *J, const double *inv_mass)
{
  const int *pstart = INTS(pl->pstart), *prow = INTS(pl->prow), *pent = INTS(pl->pent);
  const int *jrp = J->row_ptr, *part = J->particle, *rp = A->row_ptr, *col = A->col;
  const double(*d)[3] = (const double(*)[3])J->d;
  double *work = pl->work.p, *val = A->val;
  for (int i = 0; i < J->rows; i++) {
    for (int e = jrp[i], e_end = jrp[i + 1]; e < e_end; e++) {
      const int p = part[e];
      const double w = inv_mass[p]; /* a pinned particle's list is empty */
      for (int q = pstart[p], q_end = pstart[p + 1]; q < q_end && prow[q] <= i; q++)
        work[prow[q]] += w * dot3(d[e], d[pent[q]]);
    }
    for (int q = rp[i], q_end = rp[i + 1]; q < q_end && col[q] <= i; q++) {
      val[q] = work[col[q]];
      work[col[q]] = 0.0;
    }
  }
}

/* Rounding may leave A_ij and A_ji a few ulps apart (the two sums run over
 * the shared particles in different orders). Copy the lower triangle onto
 * the upper so every solver sees the same symmetric matrix, bit for bit.
 * Row j's lower entries come before its diagonal; rows are visited in
 * ascending order, so row i's upper entries are filled in ascending column
 * order, one cursor each, starting just past its diagonal. */
static void symmetrise(mr_csr *A, int *cursor)
{
  for (int j = 0; j < A->n; j++) {
    for (int q = A->row_ptr[j]; q < A->row_ptr[j + 1]; q++) {
      int i = A->col[q];
      if (i == j) {
        cursor[j] = q + 1;
        break;
      }
      A->val[cursor[i]++] = A->val[q];
    }
  }
}

static int plan_of(mr_csr *A)
{
  if (!A->plan && !(A->plan = calloc(1, sizeof *A->plan)))
    return MR_SOLVE_ENOMEM;
  return 0;
}

mr_solve_status mr_csr_reserve(mr_csr *A, int rows, int particles, int entries)
{
  if (!A || rows < 0 || particles < 0 || entries < 0)
    return MR_SOLVE_BAD_ARG;
  const size_t k = (size_t)rows;
  if (plan_of(A) != 0 || plan_reserve(A->plan, k, (size_t)particles, (size_t)entries) != 0 ||
      plan_reserve_entries(A->plan, k * k) != 0)
    return MR_SOLVE_ENOMEM;
  return MR_SOLVE_OK;
}

mr_solve_status mr_csr_assemble(mr_csr *A, const mr_jac *J, const double *inv_mass)
{
  if (!J || !A)
    return MR_SOLVE_UNAVAILABLE;
  const int ne = J->rows > 0 ? J->row_ptr[J->rows] : 0;
  if (ne > 0 && !inv_mass)
    return MR_SOLVE_UNAVAILABLE;
  if (plan_of(A) != 0)
    return MR_SOLVE_ENOMEM;
  struct mr_csr_plan *pl = A->plan;
  if (!same_source(pl, J, inv_mass, ne) && replan(A, pl, J, inv_mass, ne) != 0)
    return MR_SOLVE_ENOMEM;
  A->row_ptr = pl->rp.p;
  A->col = pl->col.p;
  A->val = pl->val.p;
  A->row_ptr[0] = 0;
  numeric(A, pl, J, inv_mass);
  symmetrise(A, pl->cursor.p);
  return MR_SOLVE_OK;
}

unsigned long mr_csr_pattern_builds(const mr_csr *A)
{
  return A && A->plan ? A->plan->builds : 0;
}

void mr_csr_free(mr_csr *A)
{
  if (!A)
    return;
  struct mr_csr_plan *pl = A->plan;
  if (pl) {
    mr_buf *const bufs[] = {&pl->rp,     &pl->col,  &pl->val,  &pl->jrp,  &pl->jpart,
                            &pl->pinned, &pl->pstart, &pl->prow, &pl->pent, &pl->mark,
                            &pl->cursor, &pl->ucol, &pl->work};
    mr_bufs_free(bufs, sizeof bufs / sizeof bufs[0]);
    free(pl);
  }
  memset(A, 0, sizeof *A);
}

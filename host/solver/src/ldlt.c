/* Sparse LDLᵀ of A = J M⁻¹ Jᵀ (§5.2 eq. 8, §5.3 eq. 9), with a pivot test
 * that finds dependent constraints.
 *
 * Rows are renumbered by whichever of minimum degree, reverse Cuthill–McKee
 * and the natural order fills in least, then factored up-looking: row k of L
 * solves L₀ D₀ l = A(0:k−1, k) against the rows already done, and the pivot
 * is d_k = A_kk − Σ l_j² d_j. The nonzeros of row k are found by walking
 * A's entries up the elimination tree, so the work is proportional to the
 * nonzeros of L, not to k².
 *
 * The pivot has a meaning here: with B = J M^-½, d_k is the squared
 * distance of row k of B from the span of the rows eliminated before it.
 * So d_k ≤ pivot_tol · A_kk says that constraint k is (to sin² ≤ pivot_tol)
 * a combination of earlier ones. Such a row is dropped: its column of L is
 * zero and λ_k = 0, exactly as if the constraint had not been written. The
 * remaining rows are independent and span the same forces Jᵀλ, so for a
 * consistent b the answer satisfies every row; for an inconsistent b it
 * satisfies the independent rows and stays bounded. */
#include "solver_internal.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#define BUF(f, name, type) ((type *)(f)->name.p)

void mr_ldlt_free(mr_ldlt *f) {
  mr_buf *const bufs[] = { &f->perm,  &f->iperm, &f->parent,  &f->lnz,  &f->flag,
                           &f->stack, &f->lp,    &f->dropped, &f->li,   &f->lx,
                           &f->diag,  &f->y,     &f->z,       &f->skip, &f->res,
                           &f->dx,    &f->cand,  &f->bits,    &f->dperm };
  mr_bufs_free(bufs, sizeof bufs / sizeof bufs[0]);
  mr_dense_free(&f->dense);
  mr_pattern_free(&f->pattern);
  for (int s = 0; s < MR_LDLT_KEPT; s++) {
    mr_ldlt_kept *k = &f->kept[s];
    mr_buf *const kbufs[] = { &k->perm,  &k->iperm,  &k->parent, &k->lp,
                              &k->dperm, &k->dfirst, &k->dplan };
    mr_bufs_free(kbufs, sizeof kbufs / sizeof kbufs[0]);
    mr_pattern_free(&k->pattern);
  }
  memset(f, 0, sizeof *f);
}

/* Elimination tree and column counts of L for the ordering in perm/iperm.
 * Returns nnz(L) below the diagonal. */
static size_t symbolic(const mr_csr *A, const int *perm, const int *iperm, int *parent, int *lnz,
                       int *flag) {
  size_t total = 0;
  for (int k = 0; k < A->n; k++) {
    parent[k] = -1;
    flag[k] = k;
    lnz[k] = 0;
    int old = perm[k];
    for (int q = A->row_ptr[old]; q < A->row_ptr[old + 1]; q++) {
      for (int i = iperm[A->col[q]]; i < k && flag[i] != k; i = parent[i]) {
        if (parent[i] == -1) parent[i] = k;
        lnz[i]++;
        total++;
        flag[i] = k;
      }
    }
  }
  return total;
}

static int reserve_order(mr_ldlt *f, size_t n) {
  const size_t si = sizeof(int);
  if (mr_buf_reserve(&f->perm, n, si) || mr_buf_reserve(&f->iperm, n, si) ||
      mr_buf_reserve(&f->dperm, n, si) || mr_buf_reserve(&f->cand, n, si) ||
      mr_buf_reserve(&f->parent, n, si) || mr_buf_reserve(&f->lnz, n, si) ||
      mr_buf_reserve(&f->flag, n, si) || mr_buf_reserve(&f->stack, 3 * n, si) ||
      (n <= MR_MIN_DEGREE_MAX_N && mr_buf_reserve(&f->bits, n * ((n + 63) / 64), sizeof(uint64_t))))
    return MR_SOLVE_ERR_NOMEM;
  return 0;
}

int mr_ldlt_reserve_order(mr_ldlt *f, int rows) {
  return reserve_order(f, (size_t)rows);
}

static int reserve_factor(mr_ldlt *f, size_t n, size_t nnz_l) {
  if (mr_buf_reserve(&f->lp, n + 1, sizeof(int)) || mr_buf_reserve(&f->dropped, n, 1) ||
      mr_buf_reserve(&f->diag, n, sizeof(double)) || mr_buf_reserve(&f->y, n, sizeof(double)) ||
      mr_buf_reserve(&f->z, n, sizeof(double)) || mr_buf_reserve(&f->skip, n, 1) ||
      mr_buf_reserve(&f->res, n, sizeof(double)) || mr_buf_reserve(&f->dx, n, sizeof(double)) ||
      mr_buf_reserve(&f->li, nnz_l, sizeof(int)) || mr_buf_reserve(&f->lx, nnz_l, sizeof(double)))
    return MR_SOLVE_ERR_NOMEM;
  return 0;
}

/* Every kept slot grows to the largest pattern kept, so that once one
 * pattern of a size was seen (or reserved for), a new pattern of that size
 * allocates nothing either: the physics allocates nothing after its first
 * step (tests/physics/test_allocation.c). */
static int reserve_slot(mr_ldlt_kept *k, size_t n, size_t nnz) {
  const size_t si = sizeof(int);
  /* The dense plan's room only for what the dense path can take. */
  const size_t dn = n < MR_SOLVE_DENSE_ROWS_MAX ? n : MR_SOLVE_DENSE_ROWS_MAX;
  if (mr_pattern_reserve(&k->pattern, n, nnz) || mr_buf_reserve(&k->perm, n, si) ||
      mr_buf_reserve(&k->iperm, n, si) || mr_buf_reserve(&k->parent, n, si) ||
      mr_buf_reserve(&k->dperm, n, si) || mr_buf_reserve(&k->lp, n + 1, si) ||
      mr_buf_reserve(&k->dfirst, dn, si) ||
      mr_buf_reserve(&k->dplan, MR_DENSE_KEPT_PLAN_ROOM(dn), si))
    return MR_SOLVE_ERR_NOMEM;
  return 0;
}

/* Every slot once, up to the room reserved already (kept_n, kept_nnz):
 * a pattern within it costs no pass over the slots. */
static int reserve_kept(mr_ldlt *f, size_t n, size_t nnz) {
  if (f->kept_roomy && n <= f->kept_n && nnz <= f->kept_nnz) return 0;
  if (n < f->kept_n) n = f->kept_n;
  if (nnz < f->kept_nnz) nnz = f->kept_nnz;
  for (int s = 0; s < MR_LDLT_KEPT; s++)
    if (reserve_slot(&f->kept[s], n, nnz)) return MR_SOLVE_ERR_NOMEM;
  f->kept_n = n;
  f->kept_nnz = nnz;
  f->kept_roomy = 1;
  return 0;
}

int mr_ldlt_reserve(mr_ldlt *f, int rows) {
  const size_t n = (size_t)rows;
  const size_t kept_n = n < MR_LDLT_KEPT_MAX_N ? n : MR_LDLT_KEPT_MAX_N;
  if (mr_dense_reserve(&f->dense,
                       rows < MR_SOLVE_DENSE_ROWS_MAX ? rows : MR_SOLVE_DENSE_ROWS_MAX) ||
      reserve_order(f, n) || reserve_factor(f, n, n * (n > 0 ? n - 1 : 0) / 2) ||
      mr_pattern_reserve(&f->pattern, n, n * n) || reserve_kept(f, kept_n, kept_n * kept_n))
    return MR_SOLVE_ERR_NOMEM;
  return 0;
}

/* The inner products the dense factor (dense.c) computes in the ordering
 * perm: row k of L spans columns f_k..k−1 (f_k its first nonzero), and
 * entry (k, j) sums over max(f_k, f_j)..j−1. first needs n ints. */
static size_t profile_work(const mr_csr *A, const int *perm, const int *iperm, int *first) {
  size_t work = 0;
  for (int k = 0; k < A->n; k++) {
    int f = k, old = perm[k];
    for (int q = A->row_ptr[old]; q < A->row_ptr[old + 1]; q++)
      if (iperm[A->col[q]] < f) f = iperm[A->col[q]];
    first[k] = f;
    for (int j = f; j < k; j++) work += 1u + (size_t)(j - (f > first[j] ? f : first[j]));
  }
  return work;
}

int mr_ldlt_order(mr_ldlt *f, const mr_csr *A, size_t *nnz_l) {
  const int n = A->n;
  if (reserve_order(f, (size_t)n)) return MR_SOLVE_ERR_NOMEM;
  int *perm = BUF(f, perm, int), *iperm = BUF(f, iperm, int), *cand = BUF(f, cand, int);
  int *parent = BUF(f, parent, int), *lnz = BUF(f, lnz, int), *flag = BUF(f, flag, int);

  /* Try the natural order, minimum degree (while its n² bits stay
     * small) and reverse Cuthill–McKee; keep whichever fills in least.
     * Each try is one symbolic pass, cheap beside a factorisation, and runs
     * only when the pattern changes. */
  int *dperm = BUF(f, dperm, int);
  size_t best = 0, best_work = 0;
  for (int way = 0; way < 3; way++) {
    if (way == 0) {
      for (int i = 0; i < n; i++) cand[i] = i;
    } else if (way == 1) {
      if (n > MR_MIN_DEGREE_MAX_N) continue;
      mr_order_min_degree(A, cand, f->bits.p, lnz);
    } else {
      mr_order_rcm(A, cand, BUF(f, stack, int));
    }
    for (int i = 0; i < n; i++) iperm[cand[i]] = i;
    size_t fill = symbolic(A, cand, iperm, parent, lnz, flag);
    if (way == 0 || fill < best) {
      best = fill;
      memcpy(perm, cand, (size_t)n * sizeof *perm);
    }
    /* The dense factor's work follows the envelope, not the fill: reverse
     * Cuthill–McKee usually wins it, minimum degree (least fill) seldom.
     * The envelope costs n × its width to measure, n² on a crowd of
     * puppets in natural order: only a system the dense path can take
     * measures it (1 000 taut-string puppets, whose pattern changes every
     * step, spent 56 % of their time here). */
    if (n > MR_SOLVE_DENSE_ROWS_MAX) continue;
    size_t work = profile_work(A, cand, iperm, flag);
    if (way == 0 || work < best_work) {
      best_work = work;
      memcpy(dperm, cand, (size_t)n * sizeof *dperm);
    }
  }
  for (int i = 0; i < n; i++) iperm[perm[i]] = i;
  *nnz_l = best;
  return 0;
}

static int analyse(mr_ldlt *f, const mr_csr *A) {
  const int n = A->n;
  f->pattern.valid = 0;
  if (mr_ldlt_order(f, A, &f->nnz_l) != 0 || reserve_factor(f, (size_t)n, f->nnz_l) != 0)
    return MR_SOLVE_ERR_NOMEM;
  /* The lnz of the ordering kept, not of the last one tried. */
  int *lnz = BUF(f, lnz, int);
  symbolic(A, BUF(f, perm, int), BUF(f, iperm, int), BUF(f, parent, int), lnz, BUF(f, flag, int));
  int *lp = BUF(f, lp, int);
  lp[0] = 0;
  for (int k = 0; k < n; k++) lp[k + 1] = lp[k] + lnz[k];
  f->analyses++;
  return mr_pattern_keep(&f->pattern, A);
}

/* Several analyses are kept, keyed on the pattern. A step mixes row sets
 * (an impulse, evaluations with resting contacts, contacts released, the
 * projection of taut strings after the step), so the pattern alternates
 * among a few, and with one analysis kept each switch ordered A again:
 * on the taut-string stick marionette (10 s of sway) 4 085 of 8 079 solves
 * re-analysed, 26 % of all instructions. With 8 kept, 590 do, and the
 * whole run takes 24 % fewer instructions. Seven taut strings, each in or
 * out of a solve, make many more patterns than a few: the stick figure
 * swaying for 10 s (the MuJoCo comparison's gentle track) met 82, and
 * with 32 kept analysed 240 times, 12.7 % of its instructions; puppet.yaml
 * met 85 (131 analyses), humanoid.yaml 74 (186), dragon.yaml 105 (168).
 * With 128 kept each pattern is analysed once. So many slots are looked
 * through by the pattern's hash, then compared whole. A kept analysis is
 * the one analyse() would compute again, so the answers are the same
 * bits. */
static int find_kept(mr_ldlt *f, const mr_csr *A, uint64_t hash) {
  for (int s = 0; s < MR_LDLT_KEPT; s++)
    if (f->kept[s].hash == hash && mr_pattern_same(&f->kept[s].pattern, A)) return s;
  return -1;
}

/* Makes kept[s] the analysis in use. */
static int restore(mr_ldlt *f, int s, const mr_csr *A) {
  const mr_ldlt_kept *k = &f->kept[s];
  const size_t n = (size_t)A->n, si = sizeof(int);
  f->pattern.valid = 0;
  if (reserve_order(f, n) || reserve_factor(f, n, k->nnz_l)) return MR_SOLVE_ERR_NOMEM;
  memcpy(f->perm.p, k->perm.p, n * si);
  memcpy(f->iperm.p, k->iperm.p, n * si);
  memcpy(f->dperm.p, k->dperm.p, n * si);
  memcpy(f->parent.p, k->parent.p, n * si);
  memcpy(f->lp.p, k->lp.p, (n + 1) * si);
  f->nnz_l = k->nnz_l;
  return mr_pattern_keep(&f->pattern, A);
}

/* Keeps the analysis in use in the least recently used slot (an empty one
 * first); returns the slot, or -1 when A is too large to keep. A large
 * pattern stays only while in use: keeping them too (tried on 600 contact
 * rows of puppets built inside each other, 425 solves above 128 rows)
 * pushed out small patterns that came back, 700 orderings in place of
 * 625; large patterns seldom come back whole. */
static int keep(mr_ldlt *f, const mr_csr *A, uint64_t hash, int *slot) {
  const size_t n = (size_t)A->n, si = sizeof(int);
  *slot = -1;
  if (A->n > MR_LDLT_KEPT_MAX_N) return 0;
  int s = 0;
  for (int t = 1; t < MR_LDLT_KEPT; t++)
    if (f->kept[t].used < f->kept[s].used) s = t;
  mr_ldlt_kept *k = &f->kept[s];
  k->pattern.valid = 0;
  k->plan_ints = 0; /* the dense plan goes with the analysis it was made for */
  if (reserve_kept(f, n, (size_t)A->row_ptr[A->n])) return MR_SOLVE_ERR_NOMEM;
  memcpy(k->perm.p, f->perm.p, n * si);
  memcpy(k->iperm.p, f->iperm.p, n * si);
  memcpy(k->dperm.p, f->dperm.p, n * si);
  memcpy(k->parent.p, f->parent.p, n * si);
  memcpy(k->lp.p, f->lp.p, (n + 1) * si);
  k->nnz_l = f->nnz_l;
  *slot = s;
  k->hash = hash;
  return mr_pattern_keep(&k->pattern, A);
}

/* The analysis for A's pattern in use: the one in use already, a kept one,
 * or a new one (then kept). */
int mr_ldlt_prepare(mr_ldlt *f, const mr_csr *A) {
  if (mr_pattern_same(&f->pattern, A)) return 0;
  /* The physics mostly swaps between two patterns (a resting contact
   * released and taken back): the one in use before this is looked at
   * before A is hashed. */
  int s = f->before, st;
  uint64_t hash = 0; /* only a new analysis, kept below, needs it */
  if (s < 0 || !mr_pattern_same(&f->kept[s].pattern, A)) {
    hash = mr_pattern_hash(A);
    s = find_kept(f, A, hash);
  }
  if (s >= 0)
    st = restore(f, s, A);
  else if ((st = analyse(f, A)) == 0)
    st = keep(f, A, hash, &s);
  if (st != 0) return st;
  /* The analysis in use is always the most recent: no stamp while it
   * stays in use. The clock moves at every change of it (dense.c keys its
   * own per-pattern work on it, and keeps that work in slot in_use). */
  ++f->clock;
  f->before = f->in_use;
  f->in_use = s;
  if (s >= 0) f->kept[s].used = f->clock;
  return 0;
}

/* Returns the number of dropped (dependent) rows; *regularised counts the
 * nearly dependent ones whose pivot was raised to reg_tol · A_kk. That is a
 * factorisation of A + E with E diagonal and nonzero only on those rows
 * (a modified Cholesky): a compliance on the directions the other rows
 * nearly span, and nowhere else, so well-conditioned rows stay exact and
 * no multiplier exceeds about |b| / (reg_tol · A_kk). */
static int factor(mr_ldlt *f, const mr_csr *A, double pivot_tol, double reg_tol, int *regularised) {
  const int n = A->n;
  const int *perm = BUF(f, perm, int), *iperm = BUF(f, iperm, int), *parent = BUF(f, parent, int);
  const int *lp = BUF(f, lp, int);
  int *lnz = BUF(f, lnz, int), *flag = BUF(f, flag, int), *stack = BUF(f, stack, int),
      *li = BUF(f, li, int);
  unsigned char *dropped = BUF(f, dropped, unsigned char);
  double *lx = BUF(f, lx, double), *diag = BUF(f, diag, double), *y = BUF(f, y, double);
  int count = 0;

  for (int k = 0; k < n; k++) y[k] = 0.0;
  for (int k = 0; k < n; k++) {
    /* Scatter column k of PAPᵀ (rows ≤ k) into y and find the rows of L
         * that row k touches, in an order where each comes before its
         * ancestors in the elimination tree. */
    int top = n, old = perm[k];
    double akk = 0.0;
    flag[k] = k;
    lnz[k] = 0;
    for (int q = A->row_ptr[old]; q < A->row_ptr[old + 1]; q++) {
      int i = iperm[A->col[q]];
      if (i > k) continue;
      y[i] += A->val[q];
      if (i == k) {
        akk = A->val[q];
        continue;
      }
      int len = 0;
      for (; flag[i] != k; i = parent[i]) {
        stack[len++] = i;
        flag[i] = k;
      }
      while (len > 0) stack[--top] = stack[--len];
    }
    double d = y[k];
    y[k] = 0.0;
    for (; top < n; top++) {
      int i = stack[top];
      double yi = y[i];
      y[i] = 0.0;
      int end = lp[i] + lnz[i];
      for (int p = lp[i]; p < end; p++) y[li[p]] -= lx[p] * yi;
      double l = dropped[i] == 1 ? 0.0 : yi / diag[i];
      d -= l * yi;
      li[end] = k;
      lx[end] = l;
      lnz[i]++;
    }
    /* The pivot test (see the top of this file); !(d > …) also catches
         * a NaN pivot. */
    if (!(akk > DBL_MIN) || !(d > pivot_tol * akk)) {
      dropped[k] = 1;
      diag[k] = 0.0;
      count++;
    } else if (d < reg_tol * akk) {
      dropped[k] = 2; /* regularised: kept, but not refined below */
      diag[k] = reg_tol * akk;
      (*regularised)++;
    } else {
      dropped[k] = 0;
      diag[k] = d;
    }
  }
  return count;
}

/* x = (P L D Lᵀ Pᵀ)⁺ b with dropped rows' unknowns set to zero. */
static void solve_factored(const mr_ldlt *f, const double *b, double *x) {
  const int n = f->pattern.n;
  const int *perm = BUF(f, perm, const int), *lp = BUF(f, lp, const int),
            *li = BUF(f, li, const int);
  const double *lx = BUF(f, lx, const double), *diag = BUF(f, diag, const double);
  const unsigned char *dropped = BUF(f, dropped, const unsigned char);
  double *z = BUF(f, z, double);
  for (int k = 0; k < n; k++) z[k] = b[perm[k]];
  for (int j = 0; j < n; j++)
    for (int p = lp[j]; p < lp[j + 1]; p++) z[li[p]] -= lx[p] * z[j];
  for (int j = 0; j < n; j++) z[j] = dropped[j] == 1 ? 0.0 : z[j] / diag[j];
  for (int j = n - 1; j >= 0; j--)
    for (int p = lp[j]; p < lp[j + 1]; p++) z[j] -= lx[p] * z[li[p]];
  for (int k = 0; k < n; k++) x[perm[k]] = z[k];
}

static void solve_factored_any(const void *f, const double *b, double *x) {
  solve_factored(f, b, x);
}

/* The default path of the LDLᵀ method: dense up to the cut-over, where it
 * is cheaper (dense.c), sparse above. */
static int dense_limit(const mr_solve_def *o) {
  return o->dense_max < MR_SOLVE_DENSE_ROWS_MAX ? o->dense_max : MR_SOLVE_DENSE_ROWS_MAX;
}

int mr_ldlt_solve(mr_ldlt *f, const mr_solve_def *o, const mr_csr *A, const double *b,
                  double b_norm, double *x, mr_solve_result *r) {
  const int n = A->n;
  if (n <= dense_limit(o)) return mr_dense_solve(f, o, A, b, b_norm, x, r);
  int st = mr_ldlt_prepare(f, A);
  if (st != 0) return st;
  r->regularised = 0;
  r->dependent = factor(f, A, o->pivot_tol, o->reg_tol, &r->regularised);
  solve_factored(f, b, x);
  r->iterations = 1;
  /* The refinement test skips dropped rows, by the caller's row index. */
  unsigned char *skip = BUF(f, skip, unsigned char);
  const unsigned char *dropped = BUF(f, dropped, unsigned char);
  const int *perm = BUF(f, perm, int);
  for (int k = 0; r->dependent + r->regularised > 0 && k < n; k++) skip[perm[k]] = dropped[k] != 0;
  st = mr_ldlt_refine(f, o, A, b, b_norm, x, r, skip, solve_factored_any, f);
  if (st != 0) return st;
  return r->dependent ? MR_SOLVE_DEPENDENT : MR_SOLVE_OK;
}

int mr_ldlt_refine(mr_ldlt *f, const mr_solve_def *o, const mr_csr *A, const double *b,
                   double b_norm, double *x, mr_solve_result *r, const unsigned char *skip,
                   mr_factored_solve solve, const void *factored) {
  /* Iterative refinement: a step or two recovers the digits that
     * elimination loses on a badly scaled system (masses far apart). The
     * test skips dropped rows, whose equations an inconsistent b can leave
     * unsatisfiable. */
  const int n = A->n;
  if (mr_buf_reserve(&f->res, (size_t)n, sizeof(double)) ||
      mr_buf_reserve(&f->dx, (size_t)n, sizeof(double)))
    return MR_SOLVE_ERR_NOMEM;
  /* The rows skipped are the dropped and the regularised ones. */
  const int skipped = r->dependent + r->regularised > 0;
  if (!skipped) skip = NULL;
  double *res = BUF(f, res, double), *dx = BUF(f, dx, double);
  const double stop = o->tol * b_norm;
  f->res_known = 0;
  for (int step = 0; step < 2; step++) {
    f->res_norm = mr_residual_norm(A, b, x, skip);
    if (!(f->res_norm > stop)) {
      f->res_known = !skipped; /* measured over every row: the answer's */
      break;
    }
    mr_residual(A, b, x, res);
    /* Refining a regularised row would undo its compliance. */
    for (int i = 0; skip && i < n; i++)
      if (skip[i]) res[i] = 0.0;
    solve(factored, res, dx);
    for (int i = 0; i < n; i++) x[i] += dx[i];
    r->iterations++;
  }
  return 0;
}

/* Dense LDLᵀ of A = J M⁻¹ Jᵀ (§5.2 eq. 8, §5.3 eq. 9) for small systems,
 * with the sparse path's pivot test (ldlt.c, README.md).
 *
 * A puppet solves a few tens of rows. At that size the sparse path's
 * bookkeeping (scattering each row, walking the elimination tree,
 * indirect addressing per entry of L) costs more than the arithmetic it
 * saves: the dense factor's inner loop is a contiguous dot product. Rows
 * are taken in the order with the least work for it (the analysis'
 * dperm, usually reverse Cuthill–McKee), and the only structure used is
 * each row's first nonzero column f_k: L's row k has no entry left of it
 * (the fill of LDLᵀ stays inside A's envelope), so the sums start there.
 *
 * Row k of PAPᵀ:
 *
 *   t_j  = A_kj − Σ_{f ≤ m < j} t_m L_jm      (t_j = L_kj d_j),  f_k ≤ j < k
 *   L_kj = t_j / d_j                            (0 when row j was dropped)
 *   d_k  = A_kk − Σ_{f_k ≤ j < k} t_j L_kj
 *
 * with f = max(f_k, f_j). d_k is the squared distance of row k of J M^-½
 * from the span of the rows before it, so the same test as the sparse path
 * drops a dependent row (d_k ≤ pivot_tol · A_kk: λ_k = 0, column k of L
 * zero) or regularises a nearly dependent one (reg_tol). Which row of a
 * dependent set is dropped follows the order; Jᵀλ is the same. */
#include "solver_internal.h"

#include <float.h>
#include <math.h>
#include <string.h>

#define DBUF MR_DENSE_BUF
#define LD   MR_DENSE_LD

void mr_dense_free(mr_dense *d) {
  mr_buf *const bufs[] = { &d->l,  &d->first,   &d->t,     &d->dinv, &d->plan, &d->mark,
                           &d->aq, &d->dropped, &d->place, &d->zero, &d->y,    &d->aval };
  mr_bufs_free(bufs, sizeof bufs / sizeof bufs[0]);
  d->valid = 0;
  d->kept_valid = 0;
  d->room = 0;
}

/* Room for any system of up to rows rows (A's pattern full). */
int mr_dense_reserve(mr_dense *d, int rows) {
  if (rows <= d->room) return 0;
  const size_t n = (size_t)rows, sd = sizeof(double), si = sizeof(int);
  if (mr_buf_reserve(&d->l, n * (n + 1), sd) || mr_buf_reserve(&d->first, n, si) ||
      mr_buf_reserve(&d->t, n + 1, sd) || mr_buf_reserve(&d->dinv, n, sd) ||
      mr_buf_reserve(&d->dropped, n, 1) || mr_buf_reserve(&d->plan, mr_dense_plan_room(n), si) ||
      mr_buf_reserve(&d->mark, n * n, 1) || mr_buf_reserve(&d->aq, 3 * n, si) ||
      mr_buf_reserve(&d->place, n * (n + 1), si) || mr_buf_reserve(&d->zero, n * (n + 1) / 2, si) ||
      mr_buf_reserve(&d->y, n + 1, sd) || mr_buf_reserve(&d->aval, n * n + 1, sd))
    return MR_SOLVE_ERR_NOMEM;
  d->room = rows;
  return 0;
}

/* s − Σ_{lo ≤ m < hi} a_m b_m, in two interleaved sums: half the loop's
 * steps, and two chains of dependent additions instead of one. */
static inline double minus_dot(double s, const double *a, const double *b, int lo, int hi) {
  double odd = 0.0;
  int m = lo;
  for (; m + 1 < hi; m += 2) {
    s -= a[m] * b[m];
    odd -= a[m + 1] * b[m + 1];
  }
  if (m < hi) s -= a[m] * b[m];
  return s + odd;
}

/* The pivot test's tolerances, what it writes and what it counts. The
 * arrays are taken out of dn once a factor: a byte stored to dropped[]
 * may alias anything, and arrays read through dn were read again at every
 * row. */
typedef struct pivots {
  unsigned char *dropped;
  double *dinv, pivot_tol, reg_tol;
  int dependent, regularised;
} pivots;

static pivots pivots_for(mr_dense *dn, double pivot_tol, double reg_tol) {
  return (pivots){ .dropped = DBUF(dn, dropped, unsigned char),
                   .dinv = DBUF(dn, dinv, double),
                   .pivot_tol = pivot_tol,
                   .reg_tol = reg_tol };
}

/* The pivot test of ldlt.c's factor(), on d_k. */
static inline void judge(pivots *pv, int k, double akk, double d) {
  if (!(akk > DBL_MIN) || !(d > pv->pivot_tol * akk)) {
    pv->dropped[k] = 1;
    pv->dinv[k] = 0.0;
    pv->dependent++;
    return;
  }
  unsigned char drop = 0;
  if (d < pv->reg_tol * akk) {
    drop = 2;
    d = pv->reg_tol * akk;
    pv->regularised++;
  }
  pv->dropped[k] = drop;
  pv->dinv[k] = 1.0 / d;
}

/* Factors the loaded PAPᵀ in place in dn->l. Returns the dropped rows'
 * count. */
static int factor(mr_dense *dn, double pivot_tol, double reg_tol, int *regularised) {
  const int n = dn->n, *first = DBUF(dn, first, int);
  double *l = DBUF(dn, l, double), *t = DBUF(dn, t, double);
  const double *dinv = DBUF(dn, dinv, double);
  pivots pv = pivots_for(dn, pivot_tol, reg_tol);
  for (int k = 0; k < n; k++) {
    double *lk = l + (size_t)k * LD(n);
    const int fk = first[k];
    double d = lk[k];
    for (int j = fk; j < k; j++) {
      const double *lj = l + (size_t)j * LD(n);
      const double s = minus_dot(lk[j], t, lj, fk > first[j] ? fk : first[j], j);
      const double ljk = s * dinv[j];
      t[j] = s;
      lk[j] = ljk;
      d -= ljk * s;
    }
    judge(&pv, k, lk[k], d);
  }
  *regularised = pv.regularised;
  return pv.dependent;
}

/* factor() over the plan: only L's entries, and in each sum only the
 * products of two entries, in minus_dot()'s order. A product it leaves
 * out has a structural zero (+0: L_kj = t_j d_j⁻¹ with t_j an untouched
 * +0), so it is ±0, and the sums, which start at A's numbers or +0 and
 * never reach −0, gain nothing from it: the same bits. A is read from
 * a, the copy of A's numbers with +0 after them (plan_pattern), not
 * loaded into L. */
static int factor_plan(mr_dense *dn, const double *a, double pivot_tol, double reg_tol,
                       int *regularised) {
  const int n = dn->n, *p = DBUF(dn, plan, const int) + 1;
  double *l = DBUF(dn, l, double), *t = DBUF(dn, t, double);
  const double *dinv = DBUF(dn, dinv, double);
  pivots pv = pivots_for(dn, pivot_tol, reg_tol);
  t[n] = 0.0;
  for (int k = 0; k < n; k++) {
    double *lk = l + (size_t)k * LD(n);
    const int *const row_end = p + p[0];
    const double akk = a[p[1]];
    double d = akk;
    lk[k] = akk; /* as load() leaves it: bound_suffices() reads it */
    for (p += 2; p < row_end;) {
      const int j = p[0], *const next = p + p[3];
      const double *lj = l + p[1];
      double s = a[p[2]], odd = 0.0;
      for (const int *m = p + 4; m < next; m += 2) {
        s -= t[m[0]] * lj[m[0]];
        odd -= t[m[1]] * lj[m[1]];
      }
      s += odd;
      const double ljk = s * dinv[j];
      t[j] = s;
      lk[j] = ljk;
      d -= ljk * s;
      p = next;
    }
    judge(&pv, k, akk, d);
  }
  *regularised = pv.regularised;
  return pv.dependent;
}

/* Both sweeps take L's row k two entries at a time. A row of odd length
 * is padded with its own diagonal place, l_kk, which holds A_kk (finite
 * when A is; a non-finite A is reported whatever the answer): in the
 * forward sweep against y_k, set to +0 beforehand, so the second sum, which
 * starts at +0 and so is never −0, gains a ±0 and keeps its bits; in the
 * backward sweep into z_k, which was read and written out already. Each
 * pair's two loads come before either store, so that the compiler makes
 * them one vector operation: the loop has no odd tail, and costs about half
 * of one taking an entry at a time (rows are 4 entries long on average). */
static void solve_envelope(const mr_dense *dn, const double *b, double *x) {
  const int n = dn->n, *perm = dn->perm, *first = DBUF(dn, first, const int);
  const double *l = DBUF(dn, l, const double), *dinv = DBUF(dn, dinv, const double);
  double *restrict y = DBUF(dn, y, double), *restrict z = DBUF(dn, t, double);
  /* x = P (L D Lᵀ)⁺ Pᵀ b with dropped rows' unknowns set to zero. The
   * forward sweep's sums read y before D⁻¹ scales it, the backward sweep
   * after: the scaled copy goes into z (the factor's scratch, free once L
   * is made) as each y_k is found, not in a pass of its own. */
  memset(y, 0, (size_t)n * sizeof *y);
  for (int k = 0; k < n; k++) {
    const double *restrict lk = l + (size_t)k * LD(n);
    double s = b[perm[k]], odd = 0.0;
    for (int m = first[k]; m < k; m += 2) {
      const double p0 = lk[m] * y[m], p1 = lk[m + 1] * y[m + 1];
      s -= p0;
      odd -= p1;
    }
    const double yk = s + odd;
    y[k] = yk;
    z[k] = yk * dinv[k];
  }
  for (int k = n - 1; k >= 0; k--) {
    const double *restrict lk = l + (size_t)k * LD(n);
    const double zk = z[k];
    x[perm[k]] = zk;
    for (int m = first[k]; m < k; m += 2) {
      const double a0 = lk[m], a1 = lk[m + 1], z0 = z[m], z1 = z[m + 1];
      z[m] = z0 - a0 * zk;
      z[m + 1] = z1 - a1 * zk;
    }
  }
}

/* The sweeps over L's pattern alone (plan_sweeps): the envelope walk's
 * bits. Each row waits only for the rows its entries name, not for every
 * row of its envelope, so rows of different branches of the elimination
 * tree overlap; the envelope walk made each row wait for the one before. */
static void solve_pattern(const mr_dense *dn, const double *b, double *x) {
  const int n = dn->n, *perm = dn->perm, *plan = DBUF(dn, plan, const int);
  const int *sweep = plan + plan[0];
  const double *l = DBUF(dn, l, const double), *dinv = DBUF(dn, dinv, const double);
  double *restrict y = DBUF(dn, y, double), *restrict z = DBUF(dn, t, double);
  y[n] = 0.0;
  const int *q = sweep;
  for (int k = 0; k < n; k++) {
    const double *restrict lk = l + (size_t)k * LD(n);
    const int *m = q + 1, *const end = m + 2 * q[0];
    double s = b[perm[k]], odd = 0.0;
    for (; m < end; m += 2) {
      s -= lk[m[0]] * y[m[0]];
      odd -= lk[m[1]] * y[m[1]];
    }
    const double yk = s + odd;
    y[k] = yk;
    z[k] = yk * dinv[k];
    q = end + 1;
  }
  for (int k = n - 1; k >= 0; k--) {
    const double *restrict lk = l + (size_t)k * LD(n);
    const double zk = z[k];
    const int *const end = q - 1, *m = end - 2 * end[0];
    x[perm[k]] = zk;
    for (; m < end; m += 2) {
      z[m[0]] -= lk[m[0]] * zk;
      z[m[1]] -= lk[m[1]] * zk;
    }
    q = end - 2 * end[0] - 1;
  }
}

static void solve_factored(const void *factored, const double *b, double *x) {
  const mr_dense *dn = factored;
  if (dn->n_plan >= 0)
    solve_pattern(dn, b, x);
  else
    solve_envelope(dn, b, x);
}

/* γ_m = m u / (1 − m u), the rounding error bound of m operations; u is
 * taken as DBL_EPSILON, twice the unit roundoff, a margin for the sums
 * that compute the bound itself. */
static double gamma_of(int m) {
  const double mu = (double)m * DBL_EPSILON;
  return mu < 0.5 ? mu / (1.0 - mu) : INFINITY;
}

/* Whether the factor's own error bound already shows ‖b − A x‖ within
 * tol ‖b‖, so that measuring it (a pass over A) cannot lead the
 * refinement test to refine. With every pivot kept and positive, the
 * computed x solves (A + E) x = b with |E| ≤ γ_{3n+1} |L||D||Lᵀ|, whose
 * 2-norm is at most the trace of L D Lᵀ, that is tr A (1 + γ_n); and the
 * residual the test would compute is off the true one by at most
 * γ_{n+1} (‖b‖ + tr A ‖x‖). So the test passes whenever
 *   (γ_{3n+1} + γ_{n+1}) (1 + γ_n) tr A ‖x‖ + γ_{n+1} ‖b‖ ≤ tol ‖b‖,
 * and the bound is reported as the residual. On the stick figure and
 * the puppet it holds on every solve, 2 to 400 times under tol ‖b‖; a
 * badly scaled system (hard case 04, masses far apart) misses it and is
 * measured. The measurement also showed A finite (solver.c); here the
 * factor read A's lower triangle, where a NaN or Inf would have dropped
 * its row, and A is looked at whole (a quarter of a measurement). */
static int bound_suffices(mr_dense *dn, const mr_csr *A, const mr_solve_def *o, double b_norm,
                          const double *x, double *bound) {
  const int n = dn->n;
  const double *l = DBUF(dn, l, const double);
  if (dn->kept_finite < 0) dn->kept_finite = mr_all_finite((size_t)A->row_ptr[n], A->val);
  if (!dn->kept_finite) return 0;
  double tr = 0.0, xx = 0.0;
  for (int k = 0; k < n; k++) {
    tr += l[(size_t)k * LD(n) + (size_t)k]; /* A_kk: the factor leaves it */
    xx += x[k] * x[k];
  }
  const double g = gamma_of(n + 1);
  *bound = (gamma_of(3 * n + 1) + g) * (1.0 + gamma_of(n)) * tr * sqrt(xx) + g * b_norm;
  return *bound <= o->tol * b_norm;
}

/* Factors A, unless the factor in L is of the same numbers already. The
 * physics solves one A for several right-hand sides (friction probes
 * the contacts' response and solves again with the friction found); the
 * same pattern, numbers (compared bit for bit) and
 * tolerances give the same factor, so it is kept. */
static void factor_unless_kept(mr_dense *dn, const mr_solve_def *o, const mr_csr *A,
                               mr_solve_result *r) {
  const size_t nnz = (size_t)A->row_ptr[A->n];
  double *kept = DBUF(dn, aval, double);
  if (dn->kept_valid && dn->kept_nnz == nnz && dn->kept_pivot == o->pivot_tol &&
      dn->kept_reg == o->reg_tol && memcmp(kept, A->val, nnz * sizeof *kept) == 0) {
    r->dependent = dn->kept_dependent;
    r->regularised = dn->kept_regularised;
    return;
  }
  r->regularised = 0;
  /* Before the factor: the plan's factor reads A here, and the +0 after
   * it for the numbers A does not store (plan_pattern). */
  memcpy(kept, A->val, nnz * sizeof *kept);
  kept[nnz] = 0.0;
  if (dn->n_plan >= 0) {
    r->dependent = factor_plan(dn, kept, o->pivot_tol, o->reg_tol, &r->regularised);
  } else {
    mr_dense_load(dn, A);
    r->dependent = factor(dn, o->pivot_tol, o->reg_tol, &r->regularised);
  }
  dn->factors++;
  dn->kept_nnz = nnz;
  dn->kept_pivot = o->pivot_tol;
  dn->kept_reg = o->reg_tol;
  dn->kept_dependent = r->dependent;
  dn->kept_regularised = r->regularised;
  dn->kept_finite = -1;
  dn->kept_valid = 1;
}

int mr_dense_solve(mr_ldlt *f, const mr_solve_def *o, const mr_csr *A, const double *b,
                   double b_norm, double *x, mr_solve_result *r) {
  mr_dense *dn = &f->dense;
  const int n = A->n;
  int st = mr_ldlt_prepare(f, A);
  if (st != 0) return st;
  if (mr_dense_reserve(dn, n) != 0 || mr_buf_reserve(&f->skip, (size_t)n, 1) != 0)
    return MR_SOLVE_ERR_NOMEM;
  dn->perm = f->dperm.p; /* a reserve may have moved it */
  if (!dn->valid || dn->clock != f->clock || dn->n != n) {
    dn->n = n;
    mr_dense_pattern_work(f, dn, A);
    dn->clock = f->clock;
    dn->valid = 1;
    dn->kept_valid = 0;
  }
  factor_unless_kept(dn, o, A, r);
  r->dense = 1;
  solve_factored(dn, b, x);
  r->iterations = 1;
  double bound;
  if (r->dependent + r->regularised == 0 && bound_suffices(dn, A, o, b_norm, x, &bound)) {
    f->res_norm = bound;
    f->res_known = 1;
    return MR_SOLVE_OK;
  }
  unsigned char *skip = f->skip.p;
  const unsigned char *dropped = DBUF(dn, dropped, unsigned char);
  for (int k = 0; r->dependent + r->regularised > 0 && k < n; k++)
    skip[dn->perm[k]] = dropped[k] != 0;
  st = mr_ldlt_refine(f, o, A, b, b_norm, x, r, skip, solve_factored, dn);
  if (st != 0) return st;
  return r->dependent ? MR_SOLVE_DEPENDENT : MR_SOLVE_OK;
}

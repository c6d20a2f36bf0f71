/* The solver front: argument checks shared by every method, the workspace,
 * and the dispatch. The methods live in one file each. */
#include "solver_internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

mr_solve_def mr_default_solve_def(void) {
  mr_solve_def d = {
    MR_DEF_COOKIE, MR_SOLVE_LDLT, 1e-10, 1000, 1e-12, 0.0, MR_SOLVE_DENSE_DEFAULT
  };
  return d;
}

/* The one table of method names, by enum value, NULL-terminated. */
static const char *const method_names[MR_SOLVE_METHOD_COUNT + 1] = {
  [MR_SOLVE_GAUSS_SEIDEL] = "gauss-seidel",
  [MR_SOLVE_CG] = "cg",
  [MR_SOLVE_LDLT] = "ldlt",
  [MR_SOLVE_EIGEN] = "eigen",
  [MR_SOLVE_METHOD_COUNT] = NULL,
};

const char *mr_solve_method_name(mr_solve_method m) {
  if ((int)m < 0 || (int)m >= MR_SOLVE_METHOD_COUNT) return "unknown";
  return method_names[m];
}

int mr_solve_method_parse(const char *name, mr_solve_method *out) {
  if (!name || !out) return -1;
  for (int m = 0; m < MR_SOLVE_METHOD_COUNT; m++) {
    if (strcmp(name, method_names[m]) == 0) {
      *out = (mr_solve_method)m;
      return 0;
    }
  }
  return -1;
}

const char *const *mr_solve_method_names(void) {
  return method_names;
}

const char *mr_solve_status_name(mr_solve_status s) {
  switch (s) {
  case MR_SOLVE_OK:
    return "ok";
  case MR_SOLVE_NOT_CONVERGED:
    return "not converged";
  case MR_SOLVE_DEPENDENT:
    return "dependent rows";
  case MR_SOLVE_ERR_NOMEM:
    return "out of memory";
  case MR_SOLVE_ERR_NONFINITE:
    return "not finite";
  case MR_SOLVE_ERR_UNAVAILABLE:
    return "unavailable";
  case MR_SOLVE_ERR_ARG:
    return "bad argument";
  }
  return "unknown";
}

mr_solver *mr_solver_create(void) {
  return calloc(1, sizeof(mr_solver));
}

mr_solve_status mr_solver_reserve(mr_solver *s, int rows) {
  if (!s || rows < 0) return MR_SOLVE_ERR_ARG;
  mr_buf *const doubles[] = { &s->x, &s->r, &s->z, &s->p, &s->q, &s->inv_diag };
  for (size_t i = 0; i < sizeof doubles / sizeof doubles[0]; i++)
    if (mr_buf_reserve(doubles[i], (size_t)rows, sizeof(double)) != 0) return MR_SOLVE_ERR_NOMEM;
  if (mr_buf_reserve(&s->dep, (size_t)rows, 1) != 0 || mr_ldlt_reserve(&s->ldlt, rows) != 0)
    return MR_SOLVE_ERR_NOMEM;
  return (mr_solve_status)mr_eigen_reserve(&s->eigen, rows);
}

void mr_solver_destroy(mr_solver *s) {
  if (!s) return;
  mr_buf *const bufs[] = { &s->x, &s->r, &s->z, &s->p, &s->q, &s->dep, &s->inv_diag };
  mr_bufs_free(bufs, sizeof bufs / sizeof bufs[0]);
  mr_ldlt_free(&s->ldlt);
  mr_eigen_free(s->eigen);
  free(s);
}

/* One term of a sum of squares kept as scale²·ssq, so that a large but
 * finite vector does not overflow. */
static void ssq_add(double *scale, double *ssq, double a) {
  if (a == 0.0) return;
  if (*scale < a) {
    *ssq = 1.0 + *ssq * (*scale / a) * (*scale / a);
    *scale = a;
  } else {
    *ssq += (a / *scale) * (a / *scale);
  }
}

/* A plain sum of squares is exact enough for a norm and costs a quarter
 * of the scaled one, unless a term overflows or the sum falls where
 * squares lose digits: then (NaN, Inf, or below this) the scaled sum,
 * which also gives Inf or NaN back when v holds one. */
#define SUMSQ_SAFE_MIN 0x1p-900

static double scaled_norm2(int n, const double *v) {
  double scale = 0.0, ssq = 1.0;
  for (int i = 0; i < n; i++) {
    double a = fabs(v[i]);
    ssq_add(&scale, &ssq, a);
  }
  return scale * sqrt(ssq);
}

double mr_norm2(int n, const double *v) {
  double ss = 0.0;
  for (int i = 0; i < n; i++) ss += v[i] * v[i];
  return ss >= SUMSQ_SAFE_MIN && ss <= DBL_MAX ? sqrt(ss) : scaled_norm2(n, v);
}

static double row_residual(const mr_csr *A, const double *b, const double *x, int i) {
  double s = b[i];
  for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++) s -= A->val[q] * x[A->col[q]];
  return s;
}

void mr_residual(const mr_csr *A, const double *b, const double *x, double *out) {
  for (int i = 0; i < A->n; i++) out[i] = row_residual(A, b, x, i);
}

static double scaled_residual_norm(const mr_csr *A, const double *b, const double *x,
                                   const unsigned char *skip) {
  double scale = 0.0, ssq = 1.0;
  for (int i = 0; i < A->n; i++)
    if (!(skip && skip[i])) ssq_add(&scale, &ssq, fabs(row_residual(A, b, x, i)));
  return scale * sqrt(ssq);
}

double mr_residual_norm(const mr_csr *A, const double *b, const double *x,
                        const unsigned char *skip) {
  const int n = A->n, *rp = A->row_ptr, *col = A->col;
  const double *val = A->val;
  double ss = 0.0;
  for (int i = 0; i < n; i++) {
    if (skip && skip[i]) continue;
    double r = b[i];
    for (int q = rp[i]; q < rp[i + 1]; q++) r -= val[q] * x[col[q]];
    ss += r * r;
  }
  return ss >= SUMSQ_SAFE_MIN && ss <= DBL_MAX ? sqrt(ss) : scaled_residual_norm(A, b, x, skip);
}

void mr_csr_diagonal(const mr_csr *A, double *diag) {
  for (int i = 0; i < A->n; i++) {
    diag[i] = 0.0;
    for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++)
      if (A->col[q] == i) diag[i] = A->val[q];
  }
}

int mr_screen_pairs(const mr_csr *A, double pivot_tol, unsigned char *dep, double *diag) {
  const int n = A->n;
  mr_csr_diagonal(A, diag);
  int count = 0;
  for (int j = 0; j < n; j++) {
    dep[j] = !(diag[j] > DBL_MIN);
    for (int q = A->row_ptr[j]; q < A->row_ptr[j + 1] && !dep[j]; q++) {
      int i = A->col[q];
      if (i >= j || dep[i]) continue;
      /* cos² of the angle between rows i and j of J M^-½; the pivot
             * row j would get after eliminating i alone is A_jj (1 − cos²). */
      double aij = A->val[q];
      if (1.0 - (aij / diag[i]) * (aij / diag[j]) <= pivot_tol) dep[j] = 1;
    }
    count += dep[j];
  }
  return count;
}

int mr_screen_for_iteration(mr_solver *s, const mr_csr *A, double pivot_tol, double *x,
                            mr_solve_result *r) {
  if (mr_buf_reserve(&s->dep, (size_t)A->n, 1) != 0 ||
      mr_buf_reserve(&s->inv_diag, (size_t)A->n, sizeof(double)) != 0)
    return MR_SOLVE_ERR_NOMEM;
  unsigned char *dep = s->dep.p;
  double *inv_diag = s->inv_diag.p;
  r->dependent = mr_screen_pairs(A, pivot_tol, dep, inv_diag);
  for (int i = 0; i < A->n; i++) {
    if (dep[i]) {
      x[i] = 0.0;
      inv_diag[i] = 0.0;
    } else {
      inv_diag[i] = 1.0 / inv_diag[i];
    }
  }
  return 0;
}

/* v·0 is 0 for a finite v and NaN for NaN or ±Inf, and a NaN stays in a
 * sum: no test and branch per number, and four sums that do not wait on
 * each other. */
int mr_all_finite(size_t n, const double *v) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += v[i] * 0.0;
    s1 += v[i + 1] * 0.0;
    s2 += v[i + 2] * 0.0;
    s3 += v[i + 3] * 0.0;
  }
  for (; i < n; i++) s0 += v[i] * 0.0;
  return (s0 + s1) + (s2 + s3) == 0.0;
}

static int all_finite(size_t n, const double *v) {
  return mr_all_finite(n, v);
}

static int a_finite(const mr_csr *A) {
  return all_finite((size_t)A->row_ptr[A->n], A->val);
}

/* LDLᵀ's refinement test measured ‖b − Aλ‖ over every row, and it was
 * finite: then so is every number of A, b and λ, since each row's sum
 * reads all of its entries, and λ_j meets A_jj > 0 in row j (no row was
 * dropped). That spares a pass over A and λ on every solve. */
static int vouched(const mr_ldlt *f) {
  return f->res_known && isfinite(f->res_norm);
}

mr_solve_status mr_solver_solve(mr_solver *s, const mr_solve_def *o, const mr_csr *A,
                                const double *b, double *x, mr_solve_result *r) {
  mr_solve_result local;
  if (!r) r = &local;
  r->status = MR_SOLVE_OK;
  r->iterations = 0;
  r->residual = 0.0;
  r->dependent = 0;
  r->regularised = 0;
  r->dense = 0;
  r->fallback = 0;

  mr_solve_def def = mr_default_solve_def();
  if (!o) o = &def;
  if (!s || !A || (A->n > 0 && (!b || !x || !A->row_ptr)) || o->cookie != MR_DEF_COOKIE ||
      (int)o->method < 0 || (int)o->method >= MR_SOLVE_METHOD_COUNT)
    return r->status = MR_SOLVE_ERR_UNAVAILABLE;
  if (A->n == 0) return r->status;
  /* ‖b‖ is finite exactly when b is. LDLᵀ's answer vouches for A
   * afterwards (vouched()); the other methods iterate on A and look first. */
  const double nb = mr_norm2(A->n, b);
  const int check_a_after = o->method == MR_SOLVE_LDLT;
  if (!isfinite(nb) || (!check_a_after && !a_finite(A))) return r->status = MR_SOLVE_ERR_NONFINITE;

  /* b = 0: λ = 0 solves every consistent system and is the smallest
     * answer; no method needs to iterate towards it. */
  if (nb == 0.0) {
    if (!a_finite(A)) return r->status = MR_SOLVE_ERR_NONFINITE;
    memset(x, 0, (size_t)A->n * sizeof *x);
    return r->status;
  }

  /* Work on a copy so that a failure (no memory, overflow) leaves the
     * caller's x as it was. A non-finite warm start is replaced by zero. */
  if (mr_buf_reserve(&s->x, (size_t)A->n, sizeof(double)) != 0)
    return r->status = MR_SOLVE_ERR_NOMEM;
  double *xw = s->x.p;
  if (all_finite((size_t)A->n, x))
    memcpy(xw, x, (size_t)A->n * sizeof *xw);
  else
    memset(xw, 0, (size_t)A->n * sizeof *xw);

  int st;
  s->ldlt.res_known = 0;
  switch (o->method) {
  case MR_SOLVE_GAUSS_SEIDEL:
    st = mr_gauss_seidel(s, o, A, b, xw, r);
    break;
  case MR_SOLVE_CG:
    st = mr_cg(s, o, A, b, xw, r);
    break;
  case MR_SOLVE_LDLT:
    st = mr_ldlt_solve(&s->ldlt, o, A, b, nb, xw, r);
    break;
  default:
    st = mr_eigen_solve(&s->eigen, o, A, b, xw, r);
    break;
  }
  if (st == MR_CG_HIDDEN_DEPENDENCY) {
    int iterations = r->iterations;
    r->dependent = r->regularised = 0;
    st = mr_ldlt_solve(&s->ldlt, o, A, b, nb, xw, r);
    r->iterations = iterations;
    r->fallback = 1;
  }
  if (st < 0) return r->status = (mr_solve_status)st;
  if (!vouched(&s->ldlt) && ((check_a_after && !a_finite(A)) || !all_finite((size_t)A->n, xw))) {
    r->iterations = r->dependent = r->regularised = r->dense = 0;
    return r->status = MR_SOLVE_ERR_NONFINITE;
  }
  memcpy(x, xw, (size_t)A->n * sizeof *x);
  /* LDLᵀ's refinement test has measured this already when it stopped on
   * it over every row: the same sum over the same numbers. */
  const double res = s->ldlt.res_known ? s->ldlt.res_norm : mr_residual_norm(A, b, x, NULL);
  r->residual = res / (nb > DBL_MIN ? nb : DBL_MIN);
  return r->status = (mr_solve_status)st;
}

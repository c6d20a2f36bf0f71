/* Conjugate gradient with a Jacobi (diagonal) preconditioner: the sparse
 * iterative solver §4.3 anticipates for larger systems. A = J M⁻¹ Jᵀ is
 * symmetric positive (semi)definite, which is what CG needs. Each step
 * minimises the A-norm error over a growing Krylov space, so the last
 * iterate is the best one so far.
 *
 * Dependent rows: rows caught by the pair screen are held at λ = 0 and
 * taken out of the product, leaving CG a smaller nonsingular system. A
 * dependency the screen cannot see (three or more rows together) shows up
 * as a search direction p that A barely stretches, pᵀAp ≤ pivot_tol ·
 * pᵀ diag(A) p: the LDLᵀ pivot test applied to p instead of a row. By then
 * the iterate is not to be trusted: with an inconsistent b the steps
 * before it were already long along the direction A barely sees (|λ| up
 * to 6.6e6 against 1e3, on 33 right-hand sides of 300), so CG hands the
 * system to LDLᵀ (MR_CG_HIDDEN_DEPENDENCY). */
#include "solver_internal.h"

static void masked_mul(const mr_csr *A, const unsigned char *dep, const double *v, double *out) {
  for (int i = 0; i < A->n; i++) {
    double sum = 0.0;
    if (!dep[i])
      for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++) sum += A->val[q] * v[A->col[q]];
    out[i] = sum;
  }
}

static double dot(int n, const double *a, const double *b) {
  double sum = 0.0;
  for (int i = 0; i < n; i++) sum += a[i] * b[i];
  return sum;
}

int mr_cg(mr_solver *s, const mr_solve_def *o, const mr_csr *A, const double *b, double *x,
          mr_solve_result *r) {
  const int n = A->n;
  const size_t dn = (size_t)n;
  if (mr_buf_reserve(&s->r, dn, sizeof(double)) != 0 ||
      mr_buf_reserve(&s->z, dn, sizeof(double)) != 0 ||
      mr_buf_reserve(&s->p, dn, sizeof(double)) != 0 ||
      mr_buf_reserve(&s->q, dn, sizeof(double)) != 0)
    return MR_SOLVE_ERR_NOMEM;
  if (mr_screen_for_iteration(s, A, o->pivot_tol, x, r) != 0) return MR_SOLVE_ERR_NOMEM;
  const unsigned char *dep = s->dep.p;
  const double *inv_diag = s->inv_diag.p;
  double *res = s->r.p, *z = s->z.p, *p = s->p.p, *ap = s->q.p;

  const double stop = o->tol * mr_norm2(n, b);
  /* The recurred residual drifts from the true one, so convergence is
     * only accepted on the true residual, computed here at each (re)start. */
  for (int restarts = 0;; restarts++) {
    masked_mul(A, dep, x, ap);
    for (int i = 0; i < n; i++) {
      res[i] = dep[i] ? 0.0 : b[i] - ap[i];
      z[i] = res[i] * inv_diag[i];
      p[i] = z[i];
    }
    if (mr_norm2(n, res) <= stop) return r->dependent ? MR_SOLVE_DEPENDENT : MR_SOLVE_OK;
    if (restarts > 3 || r->iterations >= o->max_iter) return MR_SOLVE_NOT_CONVERGED;
    double rz = dot(n, res, z);
    while (r->iterations < o->max_iter) {
      masked_mul(A, dep, p, ap);
      double pap = dot(n, p, ap);
      double pdp = 0.0;
      for (int i = 0; i < n; i++)
        if (!dep[i]) pdp += p[i] * p[i] / inv_diag[i];
      if (!(pap > o->pivot_tol * pdp) || !(pdp > 0.0)) {
        return MR_CG_HIDDEN_DEPENDENCY;
      }
      double alpha = rz / pap;
      for (int i = 0; i < n; i++) {
        x[i] += alpha * p[i];
        res[i] -= alpha * ap[i];
      }
      r->iterations++;
      if (mr_norm2(n, res) <= stop) break;
      double rz_new = 0.0;
      for (int i = 0; i < n; i++) {
        z[i] = res[i] * inv_diag[i];
        rz_new += res[i] * z[i];
      }
      double beta = rz_new / rz;
      rz = rz_new;
      for (int i = 0; i < n; i++) p[i] = z[i] + beta * p[i];
    }
  }
}

/* Gauss–Seidel, the paper's solver (§4.3): sweep the rows in order, each
 * time solving row i for λ_i with the newest values of the others,
 *     λ_i ← (b_i − Σ_{j≠i} A_ij λ_j) / A_ii,
 * until ‖Aλ − b‖ ≤ tol ‖b‖ or max_iter sweeps. A = J M⁻¹ Jᵀ is symmetric
 * positive (semi)definite with a positive diagonal, for which every sweep
 * lowers the error in the A-norm, so the last iterate is also the best, and
 * a consistent system with dependent rows still converges (the dependent
 * directions are never excited). Rows found dependent by the pair screen
 * are held at λ = 0 and left out of the stopping test, as the direct
 * solvers leave them out of the elimination. */
#include "solver_internal.h"

int mr_gauss_seidel(mr_solver *s, const mr_solve_def *o, const mr_csr *A, const double *b,
                    double *x, mr_solve_result *r) {
  const int n = A->n;
  if (mr_screen_for_iteration(s, A, o->pivot_tol, x, r) != 0) return MR_SOLVE_ERR_NOMEM;
  const unsigned char *dep = s->dep.p;
  const double *inv_diag = s->inv_diag.p;

  const double stop = o->tol * mr_norm2(n, b);
  if (mr_residual_norm(A, b, x, dep) <= stop)
    return r->dependent ? MR_SOLVE_DEPENDENT : MR_SOLVE_OK;
  for (int it = 1; it <= o->max_iter; it++) {
    for (int i = 0; i < n; i++) {
      if (dep[i]) continue;
      double sum = b[i];
      for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++) {
        if (A->col[q] != i) sum -= A->val[q] * x[A->col[q]];
      }
      x[i] = sum * inv_diag[i];
    }
    r->iterations = it;
    if (mr_residual_norm(A, b, x, dep) <= stop)
      return r->dependent ? MR_SOLVE_DEPENDENT : MR_SOLVE_OK;
  }
  return MR_SOLVE_NOT_CONVERGED;
}

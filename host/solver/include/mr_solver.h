/* mr_solver: the linear algebra behind the constraint system.
 *
 * The physics builds the constraint Jacobian J (k rows, 3n columns) row by
 * row, assembles A = J M⁻¹ Jᵀ (§5.2, eq. 8; §5.3, eq. 9) and solves
 * A λ = b for the Lagrange multipliers λ; the constraint forces (or momenta)
 * are then Jᵀ λ (§5.2, eq. 5). The mathematics is in host/solver/README.md.
 *
 * Plain C11. Nothing here prints or aborts; every failure is a return code.
 */
#ifndef MR_SOLVER_H
#define MR_SOLVER_H

#ifdef __cplusplus
extern "C" {
#endif

/* Block-sparse Jacobian J (k rows × 3n columns): row i holds entries
 * [row_ptr[i], row_ptr[i+1]), each a particle index and dC_i/dx_particle. */
typedef struct mr_jac { int rows, n_particles; int *row_ptr; int *particle; double (*d)[3];
                        int cap_rows, cap_entries; } mr_jac;
int  mr_jac_reset(mr_jac *J, int n_particles);            /* keeps capacity; 0 or MR_SOLVE_ENOMEM */
int  mr_jac_begin_row(mr_jac *J);                           /* returns the new row index or -1 */
int  mr_jac_add(mr_jac *J, int particle, const double d[3]);/* into the current row; merges a repeated particle */
void mr_jac_free(mr_jac *J);
void mr_jac_mul(const mr_jac *J, const double *v3n, double *out_k);      /* J v  */
void mr_jac_tmul(const mr_jac *J, const double *lam_k, double *out_3n);  /* Jᵀ λ (overwrites out) */

/* mr_jac_add returns nonzero for a particle out of range, no row begun, or
 * no memory. J is reset before use (a zeroed mr_jac is a valid start). */

/* Symmetric k×k matrix in CSR with both triangles stored. */
typedef struct mr_csr { int n, nnz, cap; int *row_ptr, *col; double *val; } mr_csr;
int  mr_assemble_jmjt(const mr_jac *J, const double *inv_mass /* per particle, 0 = pinned/infinite */, mr_csr *A);
void mr_csr_free(mr_csr *A);
/* mr_assemble_jmjt: A_ij = Σ_p inv_mass[p] (dC_i/dx_p · dC_j/dx_p); rows with
 * sorted columns, the diagonal always stored, bitwise symmetric. Reuses A's
 * capacity (a zeroed mr_csr is a valid start). 0, MR_SOLVE_ENOMEM, or
 * MR_SOLVE_UNAVAILABLE for a NULL J, A, or inv_mass. */

typedef enum mr_solve_method { MR_SOLVE_GAUSS_SEIDEL, MR_SOLVE_CG, MR_SOLVE_LDLT, MR_SOLVE_EIGEN } mr_solve_method;
typedef struct mr_solve_opts { mr_solve_method method; double tol; int max_iter; double pivot_tol; } mr_solve_opts;
/* Defaults: MR_SOLVE_LDLT (exact to rounding, no tolerance to tune, and it
 * names dependent rows instead of converging slowly towards them),
 * tol 1e-10, max_iter 1000, pivot_tol 1e-12. */
mr_solve_opts mr_solve_opts_default(void);
enum { MR_SOLVE_OK = 0, MR_SOLVE_ENOMEM = -1, MR_SOLVE_NOT_CONVERGED = 1, MR_SOLVE_DEPENDENT = 2, MR_SOLVE_NONFINITE = -2, MR_SOLVE_UNAVAILABLE = -3 };
typedef struct mr_solve_result { int status; int iterations; double residual; /* ‖Ax−b‖/max(‖b‖,tiny) */ int dependent; /* rows found dependent */ } mr_solve_result;
typedef struct mr_solver mr_solver;   /* reusable workspace: no allocation once warmed up to a size */
mr_solver *mr_solver_create(void);
void mr_solver_destroy(mr_solver *s);
/* x is the initial guess for the iterative methods (warm start) and the
 * result. Returns r->status (r may be NULL). MR_SOLVE_NOT_CONVERGED leaves
 * the best x found; MR_SOLVE_DEPENDENT means dependent rows were found and
 * their multipliers set to 0 (see README.md); MR_SOLVE_NONFINITE (NaN/Inf in
 * A or b) leaves x untouched. */
int  mr_solver_solve(mr_solver *s, const mr_solve_opts *o, const mr_csr *A, const double *b, double *x, mr_solve_result *r);
const char *mr_solve_method_name(mr_solve_method m);   /* "gauss-seidel", "cg", "ldlt", "eigen" */
int mr_solve_method_parse(const char *name, mr_solve_method *out); /* 0, or -1 for an unknown name */

#ifdef __cplusplus
}
#endif

#endif /* MR_SOLVER_H */

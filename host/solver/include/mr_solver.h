/* mr_solver: the linear algebra behind the constraint system.
 *
 * The physics builds the constraint Jacobian J (k rows, 3n columns) row by
 * row, assembles A = J M⁻¹ Jᵀ (§5.2, eq. 8; §5.3, eq. 9) and solves
 * A λ = b for the Lagrange multipliers λ; the constraint forces (or momenta)
 * are then Jᵀ λ (§5.2, eq. 5). The mathematics is in host/solver/README.md.
 *
 * Plain C11. Nothing here prints or aborts; every failure is a status.
 * Every object keeps its arrays between calls: once it has seen a size, the
 * same or a smaller size allocates nothing (for MR_SOLVE_EIGEN, as long as
 * A's pattern is unchanged).
 */
#ifndef MR_SOLVER_H
#define MR_SOLVER_H

#include <stddef.h>
#include <stdint.h>

#include "mr_def.h"
#include "mr_solve_method.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mr_solve_status {
  MR_SOLVE_OK = 0,
  MR_SOLVE_NOT_CONVERGED = 1, /* the iteration cap came first; x is the best found */
  MR_SOLVE_DEPENDENT = 2,     /* dependent rows found, their λ set to 0 (README.md) */
  MR_SOLVE_ERR_NOMEM = -1,
  MR_SOLVE_ERR_NONFINITE = -2,   /* NaN or Inf in A or b; x untouched */
  MR_SOLVE_ERR_UNAVAILABLE = -3, /* a NULL object, or a method outside the enum */
  MR_SOLVE_ERR_ARG = -4          /* a particle out of range, or no row begun */
} mr_solve_status;
/* "ok", "not converged", ...; "unknown" outside the enum. */
const char *mr_solve_status_name(mr_solve_status s);

/* ------------------------------------------------------------ Jacobian */

/* Block-sparse J (k rows × 3n columns): row i holds entries
 * [row_ptr[i], row_ptr[i+1]), each a particle index and dC_i/dx_particle.
 * A zeroed mr_jac is a valid start; reset it before each build. */
typedef struct mr_jac {
  int rows, n_particles;
  int *row_ptr, *particle;
  double (*d)[3];
  size_t cap_rows, cap_entries; /* private: the arrays' capacities */
} mr_jac;
mr_solve_status mr_jac_reset(mr_jac *J, int n_particles); /* keeps capacity */
/* Room for rows rows and entries entries in all, so that building J up to
 * that size allocates nothing. */
mr_solve_status mr_jac_reserve(mr_jac *J, int rows, int entries);
int mr_jac_begin_row(mr_jac *J); /* the new row's index, or -1 */
/* Into the current row; a particle named twice in a row is summed once. */
mr_solve_status mr_jac_add(mr_jac *J, int particle, const double d[3]);
/* count rows of width entries each at once: returns the index of their
 * first entry, or −1 (out of memory, a bad count or width). Row r of them
 * holds entries [e + r·width, e + (r + 1)·width), which the caller fills
 * in J->particle and J->d, each particle in range and named once per row:
 * nothing is checked or merged. For callers that know their rows' shapes
 * (a distance row names two particles, a pin one) and build J on every
 * evaluation: no call, test or search per entry. */
int mr_jac_add_rows(mr_jac *J, int count, int width);
void mr_jac_mul(const mr_jac *J, const double *v3n, double *out_k); /* J v */
/* Row i of J v alone, summed as mr_jac_mul sums it, to the bit: for a
 * caller that needs some rows again after a change that reaches only
 * them. Inline, as it runs for every row of every evaluation. */
static inline double mr_jac_row_mul(const mr_jac *J, int i, const double *v3n) {
  const int *part = J->particle;
  const double(*d)[3] = (const double(*)[3])J->d;
  double s = 0.0;
  int e = J->row_ptr[i];
  const int end = J->row_ptr[i + 1];
  if (end - e == 2) { /* a distance: the same sums, without the loop */
    const double *va = v3n + 3 * part[e], *vb = v3n + 3 * part[e + 1];
    s += d[e][0] * va[0] + d[e][1] * va[1] + d[e][2] * va[2];
    s += d[e + 1][0] * vb[0] + d[e + 1][1] * vb[1] + d[e + 1][2] * vb[2];
    e = end;
  }
  for (; e < end; e++) {
    const double *v = v3n + 3 * part[e];
    s += d[e][0] * v[0] + d[e][1] * v[1] + d[e][2] * v[2];
  }
  return s;
}
void mr_jac_tmul(const mr_jac *J, const double *lam_k, double *out_3n); /* Jᵀ λ, overwrites out */
void mr_jac_free(mr_jac *J);

/* ------------------------------------------------------- A = J M⁻¹ Jᵀ */

/* Symmetric k×k matrix in CSR with both triangles stored. A zeroed mr_csr
 * is a valid start. */
typedef struct mr_csr {
  int n, nnz;
  int *row_ptr, *col;
  double *val;
  /* Nonzero: a name for row_ptr and col that no other pattern of this
   * process ever gets (mr_csr_assemble sets it), so that a solver that has
   * seen it knows the pattern without comparing it. 0 when A is filled by
   * hand; set it to 0 after changing row_ptr or col by hand. */
  uint64_t pattern_id;
  struct mr_csr_plan *plan; /* private: arrays and the cached pattern, see assemble.c */
} mr_csr;
/* A_ij = Σ_p inv_mass[p] (dC_i/dx_p · dC_j/dx_p), inv_mass per particle
 * (0 = pinned). Rows have sorted columns, the diagonal is always stored,
 * and A is bitwise symmetric. While J's pattern (its rows' particles) and
 * the set of pinned particles are one of the last 8 met (up to 128 rows),
 * only the numbers are recomputed. MR_SOLVE_ERR_UNAVAILABLE for a NULL A, J,
 * or inv_mass. */
mr_solve_status mr_csr_assemble(mr_csr *A, const mr_jac *J, const double *inv_mass);
/* Room for any J of up to rows rows, particles particles and entries
 * entries (A dense: rows² entries), so that no assembly up to that size
 * allocates, whatever its pattern. */
mr_solve_status mr_csr_reserve(mr_csr *A, int rows, int particles, int entries);
void mr_csr_free(mr_csr *A);

/* ------------------------------------------------------------- solving */

typedef struct mr_solve_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_solve_def() */
  mr_solve_method method;
  double tol;       /* iterative methods: stop at ‖Ax − b‖ ≤ tol ‖b‖ */
  int max_iter;     /* iterative methods: sweeps or CG steps */
  double pivot_tol; /* a row is dependent when its pivot is ≤ pivot_tol · A_ii */
  double reg_tol;   /* LDLT and Eigen: a row nearly dependent, pivot_tol · A_ii < pivot <
                       reg_tol · A_ii, is regularised: its pivot is raised to
                       reg_tol · A_ii (a compliance on that direction only), so
                       its multiplier stays bounded; 0 (default) = off */
  int dense_max;    /* LDLT: a system of up to this many rows (at most
                       MR_SOLVE_DENSE_ROWS_MAX) is factored dense, with no
                       ordering or analysis; larger ones sparse. 0 = always
                       sparse. Default MR_SOLVE_DENSE_DEFAULT, where the two
                       cost the same (README.md) */
} mr_solve_def;
/* The most rows the dense path takes (its factor is rows² numbers), and
 * the default cut-over. */
#define MR_SOLVE_DENSE_ROWS_MAX 128
#define MR_SOLVE_DENSE_DEFAULT  64
/* MR_SOLVE_LDLT (exact to rounding, nothing to tune, and it names dependent
 * rows instead of converging slowly towards them), tol 1e-10, max_iter
 * 1000, pivot_tol 1e-12. */
mr_solve_def mr_default_solve_def(void);

typedef struct mr_solve_result {
  mr_solve_status status;
  int iterations;
  double residual; /* ‖Ax − b‖ / max(‖b‖, tiny); for the dense LDLᵀ, when
                      the factor's own error bound already keeps it within
                      tol, that bound (not measured: README.md) */
  int dependent;   /* rows found dependent */
  int regularised; /* rows found nearly dependent and regularised (reg_tol) */
  int fallback;    /* 1: Gauss–Seidel or CG could not finish (max_iter spent, or
                      a dependency among several rows that CG's search met)
                      and LDLᵀ solved the system; status and counts are its */
  int dense;       /* 1: the dense LDLᵀ answered (dense_max), 0: another path */
} mr_solve_result;

typedef struct mr_solver mr_solver; /* the workspace of every method */
mr_solver *mr_solver_create(void);
/* Room for any system of up to rows rows under every method (L dense:
 * rows²/2 entries), so that no solve up to that size allocates, whatever
 * its pattern. Without it each object grows to the sizes it meets. */
mr_solve_status mr_solver_reserve(mr_solver *s, int rows);
void mr_solver_destroy(mr_solver *s);
/* x is the warm start of the iterative methods and the result. Returns
 * r->status (r may be NULL; def NULL means the defaults; a def not made by
 * mr_default_solve_def gives MR_SOLVE_ERR_UNAVAILABLE). On
 * MR_SOLVE_DEPENDENT the dependent rows' λ are 0; on a negative status x is
 * untouched. An iterative method that cannot finish hands the system to
 * LDLᵀ (r->fallback), so multipliers stay bounded whatever the method: an
 * inconsistent dependency drives Gauss–Seidel's and CG's iterates along
 * the direction A does not see, without bound. */
mr_solve_status mr_solver_solve(mr_solver *s, const mr_solve_def *def, const mr_csr *A,
                                const double *b, double *x, mr_solve_result *r);

#ifdef __cplusplus
}
#endif

#endif /* MR_SOLVER_H */

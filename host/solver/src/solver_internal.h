/* Shared between the solver translation units; not part of the API. */
#ifndef MR_SOLVER_INTERNAL_H
#define MR_SOLVER_INTERNAL_H

#include "mr_solver.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The one growth rule for every array in the library: *pp (a T **) grows to
 * hold count elements of elem_size bytes, its capacity *cap doubling from
 * 16. Arrays never shrink, so a size seen once is never allocated again.
 * 0 or MR_SOLVE_ERR_NOMEM (then *pp and *cap are as they were). */
int mr_grow_to(void *pp, size_t *cap, size_t count, size_t elem_size);
static inline int mr_grow(void *pp, size_t *cap, size_t count, size_t elem_size) {
  /* The common case, inline: the physics adds every Jacobian entry
   * through here. */
  if (count <= *cap && *(void **)pp) return 0;
  return mr_grow_to(pp, cap, count, elem_size);
}

/* An array that carries its own capacity. */
typedef struct mr_buf {
  void *p;
  size_t cap;
} mr_buf;
int mr_buf_reserve(mr_buf *b, size_t count, size_t elem_size);
/* Frees every buffer of the list and zeroes it. */
void mr_bufs_free(mr_buf *const *bufs, size_t count);

/* A copy of a CSR pattern (row_ptr and col), to tell whether work that
 * depends only on the pattern (an ordering, a symbolic factorisation) still
 * holds for a new matrix. */
typedef struct mr_pattern {
  int valid, n, nnz;
  uint64_t id; /* the A->pattern_id it was last found equal to, or 0 */
  mr_buf rp, col;
} mr_pattern;
/* Whether A's pattern is pat's: by its id when pat has met it, else
 * compared, and on a match the id is remembered. */
int mr_pattern_same(mr_pattern *pat, const mr_csr *A);
/* A pattern id no other call of this process returns, never 0. */
uint64_t mr_pattern_new_id(void);
uint64_t mr_pattern_hash(const mr_csr *A);
/* FNV-1a over n ints, from h: the key a kept pattern is looked up by. */
uint64_t mr_hash_ints(uint64_t h, const int *v, size_t n);
int mr_pattern_keep(mr_pattern *pat, const mr_csr *A); /* 0 or MR_SOLVE_ERR_NOMEM */
int mr_pattern_reserve(mr_pattern *pat, size_t n, size_t nnz);
void mr_pattern_free(mr_pattern *pat);

/* How many times mr_csr_assemble has rebuilt A's pattern (not only its
 * numbers) since A was zeroed: for the tests of the pattern cache. */
unsigned long mr_csr_pattern_builds(const mr_csr *A);

/* An analysis kept for a pattern seen lately: the ordering (perm, iperm),
 * the elimination tree (parent) and L's row starts (lp, nnz_l). */
typedef struct mr_ldlt_kept {
  mr_pattern pattern;
  uint64_t hash; /* mr_pattern_hash of pattern: the key it is found by */
  mr_buf perm, iperm, parent, lp, dperm;
  size_t nnz_l;
  unsigned long used; /* f->clock when last used: the least recent goes */
  /* The dense factor's first[] and plan for this analysis (dense.c,
   * keep_plan), plan_ints ints of it; 0: none made since the analysis
   * came into the slot, or one larger than the slot's room. */
  mr_buf dfirst, dplan;
  int plan_ints;
} mr_ldlt_kept;
/* How many analyses are kept, and the largest pattern kept (rows): a
 * reserve gives every kept slot room for a full pattern of up to that
 * many rows, 64 KiB each (8 MiB for 128 rows, mostly never touched: a
 * stick puppet's world is 3 MiB larger than with 32 kept); larger systems
 * keep only the analysis in use (ldlt.c, keep, says why). The
 * benchmark's puppets solve 7 to 31 rows, and which of their taut strings
 * and contacts take part makes 74 to 105 patterns in 10 s (ldlt.c,
 * find_kept): 128 keep them all. */
#define MR_LDLT_KEPT 128

/* How many assembly plans A keeps (assemble.c). A plan stands for J's
 * pattern, which the row sets above change as they change A's: 64 take
 * the 10 s sway of a taut-string stick figure (82 patterns) from 376
 * plans made to 88, and its run 13.6 % fewer instructions with the
 * analyses kept above; about 260 KiB a plan once reserved for 128 rows. */
#define MR_CSR_KEPT        64
#define MR_LDLT_KEPT_MAX_N 128
/* The room a kept slot has for the dense factor's plan, in ints, for
 * n rows (only up to the dense path's MR_SOLVE_DENSE_ROWS_MAX): the
 * benchmark's puppets' plans, the triangular sweeps' lists included,
 * take at most 44 ints a row (the humanoid's; 28 with neither row j's
 * place in l nor the sweeps' lists); a plan that needs more is made again
 * each time its analysis comes back into use. 32 KiB a slot, 4 MiB in
 * all, once reserved for 128 rows (the arrays grow by doubling). */
#define MR_DENSE_KEPT_PLAN_ROOM(n) (56 * (size_t)(n) + 64)

/* The dense LDLᵀ's factor (dense.c): L row-major, n × n, row k used from
 * its first nonzero column first[k]; 1/d (0 for a dropped row); which rows
 * were dropped (1) or regularised (2). The order, first[], L's pattern and
 * the plan of the factor's products depend only on A's pattern: they are
 * kept while the LDLᵀ's analysis in use stays the same (clock), and first[]
 * and the plan also with the analysis' kept slot, for when it comes back. */
typedef struct mr_dense {
  int n, valid;
  int room;            /* rows the arrays hold (mr_dense_reserve) */
  unsigned long clock; /* the mr_ldlt clock the pattern work was done at */
  const int *perm;     /* the order factored, new → old (the analysis' dperm) */
  mr_buf l, first, t, dinv, dropped;
  /* plan: the factor's program (dense_plan.c, plan_pattern) from plan[1]
   * on, then the triangular sweeps' lists from plan[plan[0]] on, n_plan
   * ints in all, or n_plan < 0 when it needs more than its room and the
   * factor and the sweeps walk the envelope instead; mark: L's pattern as
   * n × n bytes and aq: 3n ints, scratch of the plan. l's rows are n + 1
   * long, and t and y n + 1: the plan pads its pairs with index n, where
   * all three are 0. */
  mr_buf plan, mark, aq;
  int n_plan;
  /* The envelope walk's load: place: per entry of A on or below the
   * diagonal, its index in A and in l (n_place pairs); zero: the places in
   * l of the rows' spans that A leaves empty (n_zero). y: b and x
   * permuted. */
  mr_buf place, zero, y;
  int n_place, n_zero;
  /* The numbers of A the factor in l is of (aval, kept_nnz), the
   * tolerances it used and what it found, and whether A is finite (−1:
   * not looked at yet); kept_valid: all of it holds (dense.c,
   * factor_unless_kept). */
  mr_buf aval;
  size_t kept_nnz;
  double kept_pivot, kept_reg;
  int kept_valid, kept_dependent, kept_regularised, kept_finite;
  unsigned long factors; /* factorisations made: for tests */
  unsigned long plans;   /* plans made (not taken from a kept slot): for tests */
} mr_dense;

/* dense.c and dense_plan.c: a buffer of mr_dense as its array, and L's
 * row stride (column n is always 0, so that the plan's padding products,
 * index n with t_n = y_n = 0, add nothing). */
#define MR_DENSE_BUF(d, name, type) ((type *)(d)->name.p)
#define MR_DENSE_LD(n)              ((size_t)(n) + 1u)

/* The C LDLᵀ's state. The ordering and the symbolic factorisation depend
 * only on A's pattern, so they are kept with a copy of the pattern they
 * were computed for: the one in use below, and up to MR_LDLT_KEPT recent
 * ones in kept[] (ldlt.c says why). */
typedef struct mr_ldlt {
  mr_pattern pattern;
  mr_ldlt_kept kept[MR_LDLT_KEPT];
  size_t kept_n, kept_nnz; /* the room every kept slot has (reserve_kept), */
  int kept_roomy;          /* once reserved */
  unsigned long clock;     /* changes of the analysis in use */
  int in_use;              /* kept[]'s slot of the analysis in use; −1: none */
  int before;              /* the slot in use before it (mr_ldlt_prepare) */
  unsigned long analyses;  /* analyses run (ordering + symbolic): for tests */
  mr_buf perm, iperm;      /* new → old, old → new */
  mr_buf dperm;            /* the dense factor's order, new → old */
  mr_buf parent, lnz, flag, stack, lp, dropped;
  mr_buf li, lx, diag, y, z;
  mr_buf skip, res, dx; /* refinement: dropped rows by old index, r, δλ */
  mr_buf cand, bits;    /* a candidate ordering; minimum degree's graph */
  size_t nnz_l;
  /* ‖Aλ − b‖ of the last solve's answer, when its refinement test
   * measured it over every row (res_known): the caller reports it
   * instead of measuring it again. */
  double res_norm;
  int res_known;
  mr_dense dense; /* small systems' path */
} mr_ldlt;

struct mr_solver {
  mr_buf x, r, z, p, q, dep, inv_diag;
  mr_ldlt ldlt;
  void *eigen; /* solver_eigen.cpp's workspace, made on first use */
};

/* ‖Ax − b‖₂ over the rows not flagged in skip (skip may be NULL). */
double mr_residual_norm(const mr_csr *A, const double *b, const double *x,
                        const unsigned char *skip);
double mr_norm2(int n, const double *v);
/* out = b − A x. */
void mr_residual(const mr_csr *A, const double *b, const double *x, double *out);

/* 1 when none of v[0..n) is NaN or ±Inf. */
int mr_all_finite(size_t n, const double *v);

/* A's diagonal (0 where none is stored). */
void mr_csr_diagonal(const mr_csr *A, double *diag);

/* Flags rows that are dependent on their own (A_ii = 0) or parallel to an
 * earlier unflagged row (cos² ≥ 1 − pivot_tol in the M⁻¹ metric); this is
 * the LDLᵀ pivot test applied to pairs. Leaves A's diagonal in diag.
 * Returns the count. */
int mr_screen_pairs(const mr_csr *A, double pivot_tol, unsigned char *dep, double *diag);
/* mr_screen_pairs as the iterative methods start, into s->dep and
 * s->inv_diag: the flagged rows' x set to 0 and their inverse diagonal to
 * 0 (they take no part), the others' inverse diagonal; their count in
 * r->dependent. 0 or MR_SOLVE_ERR_NOMEM. */
int mr_screen_for_iteration(mr_solver *s, const mr_csr *A, double pivot_tol, double *x,
                            mr_solve_result *r);
int mr_gauss_seidel(mr_solver *s, const mr_solve_def *o, const mr_csr *A, const double *b,
                    double *x, mr_solve_result *r);
/* mr_cg's answer when its search meets a dependency among several rows:
 * not a public status, the front then solves the system by LDLᵀ. */
#define MR_CG_HIDDEN_DEPENDENCY 100
int mr_cg(mr_solver *s, const mr_solve_def *o, const mr_csr *A, const double *b, double *x,
          mr_solve_result *r);
/* b_norm: ‖b‖₂ (mr_norm2), which the caller has measured already. */
int mr_ldlt_solve(mr_ldlt *f, const mr_solve_def *o, const mr_csr *A, const double *b,
                  double b_norm, double *x, mr_solve_result *r);
void mr_ldlt_free(mr_ldlt *f);
/* x = (the factor)⁺ b, for the refinement of either factor. */
typedef void (*mr_factored_solve)(const void *factored, const double *b, double *x);
/* Up to two steps of iterative refinement of x against A, skipping the rows
 * flagged in skip (by the caller's row index; read only when r counts
 * dependent or regularised rows, which are the ones flagged); leaves
 * f->res_norm and f->res_known for the caller's report. 0 or
 * MR_SOLVE_ERR_NOMEM. */
int mr_ldlt_refine(mr_ldlt *f, const mr_solve_def *o, const mr_csr *A, const double *b,
                   double b_norm, double *x, mr_solve_result *r, const unsigned char *skip,
                   mr_factored_solve solve, const void *factored);
/* dense.c: the LDLᵀ method's path for systems of up to dense_max rows. */
int mr_dense_solve(mr_ldlt *f, const mr_solve_def *o, const mr_csr *A, const double *b,
                   double b_norm, double *x, mr_solve_result *r);
int mr_dense_reserve(mr_dense *d, int rows);
void mr_dense_free(mr_dense *d);
/* dense_plan.c: the plan's room in ints for n rows; the pattern's share of
 * the work for the analysis in use (its kept plan, or a plan made and kept,
 * or the envelope walk's load lists when a plan outgrows its room); and
 * that walk's load of PAPᵀ's lower triangle into L. */
size_t mr_dense_plan_room(size_t n);
void mr_dense_pattern_work(mr_ldlt *f, mr_dense *dn, const mr_csr *A);
void mr_dense_load(mr_dense *dn, const mr_csr *A);
/* The fill-reducing ordering the LDLᵀ uses, into f->perm (new → old) and
 * f->iperm, and the nonzeros of L below the diagonal it gives; and the
 * order with the least dense-factor work into f->dperm. Uses only f's
 * ordering scratch. 0 or MR_SOLVE_ERR_NOMEM. */
int mr_ldlt_order(mr_ldlt *f, const mr_csr *A, size_t *nnz_l);
/* Makes the analysis of A's pattern (orderings, symbolic factor) the one
 * in use: kept, or computed. 0 or MR_SOLVE_ERR_NOMEM. */
int mr_ldlt_prepare(mr_ldlt *f, const mr_csr *A);
/* Room for any pattern of up to rows rows: L dense, A's pattern full.
 * 0 or MR_SOLVE_ERR_NOMEM. */
int mr_ldlt_reserve(mr_ldlt *f, int rows);
/* Room for mr_ldlt_order alone, on up to rows rows (no factor, no kept
 * analyses: Eigen's workspace orders with it and keeps nothing).
 * 0 or MR_SOLVE_ERR_NOMEM. */
int mr_ldlt_reserve_order(mr_ldlt *f, int rows);

/* The reverse Cuthill–McKee ordering of A's graph: perm[new] = old. iw needs
 * 3n ints. */
void mr_order_rcm(const mr_csr *A, int *perm, int *iw);

/* Minimum degree on the elimination graph held as bitsets: bits needs
 * n·⌈n/64⌉ words, deg n ints. Used up to MR_MIN_DEGREE_MAX_N rows. */
#define MR_MIN_DEGREE_MAX_N 2048
void mr_order_min_degree(const mr_csr *A, int *perm, uint64_t *bits, int *deg);

/* solver_eigen.cpp: Eigen's SimplicialLDLT with the same dependent-row rule
 * as the C LDLᵀ. Returns an MR_SOLVE_* status. */
int mr_eigen_solve(void **ws, const mr_solve_def *o, const mr_csr *A, const double *b, double *x,
                   mr_solve_result *r);
void mr_eigen_free(void *ws);
/* mr_solver_reserve's share for the Eigen method. */
int mr_eigen_reserve(void **ws, int rows);

#ifdef __cplusplus
}
#endif

#endif

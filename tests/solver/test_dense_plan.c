/* The dense path's factor follows L's nonzeros (host/solver/src/dense.c,
 * plan_pattern): its answers are the bits of a dense LDLᵀ that walks
 * every row's whole envelope, computed here with the same order, the same
 * split of each sum into two chains and the same pivot test, on random
 * systems of several patterns, with a row written twice (dropped or, with
 * a non-default reg_tol, regularised), with the pattern changing between
 * solves, and on a full pattern too large for the plan's room (the
 * envelope walk); a factor is made again only for new numbers or new
 * tolerances; and a plan is made again only for a pattern whose analysis
 * was not kept. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "mr_solver.h"
#include "solver_internal.h"
#include "solver_systems.h"

/* s − Σ_{lo ≤ m < hi} a_m b_m, even offsets from lo in s, odd ones in a
 * second sum, added at the end. */
static double ref_minus_dot(double s, const double *a, const double *b, int lo, int hi) {
  double odd = 0.0;
  for (int m = lo; m < hi; m++) {
    if ((m - lo) % 2 == 0)
      s -= a[m] * b[m];
    else
      odd -= a[m] * b[m];
  }
  return s + odd;
}

typedef struct ref_out {
  int dependent, regularised;
} ref_out;

/* L D Lᵀ of P A Pᵀ (perm: new → old) over each row's envelope, and
 * x = P (L D Lᵀ)⁺ Pᵀ b with the dropped rows' unknowns 0. */
static ref_out ref_solve(const mr_csr *A, const int *perm, const mr_solve_def *o, const double *b,
                         double *x) {
  const int n = A->n;
  int *iperm = malloc((size_t)n * sizeof *iperm), *first = malloc((size_t)n * sizeof *first);
  double *l = calloc((size_t)n * (size_t)n, sizeof *l), *t = calloc((size_t)n, sizeof *t);
  double *dinv = malloc((size_t)n * sizeof *dinv), *y = malloc((size_t)n * sizeof *y);
  ref_out out = { 0, 0 };
  for (int k = 0; k < n; k++) iperm[perm[k]] = k;
  for (int k = 0; k < n; k++) first[k] = k;
  for (int i = 0; i < n; i++) {
    for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++) {
      const int k = iperm[i], j = iperm[A->col[q]];
      if (j < first[k]) first[k] = j;
      if (j <= k) l[(size_t)k * (size_t)n + (size_t)j] = A->val[q];
    }
  }
  for (int k = 0; k < n; k++) {
    double *lk = l + (size_t)k * (size_t)n, d = lk[k];
    for (int j = first[k]; j < k; j++) {
      const int lo = first[k] > first[j] ? first[k] : first[j];
      const double s = ref_minus_dot(lk[j], t, l + (size_t)j * (size_t)n, lo, j);
      t[j] = s;
      lk[j] = s * dinv[j];
      d -= lk[j] * s;
    }
    const double akk = lk[k];
    if (!(akk > DBL_MIN) || !(d > o->pivot_tol * akk)) {
      dinv[k] = 0.0;
      out.dependent++;
    } else if (d < o->reg_tol * akk) {
      dinv[k] = 1.0 / (o->reg_tol * akk);
      out.regularised++;
    } else {
      dinv[k] = 1.0 / d;
    }
  }
  for (int k = 0; k < n; k++)
    y[k] = ref_minus_dot(b[perm[k]], l + (size_t)k * (size_t)n, y, first[k], k);
  for (int k = 0; k < n; k++) y[k] *= dinv[k];
  for (int k = n - 1; k >= 0; k--) {
    for (int m = first[k]; m < k; m++) y[m] -= l[(size_t)k * (size_t)n + (size_t)m] * y[k];
    x[perm[k]] = y[k];
  }
  free(iperm);
  free(first);
  free(l);
  free(t);
  free(dinv);
  free(y);
  return out;
}

/* Entries of the plan that A leaves empty and the factor fills in: they
 * read the +0 after A's nnz numbers. */
static int plan_fill(const mr_dense *dn, int nnz) {
  const int *p = (const int *)dn->plan.p + 1; /* plan[0]: where the sweeps' lists start */
  int fill = 0;
  for (int k = 0; k < dn->n; k++) {
    const int *row_end = p + p[0];
    for (p += 2; p < row_end; p += p[3]) fill += p[2] == nnz;
  }
  return fill;
}

/* Solves A x = b on the dense path, without refinement (a tolerance any
 * residual meets), and checks x and the dropped and regularised rows'
 * counts against the reference bit for bit. Returns the plan's fill
 * entries, or −1 when the factor walked the envelope. */
static int check_bits(mr_solver *s, const mr_csr *A, const double *b, double pivot_tol,
                      double reg_tol) {
  const int n = A->n;
  mr_solve_def o = mr_default_solve_def();
  o.method = MR_SOLVE_LDLT;
  o.dense_max = MR_SOLVE_DENSE_ROWS_MAX;
  o.tol = 1e300;
  o.pivot_tol = pivot_tol;
  o.reg_tol = reg_tol;
  double *x = calloc((size_t)n, sizeof *x), *ref = calloc((size_t)n, sizeof *ref);
  mr_solve_result r;
  assert_true(mr_solver_solve(s, &o, A, b, x, &r) >= 0);
  assert_int_equal(r.dense, 1);
  assert_int_equal(r.iterations, 1);
  const mr_dense *dn = &s->ldlt.dense;
  ref_out want = ref_solve(A, dn->perm, &o, b, ref);
  assert_int_equal(r.dependent, want.dependent);
  assert_int_equal(r.regularised, want.regularised);
  assert_memory_equal(x, ref, (size_t)n * sizeof *x);
  free(x);
  free(ref);
  return dn->n_plan >= 0 ? plan_fill(dn, A->row_ptr[n]) : -1;
}

typedef struct one_system {
  test_system sys;
  mr_csr A;
  double *b;
} one_system;

/* A random system of k rows (seed), with row `copy` written again (copy
 * < 0: none), scaled by 1/3 so that its pivot is rounding, not an exact 0,
 * and one of its numbers moved by tilt (then it is nearly dependent). */
static void one_make(one_system *o, int k, uint64_t seed, int copy, double tilt) {
  memset(o, 0, sizeof *o);
  test_system_random(&o->sys, k, seed);
  if (copy >= 0) {
    test_system_copy_row(&o->sys, copy);
    const int last = o->sys.k - 1;
    for (int e = o->sys.J.row_ptr[last]; e < o->sys.J.row_ptr[last + 1]; e++)
      for (int c = 0; c < 3; c++) o->sys.J.d[e][c] /= 3.0;
    o->sys.J.d[o->sys.J.row_ptr[last]][0] += tilt;
  }
  assert_int_equal(mr_csr_assemble(&o->A, &o->sys.J, o->sys.inv_mass), MR_SOLVE_OK);
  o->b = malloc((size_t)o->sys.k * sizeof *o->b);
  test_rng rng = { seed + 1 };
  test_system_consistent_rhs(&o->sys, &rng, o->b);
  if (copy >= 0) o->b[o->sys.k - 1] += 0.5; /* inconsistent: the dropped row's answer matters */
}

static void one_free(one_system *o) {
  free(o->b);
  mr_csr_free(&o->A);
  test_system_free(&o->sys);
}

static void factor_over_the_pattern_gives_the_envelope_walks_bits(void **state) {
  (void)state;
  static const int sizes[] = { 4, 9, 25, 31, 47, 64 };
  enum { N = sizeof sizes / sizeof sizes[0] };
  one_system sys[N];
  for (int z = 0; z < N; z++) one_make(&sys[z], sizes[z], 300 + (uint64_t)z, -1, 0.0);
  mr_solver *s = mr_solver_create();
  int fill = 0;
  /* Each pattern, then each again in another order: every solve after the
   * first changes the pattern, so the plan is made again each time. */
  for (int pass = 0; pass < 2; pass++) {
    for (int i = 0; i < N; i++) {
      const int z = pass ? N - 1 - i : i;
      const int f = check_bits(s, &sys[z].A, sys[z].b, 1e-12, 0.0);
      assert_true(f >= 0); /* the plan, not the envelope walk */
      fill += f;
    }
  }
  assert_true(fill > 0); /* fill the envelope holds and A does not */
  for (int z = 0; z < N; z++) one_free(&sys[z]);
  mr_solver_destroy(s);
}

/* A row written twice is dropped; written again slightly tilted, it is
 * kept with the default pivot_tol and regularised with a reg_tol above its
 * pivot. */
static void dropped_and_regularised_rows_keep_the_envelope_walks_bits(void **state) {
  (void)state;
  mr_solver *s = mr_solver_create();
  for (int copy = 3; copy < 30; copy += 13) {
    for (int tilted = 0; tilted < 2; tilted++) {
      one_system o;
      one_make(&o, 30, 40 + (uint64_t)copy, copy, tilted ? 1e-4 : 0.0);
      const double reg_tol = tilted ? 1e-6 : 0.0;
      assert_true(check_bits(s, &o.A, o.b, 1e-12, reg_tol) >= 0);
      mr_solve_def d = mr_default_solve_def();
      d.dense_max = MR_SOLVE_DENSE_ROWS_MAX;
      d.reg_tol = reg_tol;
      double *x = calloc((size_t)o.A.n, sizeof *x);
      mr_solve_result r;
      mr_solver_solve(s, &d, &o.A, o.b, x, &r);
      assert_int_equal(r.dependent, !tilted);
      assert_int_equal(r.regularised, tilted);
      free(x);
      one_free(&o);
    }
  }
  mr_solver_destroy(s);
}

/* Every row on one movable hub particle: A is full, and the plan of its
 * products (about n³/6) outgrows its room, so the factor walks the
 * envelope, with the same bits. */
static void a_full_pattern_walks_the_envelope_with_the_same_bits(void **state) {
  (void)state;
  enum { K = 90 };
  test_system sys;
  test_system_init(&sys, K + 2);
  const double hub[3] = { 0.0, 0.0, 0.0 };
  test_system_add_particle(&sys, hub, 0.5);
  test_rng rng = { 9 };
  for (int i = 0; i < K; i++) {
    double x[3];
    for (int c = 0; c < 3; c++) x[c] = test_rng_range(&rng, -1.0, 1.0);
    test_system_add_particle(&sys, x, 1.0 / (1.0 + (double)i));
    test_system_distance(&sys, 0, i + 1);
  }
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &sys.J, sys.inv_mass), MR_SOLVE_OK);
  assert_int_equal(A.row_ptr[K], K * K);
  double *b = malloc(K * sizeof *b);
  test_system_consistent_rhs(&sys, &rng, b);
  mr_solver *s = mr_solver_create();
  assert_int_equal(check_bits(s, &A, b, 1e-12, 0.0), -1);
  mr_solver_destroy(s);
  free(b);
  mr_csr_free(&A);
  test_system_free(&sys);
}

/* One A solved for several right-hand sides is factored once; new
 * numbers in the same pattern, or new tolerances, are factored again, and
 * every answer is a fresh solver's, bit for bit. */
static void a_factor_is_kept_for_the_same_numbers_only(void **state) {
  (void)state;
  one_system o;
  one_make(&o, 25, 61, 7, 0.0);
  const int n = o.A.n;
  mr_solver *s = mr_solver_create();
  mr_solve_def d = mr_default_solve_def();
  double *x = calloc((size_t)n, sizeof *x), *ref = calloc((size_t)n, sizeof *ref);
  const unsigned long before = s->ldlt.dense.factors;
  int diag3 = o.A.row_ptr[3];
  while (o.A.col[diag3] != 3) diag3++;
  for (int step = 0; step < 5; step++) {
    if (step == 1) o.b[2] += 1.0;         /* another b: the same factor */
    if (step == 2) o.A.val[diag3] *= 1.5; /* a number of A */
    if (step == 3) d.pivot_tol = 1e-40;   /* a tolerance: the copy is kept */
    if (step == 4) d.reg_tol = 1e-3;
    mr_solve_result r, rf;
    memset(x, 0, (size_t)n * sizeof *x);
    assert_true(mr_solver_solve(s, &d, &o.A, o.b, x, &r) >= 0);
    memset(ref, 0, (size_t)n * sizeof *ref);
    mr_solver *fresh = mr_solver_create();
    assert_true(mr_solver_solve(fresh, &d, &o.A, o.b, ref, &rf) >= 0);
    mr_solver_destroy(fresh);
    assert_memory_equal(x, ref, (size_t)n * sizeof *x);
    assert_int_equal(r.dependent, rf.dependent);
    assert_int_equal(r.regularised, rf.regularised);
    static const unsigned long made[] = { 1, 1, 2, 3, 4 };
    assert_int_equal(s->ldlt.dense.factors - before, made[step]);
  }
  free(x);
  free(ref);
  one_free(&o);
  mr_solver_destroy(s);
}

/* The sweeps take L's rows two entries at a time, padding a row of odd
 * length with its diagonal place: a factor kept for one A answers each new
 * right-hand side (dense; zero but for one row; zeros up front; −0 and +0
 * between nonzeros; the numbers scaled far up) with the envelope walk's
 * bits, although the previous solve left its numbers in the sweeps' scratch,
 * with a dropped row and without. */
static void a_kept_factor_gives_each_right_hand_side_the_envelope_walks_bits(void **state) {
  (void)state;
  for (int copy = -1; copy <= 11; copy += 12) {
    one_system o;
    one_make(&o, 31, 808 + (uint64_t)(copy + 1), copy, 0.0);
    const int n = o.A.n;
    mr_solver *s = mr_solver_create();
    double *b = malloc((size_t)n * sizeof *b);
    test_rng rng = { 5 };
    const unsigned long before = s->ldlt.dense.factors;
    for (int kind = 0; kind < 6; kind++) {
      for (int i = 0; i < n; i++) b[i] = test_rng_range(&rng, -1.0, 1.0);
      for (int i = 0; i < n; i++) {
        if (kind == 1 && i != n / 2) b[i] = 0.0;
        if (kind == 2 && i < 2 * n / 3) b[i] = 0.0;
        if (kind == 3 && i % 3 != 0) b[i] = i % 2 ? -0.0 : 0.0;
        if (kind == 4) b[i] *= 0x1p500;
        if (kind == 5) b[i] = o.b[i];
      }
      check_bits(s, &o.A, b, 1e-12, 0.0);
    }
    assert_int_equal(s->ldlt.dense.factors - before, 1);
    free(b);
    mr_solver_destroy(s);
    one_free(&o);
  }
}

/* Solves sys[z] through check_bits() (the envelope walk's bits) and
 * returns the plans the dense path made for it, 0 or 1. */
static unsigned long plans_for(mr_solver *s, const one_system *sys) {
  const unsigned long before = s->ldlt.dense.plans;
  assert_true(check_bits(s, &sys->A, sys->b, 1e-12, 0.0) >= 0);
  return s->ldlt.dense.plans - before;
}

/* The plan is kept with its pattern's analysis: a pattern that comes
 * back takes its plan (no plan made) and its answer is still the
 * envelope walk's, bit for bit, through patterns of the same size (a plan
 * taken for the wrong one would read other entries of A) and one with a
 * dropped row. When more patterns come and go than analyses are kept,
 * each one's slot goes to another before it comes back: the slot's plan
 * goes with it, a plan is made for every solve, and the bits still hold. */
static void a_pattern_that_comes_back_takes_its_plan_and_only_its_own(void **state) {
  (void)state;
  enum { FEW = 4, MANY = MR_LDLT_KEPT + 1 };
  one_system sys[MANY];
  for (int z = 0; z < MANY; z++) one_make(&sys[z], 25, 700 + (uint64_t)z, z == 2 ? 11 : -1, 0.0);
  mr_solver *s = mr_solver_create();
  for (int z = 0; z < FEW; z++) assert_int_equal(plans_for(s, &sys[z]), 1);
  assert_int_equal(s->ldlt.analyses, FEW); /* FEW patterns, all different */
  for (int pass = 0; pass < 3; pass++)
    for (int i = 0; i < FEW; i++) assert_int_equal(plans_for(s, &sys[(i + pass) % FEW]), 0);
  mr_solver_destroy(s);

  s = mr_solver_create();
  for (int pass = 0; pass < 2; pass++)
    for (int z = 0; z < MANY; z++) assert_int_equal(plans_for(s, &sys[z]), 1);
  assert_int_equal(s->ldlt.analyses, 2 * MANY);
  mr_solver_destroy(s);
  for (int z = 0; z < MANY; z++) one_free(&sys[z]);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(factor_over_the_pattern_gives_the_envelope_walks_bits),
    cmocka_unit_test(dropped_and_regularised_rows_keep_the_envelope_walks_bits),
    cmocka_unit_test(a_full_pattern_walks_the_envelope_with_the_same_bits),
    cmocka_unit_test(a_factor_is_kept_for_the_same_numbers_only),
    cmocka_unit_test(a_kept_factor_gives_each_right_hand_side_the_envelope_walks_bits),
    cmocka_unit_test(a_pattern_that_comes_back_takes_its_plan_and_only_its_own),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The LDLᵀ method's dense path (host/solver/src/dense.c): it agrees with
 * the Eigen oracle and with the sparse path, drops a dependent row and
 * regularises a nearly dependent one as the sparse path does, and is the
 * path taken up to dense_max rows, the sparse one above. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "mr_solver.h"
#include "solver_systems.h"

static mr_solve_def ldlt(int dense_max) {
  mr_solve_def o = mr_default_solve_def();
  o.method = MR_SOLVE_LDLT;
  o.tol = 1e-12;
  o.dense_max = dense_max;
  return o;
}

/* λ from one path; returns r. */
static mr_solve_result solve(mr_solver *s, mr_solve_def o, const mr_csr *A, const double *b,
                             double *lam) {
  mr_solve_result r;
  memset(lam, 0, (size_t)A->n * sizeof *lam);
  assert_true(mr_solver_solve(s, &o, A, b, lam, &r) >= 0);
  return r;
}

static void dense_path_agrees_with_eigen_and_the_sparse_path(void **state) {
  (void)state;
  static const int sizes[] = { 3, 10, 25, 40, 64, 100 };
  mr_solver *s = mr_solver_create();
  double worst = 0.0;
  for (size_t z = 0; z < sizeof sizes / sizeof sizes[0]; z++) {
    for (uint64_t seed = 1; seed <= 3; seed++) {
      test_system sys;
      test_system_random(&sys, sizes[z], 900 + 10 * seed + (uint64_t)sizes[z]);
      const int k = sys.k;
      mr_csr A = { 0 };
      assert_int_equal(mr_csr_assemble(&A, &sys.J, sys.inv_mass), 0);
      double *b = malloc((size_t)k * sizeof *b), *lam = malloc((size_t)k * sizeof *lam);
      double *ref = malloc((size_t)k * sizeof *ref), *sp = malloc((size_t)k * sizeof *sp);
      test_rng rng = { seed };
      test_system_consistent_rhs(&sys, &rng, b);
      mr_solve_def oe = ldlt(0);
      oe.method = MR_SOLVE_EIGEN;
      solve(s, oe, &A, b, ref);
      mr_solve_result rs = solve(s, ldlt(0), &A, b, sp);
      mr_solve_result rd = solve(s, ldlt(MR_SOLVE_DENSE_ROWS_MAX), &A, b, lam);
      assert_int_equal(rs.dense, 0);
      assert_int_equal(rd.dense, 1);
      assert_int_equal(rd.status, MR_SOLVE_OK);
      assert_true(rd.residual <= 1e-12);
      /* The factor alone meets the default tolerance: refinement would
       * hide a factor that is only close. */
      mr_solve_def od = ldlt(MR_SOLVE_DENSE_ROWS_MAX);
      od.tol = mr_default_solve_def().tol;
      assert_int_equal(solve(s, od, &A, b, lam).iterations, 1);
      double d_eigen = test_rel_diff(k, lam, ref), d_sparse = test_rel_diff(k, lam, sp);
      worst = fmax(worst, fmax(d_eigen, d_sparse));
      assert_true(d_eigen <= 1e-9);
      assert_true(d_sparse <= 1e-9);
      free(b);
      free(lam);
      free(ref);
      free(sp);
      mr_csr_free(&A);
      test_system_free(&sys);
    }
  }
  printf("dense against eigen and sparse, 3 to 100 rows: max relative difference %.2e\n", worst);
  mr_solver_destroy(s);
}

/* A row written twice in a random system, the copy scaled by 1/3 so that
 * its pivot is rounding, not an exact 0: both paths drop one row and give
 * the same forces Jᵀλ for a consistent b; for an inconsistent b both stay
 * bounded. */
static void dense_path_drops_a_row_written_twice_as_the_sparse_path_does(void **state) {
  (void)state;
  mr_solver *s = mr_solver_create();
  for (int inconsistent = 0; inconsistent < 2; inconsistent++) {
    test_system sys;
    test_system_random(&sys, 30, 77);
    test_system_copy_row(&sys, 12);
    const int k = sys.k, n3 = 3 * sys.J.n_particles;
    for (int e = sys.J.row_ptr[k - 1]; e < sys.J.row_ptr[k]; e++)
      for (int c = 0; c < 3; c++) sys.J.d[e][c] /= 3.0;
    for (int c = 0; c < n3; c++) sys.dense_j[(size_t)(k - 1) * (size_t)n3 + (size_t)c] /= 3.0;
    mr_csr A = { 0 };
    assert_int_equal(mr_csr_assemble(&A, &sys.J, sys.inv_mass), 0);
    double *b = malloc((size_t)k * sizeof *b), *ld = malloc((size_t)k * sizeof *ld),
           *ls = malloc((size_t)k * sizeof *ls), *fd = malloc((size_t)n3 * sizeof *fd),
           *fs = malloc((size_t)n3 * sizeof *fs);
    test_rng rng = { 5 };
    test_system_consistent_rhs(&sys, &rng, b);
    if (inconsistent) b[k - 1] += 1.0;
    mr_solve_result rd = solve(s, ldlt(MR_SOLVE_DENSE_ROWS_MAX), &A, b, ld);
    mr_solve_result rs = solve(s, ldlt(0), &A, b, ls);
    assert_int_equal(rd.dense, 1);
    assert_int_equal(rd.status, MR_SOLVE_DEPENDENT);
    assert_int_equal(rd.dependent, 1);
    assert_int_equal(rs.dependent, 1);
    test_dense_jt(&sys, ld, fd);
    test_dense_jt(&sys, ls, fs);
    if (!inconsistent) {
      assert_true(rd.residual < 1e-9);
      assert_true(test_rel_diff(n3, fd, fs) < 1e-9);
    } else {
      assert_true(test_norm(k, ld) < 10.0 * test_norm(k, ls));
    }
    free(b);
    free(ld);
    free(ls);
    free(fd);
    free(fs);
    mr_csr_free(&A);
    test_system_free(&sys);
  }
  mr_solver_destroy(s);
}

/* dense_max is the last size factored dense; 0 turns the path off. The
 * default and a non-default cut-over. */
static void dense_path_is_taken_up_to_the_cut_over_and_sparse_above(void **state) {
  (void)state;
  const int cuts[] = { MR_SOLVE_DENSE_DEFAULT, 10 };
  mr_solver *s = mr_solver_create();
  assert_int_equal(mr_default_solve_def().dense_max, MR_SOLVE_DENSE_DEFAULT);
  for (size_t c = 0; c < 2; c++) {
    for (int extra = 0; extra < 2; extra++) {
      test_system sys;
      test_system_random(&sys, cuts[c] + extra, 31);
      mr_csr A = { 0 };
      assert_int_equal(mr_csr_assemble(&A, &sys.J, sys.inv_mass), 0);
      double *b = malloc((size_t)sys.k * sizeof *b), *lam = malloc((size_t)sys.k * sizeof *lam);
      test_rng rng = { 3 };
      test_system_consistent_rhs(&sys, &rng, b);
      mr_solve_def o = mr_default_solve_def();
      o.dense_max = cuts[c];
      assert_int_equal(solve(s, o, &A, b, lam).dense, !extra);
      o.dense_max = 0;
      assert_int_equal(solve(s, o, &A, b, lam).dense, 0);
      free(b);
      free(lam);
      mr_csr_free(&A);
      test_system_free(&sys);
    }
  }
  mr_solver_destroy(s);
}

/* A factor whose error bound already keeps the residual within tol is
 * not measured again, and the bound reported covers the residual measured
 * directly. A tolerance the bound cannot meet (1e-15: under γ_{n+1}) is
 * measured, and that measurement is what is reported. */
static void a_factor_within_its_error_bound_is_not_measured_again(void **state) {
  (void)state;
  mr_solver *s = mr_solver_create();
  test_system sys;
  test_system_random(&sys, 25, 77);
  const int k = sys.k;
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &sys.J, sys.inv_mass), 0);
  double *b = malloc((size_t)k * sizeof *b), *lam = malloc((size_t)k * sizeof *lam);
  test_rng rng = { 78 };
  test_system_consistent_rhs(&sys, &rng, b);
  for (int tight = 0; tight < 2; tight++) {
    mr_solve_def o = ldlt(MR_SOLVE_DENSE_ROWS_MAX);
    o.tol = tight ? 1e-15 : mr_default_solve_def().tol;
    mr_solve_result r = solve(s, o, &A, b, lam);
    assert_int_equal(r.status, MR_SOLVE_OK);
    double nr = 0.0, nb = 0.0;
    for (int i = 0; i < k; i++) {
      double res = b[i];
      for (int q = A.row_ptr[i]; q < A.row_ptr[i + 1]; q++) res -= A.val[q] * lam[A.col[q]];
      nr += res * res;
      nb += b[i] * b[i];
    }
    const double measured = sqrt(nr / nb);
    if (!tight) {
      assert_int_equal(r.iterations, 1);
      assert_true(r.residual >= 10.0 * measured && r.residual <= o.tol); /* a bound */
    } else {
      assert_true(fabs(r.residual - measured) <= 1e-6 * measured);
    }
  }
  free(b);
  free(lam);
  mr_csr_free(&A);
  test_system_free(&sys);
  mr_solver_destroy(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_factor_within_its_error_bound_is_not_measured_again),
    cmocka_unit_test(dense_path_agrees_with_eigen_and_the_sparse_path),
    cmocka_unit_test(dense_path_drops_a_row_written_twice_as_the_sparse_path_does),
    cmocka_unit_test(dense_path_is_taken_up_to_the_cut_over_and_sparse_above),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

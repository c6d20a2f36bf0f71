/* Every C solver against Eigen's SimplicialLDLT on real J M⁻¹ Jᵀ systems
 * (random particles, masses, distance and pin constraints; fixed seeds) of
 * 10 to 500 constraints: ‖λ − λ_eigen‖ / ‖λ_eigen‖ ≤ 1e-9. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "mr_solver.h"
#include "solver_systems.h"

static const int sizes[] = { 10, 25, 60, 137, 250, 400, 500 };
static const uint64_t seeds[] = { 1, 2, 3 };

/* The iterative solvers are run to a residual tight enough that the
 * remaining error in λ is below the bound even on the worst-conditioned of
 * these systems; the defaults (tol 1e-10) are for the physics. */
static mr_solve_def opts_for(mr_solve_method m) {
  mr_solve_def o = mr_default_solve_def();
  o.method = m;
  if (m == MR_SOLVE_GAUSS_SEIDEL) {
    o.tol = 1e-12;
    o.max_iter = 200000;
  } else if (m == MR_SOLVE_CG) {
    o.tol = 1e-12;
    o.max_iter = 20000;
  }
  return o;
}

static void oracle_agrees_on_random_systems(void **state) {
  (void)state;
  static const mr_solve_method methods[] = { MR_SOLVE_GAUSS_SEIDEL, MR_SOLVE_CG, MR_SOLVE_LDLT };
  double worst[3] = { 0 };
  int most_iter[3] = { 0 };
  mr_solver *solver = mr_solver_create();
  assert_non_null(solver);
  mr_csr A = { 0 };
  for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
    for (size_t ri = 0; ri < sizeof seeds / sizeof seeds[0]; ri++) {
      test_system s;
      uint64_t seed = seeds[ri] * 1000u + (uint64_t)sizes[si];
      test_system_random(&s, sizes[si], seed);
      assert_int_equal(s.k, sizes[si]);
      assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
      double *b = malloc((size_t)s.k * sizeof *b);
      double *xe = calloc((size_t)s.k, sizeof *xe);
      double *x = calloc((size_t)s.k, sizeof *x);
      test_rng rng = { seed ^ 0x5eedu };
      /* Half the systems get a force-like right-hand side, half an
             * arbitrary one (any b is consistent when A is nonsingular). */
      if (ri % 2 == 0)
        test_system_consistent_rhs(&s, &rng, b);
      else
        for (int i = 0; i < s.k; i++) b[i] = test_rng_range(&rng, -1.0, 1.0);

      mr_solve_def oe = opts_for(MR_SOLVE_EIGEN);
      mr_solve_result re;
      assert_int_equal(mr_solver_solve(solver, &oe, &A, b, xe, &re), MR_SOLVE_OK);
      assert_int_equal(re.dependent, 0);
      assert_true(re.residual < 1e-12);

      for (int m = 0; m < 3; m++) {
        mr_solve_def o = opts_for(methods[m]);
        mr_solve_result r;
        memset(x, 0, (size_t)s.k * sizeof *x);
        int st = mr_solver_solve(solver, &o, &A, b, x, &r);
        if (st != MR_SOLVE_OK)
          fail_msg("%s on k=%d seed=%llu: status %d after %d iterations, residual %.3e",
                   mr_solve_method_name(methods[m]), s.k, (unsigned long long)seed, st,
                   r.iterations, r.residual);
        assert_int_equal(r.status, st);
        assert_int_equal(r.dependent, 0);
        assert_true(r.residual <= o.tol);
        double d = test_rel_diff(s.k, x, xe);
        if (d > worst[m]) worst[m] = d;
        if (r.iterations > most_iter[m]) most_iter[m] = r.iterations;
        if (d > 1e-9)
          fail_msg("%s on k=%d seed=%llu: relative difference %.3e",
                   mr_solve_method_name(methods[m]), s.k, (unsigned long long)seed, d);
      }
      free(b);
      free(xe);
      free(x);
      test_system_free(&s);
    }
  }
  for (int m = 0; m < 3; m++)
    printf("oracle: %-12s max ‖λ−λ_eigen‖/‖λ_eigen‖ = %.3e  (most iterations %d)\n",
           mr_solve_method_name(methods[m]), worst[m], most_iter[m]);
  mr_csr_free(&A);
  mr_solver_destroy(solver);
}

/* A warm start at the answer is already converged: the physics reuses the
 * last step's λ, and the iterative solvers must not throw it away. */
static void warm_start_at_the_answer_needs_no_sweeps(void **state) {
  (void)state;
  test_system s;
  test_system_random(&s, 120, 77);
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
  double b[120], x[120] = { 0 };
  test_rng rng = { 78 };
  test_system_consistent_rhs(&s, &rng, b);
  mr_solver *solver = mr_solver_create();
  mr_solve_def o = mr_default_solve_def();
  mr_solve_result r;
  o.method = MR_SOLVE_EIGEN;
  assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, &r), MR_SOLVE_OK);
  o.tol = 1e-8;
  o.max_iter = 100000;
  o.method = MR_SOLVE_GAUSS_SEIDEL;
  assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, &r), MR_SOLVE_OK);
  assert_int_equal(r.iterations, 0);
  o.method = MR_SOLVE_CG;
  assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, &r), MR_SOLVE_OK);
  assert_int_equal(r.iterations, 0);
  /* From zero the same tolerance takes sweeps. */
  memset(x, 0, sizeof x);
  o.method = MR_SOLVE_GAUSS_SEIDEL;
  assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, &r), MR_SOLVE_OK);
  assert_true(r.iterations > 1);
  mr_solver_destroy(solver);
  mr_csr_free(&A);
  test_system_free(&s);
}

/* ‖Ax − b‖ / ‖b‖ from the dense A of the test, not the solver's CSR. */
static double dense_residual(const test_system *s, const double *b, const double *x) {
  double *a = malloc((size_t)s->k * (size_t)s->k * sizeof *a),
         *r = malloc((size_t)s->k * sizeof *r);
  assert_non_null(a);
  assert_non_null(r);
  test_dense_jmjt(s, a);
  for (int i = 0; i < s->k; i++) {
    r[i] = b[i];
    for (int j = 0; j < s->k; j++) r[i] -= a[(size_t)i * (size_t)s->k + (size_t)j] * x[j];
  }
  double out = test_norm(s->k, r) / test_norm(s->k, b);
  free(a);
  free(r);
  return out;
}

/* The residual a solve reports is the true one, computed directly, in
 * every method and every ordering: on solves stopped early (a few sweeps)
 * and on an inconsistent system (a row written twice asking for another
 * value), where it is far from rounding and a wrong one shows. */
static void reported_residual_is_the_true_one(void **state) {
  (void)state;
  static const mr_solve_method methods[] = { MR_SOLVE_GAUSS_SEIDEL, MR_SOLVE_CG, MR_SOLVE_LDLT,
                                             MR_SOLVE_EIGEN };
  mr_solver *solver = mr_solver_create();
  double worst = 0;
  for (int inconsistent = 0; inconsistent < 2; inconsistent++)
    for (size_t z = 0; z < 4; z++)
      for (int m = 0; m < 4; m++) {
        test_system s;
        test_system_random(&s, sizes[z], 77 + z);
        if (inconsistent) test_system_copy_row(&s, sizes[z] / 2);
        mr_csr A = { 0 };
        assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
        double *b = malloc((size_t)s.k * sizeof *b), *x = calloc((size_t)s.k, sizeof *x);
        test_rng rng = { 5 + z };
        test_system_consistent_rhs(&s, &rng, b);
        if (inconsistent) b[s.k - 1] += 1.0 + fabs(b[s.k - 1]);
        mr_solve_def o = opts_for(methods[m]);
        if (!inconsistent) o.max_iter = 3;
        if (!inconsistent && (methods[m] == MR_SOLVE_LDLT || methods[m] == MR_SOLVE_EIGEN)) {
          mr_csr_free(&A);
          test_system_free(&s);
          free(b);
          free(x);
          continue; /* exact to rounding: nothing to compare */
        }
        mr_solve_result r;
        int st = mr_solver_solve(solver, &o, &A, b, x, &r);
        assert_true(st >= 0);
        double direct = dense_residual(&s, b, x);
        double off = fabs(r.residual - direct) / direct;
        worst = fmax(worst, off);
        if (!(off < 1e-9))
          fail_msg("%s, %d rows%s: reported residual %.6g, direct %.6g",
                   mr_solve_method_name(methods[m]), s.k, inconsistent ? ", inconsistent" : "",
                   r.residual, direct);
        free(b);
        free(x);
        mr_csr_free(&A);
        test_system_free(&s);
      }
  printf("reported residuals within %.2g of the direct ones\n", worst);
  mr_solver_destroy(solver);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(oracle_agrees_on_random_systems),
    cmocka_unit_test(warm_start_at_the_answer_needs_no_sweeps),
    cmocka_unit_test(reported_residual_is_the_true_one),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

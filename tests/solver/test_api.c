/* The solver's contract outside the happy path: non-finite input, empty
 * and trivial systems, iteration caps, names, and workspace reuse. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "mr_solver.h"
#include "solver_assert.h"
#include "solver_systems.h"

static const mr_solve_method methods[] = { MR_SOLVE_GAUSS_SEIDEL, MR_SOLVE_CG, MR_SOLVE_LDLT,
                                           MR_SOLVE_EIGEN };
#define N_METHODS 4

static void nonfinite_input_is_rejected_and_x_untouched(void **state) {
  (void)state;
  test_system s;
  test_system_random(&s, 30, 5);
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
  double b[30], x[30];
  test_rng rng = { 6 };
  test_system_consistent_rhs(&s, &rng, b);
  mr_solver *solver = mr_solver_create();
  for (int m = 0; m < N_METHODS; m++) {
    for (int where = 0; where < 4; where++) {
      double saved_a = A.val[7], saved_b = b[12];
      if (where == 0)
        A.val[7] = NAN;
      else if (where == 1)
        A.val[7] = INFINITY;
      else if (where == 2)
        b[12] = NAN;
      else
        b[12] = -INFINITY;
      for (int i = 0; i < 30; i++) x[i] = 1234.5 + i;
      mr_solve_def o = mr_default_solve_def();
      o.method = methods[m];
      mr_solve_result r;
      assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, &r), MR_SOLVE_ERR_NONFINITE);
      assert_int_equal(r.status, MR_SOLVE_ERR_NONFINITE);
      for (int i = 0; i < 30; i++) assert_true(x[i] == 1234.5 + i);
      A.val[7] = saved_a;
      b[12] = saved_b;
    }
  }
  /* A NaN mass reaches A through the assembly and is caught there. */
  s.inv_mass[3] = NAN;
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
  assert_int_equal(mr_solver_solve(solver, NULL, &A, b, x, NULL), MR_SOLVE_ERR_NONFINITE);
  mr_solver_destroy(solver);
  mr_csr_free(&A);
  test_system_free(&s);
}

/* A def filled by hand (no cookie from mr_default_solve_def) is refused
 * before anything runs, with x untouched; the same fields from the maker,
 * here a non-default method and tolerance, solve. */
static void a_solve_def_not_from_its_maker_is_refused(void **state) {
  (void)state;
  test_system s;
  test_system_random(&s, 20, 9);
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
  double b[20], x[20];
  test_rng rng = { 3 };
  test_system_consistent_rhs(&s, &rng, b);
  mr_solver *solver = mr_solver_create();
  mr_solve_def o = mr_default_solve_def();
  o.method = MR_SOLVE_CG;
  o.tol = 1e-8;
  mr_solve_def hand = o;
  hand.cookie = 0;
  for (int i = 0; i < 20; i++) x[i] = 7.5;
  mr_solve_result r;
  assert_int_equal(mr_solver_solve(solver, &hand, &A, b, x, &r), MR_SOLVE_ERR_UNAVAILABLE);
  for (int i = 0; i < 20; i++) assert_true(x[i] == 7.5);
  assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, &r), MR_SOLVE_OK);
  mr_solver_destroy(solver);
  mr_csr_free(&A);
  test_system_free(&s);
}

/* LDLᵀ looks at A after solving, through the residual it measures: a NaN
 * is still caught in every entry of A, dense path or sparse, in a row the
 * factor drops (which the residual does not read), and when b = 0. */
static void ldlt_catches_a_nonfinite_entry_wherever_it_sits(void **state) {
  (void)state;
  test_system s;
  test_system_random(&s, 30, 8);
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
  double b[30], x[30], zero[30] = { 0 };
  test_rng rng = { 9 };
  test_system_consistent_rhs(&s, &rng, b);
  mr_solver *solver = mr_solver_create();
  mr_solve_def o = mr_default_solve_def();
  for (int dense_max = 0; dense_max <= 64; dense_max += 64) {
    o.dense_max = dense_max;
    for (int q = 0; q < A.nnz; q++) {
      const double saved = A.val[q];
      A.val[q] = q % 2 ? NAN : -INFINITY;
      for (int i = 0; i < 30; i++) x[i] = 7.0 + i;
      assert_int_equal(mr_solver_solve(solver, &o, &A, q % 3 ? b : zero, x, NULL),
                       MR_SOLVE_ERR_NONFINITE);
      for (int i = 0; i < 30; i++) assert_true(x[i] == 7.0 + i);
      A.val[q] = saved;
    }
    assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, NULL), MR_SOLVE_OK);
  }
  /* A row on its own whose diagonal is NaN is dropped by the pivot test,
   * so no residual reads it. */
  int rp[4] = { 0, 1, 2, 3 }, col[3] = { 0, 1, 2 };
  double val[3] = { 1.0, NAN, 2.0 }, b3[3] = { 1.0, 1.0, 1.0 }, x3[3] = { 5, 5, 5 };
  mr_csr D = { .n = 3, .nnz = 3, .row_ptr = rp, .col = col, .val = val };
  mr_solve_result r;
  assert_int_equal(mr_solver_solve(solver, NULL, &D, b3, x3, &r), MR_SOLVE_ERR_NONFINITE);
  assert_true(x3[0] == 5 && x3[1] == 5 && x3[2] == 5);
  assert_int_equal(r.dependent, 0);
  mr_solver_destroy(solver);
  mr_csr_free(&A);
  test_system_free(&s);
}

static void empty_and_zero_systems(void **state) {
  (void)state;
  mr_solver *solver = mr_solver_create();
  mr_jac J = { 0 };
  mr_csr A = { 0 };
  assert_int_equal(mr_jac_reset(&J, 3), 0);
  assert_int_equal(mr_csr_assemble(&A, &J, (const double[]){ 1, 1, 1 }), 0);
  for (int m = 0; m < N_METHODS; m++) {
    mr_solve_def o = mr_default_solve_def();
    o.method = methods[m];
    mr_solve_result r = { 9, 9, 9.0, 9, 9, 9, 9 };
    assert_int_equal(mr_solver_solve(solver, &o, &A, NULL, NULL, &r), MR_SOLVE_OK);
    assert_int_equal(r.iterations, 0);
    assert_int_equal(r.dependent, 0);
    assert_int_equal(r.fallback, 0);
    assert_int_equal(r.dense, 0);
    assert_true(r.residual == 0.0);
  }
  /* b = 0 gives λ = 0 whatever the warm start. */
  test_system s;
  test_system_random(&s, 20, 8);
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
  double b[20] = { 0 }, x[20];
  for (int m = 0; m < N_METHODS; m++) {
    for (int i = 0; i < 20; i++) x[i] = 3.0;
    mr_solve_def o = mr_default_solve_def();
    o.method = methods[m];
    assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, NULL), MR_SOLVE_OK);
    for (int i = 0; i < 20; i++) assert_true(x[i] == 0.0);
  }
  /* A system of only zero rows: every row dependent, λ = 0. */
  const double d[3] = { 1, 0, 0 };
  assert_int_equal(mr_jac_reset(&J, 2), 0);
  mr_jac_begin_row(&J);
  mr_jac_add(&J, 0, d);
  mr_jac_begin_row(&J);
  assert_int_equal(mr_csr_assemble(&A, &J, (const double[]){ 0, 0 }), 0);
  for (int m = 0; m < N_METHODS; m++) {
    double bz[2] = { 1, -1 }, xz[2] = { 5, 5 };
    mr_solve_def o = mr_default_solve_def();
    o.method = methods[m];
    mr_solve_result r;
    assert_int_equal(mr_solver_solve(solver, &o, &A, bz, xz, &r), MR_SOLVE_DEPENDENT);
    assert_int_equal(r.dependent, 2);
    assert_true(xz[0] == 0.0 && xz[1] == 0.0);
  }
  test_system_free(&s);
  mr_jac_free(&J);
  mr_csr_free(&A);
  mr_solver_destroy(solver);
}

/* With too few sweeps the iterative methods say so, and what they leave is
 * better than where they started (the A-norm error only falls). */
static void iteration_cap_reports_not_converged(void **state) {
  (void)state;
  test_system s;
  test_system_random(&s, 200, 9);
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
  double b[200], x[200];
  test_rng rng = { 10 };
  test_system_consistent_rhs(&s, &rng, b);
  mr_solver *solver = mr_solver_create();
  for (int m = 0; m < 2; m++) {
    memset(x, 0, sizeof x);
    mr_solve_def o = mr_default_solve_def();
    o.method = methods[m];
    o.max_iter = 5;
    mr_solve_result r;
    assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, &r), MR_SOLVE_NOT_CONVERGED);
    assert_int_equal(r.iterations, 5);
    assert_true(r.residual > o.tol && r.residual < 1.0); /* λ = 0 has residual 1 */
    for (int i = 0; i < 200; i++) assert_true(isfinite(x[i]));
    /* Continuing from there (warm start) finishes the job. */
    o.max_iter = 100000;
    assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, &r), MR_SOLVE_OK);
    assert_true(r.residual <= o.tol);
  }
  /* A non-finite warm start is replaced by zero, not propagated. */
  for (int i = 0; i < 200; i++) x[i] = i % 2 ? NAN : 1.0;
  mr_solve_def o = mr_default_solve_def();
  o.method = MR_SOLVE_CG;
  assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, NULL), MR_SOLVE_OK);
  for (int i = 0; i < 200; i++) assert_true(isfinite(x[i]));
  mr_solver_destroy(solver);
  mr_csr_free(&A);
  test_system_free(&s);
}

/* The list for "expected one of" messages is the same table: every
 * method's name once, then NULL; and every status has words. */
static void name_list_and_status_names_come_from_the_tables(void **state) {
  (void)state;
  const char *const *list = mr_solve_method_names();
  int count = 0;
  for (; list[count]; count++) {
    mr_solve_method m;
    assert_int_equal(mr_solve_method_parse(list[count], &m), 0);
    assert_int_equal(m, count);
    assert_string_equal(mr_solve_method_name(m), list[count]);
  }
  assert_int_equal(count, MR_SOLVE_METHOD_COUNT);
  const mr_solve_status all[] = {
    MR_SOLVE_OK,        MR_SOLVE_NOT_CONVERGED, MR_SOLVE_DEPENDENT,
    MR_SOLVE_ERR_NOMEM, MR_SOLVE_ERR_NONFINITE, MR_SOLVE_ERR_UNAVAILABLE,
    MR_SOLVE_ERR_ARG
  };
  for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) {
    assert_string_not_equal(mr_solve_status_name(all[i]), "unknown");
    for (size_t j = 0; j < i; j++)
      assert_string_not_equal(mr_solve_status_name(all[i]), mr_solve_status_name(all[j]));
  }
  assert_string_equal(mr_solve_status_name((mr_solve_status)99), "unknown");
  assert_string_equal(mr_solve_status_name(MR_SOLVE_ERR_NOMEM), "out of memory");
}

static void names_parse_and_defaults(void **state) {
  (void)state;
  static const char *names[] = { "gauss-seidel", "cg", "ldlt", "eigen" };
  for (int m = 0; m < N_METHODS; m++) {
    mr_solve_method back = (mr_solve_method)-1;
    assert_string_equal(mr_solve_method_name(methods[m]), names[m]);
    assert_int_equal(mr_solve_method_parse(names[m], &back), 0);
    assert_int_equal(back, methods[m]);
  }
  mr_solve_method out = MR_SOLVE_CG;
  assert_int_equal(mr_solve_method_parse("gauss_seidel", &out), -1);
  assert_int_equal(mr_solve_method_parse("", &out), -1);
  assert_int_equal(mr_solve_method_parse(NULL, &out), -1);
  assert_int_equal(out, MR_SOLVE_CG);
  assert_string_equal(mr_solve_method_name((mr_solve_method)17), "unknown");

  mr_solve_def o = mr_default_solve_def();
  assert_int_equal(o.method, MR_SOLVE_LDLT);
  assert_true(o.tol == 1e-10 && o.max_iter == 1000 && o.pivot_tol == 1e-12);

  mr_solver *solver = mr_solver_create();
  mr_csr A = { 0 };
  mr_jac J = { 0 };
  const double d[3] = { 0, 1, 0 };
  mr_jac_reset(&J, 1);
  mr_jac_begin_row(&J);
  mr_jac_add(&J, 0, d);
  assert_int_equal(mr_csr_assemble(&A, &J, (const double[]){ 2.0 }), 0);
  double b[1] = { 3 }, x[1] = { 0 };
  o.method = (mr_solve_method)9;
  assert_int_equal(mr_solver_solve(solver, &o, &A, b, x, NULL), MR_SOLVE_ERR_UNAVAILABLE);
  assert_int_equal(mr_solver_solve(NULL, NULL, &A, b, x, NULL), MR_SOLVE_ERR_UNAVAILABLE);
  /* NULL options mean the defaults: 2 λ = 3. */
  assert_int_equal(mr_solver_solve(solver, NULL, &A, b, x, NULL), MR_SOLVE_OK);
  assert_near(x[0], 1.5, 1e-15);
  mr_jac_free(&J);
  mr_csr_free(&A);
  mr_solver_destroy(solver);
  mr_solver_destroy(NULL);
}

/* One workspace serves systems of changing size and pattern (the physics
 * adds and removes contact constraints), and gives bit for bit what a
 * fresh one gives: nothing cached from an earlier system leaks in. */
static void workspace_reuse_matches_a_fresh_solver(void **state) {
  (void)state;
  static const int sizes[] = { 300, 12, 300, 301, 60 };
  static const uint64_t seeds[] = { 1, 2, 3, 3, 4 };
  mr_solver *reused = mr_solver_create();
  mr_csr A = { 0 };
  for (size_t t = 0; t < sizeof sizes / sizeof sizes[0]; t++) {
    test_system s;
    test_system_random(&s, sizes[t], seeds[t]);
    if (t == 3) test_system_copy_row(&s, 100); /* 301 rows: one dependent */
    assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
    double *b = malloc((size_t)s.k * sizeof *b);
    double *x1 = malloc((size_t)s.k * sizeof *x1), *x2 = malloc((size_t)s.k * sizeof *x2);
    test_rng rng = { seeds[t] + 40 };
    test_system_consistent_rhs(&s, &rng, b);
    for (int m = 0; m < N_METHODS; m++) {
      mr_solve_def o = mr_default_solve_def();
      o.method = methods[m];
      o.max_iter = 100000;
      memset(x1, 0, (size_t)s.k * sizeof *x1);
      memset(x2, 0, (size_t)s.k * sizeof *x2);
      mr_solve_result r1, r2;
      mr_solver *fresh = mr_solver_create();
      int st1 = mr_solver_solve(reused, &o, &A, b, x1, &r1);
      int st2 = mr_solver_solve(fresh, &o, &A, b, x2, &r2);
      mr_solver_destroy(fresh);
      assert_int_equal(st1, st2);
      assert_int_equal(st1, t == 3 ? MR_SOLVE_DEPENDENT : MR_SOLVE_OK);
      assert_int_equal(r1.iterations, r2.iterations);
      assert_memory_equal(x1, x2, (size_t)s.k * sizeof *x1);
    }
    /* Same pattern, new values: the LDLᵀ's cached ordering must not
         * hold stale numbers. Scale every mass by 3: λ scales by 1/3. */
    if (t == 0) {
      mr_solve_def o = mr_default_solve_def();
      assert_int_equal(mr_solver_solve(reused, &o, &A, b, x1, NULL), MR_SOLVE_OK);
      for (int p = 0; p < s.np; p++) s.inv_mass[p] *= 3.0;
      assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
      assert_int_equal(mr_solver_solve(reused, &o, &A, b, x2, NULL), MR_SOLVE_OK);
      for (int i = 0; i < s.k; i++)
        assert_near(x2[i], x1[i] / 3.0, 1e-9 * (1.0 + (x1[i] < 0 ? -x1[i] : x1[i])));
    }
    free(b);
    free(x1);
    free(x2);
    test_system_free(&s);
  }
  mr_csr_free(&A);
  mr_solver_destroy(reused);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(nonfinite_input_is_rejected_and_x_untouched),
    cmocka_unit_test(a_solve_def_not_from_its_maker_is_refused),
    cmocka_unit_test(ldlt_catches_a_nonfinite_entry_wherever_it_sits),
    cmocka_unit_test(empty_and_zero_systems),
    cmocka_unit_test(iteration_cap_reports_not_converged),
    cmocka_unit_test(names_parse_and_defaults),
    cmocka_unit_test(name_list_and_status_names_come_from_the_tables),
    cmocka_unit_test(workspace_reuse_matches_a_fresh_solver),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The fill-reducing orderings behind the C LDLᵀ. These look inside the
 * library (solver_internal.h): fill is not visible through the API, and a
 * broken ordering would still give right answers, only slowly. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "solver_internal.h"
#include "solver_assert.h"
#include "solver_systems.h"

static int is_permutation(int n, const int *perm) {
  int ok = 1;
  unsigned char *seen = calloc((size_t)n + 1, 1);
  for (int i = 0; i < n && ok; i++) {
    ok = perm[i] >= 0 && perm[i] < n && !seen[perm[i]];
    if (ok) seen[perm[i]] = 1;
  }
  free(seen);
  return ok;
}

static void orderings_are_permutations(void **state) {
  (void)state;
  static const int sizes[] = { 1, 10, 137, 500 };
  mr_csr A = { 0 };
  for (size_t t = 0; t < sizeof sizes / sizeof sizes[0]; t++) {
    test_system s;
    test_system_random(&s, sizes[t], 300 + t);
    assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
    int n = A.n;
    int *perm = malloc((size_t)n * sizeof *perm), *iw = malloc(3 * (size_t)n * sizeof *iw);
    uint64_t *bits = malloc((size_t)n * (((size_t)n + 63) / 64) * sizeof *bits);
    mr_order_rcm(&A, perm, iw);
    assert_true(is_permutation(n, perm));
    mr_order_min_degree(&A, perm, bits, iw);
    assert_true(is_permutation(n, perm));
    free(perm);
    free(iw);
    free(bits);
    test_system_free(&s);
  }
  mr_csr_free(&A);
}

/* An arrowhead: row 0 is a constraint on every particle (a centre-of-mass
 * pin), rows 1.. are single pins. Eliminating row 0 first fills L
 * completely; minimum degree leaves it for last and L gets no fill at all.
 * The answer must be the same either way. */
static void arrowhead_gets_no_fill(void **state) {
  (void)state;
  enum { N = 120 };
  mr_jac J = { 0 };
  double inv_mass[N];
  assert_int_equal(mr_jac_reset(&J, N), 0);
  mr_jac_begin_row(&J);
  for (int p = 0; p < N; p++) {
    const double d[3] = { 1.0 / N, 0.5 / N, 0.0 };
    mr_jac_add(&J, p, d);
    inv_mass[p] = 1.0 + p % 3;
  }
  for (int p = 0; p < N; p++) {
    const double d[3] = { 0.0, 0.0, 1.0 + 0.01 * p };
    const double e[3] = { 1.0, 0.0, 0.0 };
    mr_jac_begin_row(&J);
    mr_jac_add(&J, p, p % 2 ? d : e);
  }
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &J, inv_mass), 0);
  int lower = (A.nnz - A.n) / 2;
  double b[N + 1], x[N + 1] = { 0 }, xe[N + 1] = { 0 };
  for (int i = 0; i <= N; i++) b[i] = 1.0 + i % 5;
  mr_solver *s = mr_solver_create();
  mr_solve_def o = mr_default_solve_def();
  assert_int_equal(mr_solver_solve(s, &o, &A, b, x, NULL), MR_SOLVE_OK);
  assert_int_equal((int)s->ldlt.nnz_l, lower);
  o.method = MR_SOLVE_EIGEN;
  assert_int_equal(mr_solver_solve(s, &o, &A, b, xe, NULL), MR_SOLVE_OK);
  assert_true(test_rel_diff(N + 1, x, xe) < 1e-12);
  mr_solver_destroy(s);
  mr_csr_free(&A);
  mr_jac_free(&J);
}

/* nnz of L below the diagonal for A ordered by perm, by eliminating a
 * dense boolean copy: slow and plain, independent of the library's
 * elimination tree. */
static long dense_fill(const mr_csr *A, const int *perm) {
  int n = A->n;
  int *iperm = malloc((size_t)n * sizeof *iperm);
  unsigned char *g = calloc((size_t)n * (size_t)n, 1);
  for (int i = 0; i < n; i++) iperm[perm[i]] = i;
  for (int i = 0; i < n; i++)
    for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++)
      g[(size_t)iperm[i] * (size_t)n + (size_t)iperm[A->col[q]]] = 1;
  long count = 0;
  for (int k = 0; k < n; k++) {
    for (int i = k + 1; i < n; i++) {
      if (!g[(size_t)i * (size_t)n + (size_t)k]) continue;
      count++;
      for (int j = k + 1; j < n; j++)
        if (g[(size_t)j * (size_t)n + (size_t)k]) g[(size_t)i * (size_t)n + (size_t)j] = 1;
    }
  }
  free(g);
  free(iperm);
  return count;
}

/* On the random puppet-like systems the LDLᵀ's chosen ordering fills in
 * less than the natural order and no more than RCM, and its symbolic count
 * matches the dense elimination's. */
static void chosen_ordering_fills_least(void **state) {
  (void)state;
  static const int sizes[] = { 60, 250, 500 };
  for (size_t t = 0; t < sizeof sizes / sizeof sizes[0]; t++) {
    int n = sizes[t];
    test_system s;
    test_system_random(&s, n, 1000 + (uint64_t)n);
    mr_csr A = { 0 };
    assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), 0);
    double *b = calloc((size_t)n, sizeof *b), *x = calloc((size_t)n, sizeof *x);
    int *perm = malloc((size_t)n * sizeof *perm), *iw = malloc(3 * (size_t)n * sizeof *iw);
    for (int i = 0; i < n; i++) b[i] = 1.0;
    mr_solver *solver = mr_solver_create();
    assert_int_equal(mr_solver_solve(solver, NULL, &A, b, x, NULL), MR_SOLVE_OK);
    long chosen = dense_fill(&A, solver->ldlt.perm.p);
    assert_int_equal(chosen, (long)solver->ldlt.nnz_l);
    for (int i = 0; i < n; i++) perm[i] = i;
    long natural = dense_fill(&A, perm);
    mr_order_rcm(&A, perm, iw);
    long rcm = dense_fill(&A, perm);
    print_message("k=%d: nnz(L) natural %ld, RCM %ld, chosen %ld\n", n, natural, rcm, chosen);
    assert_true(chosen < natural);
    assert_true(chosen <= rcm);
    mr_solver_destroy(solver);
    free(b);
    free(x);
    free(perm);
    free(iw);
    mr_csr_free(&A);
    test_system_free(&s);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(orderings_are_permutations),
    cmocka_unit_test(arrowhead_gets_no_fill),
    cmocka_unit_test(chosen_ordering_fills_least),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The assembly's pattern cache: a call whose Jacobian has the rows, the
 * particles and the pinned set of the last call recomputes only the
 * numbers, and the matrix it gives is the one a fresh assembly gives, bit
 * for bit; any change to the pattern is noticed and the pattern rebuilt. */
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

/* A and a fresh assembly of the same J agree in every bit. */
static void assert_same_as_fresh(const mr_csr *A, const test_system *s) {
  mr_csr fresh = { 0 };
  assert_int_equal(mr_csr_assemble(&fresh, &s->J, s->inv_mass), MR_SOLVE_OK);
  assert_int_equal(mr_csr_pattern_builds(&fresh), 1);
  assert_int_equal(A->n, fresh.n);
  assert_int_equal(A->nnz, fresh.nnz);
  assert_memory_equal(A->row_ptr, fresh.row_ptr, ((size_t)fresh.n + 1) * sizeof(int));
  assert_memory_equal(A->col, fresh.col, (size_t)fresh.nnz * sizeof(int));
  assert_memory_equal(A->val, fresh.val, (size_t)fresh.nnz * sizeof(double));
  mr_csr_free(&fresh);
}

/* New numbers in the same pattern, as a step of the physics gives: every
 * Jacobian entry and every movable particle's inverse mass changes. */
static void move(test_system *s, double by) {
  const int ne = s->J.row_ptr[s->J.rows];
  for (int e = 0; e < ne; e++)
    for (int c = 0; c < 3; c++) s->J.d[e][c] *= 1.0 + by * (double)((e + c) % 7 - 3);
  for (int p = 0; p < s->np; p++)
    if (s->inv_mass[p] != 0.0) s->inv_mass[p] *= 1.0 + by * (double)(p % 5);
}

static void cached_assembly_equals_a_fresh_one_bit_for_bit(void **state) {
  (void)state;
  test_system s;
  test_system_random(&s, 150, 7);
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), MR_SOLVE_OK);
  double *before = malloc((size_t)A.nnz * sizeof *before);
  for (int step = 1; step <= 5; step++) {
    memcpy(before, A.val, (size_t)A.nnz * sizeof *before);
    move(&s, 1e-3 * step);
    assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), MR_SOLVE_OK);
    assert_int_equal(mr_csr_pattern_builds(&A), 1);                          /* the numbers only */
    assert_true(memcmp(A.val, before, (size_t)A.nnz * sizeof *before) != 0); /* and they changed */
    assert_same_as_fresh(&A, &s);
  }
  free(before);
  mr_csr_free(&A);
  test_system_free(&s);
}

static void an_added_contact_row_is_noticed(void **state) {
  (void)state;
  test_system s;
  test_system_random(&s, 60, 11);
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), MR_SOLVE_OK);
  /* A contact: a row along the floor's normal on a movable particle. */
  const double up[3] = { 0, 0, 1 };
  test_system_pin(&s, s.np - 1, up);
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), MR_SOLVE_OK);
  assert_int_equal(mr_csr_pattern_builds(&A), 2);
  assert_int_equal(A.n, 61);
  assert_same_as_fresh(&A, &s);
  mr_csr_free(&A);
  test_system_free(&s);
}

static void a_row_naming_another_particle_is_noticed(void **state) {
  (void)state;
  test_system s;
  test_system_random(&s, 60, 13);
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), MR_SOLVE_OK);
  /* Same rows, same entry count: only the last entry's particle changes
   * (a contact moving to the next particle). */
  int last = s.J.row_ptr[s.J.rows] - 1;
  s.J.particle[last] = (s.J.particle[last] + 1) % s.np;
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), MR_SOLVE_OK);
  assert_int_equal(mr_csr_pattern_builds(&A), 2);
  assert_same_as_fresh(&A, &s);
  mr_csr_free(&A);
  test_system_free(&s);
}

static void pinning_or_releasing_a_particle_is_noticed(void **state) {
  (void)state;
  test_system s;
  test_system_random(&s, 60, 17);
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), MR_SOLVE_OK);
  int p = s.J.particle[s.J.row_ptr[s.J.rows] - 1];
  double w = s.inv_mass[p];
  assert_true(w != 0.0);
  s.inv_mass[p] = 0.0; /* pinned: its rows no longer meet through it */
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), MR_SOLVE_OK);
  assert_int_equal(mr_csr_pattern_builds(&A), 2);
  assert_same_as_fresh(&A, &s);
  s.inv_mass[p] = w; /* released: the first pattern again, whose plan is kept */
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), MR_SOLVE_OK);
  assert_int_equal(mr_csr_pattern_builds(&A), 2);
  assert_same_as_fresh(&A, &s);
  mr_csr_free(&A);
  test_system_free(&s);
}

static void a_removed_row_is_noticed(void **state) {
  (void)state;
  test_system s;
  test_system_random(&s, 60, 19);
  mr_csr A = { 0 };
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), MR_SOLVE_OK);
  s.J.rows--; /* the last contact lifts off */
  s.k--;
  assert_int_equal(mr_csr_assemble(&A, &s.J, s.inv_mass), MR_SOLVE_OK);
  assert_int_equal(mr_csr_pattern_builds(&A), 2);
  assert_int_equal(A.n, 59);
  assert_same_as_fresh(&A, &s);
  mr_csr_free(&A);
  test_system_free(&s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(cached_assembly_equals_a_fresh_one_bit_for_bit),
    cmocka_unit_test(an_added_contact_row_is_noticed),
    cmocka_unit_test(a_row_naming_another_particle_is_noticed),
    cmocka_unit_test(pinning_or_releasing_a_particle_is_noticed),
    cmocka_unit_test(a_removed_row_is_noticed),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

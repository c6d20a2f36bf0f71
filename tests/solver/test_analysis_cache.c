/* The solver keeps the analyses (ordering and symbolic factorisation) of
 * the last few patterns it saw, and the assembly the plans of the last few
 * Jacobians: a step of the physics alternates among a few row sets, and
 * each switch used to throw the one kept away. Alternating among three
 * patterns analyses (plans) each once and gives the same bits as a solver
 * (an assembly) that has seen nothing before; more patterns than are kept
 * evict the least recently used. */
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

/* One pattern more than either cache keeps; the plan tests use the first
 * MR_CSR_KEPT + 1 of them. */
enum { PLANS = MR_CSR_KEPT + 1, PATTERNS = MR_LDLT_KEPT + 1, K = 60 };
_Static_assert(PLANS <= PATTERNS, "the variants cover the plan tests");
/* The pins of a variant: one per bit of PATTERNS − 1 at most. */
enum { BITS = 16 };
_Static_assert(PATTERNS - 1 < 1 << BITS && K + BITS <= MR_LDLT_KEPT_MAX_N, "variants are kept");

/* Pattern v: the same 60 random rows, then a contact (a pin along z) on
 * the last particle but i for each bit i of v: each v gives A another
 * pattern, and every pattern stays within the rows a cache keeps. */
static void make_variant(test_system *s, int v) {
  static const double up[3] = { 0, 0, 1 };
  test_system_random(s, K, 11);
  for (int i = 0; v >> i; i++)
    if (v >> i & 1) test_system_pin(s, s->np - 1 - i, up);
}

/* x = A⁻¹ b by a solver that has seen nothing before. */
static void solve_fresh(const mr_csr *A, const double *b, double *x) {
  mr_solver *fresh = mr_solver_create();
  assert_non_null(fresh);
  mr_solve_def def = mr_default_solve_def();
  def.method = MR_SOLVE_LDLT;
  mr_solve_result r;
  memset(x, 0, (size_t)A->n * sizeof *x);
  mr_solve_status st = mr_solver_solve(fresh, &def, A, b, x, &r);
  assert_true(st == MR_SOLVE_OK || st == MR_SOLVE_DEPENDENT);
  assert_int_equal(fresh->ldlt.analyses, 1);
  mr_solver_destroy(fresh);
}

typedef struct variants {
  test_system sys[PATTERNS];
  mr_csr A[PATTERNS];
  double b[PATTERNS][K + BITS], ref[PATTERNS][K + BITS];
} variants;

static void variants_make(variants *v) {
  memset(v, 0, sizeof *v);
  test_rng rng = { 5 };
  for (int p = 0; p < PATTERNS; p++) {
    make_variant(&v->sys[p], p);
    assert_int_equal(mr_csr_assemble(&v->A[p], &v->sys[p].J, v->sys[p].inv_mass), MR_SOLVE_OK);
    test_system_consistent_rhs(&v->sys[p], &rng, v->b[p]);
    solve_fresh(&v->A[p], v->b[p], v->ref[p]);
  }
}

static void variants_free(variants *v) {
  for (int p = 0; p < PATTERNS; p++) {
    mr_csr_free(&v->A[p]);
    test_system_free(&v->sys[p]);
  }
}

/* Solves A x = b with s and checks x against ref, a fresh solver's answer,
 * bit for bit. */
static void solve_expecting(mr_solver *s, const mr_csr *A, const double *b, const double *ref) {
  mr_solve_def def = mr_default_solve_def();
  def.method = MR_SOLVE_LDLT;
  mr_solve_result r;
  double x[K + BITS] = { 0 };
  mr_solve_status st = mr_solver_solve(s, &def, A, b, x, &r);
  assert_true(st == MR_SOLVE_OK || st == MR_SOLVE_DEPENDENT);
  assert_memory_equal(x, ref, (size_t)A->n * sizeof *x);
}

/* Each test's own variants, made before it and freed after it. */
static int variants_setup(void **state) {
  variants *v = malloc(sizeof *v);
  if (v == NULL) return -1;
  variants_make(v);
  *state = v;
  return 0;
}

static int variants_teardown(void **state) {
  variants_free(*state);
  free(*state);
  return 0;
}

#define WITH_VARIANTS(test) cmocka_unit_test_setup_teardown(test, variants_setup, variants_teardown)

static void solve_and_compare(mr_solver *s, variants *v, int p) {
  solve_expecting(s, &v->A[p], v->b[p], v->ref[p]);
}

static void alternating_patterns_are_analysed_once_each(void **state) {
  variants *v = *state;
  mr_solver *s = mr_solver_create();
  assert_non_null(s);
  for (int round = 0; round < 10; round++)
    for (int p = 0; p < 3; p++) solve_and_compare(s, v, round % 2 ? 2 - p : p);
  assert_int_equal(s->ldlt.analyses, 3);
  mr_solver_destroy(s);
}

/* One pattern more than are kept, in turn: each is the least recently
 * used when it comes back, so every solve analyses; the kept ones then
 * still answer without one. */
static void the_least_recently_used_analysis_goes(void **state) {
  variants *v = *state;
  mr_solver *s = mr_solver_create();
  assert_non_null(s);
  for (int round = 0; round < 2; round++)
    for (int p = 0; p < PATTERNS; p++) solve_and_compare(s, v, p);
  assert_int_equal(s->ldlt.analyses, 2 * PATTERNS);
  for (int p = PATTERNS - 1; p >= 1; p--) solve_and_compare(s, v, p);
  assert_int_equal(s->ldlt.analyses, 2 * PATTERNS);
  solve_and_compare(s, v, 0); /* gone: it takes the place of the least recent, the last */
  assert_int_equal(s->ldlt.analyses, 2 * PATTERNS + 1);
  solve_and_compare(s, v, 1);
  assert_int_equal(s->ldlt.analyses, 2 * PATTERNS + 1);
  solve_and_compare(s, v, PATTERNS - 1);
  assert_int_equal(s->ldlt.analyses, 2 * PATTERNS + 2);
  mr_solver_destroy(s);
}

/* A pattern above the rows kept (a few hundred contact rows) keeps its
 * analysis while it repeats, and is analysed again when it changes; it
 * does not push out a small pattern's kept analysis. Every answer is the
 * fresh solver's, bit for bit. */
enum { BIG = MR_LDLT_KEPT_MAX_N + 20 };

static void a_big_pattern_is_analysed_again_only_when_it_changes(void **state) {
  static const double up[3] = { 0, 0, 1 };
  test_system sys[3];
  mr_csr A[3];
  double *b[3], *ref[3], *x = calloc(BIG + 3, sizeof *x);
  test_rng rng = { 9 };
  memset(sys, 0, sizeof sys);
  memset(A, 0, sizeof A);
  assert_non_null(x);
  for (int p = 0; p < 3; p++) {
    test_system_random(&sys[p], BIG, 13);
    for (int c = 0; c <= p; c++) test_system_pin(&sys[p], sys[p].np - 1 - c, up);
    assert_int_equal(mr_csr_assemble(&A[p], &sys[p].J, sys[p].inv_mass), MR_SOLVE_OK);
    b[p] = calloc(BIG + 3, sizeof *b[p]);
    ref[p] = calloc(BIG + 3, sizeof *ref[p]);
    assert_true(b[p] && ref[p]);
    test_system_consistent_rhs(&sys[p], &rng, b[p]);
    solve_fresh(&A[p], b[p], ref[p]);
  }
  mr_solver *s = mr_solver_create();
  assert_non_null(s);
  mr_solve_def def = mr_default_solve_def();
  def.method = MR_SOLVE_LDLT;
  variants *v = *state;
  solve_and_compare(s, v, 1); /* a small pattern, kept */
  const int order[] = { 0, 0, 0, 1, 1, 0, 2, 2, 0 }, analysed[] = { 2, 2, 2, 3, 3, 4, 5, 5, 6 };
  for (int i = 0; i < 9; i++) {
    int p = order[i];
    mr_solve_result r;
    memset(x, 0, (BIG + 3) * sizeof *x);
    mr_solve_status st = mr_solver_solve(s, &def, &A[p], b[p], x, &r);
    assert_true(st == MR_SOLVE_OK || st == MR_SOLVE_DEPENDENT);
    assert_false(r.dense);
    assert_memory_equal(x, ref[p], (size_t)A[p].n * sizeof *x);
    assert_int_equal(s->ldlt.analyses, analysed[i]);
  }
  solve_and_compare(s, v, 1); /* still kept */
  assert_int_equal(s->ldlt.analyses, 6);
  mr_solver_destroy(s);
  for (int p = 0; p < 3; p++) {
    free(b[p]);
    free(ref[p]);
    mr_csr_free(&A[p]);
    test_system_free(&sys[p]);
  }
  free(x);
}

/* A and a fresh assembly of the same J agree in every bit. */
static void assert_same_as_fresh(const mr_csr *A, const test_system *s) {
  mr_csr fresh = { 0 };
  assert_int_equal(mr_csr_assemble(&fresh, &s->J, s->inv_mass), MR_SOLVE_OK);
  assert_int_equal(A->n, fresh.n);
  assert_int_equal(A->nnz, fresh.nnz);
  assert_memory_equal(A->row_ptr, fresh.row_ptr, ((size_t)fresh.n + 1) * sizeof(int));
  assert_memory_equal(A->col, fresh.col, (size_t)fresh.nnz * sizeof(int));
  assert_memory_equal(A->val, fresh.val, (size_t)fresh.nnz * sizeof(double));
  mr_csr_free(&fresh);
}

static void alternating_jacobians_are_planned_once_each(void **state) {
  variants *v = *state;
  mr_csr A = { 0 };
  for (int round = 0; round < 10; round++) {
    for (int q = 0; q < 3; q++) {
      int p = round % 2 ? 2 - q : q;
      assert_int_equal(mr_csr_assemble(&A, &v->sys[p].J, v->sys[p].inv_mass), MR_SOLVE_OK);
      assert_same_as_fresh(&A, &v->sys[p]);
    }
  }
  assert_int_equal(mr_csr_pattern_builds(&A), 3);
  mr_csr_free(&A);
}

/* One Jacobian more than there are plans, in turn: each is the least
 * recently used when it comes back, so every assembly plans again. */
static void the_least_recently_used_plan_goes(void **state) {
  variants *v = *state;
  mr_csr A = { 0 };
  for (int round = 0; round < 2; round++) {
    for (int p = 0; p < PLANS; p++) {
      assert_int_equal(mr_csr_assemble(&A, &v->sys[p].J, v->sys[p].inv_mass), MR_SOLVE_OK);
      assert_same_as_fresh(&A, &v->sys[p]);
    }
  }
  assert_int_equal(mr_csr_pattern_builds(&A), 2 * PLANS);
  for (int p = PLANS - 1; p >= 1; p--)
    assert_int_equal(mr_csr_assemble(&A, &v->sys[p].J, v->sys[p].inv_mass), MR_SOLVE_OK);
  assert_int_equal(mr_csr_pattern_builds(&A), 2 * PLANS);
  mr_csr_free(&A);
}

/* Every plan an assembly builds names its pattern with an id no other
 * plan had, and keeps it while that plan is reused: a solver that has met
 * an id takes it for the pattern without comparing. Plans evicted and
 * built again into the same slot get new ids, and one solver fed them all
 * in turn answers each as a fresh one does. */
static void a_pattern_id_names_one_plan_only(void **state) {
  variants *v = *state;
  mr_csr A = { 0 };
  mr_solver *s = mr_solver_create();
  assert_non_null(s);
  uint64_t ids[2 * PLANS];
  for (int round = 0; round < 2; round++) {
    for (int p = 0; p < PLANS; p++) {
      assert_int_equal(mr_csr_assemble(&A, &v->sys[p].J, v->sys[p].inv_mass), MR_SOLVE_OK);
      const uint64_t id = A.pattern_id;
      assert_true(id != 0);
      for (int q = 0; q < round * PLANS + p; q++) assert_true(ids[q] != id);
      ids[round * PLANS + p] = id;
      assert_int_equal(mr_csr_assemble(&A, &v->sys[p].J, v->sys[p].inv_mass), MR_SOLVE_OK);
      assert_true(A.pattern_id == id);
      solve_expecting(s, &A, v->b[p], v->ref[p]);
    }
  }
  mr_solver_destroy(s);
  mr_csr_free(&A);
}

/* A filled by hand has no id (0): its pattern is compared, so two such
 * matrices of different patterns through one solver are told apart. */
static void patterns_filled_by_hand_are_compared(void **state) {
  variants *v = *state;
  mr_solver *s = mr_solver_create();
  assert_non_null(s);
  for (int round = 0; round < 4; round++) {
    const int p = 1 + round % 2;
    const mr_csr *a = &v->A[p];
    mr_csr hand = { .n = a->n, .nnz = a->nnz, .row_ptr = a->row_ptr, .col = a->col, .val = a->val };
    solve_expecting(s, &hand, v->b[p], v->ref[p]);
  }
  assert_int_equal(s->ldlt.analyses, 2);
  mr_solver_destroy(s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    WITH_VARIANTS(alternating_patterns_are_analysed_once_each),
    WITH_VARIANTS(the_least_recently_used_analysis_goes),
    WITH_VARIANTS(a_big_pattern_is_analysed_again_only_when_it_changes),
    WITH_VARIANTS(alternating_jacobians_are_planned_once_each),
    WITH_VARIANTS(the_least_recently_used_plan_goes),
    WITH_VARIANTS(a_pattern_id_names_one_plan_only),
    WITH_VARIANTS(patterns_filled_by_hand_are_compared),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

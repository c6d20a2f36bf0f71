/* Once warm, assembling J M⁻¹ Jᵀ and solving it allocates nothing, under
 * every method: the physics does both several times per step.
 *
 * The allocation functions are counted by tests/common/alloc.h: every call
 * to malloc, calloc, realloc, aligned allocation or operator new from the
 * library, the Eigen code compiled into it, and this test. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "alloc.h"
#include "mr_solver.h"

/* A chain of n particles hanging from a fixed first one, as the physics
 * builds it each evaluation: one distance row per link, pins along x on
 * every tenth particle, a link written twice (a dependent row, so every
 * method runs its dependent-row path), and, when contact is set, one
 * contact row on the last particle. The positions move with t. */
enum { N = 100 };

static void position(int i, double t, double x[3]) {
  x[0] = 0.1 * i;
  x[1] = 0.05 * sin(i + t);
  x[2] = 0.02 * cos(2.0 * i + t);
}

static void add_link(mr_jac *J, int a, int b, double t) {
  double xa[3], xb[3], u[3], nu[3], len = 0.0;
  position(a, t, xa);
  position(b, t, xb);
  for (int c = 0; c < 3; c++) len += (xa[c] - xb[c]) * (xa[c] - xb[c]);
  for (int c = 0; c < 3; c++) {
    u[c] = (xa[c] - xb[c]) / sqrt(len);
    nu[c] = -u[c];
  }
  assert_true(mr_jac_begin_row(J) >= 0);
  assert_int_equal(mr_jac_add(J, a, u), MR_SOLVE_OK);
  assert_int_equal(mr_jac_add(J, b, nu), MR_SOLVE_OK);
}

static void build(mr_jac *J, double t, int contact) {
  static const double along_x[3] = { 1, 0, 0 }, up[3] = { 0, 0, 1 };
  assert_int_equal(mr_jac_reset(J, N), MR_SOLVE_OK);
  for (int i = 0; i + 1 < N; i++) add_link(J, i, i + 1, t);
  add_link(J, 3, 4, t);
  for (int i = 10; i < N; i += 10) {
    assert_true(mr_jac_begin_row(J) >= 0);
    assert_int_equal(mr_jac_add(J, i, along_x), MR_SOLVE_OK);
  }
  if (contact) {
    assert_true(mr_jac_begin_row(J) >= 0);
    assert_int_equal(mr_jac_add(J, N - 1, up), MR_SOLVE_OK);
  }
}

typedef struct rig {
  mr_jac J;
  mr_csr A;
  mr_solver *solver;
  double inv_mass[N], accel[3 * N], b[2 * N], x[2 * N];
} rig;

/* One evaluation: J at time t, A = J M⁻¹ Jᵀ, b = J M⁻¹ f for gravity (a
 * consistent right-hand side, as eq. 8's −J M⁻¹ F_a term is), the solve. */
static void evaluate(rig *r, const mr_solve_def *def, double t, int contact) {
  build(&r->J, t, contact);
  assert_int_equal(mr_csr_assemble(&r->A, &r->J, r->inv_mass), MR_SOLVE_OK);
  mr_jac_mul(&r->J, r->accel, r->b);
  memset(r->x, 0, sizeof r->x);
  mr_solve_result res;
  mr_solve_status st = mr_solver_solve(r->solver, def, &r->A, r->b, r->x, &res);
  assert_true(st == MR_SOLVE_OK || st == MR_SOLVE_DEPENDENT || st == MR_SOLVE_NOT_CONVERGED);
  assert_true(res.dependent >= 1); /* the link written twice */
  assert_true(isfinite(res.residual));
}

static void rig_init(rig *r) {
  memset(r, 0, sizeof *r);
  r->solver = mr_solver_create();
  assert_non_null(r->solver);
  for (int i = 0; i < N; i++) {
    r->inv_mass[i] = i == 0 ? 0.0 : 1.0 / (0.5 + 0.01 * i);
    r->accel[3 * i + 2] = i == 0 ? 0.0 : -9.81; /* gravity on the movable ones */
  }
}

static void rig_free(rig *r) {
  mr_solver_destroy(r->solver);
  mr_csr_free(&r->A);
  mr_jac_free(&r->J);
}

/* contact_every: the contact row comes and goes every that many
 * evaluations (0: always there). Returns the allocations counted over 200
 * evaluations after one warm-up evaluation at the largest size. */
static long allocations_when_warm(mr_solve_method method, int contact_every) {
  rig r;
  rig_init(&r);
  mr_solve_def def = mr_default_solve_def();
  def.method = method;
  def.max_iter = 50; /* the count matters here, not the convergence */
  evaluate(&r, &def, 0.0, 1);
  tt_alloc_count(0);
  for (int it = 1; it <= 200; it++)
    evaluate(&r, &def, 0.01 * it, contact_every ? (it / contact_every) % 2 : 1);
  const long allocations = tt_alloc_stop();
  rig_free(&r);
  return allocations;
}

static void every_method_allocates_nothing_once_warm(void **state) {
  (void)state;
  for (int m = 0; m < MR_SOLVE_METHOD_COUNT; m++) {
    long n = allocations_when_warm((mr_solve_method)m, 0);
    if (n != 0)
      fail_msg("%s: %ld allocations in 200 assemble+solve calls", mr_solve_method_name(m), n);
  }
}

/* Every object keeps its arrays at the largest size seen, so a system
 * whose pattern changes and shrinks (a contact lifting off) and grows back
 * to a size already seen allocates nothing either. */
static void no_method_allocates_when_a_contact_comes_and_goes(void **state) {
  (void)state;
  for (int m = 0; m < MR_SOLVE_METHOD_COUNT; m++) {
    long n = allocations_when_warm((mr_solve_method)m, 25);
    if (n != 0)
      fail_msg("%s: %ld allocations in 200 assemble+solve calls", mr_solve_method_name(m), n);
  }
}

/* With room reserved for the largest system, not even the first
 * evaluation allocates, under any method, while contacts come and go: what
 * a world needs to allocate nothing after it is made. */
static void reserving_room_makes_even_the_first_evaluation_allocation_free(void **state) {
  (void)state;
  const int rows = N + 20, entries = 2 * rows;
  for (int m = 0; m < MR_SOLVE_METHOD_COUNT; m++) {
    rig r;
    rig_init(&r);
    assert_int_equal(mr_jac_reserve(&r.J, rows, entries), MR_SOLVE_OK);
    assert_int_equal(mr_csr_reserve(&r.A, rows, N, entries), MR_SOLVE_OK);
    assert_int_equal(mr_solver_reserve(r.solver, rows), MR_SOLVE_OK);
    mr_solve_def def = mr_default_solve_def();
    def.method = (mr_solve_method)m;
    def.max_iter = 50;
    tt_alloc_count(0);
    for (int it = 0; it < 100; it++) evaluate(&r, &def, 0.01 * it, (it / 10) % 2);
    const long allocations = tt_alloc_stop();
    rig_free(&r);
    if (allocations != 0)
      fail_msg("%s: %ld allocations after reserving", mr_solve_method_name(m), allocations);
  }
}

static void reserving_refuses_negative_sizes(void **state) {
  (void)state;
  mr_jac J = { 0 };
  mr_csr A = { 0 };
  mr_solver *s = mr_solver_create();
  assert_int_equal(mr_jac_reserve(&J, -1, 0), MR_SOLVE_ERR_ARG);
  assert_int_equal(mr_csr_reserve(&A, 1, -1, 0), MR_SOLVE_ERR_ARG);
  assert_int_equal(mr_solver_reserve(s, -1), MR_SOLVE_ERR_ARG);
  assert_int_equal(mr_solver_reserve(NULL, 1), MR_SOLVE_ERR_ARG);
  mr_solver_destroy(s);
}

/* The counter itself works: a cold start allocates. */
static void a_cold_start_is_counted(void **state) {
  (void)state;
  rig r;
  tt_alloc_count(0);
  rig_init(&r);
  mr_solve_def def = mr_default_solve_def();
  def.method = MR_SOLVE_EIGEN;
  evaluate(&r, &def, 0.0, 1);
  const long allocations = tt_alloc_stop();
  rig_free(&r);
  assert_true(allocations > 3);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_cold_start_is_counted),
    cmocka_unit_test(every_method_allocates_nothing_once_warm),
    cmocka_unit_test(no_method_allocates_when_a_contact_comes_and_goes),
    cmocka_unit_test(reserving_room_makes_even_the_first_evaluation_allocation_free),
    cmocka_unit_test(reserving_refuses_negative_sizes),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

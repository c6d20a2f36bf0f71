/* Friction held inside its cone (friction.c): after the rounds, whose
 * second half holds the normals still, every contact's friction is cut
 * back to μ times the normal that all the friction leaves. The step reaches
 * it only where contacts wedge (two puppets pressed together), so it is
 * tested here through the library's internal header, on hand-made normal
 * responses N worked through by hand. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <string.h>

#include "internal.h"

/* N for two contacts: column 2j+k is contact j's tangent k. */
static void two(double N[2][4], double n0_by_f1y, double n1_by_f0x) {
  memset(N, 0, 2 * 4 * sizeof(double));
  N[0][3] = n0_by_f1y;
  N[1][0] = n1_by_f0x;
}

static void assert_near(double got, double want) {
  assert_true(fabs(got - want) <= 1e-12);
}

/* Each contact's friction lifts the other (the wedge): cutting one raises
 * the other's normal, so the second cut is smaller than the first would
 * have asked. By hand: 2 → μ·1 = 0.5, which lifts contact 1 by
 * 0.2·1.5 to 1.3; 2 → 0.65, which lifts contact 0 by 0.2·1.35 to 1.27. */
static void a_wedge_is_cut_back_to_the_normals_it_leaves(void **state) {
  (void)state;
  double N[2][4], f[4] = { 2.0, 0.0, 0.0, 2.0 }, n[2] = { 1.0, 1.0 };
  const double mu[2] = { 0.5, 0.5 };
  two(N, -0.2, -0.2);
  mr_friction_hold_cone(2, f, n, mu, &N[0][0], 1e-12);
  assert_near(f[0], 0.5);
  assert_true(f[1] == 0.0 && f[2] == 0.0);
  assert_near(f[3], 0.65);
  assert_near(n[0], 1.27);
  assert_near(n[1], 1.3);
}

/* Friction within its cone everywhere is left alone, bit for bit, and so
 * are the normals; μ differs between the contacts, and one sits exactly
 * on its limit. */
static void friction_within_the_cone_is_kept(void **state) {
  (void)state;
  double N[2][4], f[4] = { 0.3, -0.4, 0.1, 0.0 }, n[2] = { 1.0, 0.5 };
  const double mu[2] = { 0.5, 0.25 };
  two(N, 0.7, -0.9);
  const double f_in[4] = { 0.3, -0.4, 0.1, 0.0 };
  mr_friction_hold_cone(2, f, n, mu, &N[0][0], 1e-12);
  assert_memory_equal(f, f_in, sizeof f);
  assert_true(n[0] == 1.0 && n[1] == 0.5);
}

/* A contact the others lift off (its normal below zero) keeps no
 * friction; the direction of a cut contact is its own. */
static void a_lifted_contact_keeps_no_friction(void **state) {
  (void)state;
  double N[2][4], f[4] = { 0.3, 0.4, 0.0, 1.0 }, n[2] = { -0.1, 4.0 };
  const double mu[2] = { 0.8, 0.1 };
  two(N, 0.0, 0.0);
  mr_friction_hold_cone(2, f, n, mu, &N[0][0], 1e-12);
  assert_true(f[0] == 0.0 && f[1] == 0.0);
  assert_near(f[2], 0.0);
  assert_near(f[3], 0.4);
  /* No friction on a lifted contact, with no tolerance: nothing to cut,
   * and no 0/0. */
  double g[2] = { 0.0, 0.0 }, m[1] = { -1.0 };
  mr_friction_hold_cone(1, g, m, mu, &N[0][0], 0.0);
  assert_true(g[0] == 0.0 && g[1] == 0.0);
}

/* Cutting a later contact presses an earlier one less, which then passes
 * its own limit: it takes a second sweep. By hand: contact 1, 2 → 0.5,
 * lowers n0 by 0.5·1.5 to 0.35; contact 0, 0.5 → 0.175. */
static void a_cut_that_unloads_an_earlier_contact_is_followed(void **state) {
  (void)state;
  double N[2][4], f[4] = { 0.5, 0.0, 0.0, 2.0 }, n[2] = { 1.1, 1.0 };
  const double mu[2] = { 0.5, 0.5 };
  two(N, 0.5, 0.0);
  mr_friction_hold_cone(2, f, n, mu, &N[0][0], 1e-12);
  assert_near(f[3], 0.5);
  assert_near(n[0], 0.35);
  assert_near(f[0], 0.175);
  assert_near(n[1], 1.0);
}

/* The tolerance: friction over by less than it stands, and by more is
 * cut. */
static void friction_over_by_less_than_the_tolerance_stands(void **state) {
  (void)state;
  double N[1][2] = { { 0.0, 0.0 } }, f[2] = { 0.0, 0.5005 }, n[1] = { 1.0 };
  const double mu[1] = { 0.5 };
  mr_friction_hold_cone(1, f, n, mu, &N[0][0], 1e-3);
  assert_true(f[1] == 0.5005);
  mr_friction_hold_cone(1, f, n, mu, &N[0][0], 1e-4);
  assert_near(f[1], 0.5);
  f[1] = 0.5015; /* over by more than it */
  mr_friction_hold_cone(1, f, n, mu, &N[0][0], 1e-3);
  assert_near(f[1], 0.5);
}

/* The rounds themselves (mr_friction_rounds), on two spheres wedged
 * between puppets, sliding at 38 and 43 m/s (the numbers of a step that
 * reset a world): each one's friction presses both contacts harder, by
 * about 2 per unit of friction, so with μ = 0.3 sliding at μN raised N at
 * every round, to 1.8e32 from 1.6e5. No contact's limit may rise past four
 * times the largest multiplier before friction. */
static void friction_pressing_contacts_harder_does_not_run_away(void **state) {
  (void)state;
  struct mr_fric_point pt[2];
  memset(pt, 0, sizeof pt);
  const double n0[2] = { 1.6e5, 1.46e5 }, inv[2] = { 18.2, 14.0 };
  const double vt[2][2] = { { 13.5, -35.3 }, { -41.1, -13.3 } };
  const double at[2][2] = { { -1.27e4, -1.99e5 }, { -1.9e5, -1.67e5 } };
  for (int i = 0; i < 2; i++) {
    pt[i].row = pt[i].contact = i;
    pt[i].scale = n0[0];
    pt[i].n = pt[i].n0 = n0[i];
    pt[i].mu = 0.3;
    pt[i].inv = inv[i];
    for (int k = 0; k < 2; k++) {
      pt[i].vt[k] = vt[i][k];
      pt[i].at[k] = pt[i].at0[k] = at[i][k];
    }
    pt[i].drive = hypot(at[i][0], at[i][1]);
  }
  const double W[4][4] = {
    { 0.237, 0.612, 0, 0 }, { 0.612, 5.28, 0, 0 }, { 0, 0, 5.89, 1.78 }, { 0, 0, 1.78, 0.593 }
  };
  const double N[2][4] = { { -1.19, 2.08, 2.66, 0.194 }, { -1.55, 2.09, 2.46, 0.525 } };
  double scratch[128];
  mr_friction_rounds(pt, 2, 1.28e-5, &W[0][0], &N[0][0], 1e-9 * n0[0], scratch);
  for (int i = 0; i < 2; i++) {
    const double f = hypot(pt[i].f[0], pt[i].f[1]);
    assert_true(isfinite(f));
    assert_true(f <= 0.3 * 4.0 * n0[0] * (1 + 1e-12));
    assert_true(f > 0.3 * n0[i]); /* it still slides at least at μ N0 */
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_wedge_is_cut_back_to_the_normals_it_leaves),
    cmocka_unit_test(friction_within_the_cone_is_kept),
    cmocka_unit_test(a_lifted_contact_keeps_no_friction),
    cmocka_unit_test(a_cut_that_unloads_an_earlier_contact_is_followed),
    cmocka_unit_test(friction_over_by_less_than_the_tolerance_stands),
    cmocka_unit_test(friction_pressing_contacts_harder_does_not_run_away),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

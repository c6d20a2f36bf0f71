/* Collision impulses through the velocity-level system (§5.3, eq. 9):
 *
 *   J M⁻¹ Jᵀ λ = −J M⁻¹ L_a + Δ,   q̇⁺ = q̇⁻ + M⁻¹ (L_a + Jᵀ λ)
 *
 * with L_a the applied momenta (the friction impulses below) and Δ the
 * change of J q̇ each row asks for. A constraint row asks for none: the
 * impulse moves the puppet as a whole, its joints hold (§5.1: velocities of
 * single particles must not simply be changed), and the rate Ċ that eq. 8's
 * correction (−K_s C − K_d Ċ) is building up is left alone; zeroing it at
 * every contact stalled that correction. Each colliding contact row (eq.
 * 13a, χ̇ < 0) asks for χ̇⁺ = −e χ̇⁻ (restitution e), or 0 for impacts
 * slower than rest_speed, which then rest. Contacts push and never pull: a
 * negative multiplier releases its contact, a contact the impulse drives
 * inwards is added, and the system is solved again. */
#include "internal.h"

#include <math.h>
#include <string.h>

/* Normal velocities χ̇⁻ before the impulse; the approaching contacts start
 * in the system, except a taut string lengthening slower than K_d times
 * its hold (mr_taut_hold). Its resting row of eq. 8 (eq. 13b) holds it,
 * as it holds a contact that touches at rest: the row's −K_d Ċ stops a
 * rate Ċ within about Ċ/K_d, inside the hold, and an impulse would change
 * the state only to cost the next step its first evaluation (a string
 * under load lengthens a little at nearly every step). The bound reads
 * no step size, so that which strings take an impulse does not change as
 * the step shrinks: bound to the step, the puppet's 1 ms reference run
 * (marionette-bench --quick) moved its hand 6.8e-4 m when its step was
 * halved, against 2.6e-4 m before the hold and 2.7e-4 m with this bound.
 * Returns whether any contact approaches; *collided when one is faster
 * than rest_speed. */
static int approach_rates(mr_world *w, const double *x, const double *v, int *collided) {
  int any = 0;
  for (int c = 0; c < w->contacts.n; c++) {
    const mr_contact *ct = &w->contacts.c[c];
    const double pre = mr_contact_rate(w, ct, x, v);
    const double hold = ct->kind == MR_CONTACT_STRING ? mr_taut_hold(w, ct->a) : 0.0;
    w->contact_pre[c] = pre;
    w->contact_active[c] = pre < 0 && !(-pre <= w->def.kd * hold);
    any |= w->contact_active[c];
    if (w->contact_pre[c] < -w->def.rest_speed) *collided = 1;
  }
  return any;
}

/* Coulomb friction at impact as applied momentum L_a, on the relative
 * tangential motion of the contact's two sides (a particle and a plane, or
 * two spheres): at most μ times the normal impulse (1 + e)·(−χ̇⁻)·m_eff the
 * contact would take on its own, and no more than stops the sliding. Also
 * M⁻¹ L_a. */
static void impact_friction(mr_world *w, const double *x, const double *v) {
  double *la = w->scratch.impact_momentum, *dv = w->scratch.impact_dv;
  int n3 = 3 * w->n;
  memset(la, 0, (size_t)n3 * sizeof *la);
  for (int c = 0; c < w->contacts.n; c++) {
    const mr_contact *ct = &w->contacts.c[c];
    const double pre = w->contact_pre[c];
    if (ct->friction <= 0 || !(pre < -w->def.rest_speed)) continue;
    double vt[3];
    double inv = mr_contact_slip(w, ct, x, v, vt);
    double speed = sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
    if (!(speed > 0) || !(inv > 0)) continue;
    double pn = (1.0 + ct->restitution) * -pre / inv;
    double mag = fmin(ct->friction * pn, speed / inv);
    mr_contact_spread(w, ct, vt, -mag / speed, la);
  }
  for (int i = 0; i < n3; i++) dv[i] = la[i] * w->inv_mass[i / 3];
}

/* The right-hand side of eq. 9 for the rows built: −J M⁻¹ L_a plus the
 * change of J q̇ each row asks for; with `elastic` 0, every contact rests
 * (χ̇⁺ = 0). */
static void rhs_eq9(mr_world *w, int rows, int elastic) {
  mr_jac_mul(&w->J, w->scratch.impact_dv, w->row_jv);
  for (int r = 0; r < rows; r++) {
    int c = w->row_contact[r];
    double target = 0.0;
    if (elastic && c >= 0 && w->contact_pre[c] < -w->def.rest_speed)
      target = -w->contacts.c[c].restitution * w->contact_pre[c];
    w->rhs[r] = (c >= 0 ? target - w->row_cdot[r] : 0.0) - w->row_jv[r];
  }
}

/* After a trial impulse, a contact with a negative multiplier leaves the
 * system; if none does, a contact the impulse drives inwards joins it.
 * Returns whether the set changed. */
static int update_contact_set(mr_world *w, int rows, const double *x) {
  int changed = 0;
  for (int r = 0; r < rows; r++) {
    int c = w->row_contact[r];
    if (c >= 0 && w->lambda[r] < 0) {
      w->contact_active[c] = 0;
      changed = 1;
    }
  }
  if (changed) return 1;
  for (int c = 0; c < w->contacts.n; c++) {
    if (w->contact_active[c]) continue;
    if (mr_contact_rate(w, &w->contacts.c[c], x, w->scratch.v_try) < -1e-9) {
      w->contact_active[c] = 1;
      changed = 1;
    }
  }
  return changed;
}

/* Solves eq. 9 until the contact set settles; the velocities q̇⁺ are left in
 * scratch.v_try. Returns the rows of the last solve, or −1. */
static int solve_eq9(mr_world *w, double t, const double *x, const double *v, int elastic) {
  int n3 = 3 * w->n, rows = 0;
  double *vt = w->scratch.v_try;
  const double *la = w->scratch.impact_momentum;
  for (int round = 0; round <= w->contacts.n + 1; round++) {
    rows = mr_rows_build(w, t, x, v);
    if (rows < 0) return -1;
    if (rows == 0) {
      for (int i = 0; i < n3; i++) vt[i] = v[i] + w->scratch.impact_dv[i];
      return 0;
    }
    rhs_eq9(w, rows, elastic);
    if (mr_solve_rows(w, 1) != 0) return -1;
    mr_jac_tmul(&w->J, w->lambda, vt);
    for (int i = 0; i < n3; i++) vt[i] = v[i] + (la[i] + vt[i]) * w->inv_mass[i / 3];
    if (!update_contact_set(w, rows, x)) return rows;
  }
  return rows;
}

/* Whether any contact bounces (eq. 9's restitution targets): without one
 * every contact rests, the least-energy impulse, and there is nothing for
 * gains_energy to check (puppet.yaml's taut strings touch and take an
 * impulse at nearly every step, slower than rest_speed). */
static int bounces(const mr_world *w) {
  for (int c = 0; c < w->contacts.n; c++)
    if (w->contact_pre[c] < -w->def.rest_speed && w->contacts.c[c].restitution > 0) return 1;
  return 0;
}

static double kinetic_energy(const mr_world *w, const double *v) {
  double e = 0.0;
  for (int i = 0; i < w->n; i++)
    if (w->inv_mass[i] > 0)
      e += (v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]) /
           w->inv_mass[i];
  return 0.5 * e;
}

/* Whether the impulse of the last solve (its `rows` rows, λ) added kinetic
 * energy that nothing did work for. With q̇⁺ = q̇⁻ + M⁻¹ Jᵀ λ,
 *
 *   ΔT = ½ (q̇⁺ + q̇⁻)ᵀ Jᵀ λ = Σ_r λ_r (½ (χ̇⁺_r + χ̇⁻_r) − k_r),
 *
 * k_r = χ̇_r − J_r q̇ the part of a row's rate J does not see (a frame
 * moving a taut string's end, a link to a moving frame). −λ_r k_r is the
 * work of the hand, which may add energy; so may a constraint row, which
 * keeps its rate (χ̇⁺ = χ̇⁻, Δ = 0). A contact that rests or bounces
 * (χ̇⁺ = −e χ̇⁻, 0 ≤ e ≤ 1) takes energy out, and so does the whole set
 * when it rests: the inelastic impulse is the least-energy one that the
 * contacts allow. Not so Newton's law of restitution on several contacts
 * at once: a ball between a taut string and a rod striking it 3° off the
 * string's line has two sphere contacts with the rod and the string,
 * nearly dependent, whose restitution targets no impulse meets, and the
 * solve met them with a kinetic energy 57 times what there was (75 J to
 * 4 244 J: the ball left at 253 m/s, and the world reset as diverged). */
static int gains_energy(mr_world *w, int rows, const double *v, double before, double *bound) {
  mr_jac_mul(&w->J, v, w->row_jv);
  double allowed = 0.0;
  for (int r = 0; r < rows; r++) {
    const double seen = w->row_jv[r], k = w->row_cdot[r] - seen;
    allowed -= w->lambda[r] * k;
    if (w->row_contact[r] < 0) allowed += w->lambda[r] * seen;
  }
  *bound = before + allowed + 1e-6 * (before + fabs(allowed));
  const double after = kinetic_energy(w, w->scratch.v_try);
  return !(after <= *bound);
}

/* The resting impulse's q̇⁺ (scratch.v_try) moved towards the bouncing
 * one's, q̇ = q̇_r + α (q̇_b − q̇_r), with the largest α ≤ 1 whose kinetic
 * energy is within `bound`. Both keep every contact from closing and
 * every joint's rate, and so does any such mixture; T(α) is a convex
 * quadratic. `bounced` is over the bound. */
static void keep_bounce(mr_world *w, const double *bounced, double bound) {
  double *v = w->scratch.v_try, a = 0.0, b = 0.0;
  for (int i = 0; i < 3 * w->n; i++) {
    const double im = w->inv_mass[i / 3];
    if (!(im > 0)) continue;
    const double d = bounced[i] - v[i];
    a += 0.5 * d * d / im;
    b += v[i] * d / im;
  }
  /* T(1) is the bounce's, over the bound, so the larger root is below 1.
   * With the resting impulse over the bound too it is where a move
   * towards the bounce brings T down to it, if any; else α = 0. */
  const double c = kinetic_energy(w, v) - bound;
  const double alpha = a > 0 ? (-b + sqrt(b * b - 4.0 * a * c)) / (2.0 * a) : 0.0;
  if (!(alpha > 0)) return;
  for (int i = 0; i < 3 * w->n; i++)
    if (w->inv_mass[i / 3] > 0) v[i] += alpha * (bounced[i] - v[i]);
}

int mr_impulses_apply(mr_world *w, double t, int *collided) {
  *collided = 0;
  if (w->contacts.n == 0) return 0;
  mr_taut_set_time(w, t);
  if (!approach_rates(w, w->x, w->v, collided)) return 0;
  impact_friction(w, w->x, w->v);
  const int elastic = bounces(w);
  const double before = elastic ? kinetic_energy(w, w->v) : 0.0;
  int rows = solve_eq9(w, t, w->x, w->v, 1);
  double bound;
  if (elastic && rows > 0 && gains_energy(w, rows, w->v, before, &bound)) {
    /* Restitution that creates energy: every contact rests, and as much
     * of the bounce as the energy allows is given back. */
    double *bounced = w->scratch.vs; /* free between steps */
    memcpy(bounced, w->scratch.v_try, (size_t)(3 * w->n) * sizeof *bounced);
    int again = 0;
    approach_rates(w, w->x, w->v, &again);
    rows = solve_eq9(w, t, w->x, w->v, 0);
    if (rows >= 0) keep_bounce(w, bounced, bound);
  }
  if (rows < 0) return -1;
  memcpy(w->v, w->scratch.v_try, (size_t)(3 * w->n) * sizeof *w->v);
  if (*collided) w->stats.collisions++;
  return 0;
}

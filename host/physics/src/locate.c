/* Locating a contact in time (§4.5, §5.4): a contact apart at the start of
 * a step and gone through within it (a part meeting the floor or another
 * part, a slack string snapping taut) cuts the step to the moment it is
 * reached, so that nothing goes deeper than the slop.
 *
 * The moment is the root of f(τ) = g(τ) − aim, g the smallest swept gap
 * of the offending contacts over [t, t + τ] (collide.c), aim = −slop/2,
 * accepted within |f| ≤ slop/2. Each true value of f costs an integration
 * from the start state to τ, the price of a whole step. The step already
 * integrated gives a cheap model of it instead: each particle on the cubic
 * Hermite through (x₀, v₀) and the latest end (x_e, v_e) at τ_e,
 *
 *   x(s) = (2s³ − 3s² + 1) x₀ + (s³ − 2s² + s) τ_e v₀ + (3s² − 2s³) x_e
 *          + (s³ − s²) τ_e v_e,   s = τ/τ_e,
 *
 * the path the swept tests already take between the step's ends, RK4's
 * own to high order. Its swept gap over [0, τ] is that of the Hermite
 * through (x₀, v₀) and (x(s), ẋ(s)) (a cubic is its ends), so where it
 * reaches the aim is found with no evaluation at all, and one integration
 * there is usually within the tolerance. Every trial still keeps a bracket
 * of true values, [lo, hi] with f(lo) > 0 > f(hi), and where the model
 * misses twice the search goes on by regula falsi (Illinois) in it: the
 * contact is never skipped. */
#include "internal.h"

#include <math.h>

/* How many trials a location may take, and how many of them may come
 * from the model before the bracket alone leads. */
#define MAX_TRIALS   24
#define MODEL_TRIALS 2

/* The smallest swept gap of the offending contacts over the step from the
 * start state to (x1, v1) at h. */
static double offenders_gap(mr_world *w, const double *x1, const double *v1, double h) {
  const mr_sweep sw = { w->scratch.x0, w->scratch.v0, x1, v1, h };
  double g = INFINITY;
  for (int i = 0; i < w->probe.n; i++)
    if (w->probe_valid[i]) {
      double c = mr_contact_swept_gap(w, &w->probe.c[i], &sw, 1);
      if (c < g || c != c) g = c;
    }
  return g;
}

/* Contacts touching at the start are in the force system (eq. 13b), which
 * pushes them back out; only contacts that were apart can be located in
 * time. Rolling back for a touching one would cut the step to nothing.
 * Touching and clearly separating is apart too (eval.c leaves such a
 * contact out of the force system): a part that lifts off and lands again
 * within the step has met a new contact, found at its own time.
 *
 * Not so a taut string touching at the start: its row is one of the
 * step's contacts (held during it), taken up at every stage that sees
 * the string taut. What it goes over within the step is an over-length,
 * which the step rule holds as it holds a deviation (step.c, end_error)
 * and the projection after the step takes back, removing the lengthening
 * speed as an inelastic snap's impulse would (string_correction.c).
 * Locating its return cost a trial integration for each bracket: the
 * string leaves its rest length at the start, so the swept gap sits at
 * that start gap, a hair over the tolerance, until it jumps past it (on
 * the Fig. 10 track, 306 of 740 locations, 6.5 integrations each). Only a
 * string slack by more than the slop at the start snaps, and is located.
 *
 * Marks the offenders in probe_valid (its own flags: every trial
 * integration rewrites contact_active) and returns the smallest start gap
 * of them, or INFINITY if there is none. */
static double mark_offenders(mr_world *w) {
  const double slop = w->def.contact_slop, separating = 0.1 * w->def.rest_speed;
  const double *x0 = w->scratch.x0, *v0 = w->scratch.v0;
  double g0 = INFINITY;
  for (int i = 0; i < w->probe.n; i++) {
    const mr_contact *ct = &w->probe.c[i];
    double c0 = mr_contact_gap(w, ct, x0);
    w->probe_valid[i] = c0 > slop || (ct->kind != MR_CONTACT_STRING && c0 > -0.5 * slop &&
                                      mr_contact_rate(w, ct, x0, v0) > separating);
    if (w->probe_valid[i] && c0 < g0) g0 = c0;
  }
  return g0;
}

/* f on the model: the state at tau on the Hermite through the start and the
 * latest end (w->x1, w->v1 at span) goes into scratch.xs, vs (free between
 * integrations), and the offenders' swept gap over [0, tau] to it, less
 * the aim. */
static double model_f(mr_world *w, double span, double tau, double aim) {
  const double s = tau / span, s2 = s * s, s3 = s2 * s;
  const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0, h10 = (s3 - 2.0 * s2 + s) * span;
  const double h01 = 3.0 * s2 - 2.0 * s3, h11 = (s3 - s2) * span;
  const double d00 = (6.0 * s2 - 6.0 * s) / span, d10 = 3.0 * s2 - 4.0 * s + 1.0;
  const double d11 = 3.0 * s2 - 2.0 * s;
  const double *x0 = w->scratch.x0, *v0 = w->scratch.v0, *x1 = w->x1, *v1 = w->v1;
  double *x = w->scratch.xs, *v = w->scratch.vs;
  for (int i = 0; i < 3 * w->n; i++) {
    x[i] = h00 * x0[i] + h10 * v0[i] + h01 * x1[i] + h11 * v1[i];
    v[i] = d00 * (x0[i] - x1[i]) + d10 * v0[i] + d11 * v1[i];
  }
  return offenders_gap(w, x, v, tau) - aim;
}

/* Where f on the model crosses zero within (lo, hi), to a quarter of the
 * tolerance, by Illinois on the model (no evaluation); NaN when the model
 * does not cross there. Past the latest end the model is the same cubic
 * carried on, trusted up to twice its span. */
static double model_root(mr_world *w, double span, double lo, double hi, double aim) {
  const double tol = 0.125 * w->def.contact_slop;
  if (hi > 2.0 * span) hi = 2.0 * span;
  if (!(hi > lo)) return NAN;
  double a = lo, fa = model_f(w, span, lo, aim), b = hi, fb = model_f(w, span, hi, aim);
  if (!(fa > 0 && fb < 0)) return NAN;
  int side = 0;
  for (int it = 0; it < 40; it++) {
    double m = b - fb * (b - a) / (fb - fa);
    if (!(m > a && m < b)) m = 0.5 * (a + b);
    double fm = model_f(w, span, m, aim);
    if (fabs(fm) <= tol) return m;
    if (fm < 0) {
      b = m, fb = fm;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else if (fm > 0) {
      a = m, fa = fm;
      if (side == 1) fb *= 0.5;
      side = 1;
    } else {
      return NAN;
    }
  }
  return NAN;
}

/* The fastest the two sides of any offender move apart or together in
 * the state (x, v), m/s, its normal and sliding parts both (two spheres
 * passing side by side close their swept gap by sliding); NaN if any is. */
static double top_rate(mr_world *w, const double *x, const double *v) {
  double top = 0.0;
  for (int i = 0; i < w->probe.n; i++)
    if (w->probe_valid[i]) {
      const mr_contact *c = &w->probe.c[i];
      double slide[3], r = mr_contact_rate(w, c, x, v);
      mr_contact_slip(w, c, x, v, slide);
      r = r * r + slide[0] * slide[0] + slide[1] * slide[1] + slide[2] * slide[2];
      if (r > top || r != r) top = r;
    }
  return sqrt(top);
}

/* The bracket's two true values differ by more than its width could
 * close at eight times `closing`, the fastest rate seen at the start and
 * at the latest trial's end (room for the speed gained between): f jumps
 * there rather than crosses. It does when an offender is a contact the
 * force system also holds (a string touching and going slack at the
 * start, taut again within the step): a trial whose middle stages see it
 * taut includes its row, and one a hair shorter does not, and no trial
 * lands within the tolerance. lo is then the last moment short of it;
 * taken too early it costs a step, never the contact (the next step
 * locates it again). */
static int jumps(double lo, double hi, double f_lo, double f_hi, double closing) {
  return lo > 0 && f_lo - f_hi > 8.0 * closing * (hi - lo);
}

/* A contact went through during [t, t + h], w->x1, w->v1 the state at its
 * end: leaves the state at the located t + h* there and returns h* (h when
 * no offender was apart at the start). *err on a failed integration. */
double mr_locate_contact(mr_world *w, double t, double h, int *err) {
  const double slop = w->def.contact_slop, aim = -0.5 * slop;
  const double g0 = mark_offenders(w);
  if (g0 == INFINITY) return h;
  w->stats.located++;
  const double rate0 = top_rate(w, w->scratch.x0, w->scratch.v0);
  double lo = 0.0, flo = g0 - aim, hi = h, fhi = offenders_gap(w, w->x1, w->v1, h) - aim;
  double true_lo = flo, true_hi = fhi, end = h; /* w->x1 is the state at end */
  int side = 0;
  for (int it = 0; it < MAX_TRIALS; it++) {
    double hm = it < MODEL_TRIALS ? model_root(w, end, lo, hi, aim) : NAN;
    if (!(hm > lo && hm < hi)) hm = hi - fhi * (hi - lo) / (fhi - flo);
    if (!(hm > lo && hm < hi)) hm = 0.5 * (lo + hi);
    w->stats.location_integrations++;
    if (mr_integrate(w, t, hm, w->scratch.x0, w->scratch.v0, w->x1, w->v1, NULL) != 0) {
      *err = 1;
      return h;
    }
    end = hm;
    double fm = offenders_gap(w, w->x1, w->v1, hm) - aim;
    if (fabs(fm) <= 0.5 * slop) return hm;
    if (fm < 0) {
      hi = hm, fhi = true_hi = fm;
      if (side == -1) flo *= 0.5;
      side = -1;
    } else {
      lo = hm, flo = true_lo = fm;
      if (side == 1) fhi *= 0.5;
      side = 1;
    }
    if (jumps(lo, hi, true_lo, true_hi, fmax(rate0, top_rate(w, w->x1, w->v1)))) break;
  }
  /* Not within the tolerance: stop just before the contact. */
  double hs = lo > 0 ? lo : hi;
  if (hs != end) {
    w->stats.location_integrations++;
    if (mr_integrate(w, t, hs, w->scratch.x0, w->scratch.v0, w->x1, w->v1, NULL) != 0) *err = 1;
  }
  return hs;
}

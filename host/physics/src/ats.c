/* §4.5: the adaptive time step rule, a pure function of the last step's
 * size and its largest relative constraint deviation.
 *
 *   Δt_new = Δt_old · (threshold / error)^¼       (RK4 is O(h⁴))
 *
 * Two thresholds (§7: 0.01 % and 1 %) make a dead band: below `low` the step
 * grows towards low's error, above `high` the step is rejected and retried
 * shorter towards high's error (a milder cut than aiming at `low`, which is
 * what §7 says the upper threshold is for), between them Δt is kept.
 *
 * A rejected step is retried at most half as long: the error measured is
 * the state's deviation, which includes drift left by earlier steps, so an
 * error just over `high` is often not cut by a shorter step at all, and a
 * fourth root of a ratio near 1 would creep down through dozens of
 * retries. Halving reaches the lower bound from the upper in three. */
#include "mr_physics.h"

#include <math.h>

/* x^¼ as two square roots: IEEE 754 requires sqrt to be correctly
 * rounded, so this gives the same bits under every libm, compiler and
 * optimisation level; pow carries no such promise and would put the pinned
 * state hashes at the mercy of the C library. */
static double fourth_root(double x) {
  return sqrt(sqrt(x));
}

static double clamp(double v, double lo, double hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

mr_ats_decision mr_ats_next(const mr_ats_params *p, double dt_old, double error) {
  mr_ats_decision d = { 1, dt_old };
  if (!p) return d;
  if (!(error == error) || error > p->high) {
    /* NaN counts as too large. At the lower bound there is nothing shorter
     * to retry with: the step stands (divergence is judged elsewhere). */
    if (dt_old <= p->dt_min) {
      d.dt_next = p->dt_min;
      return d;
    }
    d.accept = 0;
    d.dt_next = (error == error) ? dt_old * fmin(fourth_root(p->high / error), 0.5) : p->dt_min;
  } else if (error < p->low) {
    d.dt_next = error > 0 ? dt_old * fourth_root(p->low / error) : p->dt_max;
  }
  d.dt_next = clamp(d.dt_next, p->dt_min, p->dt_max);
  return d;
}

/* The local error estimate's own rule, beside the §4.5 one: the estimate
 * measures what each step adds to the trajectory's error, so it is steered
 * towards `low` from both sides (the usual controller of embedded
 * Runge–Kutta pairs, with its safety factor 0.9 and a step changed at most
 * fivefold either way), where the deviation's dead band would keep
 * any error up to `high`: a step whose estimate is 99 times the aim would
 * be kept, and its errors piled up. The estimate is that of the embedded
 * third-order solution, O(h⁴), hence the fourth root. */
double mr_ats_aim(const mr_ats_params *p, double dt_old, double estimate) {
  if (!p) return dt_old;
  double f = 0.2; /* NaN: cut hardest */
  if (estimate == estimate) f = estimate > 0 ? 0.9 * fourth_root(p->low / estimate) : 5.0;
  return clamp(dt_old * clamp(f, 0.2, 5.0), p->dt_min, p->dt_max);
}

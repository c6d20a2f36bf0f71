/* The One Euro filter (Casiez, Roussel and Vogel, "1€ Filter: A Simple
 * Speed-based Low-pass Filter for Noisy Input in Interactive Systems",
 * CHI 2012): an exponential smoother whose cutoff rises with the speed of
 * the signal, so a hand held still is steady and a fast move lags little.
 *
 *   α(f_c, T) = 1 / (1 + τ/T),  τ = 1/(2π f_c)       (smoothing factor)
 *   ẋ̂_i = α(d_cutoff, T) (x_i − x̂_{i−1})/T + (1 − α) ẋ̂_{i−1}
 *   f_c = min_cutoff + β |ẋ̂_i|
 *   x̂_i = α(f_c, T) x_i + (1 − α) x̂_{i−1}
 */
#include "mr_control.h"

#include <math.h>

static double alpha(double cutoff, double dt) {
  const double tau = 1.0 / (2.0 * 3.14159265358979323846 * cutoff);
  return 1.0 / (1.0 + tau / dt);
}

void mr_one_euro_init(mr_one_euro *f, double min_cutoff, double beta, double d_cutoff) {
  f->min_cutoff = min_cutoff;
  f->beta = beta;
  f->d_cutoff = d_cutoff;
  f->x = f->dx = f->t = 0.0;
  f->started = false;
}

double mr_one_euro_filter(mr_one_euro *f, double x, double t) {
  if (!f->started || !(t > f->t)) {
    /* The first sample, or a repeat at the same time: nothing to smooth
     * against, so the output starts (or stays) at the input. */
    if (!f->started) {
      f->x = x;
      f->dx = 0.0;
    }
    f->t = t;
    f->started = true;
    return f->x;
  }
  const double dt = t - f->t;
  const double a_d = alpha(f->d_cutoff, dt);
  f->dx = a_d * (x - f->x) / dt + (1.0 - a_d) * f->dx;
  const double a = alpha(f->min_cutoff + f->beta * fabs(f->dx), dt);
  f->x = a * x + (1.0 - a) * f->x;
  f->t = t;
  return f->x;
}

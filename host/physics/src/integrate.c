/* Integrators for q̇ = v, v̇ = a(t, q, v). RK4 is the default (§4.2: its
 * O(h⁴) error is what the ATS rule's fourth root assumes); explicit Euler,
 * semi-implicit Euler and midpoint are here to show what accuracy costs. */
#include "internal.h"

#include <string.h>

static void axpy(int n, double *out, const double *x, double h, const double *y) {
  for (int i = 0; i < n; i++) out[i] = x[i] + h * y[i];
}

int mr_integrate(mr_world *w, double t, double h, const double *x0, const double *v0, double *x1,
                 double *v1) {
  int n3 = 3 * w->n;
  size_t bytes = (size_t)n3 * sizeof(double);
  double *xs = w->scratch.xs, *vs = w->scratch.vs;
  double *k = w->scratch.k; /* kv1 ka1 kv2 ka2 kv3 ka3 kv4 ka4 */
  double *kv1 = k, *ka1 = k + n3, *kv2 = k + 2 * n3, *ka2 = k + 3 * n3;
  double *kv3 = k + 4 * n3, *ka3 = k + 5 * n3, *kv4 = k + 6 * n3, *ka4 = k + 7 * n3;
  memcpy(kv1, v0, bytes);
  memcpy(xs, x0, bytes);
  if (mr_eval(w, t, h, xs, kv1, ka1) != 0) return -1;
  switch (w->def.integrator) {
  case MR_INTEGRATOR_EULER:
    axpy(n3, x1, xs, h, kv1);
    axpy(n3, v1, kv1, h, ka1);
    break;
  case MR_INTEGRATOR_SEMI_IMPLICIT_EULER:
    axpy(n3, v1, kv1, h, ka1);
    axpy(n3, x1, xs, h, v1);
    break;
  case MR_INTEGRATOR_MIDPOINT:
    axpy(n3, vs, kv1, 0.5 * h, ka1);
    axpy(n3, x1, xs, 0.5 * h, kv1);
    if (mr_eval(w, t + 0.5 * h, h, x1, vs, ka2) != 0) return -1;
    axpy(n3, x1, xs, h, vs);
    axpy(n3, v1, kv1, h, ka2);
    break;
  case MR_INTEGRATOR_RK4:
  default: {
    double *xa = x1; /* stage positions; x1 is written last */
    axpy(n3, xa, xs, 0.5 * h, kv1);
    axpy(n3, kv2, kv1, 0.5 * h, ka1);
    if (mr_eval(w, t + 0.5 * h, h, xa, kv2, ka2) != 0) return -1;
    axpy(n3, xa, xs, 0.5 * h, kv2);
    axpy(n3, kv3, kv1, 0.5 * h, ka2);
    if (mr_eval(w, t + 0.5 * h, h, xa, kv3, ka3) != 0) return -1;
    axpy(n3, xa, xs, h, kv3);
    axpy(n3, kv4, kv1, h, ka3);
    if (mr_eval(w, t + h, h, xa, kv4, ka4) != 0) return -1;
    const double h6 = h / 6.0;
    for (int i = 0; i < n3; i++) {
      x1[i] = xs[i] + h6 * (kv1[i] + 2.0 * kv2[i] + 2.0 * kv3[i] + kv4[i]);
      v1[i] = kv1[i] + h6 * (ka1[i] + 2.0 * ka2[i] + 2.0 * ka3[i] + ka4[i]);
    }
    break;
  }
  }
  mr_frames_place(w, t + h, x1, v1);
  return 0;
}

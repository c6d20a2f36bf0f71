/* Friction's algebra once its response is measured (friction.c): the
 * Delassus operator W of the contacts' tangents and its normal part N in
 * hand, each contact's friction is found with no further solve. The
 * stopping targets are projected onto what friction can reach, projected
 * Gauss–Seidel takes each contact's stopping force through its own 2×2
 * block of W or slides it at its limit μN, and the friction found is held
 * inside its cone on the normals it leaves. */
#include "internal.h"

#include <math.h>
#include <string.h>

/* What stopping point p within tau asks of its slip: a_t + v_t/tau, the
 * residual the rounds drive to zero where the contact sticks. */
static void target(const struct mr_fric_point *p, double tau, double r[2]) {
  r[0] = p->at[0] + p->vt[0] / tau;
  r[1] = p->at[1] + p->vt[1] / tau;
}

/* d = −B⁺ r for the symmetric part of a 2×2 block B of W, B⁺ its
 * pseudo-inverse: a direction the constraints hold the contact in
 * (an eigenvalue under eps) takes no friction, since none could move it. */
static void stop_along(const double *b, int ld, const double r[2], double eps, double d[2]) {
  const double p = b[0], s = b[ld + 1], q = 0.5 * (b[1] + b[ld]);
  const double mean = 0.5 * (p + s), half = 0.5 * (p - s);
  const double spread = sqrt(half * half + q * q), l1 = mean + spread, l2 = mean - spread;
  d[0] = d[1] = 0.0;
  if (!(l1 > eps)) return;
  if (l2 > eps) {
    const double det = p * s - q * q;
    d[0] = -(s * r[0] - q * r[1]) / det;
    d[1] = -(p * r[1] - q * r[0]) / det;
    return;
  }
  /* Rank one: along l1's eigenvector u, d = −u (u·r)/l1. */
  double u0 = q, u1 = l1 - p;
  if (fabs(half) > fabs(q) && half > 0) {
    u0 = l1 - s;
    u1 = q;
  }
  const double len = sqrt(u0 * u0 + u1 * u1);
  if (!(len > 0)) {
    u0 = half >= 0 ? 1.0 : 0.0;
    u1 = 1.0 - u0;
  } else {
    u0 /= len;
    u1 /= len;
  }
  const double ur = (u0 * r[0] + u1 * r[1]) / l1;
  d[0] = -u0 * ur;
  d[1] = -u1 * ur;
}

/* How far friction may raise the normal a contact's limit is taken on:
 * its own friction, its own limit this many times; all of it, to this
 * many times the largest multiplier of its block before friction
 * (mr_fric_point.scale). */
#define RAISED_MAX 4.0

/* x, or at most cap; NaN stays NaN. */
static double at_most(double x, double cap) {
  return x > cap ? cap : x;
}

/* The friction point p takes: f_stop through its block wii of W, or, if
 * that is more than μN allows, μN along the way it slides. N counts the
 * contact's own friction: with nii = ∂N/∂f of its own, N = N_o + nii·f,
 * N_o what the others leave. Friction that lifts its own contact (nii·g
 * < 0 along the sliding direction g) slides at μN_o/(1 − μ nii·g), where
 * the two agree; friction that presses its own contact harder raises its
 * own limit at most RAISED_MAX-fold (the rounds cycled, two bodies
 * wedged, μN growing with f).
 *
 * Nor may the contacts raise each other's limits without bound: two
 * spheres wedged between puppets and sliding at 40 m/s, each one's
 * friction pressing both harder (by about 2 per unit of friction, μ =
 * 0.3), took N up at every round, from 1.6e5 to 1.8e32, and the world
 * reset. Rigid contacts with Coulomb friction can have no answer there
 * (Painlevé's paradox). The limit is taken on N held to RAISED_MAX times
 * the block's largest multiplier before friction. Of the pinned runs only
 * hard case 30's wedge reaches it. */
static void take(const struct mr_fric_point *p, const double *wii, int ld, const double nii[2],
                 double tau, double next[2]) {
  double r[2], d[2];
  target(p, tau, r);
  stop_along(wii, ld, r, 1e-9 * p->inv, d);
  next[0] = p->f[0] + d[0];
  next[1] = p->f[1] + d[1];
  const double cap = RAISED_MAX * p->scale;
  const double others = p->n - (nii[0] * p->f[0] + nii[1] * p->f[1]);
  const double need = sqrt(next[0] * next[0] + next[1] * next[1]);
  if (need <= p->mu * at_most(others + nii[0] * next[0] + nii[1] * next[1], cap)) return;
  /* Sliding: against the sliding velocity, unless that is too slow to
   * count in what stopping asks (rounding, or a contact only now starting
   * to slide), when against the way it is driven. */
  const double speed = sqrt(p->vt[0] * p->vt[0] + p->vt[1] * p->vt[1]);
  double g[2] = { 0.0, 0.0 };
  if (speed > 1e-3 * tau * p->drive) {
    g[0] = -p->vt[0] / speed;
    g[1] = -p->vt[1] / speed;
  } else if (p->drive > 0) {
    g[0] = -p->at0[0] / p->drive;
    g[1] = -p->at0[1] / p->drive;
  } else if (need > 0) {
    g[0] = next[0] / need;
    g[1] = next[1] / need;
  }
  const double s =
      others > 0
          ? at_most(p->mu * others /
                        fmax(1.0 - p->mu * (nii[0] * g[0] + nii[1] * g[1]), 1.0 / RAISED_MAX),
                    p->mu * cap)
          : 0.0;
  next[0] = s * g[0];
  next[1] = s * g[1];
}

/* The slip the friction can change is W's range: where contacts share a
 * body (a puppet lying on a floor on many spheres), W is singular (30
 * tangents, rank 12 on hard case 06b), and the stopping targets
 * a_t + v_t/(h/2) are not all in its range: the contacts' velocities
 * differ by what the constraints' drift leaves, 24 % of the targets' size
 * there. No friction moves the rest, and the rounds, each contact
 * stopping its own, traded internal forces for it without end (169 of
 * 181 evaluations of 06b at the cap). So the targets are projected onto
 * the range first, and what is left out stays as slip no friction can
 * stop. The range is spanned by the columns of L in W = Pᵀ L Lᵀ P, a
 * Cholesky factor with diagonal pivoting that stops at the rank; the
 * projection is L (LᵀL)⁻¹ Lᵀ. c holds 8m² + 6m. */
static void reachable(struct mr_fric_point *pt, int m, double tau, const double *W, double *c) {
  const int n = 2 * m;
  double *l = c, *g = l + (size_t)n * (size_t)n, *r = g + (size_t)n * (size_t)n, *y = r + n;
  int *perm = (int *)(y + n);
  memcpy(l, W, (size_t)n * (size_t)n * sizeof *l);
  double big = 0.0;
  for (int i = 0; i < n; i++) {
    perm[i] = i;
    big = fmax(big, l[(size_t)i * (size_t)n + (size_t)i]);
    if (i % 2 == 0) target(&pt[i / 2], tau, r + i);
  }
#define L_(i, j) l[(size_t)perm[i] * (size_t)n + (size_t)perm[j]]
  int k = 0;
  for (; k < n; k++) {
    int best = k;
    for (int i = k + 1; i < n; i++)
      if (L_(i, i) > L_(best, best)) best = i;
    if (!(L_(best, best) > 1e-9 * big)) break;
    const int t = perm[k];
    perm[k] = perm[best];
    perm[best] = t;
    const double d = sqrt(L_(k, k));
    L_(k, k) = d;
    for (int i = k + 1; i < n; i++) L_(i, k) /= d;
    /* Both triangles: a later pivot's swap reads either. */
    for (int j = k + 1; j < n; j++)
      for (int i = k + 1; i < n; i++) L_(i, j) -= L_(i, k) * L_(j, k);
  }
  if (k == n || k == 0) return; /* W invertible, or nothing moves: nothing to take out */
  /* g = LᵀL (k × k, in its own lower triangle), y = Lᵀ r. */
  for (int a = 0; a < k; a++) {
    double s = 0.0;
    for (int i = a; i < n; i++) s += L_(i, a) * r[perm[i]];
    y[a] = s;
    for (int b = 0; b <= a; b++) {
      double t = 0.0;
      for (int i = a; i < n; i++) t += L_(i, a) * L_(i, b);
      g[(size_t)a * (size_t)k + (size_t)b] = t;
    }
  }
  /* Cholesky of g, and y = g⁻¹ y. */
  for (int a = 0; a < k; a++) {
    double *ga = g + (size_t)a * (size_t)k;
    for (int b = 0; b <= a; b++) {
      double s = ga[b];
      const double *gb = g + (size_t)b * (size_t)k;
      for (int e = 0; e < b; e++) s -= ga[e] * gb[e];
      ga[b] = b < a ? s / gb[b] : sqrt(s);
    }
  }
  for (int a = 0; a < k; a++) {
    double s = y[a];
    for (int e = 0; e < a; e++) s -= g[(size_t)a * (size_t)k + (size_t)e] * y[e];
    y[a] = s / g[(size_t)a * (size_t)k + (size_t)a];
  }
  for (int a = k - 1; a >= 0; a--) {
    double s = y[a];
    for (int e = a + 1; e < k; e++) s -= g[(size_t)e * (size_t)k + (size_t)a] * y[e];
    y[a] = s / g[(size_t)a * (size_t)k + (size_t)a];
  }
  /* The part of each target out of the range is taken off its slip. */
  for (int i = 0; i < n; i++) {
    double s = 0.0;
    for (int a = 0; a < k && a <= i; a++) s += L_(i, a) * y[a];
    const int q = perm[i];
    pt[q / 2].at[q % 2] -= r[q] - s;
  }
#undef L_
}

/* Projected Gauss–Seidel over the points until no friction changes by
 * more than tol (N). */
static void rounds(struct mr_fric_point *pt, int m, double tau, const double *W, const double *N,
                   double tol) {
  const size_t ld = (size_t)(2 * m);
  for (int round = 0; round < MR_FRICTION_ROUNDS; round++) {
    /* Past half the rounds the normals are held where they are: on fixed
     * limits the rounds converge. */
    const int held = round >= MR_FRICTION_ROUNDS / 2;
    double change = 0.0;
    for (int i = 0; i < m; i++) {
      struct mr_fric_point *p = &pt[i];
      const double *nii = N + (size_t)i * ld + (size_t)(2 * i);
      const double none[2] = { 0.0, 0.0 };
      double next[2], d[2];
      take(p, W + (size_t)(2 * i) * ld + (size_t)(2 * i), (int)ld, held ? none : nii, tau, next);
      d[0] = next[0] - p->f[0];
      d[1] = next[1] - p->f[1];
      p->f[0] = next[0];
      p->f[1] = next[1];
      change = fmax(change, fmax(fabs(d[0]), fabs(d[1])));
      if (d[0] == 0.0 && d[1] == 0.0) continue;
      for (int j = 0; j < m; j++) {
        const double *wj = W + (size_t)(2 * j) * ld + (size_t)(2 * i);
        pt[j].at[0] += wj[0] * d[0] + wj[1] * d[1];
        pt[j].at[1] += wj[ld] * d[0] + wj[ld + 1] * d[1];
        if (held) continue;
        const double *nj = N + (size_t)j * ld + (size_t)(2 * i);
        pt[j].n += nj[0] * d[0] + nj[1] * d[1];
      }
    }
    if (!(change > tol)) break;
  }
}

/* The rounds' second half holds the normals still, so the friction they
 * end on may pass μ times the normals it actually leaves: two puppets
 * wedged together (clash.yaml) ended 33 of 1 261 evaluations over it, by
 * up to a third of the largest multiplier. N is linear, so those normals
 * are n = n0 + N f, with no solve; a contact over μ max(n, 0) is cut back
 * to it along its own direction, and the others' normals follow. Friction
 * only ever shrinks here, and each cut takes more than tol off it, so the
 * sweeps end once nothing is over by more than tol; two contacts that
 * unload each other almost as fast as they are cut could take longer than
 * MR_FRICTION_ROUNDS sweeps, which is where they stop. f: 2m; n: m, the
 * normals f leaves, kept up to date; N: m × 2m, row-major. */
void mr_friction_hold_cone(int m, double *f, double *n, const double *mu, const double *N,
                           double tol) {
  const size_t ld = (size_t)(2 * m);
  for (int sweep = 0; sweep < MR_FRICTION_ROUNDS; sweep++) {
    int cut = 0;
    for (int i = 0; i < m; i++) {
      const double mag = sqrt(f[2 * i] * f[2 * i] + f[2 * i + 1] * f[2 * i + 1]);
      const double limit = mu[i] * fmax(n[i], 0.0);
      if (!(mag > limit + tol)) continue;
      const double s = limit / mag - 1.0, d0 = s * f[2 * i], d1 = s * f[2 * i + 1];
      f[2 * i] += d0;
      f[2 * i + 1] += d1;
      for (int j = 0; j < m; j++)
        n[j] +=
            N[(size_t)j * ld + (size_t)(2 * i)] * d0 + N[(size_t)j * ld + (size_t)(2 * i) + 1] * d1;
      cut = 1;
    }
    if (!cut) return;
  }
}

/* The normals the rounds' friction leaves, from the ones before it, and
 * that friction held inside its cone on them (mr_friction_hold_cone).
 * c holds 4m: the share reachable() is done with. */
static void cone_on_normals(struct mr_fric_point *pt, int m, const double *N, double tol,
                            double *c) {
  double *f = c, *n = f + 2 * m, *mu = n + m;
  const size_t ld = (size_t)(2 * m);
  for (int i = 0; i < m; i++) {
    f[2 * i] = pt[i].f[0];
    f[2 * i + 1] = pt[i].f[1];
    mu[i] = pt[i].mu;
  }
  for (int i = 0; i < m; i++) {
    double s = pt[i].n0;
    for (int j = 0; j < 2 * m; j++) s += N[(size_t)i * ld + (size_t)j] * f[j];
    n[i] = s;
  }
  mr_friction_hold_cone(m, f, n, mu, N, tol);
  for (int i = 0; i < m; i++) {
    pt[i].f[0] = f[2 * i];
    pt[i].f[1] = f[2 * i + 1];
  }
}

/* Nothing slides or is pushed along any contact (a body lying still on
 * a floor): no friction is asked, and no probe need be made. */
int mr_friction_asks(const struct mr_fric_point *pt, int m, double tau, double tol) {
  double ask = 0.0;
  for (int i = 0; i < m; i++) {
    double r[2];
    target(&pt[i], tau, r);
    ask = fmax(ask, sqrt(r[0] * r[0] + r[1] * r[1]) / pt[i].inv);
  }
  return ask > tol || ask != ask;
}

void mr_friction_rounds(struct mr_fric_point *pt, int m, double tau, const double *W,
                        const double *N, double tol, double *scratch) {
  reachable(pt, m, tau, W, scratch);
  rounds(pt, m, tau, W, N, tol);
  cone_on_normals(pt, m, N, tol, scratch);
}

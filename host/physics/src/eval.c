/* One evaluation of the equations of motion (§4.2, §5.2): the passes of
 * applied forces, then the constraint forces from eq. 8, then q̈ = M⁻¹ F.
 * Every integrator stage calls this once. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int mr_solve_reserve(mr_world *w, int rows)
{
  if (rows <= w->cap_rows)
    return 0;
  int cap = w->cap_rows ? w->cap_rows : 16;
  while (cap < rows)
    cap *= 2;
  double **arr[] = {&w->rhs, &w->lambda, &w->row_c, &w->row_cdot, &w->row_bias, &w->row_jv};
  for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) {
    double *p = realloc(*arr[i], (size_t)cap * sizeof *p);
    if (!p)
      return -1;
    *arr[i] = p;
  }
  int *rc = realloc(w->row_contact, (size_t)cap * sizeof *rc);
  if (!rc)
    return -1;
  w->row_contact = rc;
  w->cap_rows = cap;
  return 0;
}

/* Contact rows are often redundant with each other and with the rigid
 * groups (a tetrahedron resting on three points of a floor, a puppet lying
 * down). A dependent row's multiplier is set to zero, which for a contact
 * means that point is left to sink and then bounces: the chatter of a body
 * that never comes to rest. A compliance of 1e-6 of its own diagonal on each
 * contact row (a soft contact: 1e-6 g of sag under its own weight) keeps
 * them independent, so redundant contacts share the load. Constraint rows
 * keep their exact, reported treatment. */
static void soften_contacts(mr_world *w)
{
  mr_csr *A = &w->A;
  for (int r = 0; r < A->n; r++) {
    if (w->row_contact[r] < 0)
      continue;
    for (int e = A->row_ptr[r]; e < A->row_ptr[r + 1]; e++)
      if (A->col[e] == r)
        A->val[e] *= 1.0 + 1e-6;
  }
}

int mr_solve_rows(mr_world *w, int assemble)
{
  int k = w->J.rows;
  if (assemble) {
    if (mr_csr_assemble(&w->A, &w->J, w->inv_mass) != 0)
      return -1;
    soften_contacts(w);
  }
  memset(w->lambda, 0, (size_t)k * sizeof *w->lambda);
  mr_solve_result r;
  w->pass_calls[MR_PASS_SOLVE]++;
  w->stats.solves++;
  int st = mr_solver_solve(w->solver, &w->opts, &w->A, w->rhs, w->lambda, &r);
  w->stats.solver_iterations += (uint64_t)(r.iterations > 0 ? r.iterations : 0);
  if (st == MR_SOLVE_NONFINITE) {
    /* NaN or Inf in the system (a callback curve, an exploded state): let it
     * reach the state, where the step sees it and resets the world (§7). */
    for (int i = 0; i < k; i++)
      w->lambda[i] = NAN;
    w->stats.solver_failures++;
    return 0;
  }
  if (st == MR_SOLVE_ENOMEM || st == MR_SOLVE_UNAVAILABLE) {
    w->stats.solver_failures++;
    w->fail = mr_fail(w, MR_ERR_SOLVER, "solver %s: %s (%d rows)", mr_solve_method_name(w->opts.method),
                      st == MR_SOLVE_ENOMEM ? "out of memory" : "not built into this library", k);
    return -1;
  }
  if (st == MR_SOLVE_NOT_CONVERGED)
    w->stats.solver_failures++;
  if (r.dependent > w->last_dependent)
    w->last_dependent = r.dependent;
  w->stats.dependent_rows = r.dependent;
  return 0;
}

/* a = M⁻¹ f for every particle (0 on frame particles). */
static void accelerations(const mr_world *w, const double *f, double *a)
{
  for (int i = 0; i < w->n; i++)
    for (int k = 0; k < 3; k++)
      a[3 * i + k] = f[3 * i + k] * w->inv_mass[i];
}

/* Rows of the constraints and of the active contacts (w->contact_active)
 * into w->J, with C, Ċ and the bias J̇q̇ + ∂²C/∂t² per row, and for each
 * row the contact it stands for (-1 for a constraint). Returns the number
 * of rows, or -1 when out of memory. The force solve (eq. 8) and the
 * impulse solve (eq. 9, which does not read the bias) share it. */
int mr_rows_build(mr_world *w, double t, const double *x, const double *v)
{
  int nc = mr_constraint_row_count(w);
  if (mr_solve_reserve(w, nc + w->contacts.n) != 0 || mr_jac_reset(&w->J, w->n) != 0)
    return -1;
  int r = 0;
  if (nc > 0) {
    r = mr_constraints_rows(w, t, x, v, w->row_c, w->row_cdot, w->row_bias);
    if (r < 0)
      return -1;
  }
  for (int i = 0; i < r; i++)
    w->row_contact[i] = -1;
  for (int c = 0; c < w->contacts.n; c++) {
    if (!w->contact_active[c])
      continue;
    double chi, chidot, jdqd;
    if (mr_contact_row(w, &w->contacts.c[c], x, v, &chi, &chidot, &jdqd) != 0)
      return -1;
    w->row_c[r] = chi;
    w->row_cdot[r] = chidot;
    w->row_bias[r] = jdqd;
    w->row_contact[r] = c;
    r++;
  }
  return r;
}

/* §5.2, eq. 8: b = −J̇q̇ − J M⁻¹ F_a − K_s C − K_d Ċ − ∂²C/∂t². */
static void rhs_eq8(mr_world *w, int rows, const double *a_free)
{
  mr_jac_mul(&w->J, a_free, w->row_jv);
  for (int i = 0; i < rows; i++)
    w->rhs[i] = -w->row_bias[i] - w->row_jv[i] - w->def.ks * w->row_c[i] - w->def.kd * w->row_cdot[i];
}

/* Coulomb friction at resting contacts (§4.4), with N the contact's
 * multiplier, on the relative motion of its two sides (a particle against a
 * plane, or two spheres of the sphere trees). The friction that would stop
 * the sliding within half a step against everything else pushing along the
 * contact is
 *   f_stop = f_now − m_eff (a_t + v_t / (h/2)),
 * with v_t, a_t the relative tangential velocity and acceleration under all
 * forces so far (applied, constraint, and every contact's friction f_now of
 * the previous round) and m_eff the effective mass of that relative motion.
 * If |f_stop| ≤ μN the contact sticks and f_stop is the friction: static
 * friction, so a body on a slope its friction can hold stays put instead of
 * creeping at about g sinθ h/2. Otherwise it slides, and friction is μN
 * against the sliding velocity. fr holds each contact's friction (3 per
 * contact); each change is added to f, and to acc so that the next contact
 * on the same particle sees it. Returns the largest change, N. */
static double friction(mr_world *w, int rows, const double *x, const double *v, double *acc, double *fr,
                       double *f)
{
  const double tau = 0.5 * w->h_step;
  double change = 0.0;
  for (int r = 0; r < rows; r++) {
    int c = w->row_contact[r];
    if (c < 0)
      continue;
    const mr_contact *ct = &w->contacts.c[c];
    if (ct->friction <= 0)
      continue;
    double *fc = &fr[3 * c], next[3] = {0, 0, 0};
    double nforce = w->lambda[r];
    if (nforce > 0) {
      double vt[3], at[3];
      double inv = mr_contact_slip(w, ct, x, v, vt);
      mr_contact_slip(w, ct, x, acc, at);
      if (!(inv > 0))
        continue;
      for (int k = 0; k < 3; k++)
        next[k] = fc[k] - (at[k] + vt[k] / tau) / inv;
      double speed = sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
      double need = sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2]);
      double limit = ct->friction * nforce;
      if (need > limit)
        for (int k = 0; k < 3; k++)
          next[k] = speed > 0 ? -limit * vt[k] / speed : limit * next[k] / need;
    }
    double d[3];
    for (int k = 0; k < 3; k++) {
      d[k] = next[k] - fc[k];
      change = fmax(change, fabs(d[k]));
      fc[k] = next[k];
    }
    mr_contact_spread(w, ct, d, 1.0, 0, f);
    mr_contact_spread(w, ct, d, 1.0, 1, acc);
  }
  return change;
}

int mr_eval(mr_world *w, double t, double *x, double *v, double *a)
{
  int n3 = 3 * w->n;
  double *f = w->f;
  mr_frames_place(w, t, x, v);
  memset(f, 0, (size_t)n3 * sizeof *f);
  for (int p = 0; p < w->n_force_passes; p++) {
    w->pass_calls[w->force_pass_ids[p]]++;
    w->force_passes[p](w, t, x, v, f);
  }
  accelerations(w, f, a);
  if (!w->has_solve)
    return 0;
  /* §5.4: a touching contact takes part unless it is apart and clearly
   * separating (χ ≥ 0, χ̇ > rest_speed/10): holding that one back would do
   * work on it (a ball would bounce higher than it fell). The margin keeps
   * a body at rest, whose contact points move by rounding, from switching
   * its contacts off and on between the stages of one step, which made a
   * lying puppet jitter at 0.1 m/s. */
  const double separating = 0.1 * w->def.rest_speed;
  for (int c = 0; c < w->contacts.n; c++) {
    const mr_contact *ct = &w->contacts.c[c];
    w->contact_active[c] =
      !(mr_contact_gap(w, ct, x) >= 0.0 && mr_contact_rate(w, ct, x, v) > separating);
  }
  int rows = 0;
  /* Resting contacts push and never pull (§5.4, eq. 13b): a contact whose
   * multiplier comes out negative is released and the system solved again. */
  for (int round = 0; round <= w->contacts.n; round++) {
    rows = mr_rows_build(w, t, x, v);
    if (rows < 0)
      return -1;
    if (rows == 0)
      return 0;
    rhs_eq8(w, rows, a);
    if (mr_solve_rows(w, 1) != 0)
      return -1;
    int released = 0;
    for (int r = 0; r < rows; r++) {
      int c = w->row_contact[r];
      if (c >= 0 && w->lambda[r] < 0) {
        w->contact_active[c] = 0;
        released = 1;
      }
    }
    if (!released)
      break;
  }
  int has_friction = 0;
  for (int r = 0; r < rows && !has_friction; r++)
    has_friction = w->row_contact[r] >= 0 && w->contacts.c[w->row_contact[r]].friction > 0 &&
                   w->lambda[r] > 0;
  if (has_friction) {
    /* Friction is an applied force the constraints must carry too: add it
     * and solve again with the same J M⁻¹ Jᵀ. The constraints then share
     * it out differently, which changes what each contact must hold, so
     * repeat a few rounds (a rigid body on a slope sticks only when its
     * contacts agree). Each round needs a + M⁻¹ Jᵀ λ, put in pa (free
     * during a step). */
    memset(w->fric, 0, (size_t)w->contacts.n * 3 * sizeof *w->fric);
    double scale = 0;
    for (int r = 0; r < rows; r++)
      scale = fmax(scale, fabs(w->lambda[r]));
    for (int round = 0; round < 32; round++) {
      mr_jac_tmul(&w->J, w->lambda, w->pa);
      for (int i = 0; i < n3; i++)
        w->pa[i] = a[i] + w->pa[i] * w->inv_mass[i / 3];
      double change = friction(w, rows, x, v, w->pa, w->fric, f);
      if (round > 0 && !(change > 1e-9 * scale))
        break;
      accelerations(w, f, a);
      rhs_eq8(w, rows, a);
      if (mr_solve_rows(w, 0) != 0)
        return -1;
    }
  }
  /* §5.2, eq. 5: F_c = Jᵀ λ. */
  mr_jac_tmul(&w->J, w->lambda, w->tmp3n);
  double big = 0;
  for (int r = 0; r < rows; r++) {
    double l = fabs(w->lambda[r]);
    if (l > big || l != l)
      big = l;
  }
  w->stats.max_multiplier = big;
  for (int i = 0; i < n3; i++)
    a[i] += w->tmp3n[i] * w->inv_mass[i / 3];
  return 0;
}

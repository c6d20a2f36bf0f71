/* Collision impulses through the velocity-level system (§5.3, eq. 9):
 *
 *   J M⁻¹ Jᵀ λ = −J M⁻¹ L_a − Ċ⁻ + target,   q̇⁺ = q̇⁻ + M⁻¹ (L_a + Jᵀ λ)
 *
 * with L_a the applied momenta (the friction impulses below) and Ċ⁻ = J q̇⁻
 * + ∂C/∂t before the impulse. Every constraint row has target 0, so the
 * velocities after the impulse keep Ċ = 0 and the puppet's joints hold
 * (§5.1: velocities of single particles must not simply be changed). Each
 * colliding contact row (eq. 13a, χ̇ < 0) has target −e χ̇⁻ (restitution e),
 * or 0 for impacts slower than rest_speed, which then rest. Contacts push
 * and never pull: a negative multiplier releases its contact, a contact that
 * the impulse drives inwards is added, and the system is solved again. The
 * position terms K_s C, K_d Ċ of eq. 9 are left to eq. 8's correction during
 * the step: an impulse is instantaneous and moves nothing. */
#include "internal.h"

#include <math.h>
#include <string.h>

static int build(mr_world *w, double t, const double *x, const double *v, const unsigned char *active,
                 int *nrows)
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
    if (!active[c])
      continue;
    double chidot, jdqd;
    w->row_c[r] = mr_contact_row(w, &w->contacts.c[c], x, v, &chidot, &jdqd);
    w->row_cdot[r] = chidot;
    w->row_contact[r] = c;
    r++;
  }
  *nrows = r;
  return 0;
}

int mr_impulses_apply(mr_world *w, double t, int *collided)
{
  *collided = 0;
  int nct = w->contacts.n;
  if (nct == 0)
    return 0;
  const double *x = w->x;
  double *v = w->v;
  double *pa = w->pa;
  int n3 = 3 * w->n;
  unsigned char *active = w->contact_active;
  /* Normal velocities before the impulse, from every contact's row. */
  double *pre = w->contact_pre;
  if (mr_jac_reset(&w->J, w->n) != 0)
    return -1;
  int any = 0;
  for (int c = 0; c < nct; c++) {
    double jdqd;
    mr_contact_row(w, &w->contacts.c[c], x, v, &pre[c], &jdqd);
    active[c] = pre[c] < 0;
    any |= active[c];
    if (pre[c] < -w->def.rest_speed)
      *collided = 1;
  }
  if (!any)
    return 0;
  /* Coulomb friction at impact as applied momentum: the tangential impulse
   * is at most μ times the normal impulse a free particle would take. */
  memset(pa, 0, (size_t)n3 * sizeof *pa);
  for (int c = 0; c < nct; c++) {
    const mr_contact *ct = &w->contacts.c[c];
    if (ct->kind != MR_CONTACT_PLANE || ct->friction <= 0 || !(pre[c] < -w->def.rest_speed))
      continue;
    int p = ct->a;
    const double *n = w->planes[ct->b].n;
    const double *vp = &v[3 * p];
    double vn = vp[0] * n[0] + vp[1] * n[1] + vp[2] * n[2];
    double vt[3] = {vp[0] - vn * n[0], vp[1] - vn * n[1], vp[2] - vn * n[2]};
    double speed = sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
    if (!(speed > 0))
      continue;
    double pn = w->mass[p] * (1.0 + ct->restitution) * -pre[c];
    double mag = fmin(ct->friction * pn, w->mass[p] * speed);
    for (int k = 0; k < 3; k++)
      pa[3 * p + k] -= mag * vt[k] / speed;
  }
  for (int i = 0; i < n3; i++)
    w->tmp3n[i] = pa[i] * w->inv_mass[i / 3];
  for (int round = 0; round <= nct + 1; round++) {
    int rows;
    if (build(w, t, x, v, active, &rows) != 0)
      return -1;
    if (rows == 0) {
      for (int i = 0; i < n3; i++)
        w->f[i] = v[i] + w->tmp3n[i];
      break;
    }
    mr_jac_mul(&w->J, w->tmp3n, w->row_jv);
    for (int r = 0; r < rows; r++) {
      int c = w->row_contact[r];
      double target = 0.0;
      if (c >= 0 && pre[c] < -w->def.rest_speed)
        target = -w->contacts.c[c].restitution * pre[c];
      w->rhs[r] = target - w->row_cdot[r] - w->row_jv[r];
    }
    if (mr_solve_rows(w, 1) != 0)
      return -1;
    /* Trial velocities q̇⁺ into w->f. */
    mr_jac_tmul(&w->J, w->lambda, w->f);
    for (int i = 0; i < n3; i++)
      w->f[i] = v[i] + (pa[i] + w->f[i]) * w->inv_mass[i / 3];
    int changed = 0;
    for (int r = 0; r < rows; r++) {
      int c = w->row_contact[r];
      if (c >= 0 && w->lambda[r] < 0) {
        active[c] = 0;
        changed = 1;
      }
    }
    if (!changed) {
      /* A contact the impulse pushes inwards joins the system. */
      if (mr_jac_reset(&w->J, w->n) != 0)
        return -1;
      for (int c = 0; c < nct; c++) {
        if (active[c])
          continue;
        double after, jdqd;
        mr_contact_row(w, &w->contacts.c[c], x, w->f, &after, &jdqd);
        if (after < -1e-9) {
          active[c] = 1;
          changed = 1;
        }
      }
    }
    if (!changed)
      break;
  }
  memcpy(v, w->f, (size_t)n3 * sizeof *v);
  if (*collided)
    w->stats.collisions++;
  return 0;
}

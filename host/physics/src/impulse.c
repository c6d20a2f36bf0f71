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
  /* Normal velocities χ̇⁻ before the impulse. */
  double *pre = w->contact_pre;
  int any = 0;
  for (int c = 0; c < nct; c++) {
    pre[c] = mr_contact_rate(w, &w->contacts.c[c], x, v);
    active[c] = pre[c] < 0;
    any |= active[c];
    if (pre[c] < -w->def.rest_speed)
      *collided = 1;
  }
  if (!any)
    return 0;
  /* Coulomb friction at impact as applied momentum, on the relative
   * tangential motion of the contact's two sides (a particle and a plane, or
   * two spheres): at most μ times the normal impulse (1 + e)·(−χ̇⁻)·m_eff the
   * contact would take on its own, and no more than stops the sliding. */
  memset(pa, 0, (size_t)n3 * sizeof *pa);
  for (int c = 0; c < nct; c++) {
    const mr_contact *ct = &w->contacts.c[c];
    if (ct->friction <= 0 || !(pre[c] < -w->def.rest_speed))
      continue;
    double vt[3];
    double inv = mr_contact_slip(w, ct, x, v, vt);
    double speed = sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
    if (!(speed > 0) || !(inv > 0))
      continue;
    double pn = (1.0 + ct->restitution) * -pre[c] / inv;
    double mag = fmin(ct->friction * pn, speed / inv);
    mr_contact_spread(w, ct, vt, -mag / speed, 0, pa);
  }
  for (int i = 0; i < n3; i++)
    w->tmp3n[i] = pa[i] * w->inv_mass[i / 3];
  for (int round = 0; round <= nct + 1; round++) {
    int rows = mr_rows_build(w, t, x, v);
    if (rows < 0)
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
      w->rhs[r] = (c >= 0 ? target - w->row_cdot[r] : 0.0) - w->row_jv[r];
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
      for (int c = 0; c < nct; c++) {
        if (active[c])
          continue;
        if (mr_contact_rate(w, &w->contacts.c[c], x, w->f) < -1e-9) {
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

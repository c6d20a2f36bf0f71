/* String-length correction (§6.2, after [19]): springs stretch under the
 * puppet's weight and under fast pulls, which shows as rubbery strings. After
 * each step, every string longer than (1 + max_stretch)·rest is shortened by
 * moving its puppet end back towards the frame, and the part of the puppet
 * end's velocity that lengthens the string is removed (the same principle
 * applied to the damper).
 *
 * Moving one particle of a rigid group alone would tear the group, so each
 * sweep over the strings is followed by a sweep that projects the geometric
 * constraints back onto their lengths and points (mass-weighted: a particle
 * moves in proportion to its inverse mass), and the two alternate until no
 * string is over length or the iteration budget is spent. The group thus
 * moves as a whole towards the frame. What is left over is settled by the
 * correction terms of eq. 8 in the next steps. */
#include "internal.h"

#include <math.h>

static int shorten_strings(mr_world *w, double limit) {
  int moved = 0;
  const mr_list *l = MR_FORCES(w, STRINGS);
  for (int i = 0; i < l->n; i++) {
    const mr_string *s = &MR_AT(*l, mr_string, i);
    double *xp = &w->x[3 * s->puppet_particle], *vp = &w->v[3 * s->puppet_particle];
    const double *xf = &w->x[3 * s->frame_particle], *vf = &w->v[3 * s->frame_particle];
    double d[3] = { xp[0] - xf[0], xp[1] - xf[1], xp[2] - xf[2] };
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double max = s->rest * limit;
    /* A hair of tolerance, so rounding in the projection cannot keep the
     * sweep busy. */
    if (!(len > max * (1.0 + 1e-9)) || !(len > 0)) continue;
    double u[3] = { d[0] / len, d[1] / len, d[2] / len };
    double rate = 0;
    for (int k = 0; k < 3; k++) {
      xp[k] = xf[k] + u[k] * max;
      rate += (vp[k] - vf[k]) * u[k];
    }
    if (rate > 0)
      for (int k = 0; k < 3; k++) vp[k] -= rate * u[k];
    moved = 1;
  }
  return moved;
}

/* One Gauss–Seidel sweep of position projection over the constraints. */
static void project_constraints(mr_world *w) {
  double *x = w->x;
  for (int i = 0; i < w->distances.n; i++) {
    const mr_distance *c = &MR_AT(w->distances, mr_distance, i);
    double wa = w->inv_mass[c->a], wb = w->inv_mass[c->b];
    double d[3], len = 0;
    for (int k = 0; k < 3; k++) {
      d[k] = x[3 * c->a + k] - x[3 * c->b + k];
      len += d[k] * d[k];
    }
    len = sqrt(len);
    if (!(len > 1e-12) || wa + wb == 0.0) continue;
    double s = (len - c->length) / (len * (wa + wb));
    for (int k = 0; k < 3; k++) {
      x[3 * c->a + k] -= wa * s * d[k];
      x[3 * c->b + k] += wb * s * d[k];
    }
  }
  for (int i = 0; i < w->pins.n; i++)
    for (int k = 0; k < 3; k++)
      x[3 * MR_AT(w->pins, mr_pin, i).particle + k] = MR_AT(w->pins, mr_pin, i).point[k];
  for (int i = 0; i < w->curves.n; i++) {
    double p[3], pv[3], pa[3];
    mr_curve_eval(&MR_AT(w->curves, mr_curve, i), w->t, p, pv, pa);
    for (int k = 0; k < 3; k++) x[3 * MR_AT(w->curves, mr_curve, i).particle + k] = p[k];
  }
}

void mr_strings_correct(mr_world *w) {
  w->pass_calls[MR_PASS_STRING_CORRECTION]++;
  const double limit = 1.0 + w->def.string_max_stretch;
  const int constrained = w->distances.n + w->pins.n + w->curves.n > 0;
  for (int it = 0; it < w->def.string_correction_iterations; it++) {
    if (!shorten_strings(w, limit)) break;
    if (constrained) project_constraints(w);
  }
}

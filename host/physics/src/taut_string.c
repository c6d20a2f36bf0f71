/* Strings that hold their length (MR_STRING_TAUT): a real marionette
 * string does not stretch, it goes slack or taut. The paper's strings are
 * springs (§6.2); holding a spring to 1 % takes stiff springs and tiny
 * steps. Here a taut-mode string is a unilateral constraint
 *
 *   χ = rest − |x_p − x_f| ≥ 0,
 *
 * handled exactly as a contact (§5.4, eq. 13): found when χ ≤ slop, a
 * resting row of eq. 8 that pulls and never pushes (a negative λ releases
 * it), an inelastic impulse of eq. 9 when it snaps taut (χ̇ < 0 at the start
 * of a step), and a step that overshoots the snap is located in time and
 * cut there (§4.5). With d = x_p − x_f, L = |d|, u = d/L:
 *
 *   J = −uᵀ at the puppet particle (the frame end is kinematic),
 *   χ̇ = −u·(v_p − v_f),
 *   J̇q̇ + ∂²χ/∂t² = −(|ḋ|² − L̇²)/L + u·a_f,
 *
 * with a_f = p̈ + ω̇ × r + ω × (ω × r) the frame end's acceleration on the
 * frame's path (frame.c), whose velocity is continuous across targets. */
#include "internal.h"

#include <math.h>
#include <string.h>

static const mr_string *string_at(const mr_world *w, int i) {
  return &MR_AT(*MR_FORCES(w, STRINGS), mr_string, i);
}

/* d = x_p − x_f and its length. */
static double geometry(const mr_string *s, const double *x, double d[3]) {
  const double *xp = &x[3 * s->puppet_particle], *xf = &x[3 * s->frame_particle];
  for (int k = 0; k < 3; k++) d[k] = xp[k] - xf[k];
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

void mr_taut_set_time(mr_world *w, double t) {
  w->taut_t = t;
}

static mr_string *string_mut(mr_world *w, int i) {
  return &MR_AT(*MR_FORCES(w, STRINGS), mr_string, i);
}

/* The string's geometry and its frame end's motion at w->taut_t. */
static void motion(const mr_world *w, const mr_string *s, const double *x, mr_taut_motion *m) {
  m->len = geometry(s, x, m->d);
  mr_frame_point_motion(w, s->frame_particle, w->taut_t, x, m->vf, m->af);
}

int mr_taut_detect(mr_world *w, const double *x, double gap, mr_contact_list *out) {
  const mr_list *l = MR_FORCES(w, STRINGS);
  for (int i = 0; i < l->n; i++) {
    const mr_string *s = string_at(w, i);
    if (!s->taut) continue;
    double d[3], chi = s->rest - geometry(s, x, d);
    if (chi <= gap || chi != chi)
      if (mr_contact_push(out, MR_CONTACT_STRING, i, -1, 0.0, 0.0) != 0) return -1;
  }
  return 0;
}

double mr_taut_gap(const mr_world *w, int string, const double *x) {
  double d[3];
  const mr_string *s = string_at(w, string);
  return s->rest - geometry(s, x, d);
}

/* χ̇ = −d·(v_p − v_f)/L, 0 for a string of no length. */
static double rate_of(const double d[3], double len, const double *vp, const double vf[3]) {
  if (!(len > 1e-12)) return 0.0;
  return -(d[0] * (vp[0] - vf[0]) + d[1] * (vp[1] - vf[1]) + d[2] * (vp[2] - vf[2])) / len;
}

double mr_taut_rate(const mr_world *w, int string, const double *x, const double *v) {
  const mr_string *s = string_at(w, string);
  double d[3], len = geometry(s, x, d), vf[3];
  mr_frame_point_velocity(w, s->frame_particle, w->taut_t, x, vf);
  return rate_of(d, len, &v[3 * s->puppet_particle], vf);
}

int mr_taut_separating(mr_world *w, int string, const double *x, const double *v,
                       double separating) {
  mr_string *s = string_mut(w, string);
  motion(w, s, x, &s->seen);
  const mr_taut_motion *m = &s->seen;
  return s->rest - m->len >= 0.0 &&
         rate_of(m->d, m->len, &v[3 * s->puppet_particle], m->vf) > separating;
}

/* The row's numbers from the string's motion m, J's entry −u into g
 * when asked. */
static void numbers_of(const mr_string *s, const mr_taut_motion *m, const double *v, double *g,
                       double *chi, double *chidot, double *jdqd) {
  const double len = m->len, *af = m->af;
  double u[3] = { 0, 0, 0 };
  if (len > 1e-12)
    for (int k = 0; k < 3; k++) u[k] = m->d[k] / len;
  if (g)
    for (int k = 0; k < 3; k++) g[k] = -u[k];
  const double *vp = &v[3 * s->puppet_particle];
  double dv[3] = { vp[0] - m->vf[0], vp[1] - m->vf[1], vp[2] - m->vf[2] };
  double rate = u[0] * dv[0] + u[1] * dv[1] + u[2] * dv[2];
  *chi = s->rest - len;
  *chidot = -rate;
  *jdqd =
      (len > 1e-12 ? -(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2] - rate * rate) / len : 0.0) +
      u[0] * af[0] + u[1] * af[1] + u[2] * af[2];
}

/* The row of mr_taut_row from the string's motion m. */
static int row_of(mr_world *w, const mr_string *s, const mr_taut_motion *m, const double *v,
                  double *chi, double *chidot, double *jdqd) {
  double g[3];
  numbers_of(s, m, v, g, chi, chidot, jdqd);
  if (mr_jac_begin_row(&w->J) < 0 || mr_jac_add(&w->J, s->puppet_particle, g) != 0) return -1;
  return 0;
}

int mr_taut_row(mr_world *w, int string, const double *x, const double *v, double *chi,
                double *chidot, double *jdqd) {
  const mr_string *s = string_at(w, string);
  mr_taut_motion m;
  motion(w, s, x, &m);
  return row_of(w, s, &m, v, chi, chidot, jdqd);
}

int mr_taut_row_seen(mr_world *w, int string, const double *v, double *chi, double *chidot,
                     double *jdqd) {
  const mr_string *s = string_at(w, string);
  return row_of(w, s, &s->seen, v, chi, chidot, jdqd);
}

void mr_taut_row_again(const mr_world *w, int string, const double *v, double *chi, double *chidot,
                       double *jdqd) {
  const mr_string *s = string_at(w, string);
  numbers_of(s, &s->seen, v, NULL, chi, chidot, jdqd);
}

/* The lengthening a taut string is left to: a tenth of the §4.5 rule's
 * lower threshold of its rest length. Within it the state is left alone,
 * so that the step's last evaluation serves the next step's first
 * (integrate.c): a projection or an impulse changes the state, and each
 * cost a whole evaluation (the walk's strings took an impulse at 439 of
 * its 445 steps, most of them lengthening slower than 0.1 mm/s). A tenth,
 * because the over-length is part of the error the rule steers by
 * (step.c, end_error): at the lower threshold itself it held the step
 * from growing (the walk took 505 steps instead of 445). */
double mr_taut_hold(const mr_world *w, int string) {
  return 0.1 * w->def.deviation_low * string_at(w, string)->rest;
}

double mr_taut_overlength(const mr_world *w, const double *x) {
  double worst = 0.0;
  if (w->n_taut == 0) return worst;
  const mr_list *l = MR_FORCES(w, STRINGS);
  for (int i = 0; i < l->n; i++) {
    const mr_string *s = string_at(w, i);
    if (!s->taut || !(s->rest > 0)) continue;
    double d[3], over = (geometry(s, x, d) - s->rest) / s->rest;
    if (over > worst || over != over) worst = over;
  }
  return worst;
}

double mr_world_string_stretch(const mr_world *w) {
  if (w == NULL || MR_FORCES(w, STRINGS)->n == 0) return 0.0;
  const mr_list *l = MR_FORCES(w, STRINGS);
  double worst = -INFINITY;
  for (int i = 0; i < l->n; i++) {
    const mr_string *s = string_at(w, i);
    if (!(s->rest > 0)) continue;
    double d[3], r = geometry(s, w->x, d) / s->rest - 1.0;
    if (r > worst) worst = r;
  }
  return worst == -INFINITY ? 0.0 : worst;
}

static const char *const mode_names[] = { "spring", "taut" };

const char *mr_string_mode_name(mr_string_mode m) {
  return (unsigned)m < 2 ? mode_names[m] : "unknown";
}

int mr_string_mode_parse(const char *name, mr_string_mode *out) {
  for (int m = 0; name && m < 2; m++)
    if (strcmp(name, mode_names[m]) == 0) {
      if (out) *out = (mr_string_mode)m;
      return 0;
    }
  return -1;
}

/* Applied forces F_a (§5.1, §6.2). Each kind is one pass; a world's pass
 * list holds only the kinds it declared, so an undeclared effect does not
 * exist in the world rather than being skipped by a test per particle.
 *
 * A kind is: a line in MR_FORCE_KINDS (mr_physics.h), its element struct,
 * its pass (stem_pass), its default maker and its add call, all here. */
#include "internal.h"

#include <math.h>
#include <string.h>

/* ------------------------------------------------------------- elements */

typedef struct mr_spring {
  int a, b;
  double rest, ks, kd;
} mr_spring;
typedef struct mr_antigravity {
  int acted, trigger;
  double d0, fraction, max_scale;
} mr_antigravity;
typedef struct mr_triggered {
  int acted, control, trigger;
  double d0, gain, max_force;
} mr_triggered;
typedef struct mr_sine_spring {
  int a, b;
  double rest, max_force, reach, kd;
} mr_sine_spring;

/* ---------------------------------------------------------------- passes */

static void gravity_pass(mr_world *w, double t, const double *x, const double *v, double *f) {
  (void)t, (void)x, (void)v;
  /* Locals: the stores into f could otherwise be the world's fields. */
  const double g[3] = { w->def.gravity[0], w->def.gravity[1], w->def.gravity[2] };
  const double *mass = w->mass;
  const int n = w->n;
  for (int i = 0; i < n; i++) {
    double m = mass[i];
    f[3 * i + 0] += m * g[0];
    f[3 * i + 1] += m * g[1];
    f[3 * i + 2] += m * g[2];
  }
}

/* Viscous friction F = −drag·v: the paper's default "particle friction". */
static void drag_pass(mr_world *w, double t, const double *x, const double *v, double *f) {
  (void)t, (void)x;
  const double c = w->def.drag, cap = w->drag_rate_cap, *mass = w->mass, *inv_mass = w->inv_mass;
  const int n = w->n;
  for (int i = 0; i < n; i++) {
    if (inv_mass[i] == 0.0) continue;
    /* fmin(c, cap·m) (see mr_forces_stable_dt), inline: a NaN loses. */
    const double y = cap * mass[i];
    const double ci = c != c ? y : (y < c ? y : c);
    f[3 * i] -= ci * v[3 * i];
    f[3 * i + 1] -= ci * v[3 * i + 1];
    f[3 * i + 2] -= ci * v[3 * i + 2];
  }
}

/* Length L, unit direction u = (x_a − x_b)/L and rate L̇ = u·(v_a − v_b). */
static double line(const double *x, const double *v, int a, int b, double u[3], double *rate) {
  const double *xa = x + 3 * a, *xb = x + 3 * b, *va = v + 3 * a, *vb = v + 3 * b;
  const double d[3] = { xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2] };
  const double dv[3] = { va[0] - vb[0], va[1] - vb[1], va[2] - vb[2] };
  double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(len > 1e-12)) {
    u[0] = u[1] = u[2] = 0.0;
    *rate = 0.0;
    return len;
  }
  u[0] = d[0] / len;
  u[1] = d[1] / len;
  u[2] = d[2] / len;
  *rate = u[0] * dv[0] + u[1] * dv[1] + u[2] * dv[2];
  return len;
}

/* Equal and opposite forces s·u on a and −s·u on b. */
static void push_pair(double *f, int a, int b, const double u[3], double s) {
  const double g[3] = { s * u[0], s * u[1], s * u[2] };
  f[3 * a] += g[0];
  f[3 * a + 1] += g[1];
  f[3 * a + 2] += g[2];
  f[3 * b] -= g[0];
  f[3 * b + 1] -= g[1];
  f[3 * b + 2] -= g[2];
}

/* F_a = −(ks (L − rest) + kd L̇) u. */
static void springs_pass(mr_world *w, double t, const double *x, const double *v, double *f) {
  (void)t;
  const mr_list *l = MR_FORCES(w, SPRINGS);
  for (int i = 0; i < l->n; i++) {
    const mr_spring *s = &MR_AT(*l, mr_spring, i);
    double u[3], rate;
    double len = line(x, v, s->a, s->b, u, &rate);
    push_pair(f, s->a, s->b, u, -(s->ks * (len - s->rest) + s->kd * rate));
  }
}

/* A string pulls and never pushes: tension max(0, ks (L − rest) + kd L̇). */
static void strings_pass(mr_world *w, double t, const double *x, const double *v, double *f) {
  (void)t;
  const mr_list *l = MR_FORCES(w, STRINGS);
  for (int i = 0; i < l->n; i++) {
    const mr_string *s = &MR_AT(*l, mr_string, i);
    if (s->taut) continue; /* a contact row, not a force (taut_string.c) */
    double u[3], rate;
    double len = line(x, v, s->puppet_particle, s->frame_particle, u, &rate);
    if (len <= s->rest) continue;
    double tension = s->ks * (len - s->rest) + s->kd * rate;
    if (tension > 0) push_pair(f, s->puppet_particle, s->frame_particle, u, -tension);
  }
}

static double dist(const double *x, int a, int b) {
  double d[3] = { x[3 * a] - x[3 * b], x[3 * a + 1] - x[3 * b + 1], x[3 * a + 2] - x[3 * b + 2] };
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* §6.2: F = −g · fraction · M_puppet · min(d/d0, max_scale). */
static void antigravity_pass(mr_world *w, double t, const double *x, const double *v, double *f) {
  (void)t, (void)v;
  const double *g = w->def.gravity;
  const mr_list *l = MR_FORCES(w, ANTIGRAVITY);
  for (int i = 0; i < l->n; i++) {
    const mr_antigravity *a = &MR_AT(*l, mr_antigravity, i);
    double scale = dist(x, a->trigger, a->acted) / a->d0;
    if (scale > a->max_scale) scale = a->max_scale;
    double s = a->fraction * w->puppet_mass[w->puppet[a->acted]] * scale;
    for (int k = 0; k < 3; k++) f[3 * a->acted + k] -= s * g[k];
  }
}

/* §6.2: F = clamp(gain · M_puppet · (d − d0), ±max) · û(acted → control),
 * d = |x_control − x_trigger|. */
static void triggered_pass(mr_world *w, double t, const double *x, const double *v, double *f) {
  (void)t, (void)v;
  const mr_list *list = MR_FORCES(w, TRIGGERED);
  for (int i = 0; i < list->n; i++) {
    const mr_triggered *a = &MR_AT(*list, mr_triggered, i);
    double s =
        a->gain * w->puppet_mass[w->puppet[a->acted]] * (dist(x, a->control, a->trigger) - a->d0);
    if (s > a->max_force) s = a->max_force;
    if (s < -a->max_force) s = -a->max_force;
    double l = dist(x, a->control, a->acted);
    if (!(l > 1e-12)) continue;
    for (int k = 0; k < 3; k++)
      f[3 * a->acted + k] += s * (x[3 * a->control + k] - x[3 * a->acted + k]) / l;
  }
}

/* §6.2: |F| = max · sin(π/2 · min(|L − rest|/reach, 1)): a shifted sine from
 * 0° to 90°, flat (capped) beyond `reach`, restoring, plus damping. */
static void sine_springs_pass(mr_world *w, double t, const double *x, const double *v, double *f) {
  (void)t;
  const double half_pi = 1.57079632679489661923;
  const mr_list *l = MR_FORCES(w, SINE_SPRINGS);
  for (int i = 0; i < l->n; i++) {
    const mr_sine_spring *s = &MR_AT(*l, mr_sine_spring, i);
    double u[3], rate;
    double delta = line(x, v, s->a, s->b, u, &rate) - s->rest;
    double r = fabs(delta) / s->reach;
    double mag = s->max_force * mr_sin(half_pi * (r < 1 ? r : 1.0));
    push_pair(f, s->a, s->b, u, -(copysign(mag, delta) + s->kd * rate));
  }
}

/* The first two passes when they are gravity and drag (the order of
 * MR_FORCE_KINDS when both are on), on an f not yet zeroed: one loop
 * instead of a memset and two, each sum started from 0 and taken in the
 * order the two passes take it, so the bits are theirs. */
static void gravity_and_drag(mr_world *w, const double *v, double *f) {
  const double g[3] = { w->def.gravity[0], w->def.gravity[1], w->def.gravity[2] };
  const double c = w->def.drag, cap = w->drag_rate_cap, *mass = w->mass, *inv_mass = w->inv_mass;
  const int n = w->n;
  for (int i = 0; i < n; i++) {
    const double m = mass[i];
    double fx = 0.0 + m * g[0], fy = 0.0 + m * g[1], fz = 0.0 + m * g[2];
    if (inv_mass[i] != 0.0) {
      const double y = cap * m;
      const double ci = c != c ? y : (y < c ? y : c);
      fx -= ci * v[3 * i];
      fy -= ci * v[3 * i + 1];
      fz -= ci * v[3 * i + 2];
    }
    f[3 * i] = fx;
    f[3 * i + 1] = fy;
    f[3 * i + 2] = fz;
  }
}

void mr_forces_apply(mr_world *w, double t, const double *x, const double *v, double *f) {
  int p = 0;
  if (w->n_force_passes >= 2 && w->force_passes[0] == gravity_pass &&
      w->force_passes[1] == drag_pass) {
    w->pass_calls[w->force_pass_ids[0]]++;
    w->pass_calls[w->force_pass_ids[1]]++;
    gravity_and_drag(w, v, f);
    p = 2;
  } else {
    memset(f, 0, (size_t)(3 * w->n) * sizeof *f);
  }
  for (; p < w->n_force_passes; p++) {
    w->pass_calls[w->force_pass_ids[p]]++;
    w->force_passes[p](w, t, x, v, f);
  }
}

int mr_forces_build_passes(mr_world *w) {
#define MR_ROW_(id, stem, name) { MR_EFFECT_##id, MR_PASS_##id, stem##_pass },
  static const struct {
    uint32_t effect;
    mr_pass pass;
    mr_force_pass fn;
  } table[] = { MR_FORCE_KINDS(MR_ROW_) };
#undef MR_ROW_
  w->n_force_passes = 0;
  for (size_t i = 0; i < sizeof table / sizeof table[0]; i++) {
    if (!(w->def.effects & table[i].effect)) continue;
    if (w->n_force_passes >= MR_MAX_PASSES) return -1;
    w->force_passes[w->n_force_passes] = table[i].fn;
    w->force_pass_ids[w->n_force_passes] = table[i].pass;
    w->n_force_passes++;
  }
  return 0;
}

/* ------------------------------------------------------- stiff modes */

/* The step rule of §4.5 watches the constraints and the error estimate; a
 * stiff spring on a light particle can still grow without bound between
 * two looks, once h·|λ| leaves the integrator's stability region. The
 * largest |λ| of the linearised applied forces is bounded per particle
 * (Gershgorin on M⁻¹K and M⁻¹C, columns of kinematic particles left out):
 *   ω² ≤ inv_i (Σ k + Σ k of the links whose other end moves),
 *   rate ≤ inv_i (Σ c + the same) + drag·inv_i,
 * and |λ| ≤ max(ω, rate) for x'' + rate x' + ω² x = 0. RK4's region
 * reaches −2.78 on the real axis and ±2.83 on the imaginary one; 2.5 keeps
 * a margin on every ray between. The first-order methods get 2. */
static double reach(const mr_world *w) {
  return w->def.integrator == MR_INTEGRATOR_RK4 ? 2.5 : 2.0;
}

/* A link whose own mode needs a step below `floor` is softened to the
 * limit there (its stiffness and damping scaled down), so that a 1 mg
 * particle on a string cannot demand a million steps a second. Returns 1
 * if it was. */
static int soften(const mr_world *w, int a, int b, double *k, double *c, double floor) {
  double inv = w->inv_mass[a] + w->inv_mass[b], top = reach(w) / floor;
  int changed = 0;
  if (*k * inv > top * top) {
    *k = top * top / inv;
    changed = 1;
  }
  if (*c * inv > top) {
    *c = top / inv;
    changed = 1;
  }
  return changed;
}

/* Adds one link's k and c to its ends' Gershgorin sums (4 per particle:
 * Σk, Σk of moving neighbours, Σc, Σc of moving neighbours). */
static void add_link(const mr_world *w, double *sum, int a, int b, double k, double c) {
  const int ends[2][2] = { { a, b }, { b, a } };
  for (int e = 0; e < 2; e++) {
    int i = ends[e][0], j = ends[e][1];
    int other_moves = w->inv_mass[j] > 0;
    sum[4 * i + 0] += k;
    sum[4 * i + 1] += other_moves ? k : 0.0;
    sum[4 * i + 2] += c;
    sum[4 * i + 3] += other_moves ? c : 0.0;
  }
}

/* Every spring-like link: springs, strings, and sine springs at their
 * steepest (slope max_force·π/2 / reach at rest), softened if need be. */
static int links(mr_world *w, double *sum, double floor) {
  int softened = 0;
  mr_list *l = MR_FORCES(w, SPRINGS);
  for (int i = 0; i < l->n; i++) {
    mr_spring *s = &MR_AT(*l, mr_spring, i);
    softened += soften(w, s->a, s->b, &s->ks, &s->kd, floor);
    add_link(w, sum, s->a, s->b, s->ks, s->kd);
  }
  l = MR_FORCES(w, STRINGS);
  for (int i = 0; i < l->n; i++) {
    mr_string *s = &MR_AT(*l, mr_string, i);
    if (s->taut) continue;
    softened += soften(w, s->puppet_particle, s->frame_particle, &s->ks, &s->kd, floor);
    add_link(w, sum, s->puppet_particle, s->frame_particle, s->ks, s->kd);
  }
  l = MR_FORCES(w, SINE_SPRINGS);
  const double half_pi = 1.57079632679489661923;
  for (int i = 0; i < l->n; i++) {
    mr_sine_spring *s = &MR_AT(*l, mr_sine_spring, i);
    double k = s->max_force * half_pi / s->reach;
    if (soften(w, s->a, s->b, &k, &s->kd, floor)) {
      s->reach = s->max_force * half_pi / k;
      softened++;
    }
    add_link(w, sum, s->a, s->b, k, s->kd);
  }
  return softened;
}

double mr_forces_stable_dt(mr_world *w) {
  const double floor = w->def.dt_floor > 0 ? w->def.dt_floor : 0.01 * w->def.dt_min;
  double *sum = w->scratch.k; /* 24 per particle; 4 used */
  memset(sum, 0, (size_t)w->n * 4 * sizeof *sum);
  int softened = links(w, sum, floor);
  double drag = (w->def.effects & MR_EFFECT_DRAG) ? w->def.drag : 0.0;
  /* Drag too is capped at the floor's rate on a particle light enough. */
  w->drag_rate_cap = reach(w) / floor;
  double top = 0.0;
  for (int i = 0; i < w->n; i++) {
    double inv = w->inv_mass[i];
    if (!(inv > 0)) continue;
    double omega = sqrt(inv * (sum[4 * i] + sum[4 * i + 1]));
    double rate = inv * (sum[4 * i + 2] + sum[4 * i + 3]) + fmin(drag * inv, w->drag_rate_cap);
    top = fmax(top, fmax(omega, rate));
  }
  if (w->def.effects & MR_EFFECT_CONSTRAINTS) /* eq. 8's feedback: C̈ + kd Ċ + ks C = 0 */
    top = fmax(top, fmax(sqrt(w->def.ks), w->def.kd));
  w->stats.softened_forces = (uint64_t)softened;
  return top > 0 ? reach(w) / top : INFINITY;
}

/* ---------------------------------------------------------- add helpers */

/* Two distinct existing particles; fills *len with their distance. */
static mr_status check_pair(mr_world *w, int a, int b, const char *what, double *len) {
  if (mr_check_particle(w, a, what) != 0 || mr_check_particle(w, b, what) != 0) return MR_ERR_ID;
  if (a == b) return mr_fail(w, MR_ERR_ARG, "%s: both ends are particle %d", what, a);
  *len = dist(w->x, a, b);
  return MR_OK;
}

static mr_status check_rest(mr_world *w, const char *what, double rest, double current,
                            double *out) {
  if (!isfinite(rest)) return mr_fail(w, MR_ERR_NONFINITE, "%s: rest length is NaN or Inf", what);
  *out = rest < 0 ? current : rest;
  return MR_OK;
}

static mr_status check_gains(mr_world *w, const char *what, double a, double b) {
  if (!isfinite(a) || !isfinite(b))
    return mr_fail(w, MR_ERR_NONFINITE, "%s: a coefficient is NaN or Inf", what);
  if (a < 0 || b < 0)
    return mr_fail(w, MR_ERR_ARG, "%s: coefficients must be >= 0 (got %g, %g)", what, a, b);
  return MR_OK;
}

/* ----------------------------------------------------------------- kinds */

mr_spring_def mr_default_spring_def(void) {
  return (mr_spring_def){
    .cookie = MR_DEF_COOKIE, .rest_length = -1.0, .stiffness = 100.0, .damping = 1.0
  };
}

mr_status mr_world_add_spring(mr_world *w, const mr_spring_def *def, int *out_id) {
  const char *what = "mr_world_add_spring";
  double len = 0.0, rest = 0.0;
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_SPRINGS, what);
  if (s == MR_OK) s = check_pair(w, def->a, def->b, what, &len);
  if (s == MR_OK) s = check_rest(w, what, def->rest_length, len, &rest);
  if (s == MR_OK) s = check_gains(w, what, def->stiffness, def->damping);
  if (s != MR_OK) return s;
  mr_spring e = { def->a, def->b, rest, def->stiffness, def->damping };
  return mr_add_push(w, MR_FORCES(w, SPRINGS), &e, sizeof e, out_id, what);
}

mr_string_def mr_default_string_def(void) {
  return (mr_string_def){
    .cookie = MR_DEF_COOKIE,
    .rest_length = -1.0,
    .stiffness = 500.0,
    .damping = 5.0,
    .mode = MR_STRING_TAUT,
  };
}

mr_status mr_world_add_string(mr_world *w, const mr_string_def *def, int *out_id) {
  const char *what = "mr_world_add_string";
  double len = 0.0, rest = 0.0;
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_STRINGS, what);
  if (s == MR_OK) s = check_pair(w, def->frame_particle, def->puppet_particle, what, &len);
  if (s != MR_OK) return s;
  if (w->frame[def->frame_particle] < 0)
    return mr_fail(w, MR_ERR_ARG, "%s: particle %d is not on a control frame", what,
                   def->frame_particle);
  if (w->frame[def->puppet_particle] >= 0)
    return mr_fail(w, MR_ERR_ARG, "%s: puppet particle %d is on a control frame", what,
                   def->puppet_particle);
  s = check_rest(w, what, def->rest_length, len, &rest);
  if (s == MR_OK) s = check_gains(w, what, def->stiffness, def->damping);
  if (s != MR_OK) return s;
  if (def->mode != MR_STRING_SPRING && def->mode != MR_STRING_TAUT)
    return mr_fail(w, MR_ERR_ARG, "%s: mode %d is neither spring nor taut", what, (int)def->mode);
  int taut = def->mode == MR_STRING_TAUT;
  if (taut && !(rest > 0))
    return mr_fail(w, MR_ERR_DEGENERATE, "%s: a taut string needs a rest length above 0", what);
  mr_string e = { .frame_particle = def->frame_particle,
                  .puppet_particle = def->puppet_particle,
                  .rest = rest,
                  .ks = def->stiffness,
                  .kd = def->damping,
                  .taut = taut };
  s = mr_add_push(w, MR_FORCES(w, STRINGS), &e, sizeof e, out_id, what);
  if (s == MR_OK && taut) {
    w->n_taut++;
    w->has_solve = 1; /* its rows go through the solve of eq. 8 */
  }
  return s;
}

mr_antigravity_def mr_default_antigravity_def(void) {
  return (mr_antigravity_def){ .cookie = MR_DEF_COOKIE, .fraction = 0.5, .max_scale = 2.0 };
}

mr_status mr_world_add_antigravity(mr_world *w, const mr_antigravity_def *def, int *out_id) {
  const char *what = "mr_world_add_antigravity";
  double d0 = 0.0;
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_ANTIGRAVITY, what);
  if (s == MR_OK) s = check_pair(w, def->acted, def->trigger, what, &d0);
  if (s == MR_OK) s = check_gains(w, what, def->fraction, def->max_scale);
  if (s != MR_OK) return s;
  if (!(d0 > 1e-9))
    return mr_fail(w, MR_ERR_DEGENERATE, "%s: acted %d and trigger %d coincide", what, def->acted,
                   def->trigger);
  mr_antigravity e = { def->acted, def->trigger, d0, def->fraction, def->max_scale };
  return mr_add_push(w, MR_FORCES(w, ANTIGRAVITY), &e, sizeof e, out_id, what);
}

mr_triggered_def mr_default_triggered_def(void) {
  return (mr_triggered_def){ .cookie = MR_DEF_COOKIE, .gain = 10.0, .max_force = 100.0 };
}

mr_status mr_world_add_triggered(mr_world *w, const mr_triggered_def *def, int *out_id) {
  const char *what = "mr_world_add_triggered";
  double d0 = 0.0, unused = 0.0;
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_TRIGGERED, what);
  if (s == MR_OK) s = check_pair(w, def->control, def->trigger, what, &d0);
  if (s == MR_OK) s = check_pair(w, def->acted, def->control, what, &unused);
  if (s == MR_OK) s = check_gains(w, what, def->gain, def->max_force);
  if (s != MR_OK) return s;
  mr_triggered e = { def->acted, def->control, def->trigger, d0, def->gain, def->max_force };
  return mr_add_push(w, MR_FORCES(w, TRIGGERED), &e, sizeof e, out_id, what);
}

mr_sine_spring_def mr_default_sine_spring_def(void) {
  return (mr_sine_spring_def){
    .cookie = MR_DEF_COOKIE, .rest_length = -1.0, .max_force = 50.0, .reach = 0.1, .damping = 1.0
  };
}

mr_status mr_world_add_sine_spring(mr_world *w, const mr_sine_spring_def *def, int *out_id) {
  const char *what = "mr_world_add_sine_spring";
  double len = 0.0, rest = 0.0;
  mr_status s = MR_ADD_CHECK(w, def, MR_EFFECT_SINE_SPRINGS, what);
  if (s == MR_OK) s = check_pair(w, def->a, def->b, what, &len);
  if (s == MR_OK) s = check_rest(w, what, def->rest_length, len, &rest);
  if (s == MR_OK) s = check_gains(w, what, def->max_force, def->damping);
  if (s != MR_OK) return s;
  if (!isfinite(def->reach) || !(def->reach > 0))
    return mr_fail(w, MR_ERR_ARG, "%s: reach must be > 0 (got %g)", what, def->reach);
  mr_sine_spring e = { def->a, def->b, rest, def->max_force, def->reach, def->damping };
  return mr_add_push(w, MR_FORCES(w, SINE_SPRINGS), &e, sizeof e, out_id, what);
}

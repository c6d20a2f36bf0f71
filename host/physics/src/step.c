/* The step, as a list of stages:
 *   1. contacts at the start state: impulses for collisions (eq. 9, 13a),
 *      the rest kept as resting contacts for the force solve (eq. 13b);
 *   2. integrate over Δt (RK4 by default), every stage running the world's
 *      passes and the constraint solve of eq. 8;
 *   3. divergence test (§7): NaN/Inf or a deviation past the hard bound
 *      retries once at the lower bound, then restores the start state;
 *   4. the ATS rule (§4.5) on the largest relative deviation: reject and
 *      retry, or accept and choose the next Δt;
 *   5. penetration test at the end state: if a contact went through, the
 *      state is restored and stepped only to the contact time (§4.5), and
 *      Δt then doubles each step until the ATS rule governs again;
 *   6. post-step passes (string-length correction).
 * mr_world_step_to repeats this and shortens the last step to land exactly
 * on the requested time (§4.6). */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int realloc_d(double **p, size_t n)
{
  double *q = realloc(*p, n * sizeof *q);
  if (!q)
    return -1;
  *p = q;
  return 0;
}

static int ensure_contact_capacity(mr_world *w, const mr_contact_list *l)
{
  if (l->n <= w->cap_active)
    return 0;
  int cap = l->cap;
  unsigned char *a = realloc(w->contact_active, (size_t)cap);
  if (!a)
    return -1;
  w->contact_active = a;
  if (realloc_d(&w->contact_pre, (size_t)cap) != 0 || realloc_d(&w->fric, 3 * (size_t)cap) != 0)
    return -1;
  w->cap_active = cap;
  return 0;
}

/* Derived data: scratch sized to the particles, puppet masses (for the §6.2
 * forces), sphere trees. Rebuilt when elements were added. */
int mr_world_ensure_ready(mr_world *w)
{
  if (!w->dirty && w->cap_scratch >= w->n)
    return 0;
  size_t n3 = (size_t)(w->n > 0 ? w->n : 1) * 3;
  double **arr[] = {&w->f, &w->tmp3n, &w->pa, &w->x0, &w->v0, &w->xs, &w->vs};
  for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++)
    if (realloc_d(arr[i], n3) != 0)
      return -1;
  if (realloc_d(&w->k, 8 * n3) != 0)
    return -1;
  w->cap_scratch = w->n;
  int np = 0;
  for (int i = 0; i < w->n; i++)
    if (w->puppet[i] + 1 > np)
      np = w->puppet[i] + 1;
  free(w->puppet_mass);
  w->puppet_mass = calloc((size_t)(np > 0 ? np : 1), sizeof *w->puppet_mass);
  if (!w->puppet_mass)
    return -1;
  w->npuppets = np;
  for (int i = 0; i < w->n; i++)
    w->puppet_mass[w->puppet[i]] += w->mass[i];
  if (w->def.effects & (MR_EFFECT_SELF_COLLISION | MR_EFFECT_PUPPET_COLLISION))
    if (mr_trees_build(w) != 0)
      return -1;
  w->dirty = 0;
  return 0;
}

static int all_finite(const double *a, int n)
{
  for (int i = 0; i < n; i++)
    if (!isfinite(a[i]))
      return 0;
  return 1;
}

/* §7: back to the start configuration, and carry on. */
static void reset_to_start(mr_world *w, double e)
{
  for (int i = 0; i < w->n; i++) {
    if (w->frame[i] >= 0)
      continue;
    memcpy(&w->x[3 * i], &w->x_start[3 * i], 3 * sizeof(double));
    memcpy(&w->v[3 * i], &w->v_start[3 * i], 3 * sizeof(double));
  }
  mr_frames_place(w, w->t, w->x, w->v);
  w->dt_next = fmin(fmax(w->def.dt_initial, w->def.dt_min), w->def.dt_max);
  w->recovering = 0;
  w->contacts.n = 0;
  w->stats.divergences++;
  if (e == e)
    mr_fail(w, MR_DIVERGED, "t=%.6f s: deviation %.3g passed the divergence bound %.3g; reset to the "
            "start configuration", w->t, e, w->def.divergence_bound);
  else
    mr_fail(w, MR_DIVERGED, "t=%.6f s: the state became NaN or Inf; reset to the start configuration",
            w->t);
}

static double offenders_gap(mr_world *w, const double *x, const unsigned char *valid)
{
  double g = INFINITY;
  for (int i = 0; i < w->probe.n; i++)
    if (valid[i]) {
      double c = mr_contact_gap(w, &w->probe.c[i], x);
      if (c < g || c != c)
        g = c;
    }
  return g;
}

/* A contact went through during [t, t + h]. Find the contact time h* by
 * regula falsi (Illinois) on the smallest gap of the offending contacts,
 * aiming at −slop/2, each trial a full integration from the start state, and
 * leave the state at t + h* in x1, v1 (§4.5, §5.4). Returns h*. */
static double locate_contact(mr_world *w, double t, double h, int *err)
{
  const double slop = w->def.contact_slop, aim = -0.5 * slop;
  /* Its own flags: every trial integration rewrites contact_active. */
  if (w->probe.n > w->cap_valid) {
    unsigned char *p = realloc(w->probe_valid, (size_t)w->probe.cap);
    if (!p) {
      *err = 1;
      return h;
    }
    w->probe_valid = p;
    w->cap_valid = w->probe.cap;
  }
  unsigned char *valid = w->probe_valid;
  int any = 0;
  double g0 = INFINITY;
  for (int i = 0; i < w->probe.n; i++) {
    double c0 = mr_contact_gap(w, &w->probe.c[i], w->x0);
    /* Contacts touching at the start are in the force system (eq. 13b),
     * which pushes them back out; only contacts that were apart can be
     * located in time. Rolling back for a touching one would cut the step
     * to nothing. */
    valid[i] = c0 > slop;
    any |= valid[i];
    if (valid[i] && c0 < g0)
      g0 = c0;
  }
  if (!any)
    return h;
  double lo = 0.0, flo = g0 - aim, hi = h, fhi = offenders_gap(w, w->x1, valid) - aim;
  int side = 0;
  for (int it = 0; it < 24; it++) {
    double hm = hi - fhi * (hi - lo) / (fhi - flo);
    if (!(hm > lo && hm < hi))
      hm = 0.5 * (lo + hi);
    if (mr_integrate(w, t, hm, w->x0, w->v0, w->x1, w->v1) != 0) {
      *err = 1;
      return h;
    }
    double fm = offenders_gap(w, w->x1, valid) - aim;
    if (fabs(fm) <= 0.5 * slop)
      return hm;
    if (fm < 0) {
      hi = hm;
      fhi = fm;
      if (side == -1)
        flo *= 0.5;
      side = -1;
    } else {
      lo = hm;
      flo = fm;
      if (side == 1)
        fhi *= 0.5;
      side = 1;
    }
  }
  /* Not within the slop after all trials: stop just before the contact. */
  double hs = lo > 0 ? lo : hi;
  if (mr_integrate(w, t, hs, w->x0, w->v0, w->x1, w->v1) != 0)
    *err = 1;
  return hs;
}

static void record_step(mr_world *w, double h, double e)
{
  mr_stats *s = &w->stats;
  s->steps++;
  s->last_dt = h;
  if (h < s->min_dt)
    s->min_dt = h;
  if (h > s->max_dt)
    s->max_dt = h;
  s->last_error = e;
  if (e > s->max_error)
    s->max_error = e;
}

/* An inner stage failed: keep the solver's own message, or name memory. */
static mr_status inner_failure(mr_world *w, const char *what)
{
  mr_status s = w->fail;
  w->fail = MR_OK;
  if (s != MR_OK)
    return s;
  return mr_fail(w, MR_ERR_NOMEM, "mr_world_step_to: out of memory (%s)", what);
}

/* Takes steps until t_target (INFINITY: exactly one planned step). */
static mr_status advance(mr_world *w, double t_target, mr_step_report *report)
{
  mr_step_report rep;
  memset(&rep, 0, sizeof rep);
  if (report)
    *report = rep;
  if (mr_world_ensure_ready(w) != 0)
    return mr_fail(w, MR_ERR_NOMEM, "mr_world_step_to: out of memory");
  w->started = 1;
  w->last_dependent = 0;
  const mr_ats_params ats = {w->def.dt_min, w->def.dt_max, w->def.deviation_low, w->def.deviation_high};
  const int colliders = mr_colliders(w);
  const int n3 = 3 * w->n;
  const size_t bytes = (size_t)n3 * sizeof(double);
  const int single = isinf(t_target);
  mr_status result = MR_OK;
  int calls = 0;

  while (single ? calls == 0 : w->t < t_target) {
    if (calls++ >= w->def.max_steps_per_call) {
      if (report)
        *report = rep;
      return mr_fail(w, MR_ERR_LIMIT, "mr_world_step_to: %d steps did not reach t=%.9g s (at %.9g s)",
                     w->def.max_steps_per_call, t_target, w->t);
    }
    const double t = w->t, rem = t_target - t, planned = w->dt_next;
    double h = planned;
    int landing = 0;
    /* Land on the target; never leave a sliver of a step behind it. */
    if (!single && (h >= rem || rem - h < 1e-3 * h)) {
      h = rem;
      landing = 1;
    }
    /* Rounding in t + Δt must not count as a shortened step. */
    int shortened = landing && h < planned * (1.0 - 1e-9);

    /* 1. Contacts at the start state. */
    if (colliders) {
      if (mr_contacts_detect(w, w->x, w->def.contact_slop, &w->contacts) != 0 ||
          ensure_contact_capacity(w, &w->contacts) != 0)
        return mr_fail(w, MR_ERR_NOMEM, "mr_world_step_to: out of memory (contacts)");
      int collided = 0;
      if (mr_impulses_apply(w, t, &collided) != 0)
        return inner_failure(w, "impulses");
      rep.collisions += collided;
      w->stats.resting_contacts = w->contacts.n;
    }
    if (bytes > 0) { /* an empty world has no arrays yet */
      memcpy(w->x0, w->x, bytes);
      memcpy(w->v0, w->v, bytes);
    }

    double e = 0.0;
    mr_ats_decision dec = {1, planned};
    int diverged = 0, rejected_any = 0;
    for (;;) {
      /* 2. Integrate. */
      if (mr_integrate(w, t, h, w->x0, w->v0, w->x1, w->v1) != 0)
        return inner_failure(w, "solve");
      e = mr_constraints_deviation(w, t + h, w->x1);
      /* 3. Divergence. */
      if (!all_finite(w->x1, n3) || !all_finite(w->v1, n3) || !(e <= w->def.divergence_bound)) {
        if (h > w->def.dt_min) {
          h = w->def.dt_min;
          landing = 0;
          w->stats.rejected++;
          rep.rejected++;
          rejected_any = 1;
          continue;
        }
        rep.divergences++;
        result = MR_DIVERGED;
        diverged = 1;
        break;
      }
      /* 4. The ATS rule. */
      dec = mr_ats_next(&ats, h, e);
      if (!dec.accept) {
        w->stats.rejected++;
        rep.rejected++;
        rejected_any = 1;
        h = dec.dt_next;
        landing = !single && h >= t_target - t;
        if (landing)
          h = t_target - t;
        continue;
      }
      break;
    }
    if (diverged) {
      /* The failed step's time passes and the world starts again at its
       * end (frames where the hand is then), so a cause tied to a moment
       * (a curve gone NaN) is left behind. The puppet returns to its start
       * configuration itself, not carried along by the frame: measured on
       * the no-friction extreme case, carrying it under a frame swinging at
       * 11 m/s diverged again more often (21 resets against 13). */
      w->t = landing ? t_target : t + h;
      reset_to_start(w, e);
      continue;
    }

    /* 5. Penetration at the end state. */
    int located = 0;
    if (colliders) {
      if (mr_contacts_detect(w, w->x1, -w->def.contact_slop, &w->probe) != 0)
        return mr_fail(w, MR_ERR_NOMEM, "mr_world_step_to: out of memory (contacts)");
      if (w->probe.n > 0) {
        int err = 0;
        double hc = locate_contact(w, t, h, &err);
        if (err)
          return inner_failure(w, "contact time");
        if (hc < h) {
          located = 1;
          h = hc;
          landing = 0;
          e = mr_constraints_deviation(w, t + h, w->x1);
        }
      }
    }

    /* Accept: the end state becomes the state. */
    double *tx = w->x, *tv = w->v;
    w->x = w->x1;
    w->v = w->v1;
    w->x1 = tx;
    w->v1 = tv;
    w->t = landing ? t_target : t + h;
    rep.steps++;
    record_step(w, h, e);

    /* 6. Post-step passes. */
    if (w->has_string_correction)
      mr_strings_correct(w);

    /* Next Δt. */
    if (located) {
      w->dt_next = fmin(fmax(2.0 * h, 1e-3 * w->def.dt_min), w->def.dt_max);
      w->recovering = 1;
    } else if (w->recovering) {
      double twice = 2.0 * planned;
      if (twice < dec.dt_next) {
        w->dt_next = twice;
      } else {
        w->dt_next = dec.dt_next;
        w->recovering = 0;
      }
    } else if (!shortened || rejected_any) {
      w->dt_next = dec.dt_next;
    }
  }
  rep.dependent = w->last_dependent;
  if (report)
    *report = rep;
  if (result == MR_OK && w->last_dependent > 0) {
    mr_fail(w, MR_DEPENDENT, "%d dependent constraint rows found; their multipliers were set to 0",
            w->last_dependent);
    return MR_DEPENDENT;
  }
  return result;
}

mr_status mr_world_step_to(mr_world *w, double t_target, mr_step_report *report)
{
  if (report)
    memset(report, 0, sizeof *report);
  if (!w)
    return MR_ERR_ARG;
  if (!isfinite(t_target))
    return mr_fail(w, MR_ERR_NONFINITE, "mr_world_step_to: target time is NaN or Inf");
  if (t_target < w->t)
    return mr_fail(w, MR_ERR_TIME, "mr_world_step_to: target %.9g s is before the world time %.9g s",
                   t_target, w->t);
  return advance(w, t_target, report);
}

mr_status mr_world_step(mr_world *w, mr_step_report *report)
{
  if (report)
    memset(report, 0, sizeof *report);
  if (!w)
    return MR_ERR_ARG;
  return advance(w, INFINITY, report);
}

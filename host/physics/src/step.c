/* The step (§4.1, Fig. 4), as its stages. Each evaluation of the
 * equations of motion inside the integrator runs stages 1–4 (eval.c):
 *   1. place the frames;  2. applied forces;  3. constraint rows;
 *   4. the solve (eq. 8).
 * A step around them, here:
 *   6a. contacts at the start state: detect, impulses by eq. 9 (§5.3) for
 *       the colliding ones, the rest held as resting contacts (eq. 13b);
 *   5.  integrate over Δt (RK4 by default, integrate.c);
 *   8.  the divergence check (§7): NaN/Inf or a deviation past the hard
 *       bound retries once at the lower bound, then restores the start;
 *   7.  the ATS decision (§4.5) on the largest relative deviation: reject
 *       and retry shorter, or accept;
 *   6b. collisions over the step: detect a contact gone through at the end
 *       or on the way (a swept test, collide.c), locate its time, roll
 *       back and step only to it (§4.5, §5.4); a touching contact sunk
 *       past the slop and half a millimetre retries the step at half;
 *   then accept, the string-length correction (§6.2), and the next Δt (7):
 *   doubled after a located contact until the ATS rule governs again.
 * mr_world_step takes one step; mr_world_step_to repeats it and shortens
 * the last step to land exactly on the requested time (§4.6). The per-step
 * state lives in an mr_step_ctx; the world keeps only state. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* One step's (or one call's) bookkeeping. */
typedef struct mr_step_ctx {
  /* the call */
  int to_target; /* 1: mr_world_step_to (land on t_target) */
  double t_target;
  mr_step_report rep; /* summed over the call */
  mr_status result;   /* MR_OK, or MR_DIVERGED once a reset happened */
  /* the step under way */
  double t;            /* world time at its start */
  double planned;      /* Δt the ATS chose after the previous step */
  double h;            /* Δt being tried, then taken */
  double asked;        /* the Δt the rule asked for: h, unless h was
                          stretched by a hair to land on t_target */
  int landing;         /* h ends exactly on t_target */
  int shortened;       /* landing cut h below the planned Δt */
  int rejected_any;    /* a try of this step was rejected */
  int located;         /* h was cut to a contact time (§4.5) */
  int sank;            /* a try was cut for a touching contact sinking */
  double error;        /* relative deviation of the end state (§4.5) */
  double int_error;    /* scaled local error estimate (integrate.c) */
  double speed;        /* fastest particle of the end state, m/s */
  int fastest;         /* its id */
  mr_ats_decision dec; /* the ATS rule on the accepted try */
} mr_step_ctx;

/* ------------------------------------------------------------- helpers */

/* §7: back to the start configuration (a puppet hanging from a frame
 * under that frame, restart.c), and carry on. The message names what was
 * seen: a NaN, a particle past max_speed, or the deviation. */
static void reset_to_start(mr_world *w, const mr_step_ctx *c) {
  mr_restart_place(w);
  mr_frames_place(w, w->t, w->x, w->v);
  w->dt_next = fmin(fmax(w->def.dt_initial, w->def.dt_min), w->def.dt_max);
  w->recovering = 0;
  w->contacts.n = 0;
  mr_trees_restore_overlaps(w);
  w->stats.divergences++;
  if (c->speed != c->speed || c->error != c->error)
    mr_fail(w, MR_DIVERGED,
            "t=%.6f s: the state became NaN or Inf; reset to the start configuration", w->t);
  else if (c->speed > w->def.max_speed)
    mr_fail(w, MR_DIVERGED,
            "t=%.6f s: particle %d reached %.3g m/s, past max_speed %.3g m/s; reset to the "
            "start configuration",
            w->t, c->fastest, c->speed, w->def.max_speed);
  else
    mr_fail(w, MR_DIVERGED,
            "t=%.6f s: deviation %.3g passed the divergence bound %.3g; reset to the "
            "start configuration",
            w->t, c->error, w->def.divergence_bound);
}

/* The fastest dynamic particle of (x, v): its speed (NaN if any value is
 * not finite) into c. */
static void fastest(const mr_world *w, const double *x, const double *v, mr_step_ctx *c) {
  c->speed = 0.0;
  c->fastest = -1;
  for (int i = 0; i < w->n; i++) {
    const double *q = &v[3 * i], *p = &x[3 * i];
    if (!isfinite(p[0] + p[1] + p[2]) || !isfinite(q[0] + q[1] + q[2])) {
      c->speed = NAN;
      c->fastest = i;
      return;
    }
    if (!(w->inv_mass[i] > 0)) continue;
    double s = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    if (s > c->speed) {
      c->speed = s;
      c->fastest = i;
    }
  }
}

/* The bounds the ATS works within: the scene's, lowered to the
 * integrator's stability limit where that is shorter (forces.c). */
static mr_ats_params ats_params(const mr_world *w) {
  const mr_ats_params p = { fmin(w->def.dt_min, w->stable_dt), fmin(w->def.dt_max, w->stable_dt),
                            w->def.deviation_low, w->def.deviation_high };
  return p;
}

/* The shortest step the local error estimate may ask for (see
 * ats_decision); forces.c softens what would need less. */
static double floor_dt(const mr_world *w) {
  return fmin(w->def.dt_floor > 0 ? w->def.dt_floor : 0.01 * w->def.dt_min, w->stable_dt);
}

/* h for a retry, and whether it lands: never past the target, and never a
 * sliver short of it. */
static void retry_with(mr_step_ctx *c, double h) {
  c->h = h;
  c->landing = 0;
  if (c->to_target) {
    double rem = c->t_target - c->t;
    if (c->h >= rem || rem - c->h < 1e-3 * c->h) {
      c->h = rem;
      c->landing = 1;
    }
  }
  /* The rule judges the Δt it asked for: a hair's stretch to land is not
   * a longer step to reject again (that would loop at the lower bound). */
  c->asked = fmin(h, c->h);
}

/* An inner stage failed: keep the solver's own message, or name memory. */
static mr_status inner_failure(mr_world *w, const char *what) {
  mr_status s = w->fail;
  w->fail = MR_OK;
  if (s != MR_OK) return s;
  return mr_fail(w, MR_ERR_NOMEM, "mr_world_step_to: out of memory (%s)", what);
}

static void count_rejection(mr_world *w, mr_step_ctx *c) {
  w->stats.rejected++;
  c->rep.rejected++;
  c->rejected_any = 1;
}

/* ---------------------------------------------------------- the stages */

/* Δt for this step: the planned one, or exactly what is left to t_target
 * (never leaving a sliver of a step behind it). Speed alone never shortens
 * it: a contact crossed within the step is found by the swept test (6b),
 * so a fast puppet far from anything keeps its step. */
static void plan(mr_world *w, mr_step_ctx *c) {
  c->t = w->t;
  c->planned = fmin(w->dt_next, w->stable_dt);
  c->h = c->planned;
  c->landing = 0;
  if (c->to_target) {
    double rem = c->t_target - c->t;
    if (c->h >= rem || rem - c->h < 1e-3 * c->h) {
      c->h = rem;
      c->landing = 1;
    }
  }
  c->asked = fmin(c->h, c->planned);
  /* Rounding in t + Δt must not count as a shortened step. */
  c->shortened = c->landing && c->h < c->planned * (1.0 - 1e-9);
  c->rejected_any = 0;
  c->located = 0;
  c->sank = 0;
  c->error = 0.0;
  c->int_error = 0.0;
  c->speed = 0.0;
  c->fastest = -1;
  c->dec = (mr_ats_decision){ 1, c->planned };
}

/* 6a: contacts at the start state; impulses for the colliding ones. */
static mr_status impacts(mr_world *w, mr_step_ctx *c) {
  /* A taut string's frame end moves with the velocity of the frame's new
   * segment from now on: its snap is judged against that one. */
  if (w->n_taut > 0) mr_frames_place(w, c->t, w->x, w->v);
  mr_trees_note_apart(w, w->x);
  if (mr_contacts_detect(w, w->x, w->def.contact_slop, &w->contacts) != 0 ||
      mr_world_contact_capacity(w, w->contacts.n) != 0)
    return mr_fail(w, MR_ERR_NOMEM, "mr_world_step_to: out of memory (contacts)");
  int collided = 0;
  if (mr_impulses_apply(w, c->t, &collided) != 0) return inner_failure(w, "impulses");
  c->rep.collisions += collided;
  w->stats.resting_contacts = w->contacts.n;
  return MR_OK;
}

enum verdict { TRY_ACCEPT, TRY_AGAIN, TRY_DIVERGED };

static mr_status penetration(mr_world *w, mr_step_ctx *c);

/* The end state is finite, within max_speed and within the divergence bound. */
static int sound(const mr_world *w, mr_step_ctx *c) {
  fastest(w, w->x1, w->v1, c);
  return c->speed <= w->def.max_speed && c->error <= w->def.divergence_bound;
}

/* 8: NaN/Inf or a deviation past the bound. Retried once at the lower
 * bound. A step that crossed a contact there (a slack string snapping
 * taut, two parts meeting) can end far off its constraints only because
 * that contact's force was not in it: it is cut to the contact time (6b)
 * and kept if sound there, unless that time is no time at all (under a
 * millionth of the floor step): an end state flung to 1e41 m puts the
 * root of a contact already touching at the start at τ ≈ 1e-37 s, and
 * keeping it stopped the clock, every step cut there again (puppets
 * wedged at the control limits: 1 100 steps of 1e-24 s a second, for
 * ever). Otherwise, when the local error estimate too
 * says the step is too long (a part spinning at 400 rad/s turns 4 rad in
 * a step of dt_min), it is retried once more at the floor that estimate
 * may use (ats_decision), and diverged only if it happens there too. *st:
 * the failure of the cut, else unchanged. */
static enum verdict divergence_check(mr_world *w, mr_step_ctx *c, mr_status *st) {
  if (sound(w, c)) return TRY_ACCEPT;
  double lowest = ats_params(w).dt_min;
  if (c->asked < lowest) lowest = floor_dt(w);
  if (c->asked > lowest) {
    retry_with(c, lowest);
    count_rejection(w, c);
    return TRY_AGAIN;
  }
  if (mr_colliders(w)) {
    if ((*st = penetration(w, c)) != MR_OK) return TRY_DIVERGED;
    if (c->located && c->h > 1e-6 * floor_dt(w) && sound(w, c)) return TRY_ACCEPT;
  }
  if (c->int_error > w->def.deviation_high && c->asked > floor_dt(w)) {
    c->located = 0;
    retry_with(c, floor_dt(w));
    count_rejection(w, c);
    return TRY_AGAIN;
  }
  /* The step's own time passes, not the contact's: a cause that stays
   * (a curve no step follows) would be cut to the same sliver at every
   * reset, and the clock would creep by 1e-22 s a step. */
  c->h = c->asked;
  c->located = 0;
  c->rep.divergences++;
  c->result = MR_DIVERGED;
  return TRY_DIVERGED;
}

/* The relative deviation of an end state (§4.5): the constraints', and
 * the over-length of taut strings, which the rule holds the same way. */
static double end_error(const mr_world *w, double t, const double *x) {
  double e = mr_constraints_deviation(w, t, x);
  if (w->n_taut == 0) return e;
  double o = mr_taut_overlength(w, x);
  return (o > e || o != o) ? o : e;
}

/* 7: the §4.5 rule; a rejected try is retried with the Δt it gives. */
/* The error the rule sees: the worse of the deviation (§4.5) and the local
 * error estimate; NaN wins. */
static double step_error(const mr_step_ctx *c) {
  return (c->int_error > c->error || c->int_error != c->int_error) ? c->int_error : c->error;
}

static int estimating(const mr_world *w) {
  return w->def.error_length > 0 || w->def.error_speed > 0;
}

/* Below dt_min, where only an estimate over `high` can have put it, a
 * step the rule accepts climbs back as a step at dt_min is held: the
 * bound keeps any estimate up to `high` at dt_min, and the aim at `low`
 * never binds there. (A step accepted over `high` is at the floor, where
 * the aim below clamps to it; after a located contact next_dt doubles
 * instead.) Held to `low` below it, with the deviation's
 * dead band keeping Δt, the step crept back by fourth roots: 6 093 of
 * Fig. 10's 8 670 steps ran under dt_min, one stretch of 20 at 8.7 ms with
 * estimates under 10⁻³. So the estimate may lengthen the step towards a
 * quarter of `high`, the deviation going through §4.5's rule alone
 * (Fig. 10: 44 770 evaluations, 49 521 before; aimed at `high` itself,
 * 43 874, but hard case 02 then took 149 136 against 139 304, 136 920
 * before). It never shortens the step (that cost the ball thrown at
 * 40 m/s 22 % more evaluations), nor takes over from the doubling after a
 * located contact (§4.5; the walk took 5 % more). ats: the rule's bounds,
 * down to the floor. */
static double climb(const mr_ats_params *ats, const mr_step_ctx *c) {
  mr_ats_params aim = *ats;
  aim.low = 0.25 * ats->high;
  const double deviation = mr_ats_next(ats, c->asked, c->error).dt_next;
  return fmin(deviation, mr_ats_aim(&aim, c->asked, c->int_error));
}

/* The lower bound is the paper's for the deviation (§7: a real-time
 * budget). A mode it cannot resolve (a light joint between constraints,
 * a chain pulled taut, whose frequency grows with its tension) shows in
 * the local error estimate, not in the deviation, and would blow up at
 * dt_min: for that error alone the step may go down to dt_min/100. */
static enum verdict ats_decision(mr_world *w, mr_step_ctx *c) {
  mr_ats_params ats = ats_params(w);
  if (c->int_error > ats.high || c->asked < ats.dt_min) ats.dt_min = floor_dt(w);
  c->dec = mr_ats_next(&ats, c->asked, step_error(c));
  if (c->dec.accept) {
    if (estimating(w)) {
      mr_ats_params aim = ats_params(w);
      c->dec.dt_next = fmin(c->dec.dt_next, mr_ats_aim(&aim, c->asked, c->int_error));
      if (c->asked < aim.dt_min && !w->recovering)
        c->dec.dt_next = fmax(c->dec.dt_next, climb(&ats, c));
    }
    return TRY_ACCEPT;
  }
  count_rejection(w, c);
  retry_with(c, c->dec.dt_next);
  return TRY_AGAIN;
}

/* 5, 8, 7: integrate from the start state until a try is accepted or the
 * world diverged. MR_OK, or the failure of an inner stage. */
static mr_status integrate_until_accepted(mr_world *w, mr_step_ctx *c, enum verdict *v) {
  for (;;) {
    if (mr_integrate(w, c->t, c->h, w->scratch.x0, w->scratch.v0, w->x1, w->v1, &c->int_error) != 0)
      return inner_failure(w, "solve");
    c->error = end_error(w, c->t + c->h, w->x1);
    mr_status st = MR_OK;
    *v = divergence_check(w, c, &st);
    if (st != MR_OK) return st;
    if (*v == TRY_AGAIN) continue;
    if (*v == TRY_DIVERGED) return MR_OK;
    *v = ats_decision(w, c);
    if (*v == TRY_ACCEPT) return MR_OK;
  }
}

/* The contacts whose swept gap over the step to (x1, v1) may pass −slop. */
static mr_status probe(mr_world *w, const mr_step_ctx *c) {
  const mr_sweep sw = { w->scratch.x0, w->scratch.v0, w->x1, w->v1, c->h };
  if (mr_contacts_sweep(w, &sw, -w->def.contact_slop, &w->probe) != 0 ||
      mr_world_contact_capacity(w, w->probe.n) != 0)
    return mr_fail(w, MR_ERR_NOMEM, "mr_world_step_to: out of memory (contacts)");
  return MR_OK;
}

/* What the step taken leaves deeper than the slop (contacts touching at its
 * start, which are not located): the deepest along the paths between its
 * ends. Every other contact stayed within the slop along the whole step.
 * Strings are over-lengths, not depths. *sunk: how far the deepest of
 * them went past both the slop and half a millimetre (MR_SINK_MAX)
 * and its own depth at the start. */
static double step_depth(mr_world *w, const mr_step_ctx *c, double *sunk) {
  const mr_sweep sw = { w->scratch.x0, w->scratch.v0, w->x1, w->v1, c->h };
  const double limit = w->def.contact_slop + MR_SINK_MAX;
  double deepest = 0.0;
  *sunk = 0.0;
  for (int i = 0; i < w->probe.n; i++)
    if (w->probe.c[i].kind != MR_CONTACT_STRING) {
      const mr_contact *ct = &w->probe.c[i];
      const double d = -mr_contact_swept_gap(w, ct, &sw, 0);
      const double past = d - fmax(limit, -mr_contact_gap(w, ct, sw.x0));
      deepest = fmax(deepest, d);
      *sunk = fmax(*sunk, past);
    }
  return deepest;
}

/* A contact touching at the start is held by the force system (eq. 13b)
 * at the level of accelerations only: over a long step of parts turning
 * fast its spheres still sink into each other (a frame's whole 16.7 ms
 * step: 1.35 mm, against the slop's 0.1), and no deviation shows it. So a
 * step that takes one deeper than the slop and half a millimetre, and
 * deeper than it was, is retried at half its length, down to the floor
 * step: the depth stays within the slop plus 1 mm. (Held to half a
 * millimetre past its own start depth instead, a contact sank a little
 * further at each step: 1.56 mm in five.) A step that sinks one by more
 * than a further half millimetre goes on halving below the floor, down to
 * a thousandth of it: parts squeezed out of a wedge reach hundreds of m/s
 * before the world resets, and at the floor step such a contact went
 * 5.6 mm deep in the last 3 ms (hard case 30, once friction no longer
 * reset it earlier). A contact creeping deeper by less stays with the
 * floor step (retried below it, one pile of five puppets took 15 000
 * more tries and nine times the CPU), and the correction after the step
 * takes it back out to that depth (string_correction.c, deep_contacts,
 * which reads the step's depth kept here). Otherwise the step's depth
 * goes into the stats. */
static int sinks_too_far(mr_world *w, mr_step_ctx *c) {
  double sunk, deepest = step_depth(w, c, &sunk);
  const double floor = floor_dt(w), least = sunk > MR_SINK_MAX ? 1e-3 * floor : floor;
  if (sunk > 0 && c->h > least) {
    c->located = 0;
    c->sank = 1;
    retry_with(c, fmax(0.5 * c->h, c->h > floor ? floor : least));
    count_rejection(w, c);
    return 1;
  }
  w->step_deepest = deepest;
  if (deepest > w->stats.max_penetration) w->stats.max_penetration = deepest;
  return 0;
}

/* 6b: a contact gone through during the step, at its end or on the way:
 * roll back and step only to its time. */
static mr_status penetration(mr_world *w, mr_step_ctx *c) {
  mr_status st = probe(w, c);
  /* Cut back to the first contact, the state at the new end may have
   * another contact gone through (one that was apart at the old end): look
   * again until the end state has none left to locate. */
  for (int round = 0; st == MR_OK && round < 16 && w->probe.n > 0; round++) {
    int err = 0;
    double hc = mr_locate_contact(w, c->t, c->h, &err);
    if (err) return inner_failure(w, "contact time");
    if (!(hc < c->h)) break;
    c->located = 1;
    c->h = hc;
    c->landing = 0;
    c->error = end_error(w, c->t + c->h, w->x1);
    st = probe(w, c);
  }
  return st;
}

static void record_step(mr_world *w, const mr_step_ctx *c) {
  mr_stats *s = &w->stats;
  const double h = c->h, e = c->error;
  s->steps++;
  s->last_dt = h;
  /* A step cut only to land on the requested time is not the rule's
   * choice: it is reported apart, so "dt min" says what the ATS did. */
  if (c->shortened && !c->rejected_any && !c->located) {
    if (h < s->min_dt_landing) s->min_dt_landing = h;
  } else if (h < s->min_dt) {
    s->min_dt = h;
  }
  if (h > s->max_dt) s->max_dt = h;
  s->last_error = e;
  if (e > s->max_error) s->max_error = e;
  if (c->int_error > s->max_integration_error) s->max_integration_error = c->int_error;
}

/* §6.2 [19] on the constraints: a step the rule had to accept with its
 * deviation over the threshold (at the lower bound, or cut to a contact or
 * a landing) is projected back onto the constraints, positions then
 * velocities, and counted; never taken silently. */
static mr_status correct(mr_world *w, mr_step_ctx *c) {
  if (!(c->error > w->def.deviation_high)) return MR_OK;
  double t1 = c->t + c->h;
  int rounds = mr_project_positions(w, t1, w->x1, w->v1, w->def.deviation_low, 20);
  if (rounds < 0 && w->fail != MR_OK) return inner_failure(w, "projection");
  if (mr_project_velocities(w, t1, w->x1, w->v1) != 0) return inner_failure(w, "projection");
  c->error = end_error(w, t1, w->x1);
  w->stats.corrections++;
  c->rep.corrections++;
  return MR_OK;
}

/* The end state becomes the state. */
static void accept(mr_world *w, mr_step_ctx *c) {
  double *tx = w->x, *tv = w->v;
  w->x = w->x1;
  w->v = w->v1;
  w->x1 = tx;
  w->v1 = tv;
  w->t = c->landing ? c->t_target : c->t + c->h;
  c->rep.steps++;
  record_step(w, c);
}

/* 7, second half: the Δt the next step will try. After a located contact
 * it doubles each step "until the allowable error threshold level is
 * reached again" (§4.5): until the rule would shorten the step or rejected
 * a try of it. A rule that only holds Δt (its error between the
 * thresholds) does not stop it: a deviation left by the contact, which no
 * shorter step lowers, would keep Δt at the cut's sliver (two puppets
 * meeting at 10 m/s: 0.2 ms steps for 0.3 s). A step shortened only to land
 * on the target keeps the plan. */
static void next_dt(mr_world *w, const mr_step_ctx *c) {
  const mr_ats_params ats = ats_params(w);
  if (c->located) {
    w->dt_next = fmin(fmax(2.0 * c->h, 1e-3 * ats.dt_min), ats.dt_max);
    w->recovering = 1;
  } else if (w->recovering) {
    double twice = fmin(2.0 * c->planned, ats.dt_max);
    if (!c->rejected_any && c->dec.dt_next >= c->asked && twice < ats.dt_max) {
      w->dt_next = twice;
    } else {
      w->dt_next = fmin(c->dec.dt_next, twice);
      w->recovering = 0;
    }
  } else if (!c->shortened || c->rejected_any) {
    w->dt_next = c->dec.dt_next;
  }
  /* The rule saw only the try kept: a longer one let a contact sink. */
  if (c->sank && w->dt_next > c->h) w->dt_next = c->h;
}

/* One step, every stage. MR_OK (also after a divergence reset, which
 * c->result records), or a failure. */
static mr_status step_once(mr_world *w, mr_step_ctx *c) {
  const int colliders = mr_colliders(w);
  const size_t bytes = (size_t)(3 * w->n) * sizeof(double);
  mr_status st;
  plan(w, c);
  if (colliders && (st = impacts(w, c)) != MR_OK) return st;
  if (bytes > 0) { /* an empty world has no arrays yet */
    memcpy(w->scratch.x0, w->x, bytes);
    memcpy(w->scratch.v0, w->v, bytes);
  }
  enum verdict v;
  do {
    if ((st = integrate_until_accepted(w, c, &v)) != MR_OK) return st;
    if (v == TRY_DIVERGED || !colliders) break;
    if ((st = penetration(w, c)) != MR_OK) return st;
  } while (sinks_too_far(w, c));
  if (v == TRY_DIVERGED) {
    /* The failed step's time passes and the world starts again at its
     * end (frames where the hand is then), so a cause tied to a moment
     * (a curve gone NaN) is left behind. A puppet hanging from a frame
     * starts again under it there (restart.c). */
    w->t = c->landing ? c->t_target : c->t + c->h;
    reset_to_start(w, c);
    return MR_OK;
  }
  if ((st = correct(w, c)) != MR_OK) return st;
  accept(w, c);
  /* The rule has measured the deviation of this state already (end_error:
   * at least the constraints'), unless a landing moved its time. */
  const double known = w->t == c->t + c->h ? c->error : NAN;
  if ((w->has_string_correction || w->n_taut > 0) && mr_strings_correct(w, known) != 0)
    return mr_fail(w, MR_ERR_NOMEM, "mr_world_step_to: out of memory (string-length correction)");
  next_dt(w, c);
  return MR_OK;
}

/* ------------------------------------------------------------ the calls */

static mr_status begin(mr_world *w, mr_step_ctx *c) {
  memset(c, 0, sizeof *c);
  if (mr_world_ensure_ready(w) != 0)
    return mr_fail(w, MR_ERR_NOMEM, "mr_world_step_to: out of memory");
  w->started = 1;
  w->last_dependent = 0;
  return MR_OK;
}

static mr_status finish(mr_world *w, mr_step_ctx *c, mr_step_report *report) {
  c->rep.dependent = w->last_dependent;
  if (report) *report = c->rep;
  if (c->result == MR_OK && w->last_dependent > 0) {
    mr_fail(w, MR_DEPENDENT, "%d dependent constraint rows found; their multipliers were set to 0",
            w->last_dependent);
    return MR_DEPENDENT;
  }
  return c->result;
}

mr_status mr_world_step_to(mr_world *w, double t_target, mr_step_report *report) {
  if (report) memset(report, 0, sizeof *report);
  if (!w) return MR_ERR_ARG;
  if (!isfinite(t_target))
    return mr_fail(w, MR_ERR_NONFINITE, "mr_world_step_to: target time is NaN or Inf");
  if (t_target < w->t)
    return mr_fail(w, MR_ERR_TIME,
                   "mr_world_step_to: target %.9g s is before the world time %.9g s", t_target,
                   w->t);
  mr_step_ctx c;
  mr_status st = begin(w, &c);
  if (st != MR_OK) return st;
  c.to_target = 1;
  c.t_target = t_target;
  for (int calls = 0; w->t < t_target; calls++) {
    if (calls >= w->def.max_steps_per_call) {
      if (report) *report = c.rep;
      return mr_fail(w, MR_ERR_LIMIT,
                     "mr_world_step_to: %d steps did not reach t=%.9g s (at %.9g s)",
                     w->def.max_steps_per_call, t_target, w->t);
    }
    if ((st = step_once(w, &c)) != MR_OK) return st;
  }
  return finish(w, &c, report);
}

mr_status mr_world_step(mr_world *w, mr_step_report *report) {
  if (report) memset(report, 0, sizeof *report);
  if (!w) return MR_ERR_ARG;
  mr_step_ctx c;
  mr_status st = begin(w, &c);
  if (st == MR_OK) st = step_once(w, &c);
  return st == MR_OK ? finish(w, &c, report) : st;
}

/* String-length correction (§6.2, after [19]): springs stretch under the
 * puppet's weight and under fast pulls, which shows as rubbery strings.
 * After each step, every string longer than (1 + max_stretch)·rest is
 * brought back to that length, and the part of the velocity that would
 * lengthen it further is removed (the same principle applied to the
 * damper).
 *
 * A string that is too long becomes, for the correction, one more
 * constraint row beside the puppet's own: C = |x_p − x_f| − max, with
 * J = uᵀ at the puppet particle (the frame end is kinematic). All rows are
 * projected together, by the mass-weighted Newton step of project.c:
 *   Δx = M⁻¹ Jᵀ μ,   (J M⁻¹ Jᵀ) μ = −C.
 * So the puppet moves as a whole towards the frame and its links keep
 * their lengths, instead of one end being dragged off its limb and the
 * limb pulled back after it, which fought each other and tore the links
 * (the sweep this replaces tore a stick marionette's links by 12–19 %).
 * The velocities follow with the rows of the strings at full length that
 * are lengthening: Δv = M⁻¹ Jᵀ ν,  (J M⁻¹ Jᵀ) ν = −Ċ. */
#include "internal.h"

#include <math.h>
#include <string.h>

/* A hair between where a string is taken up and where it is taken to, so
 * that rounding in the projection cannot keep the loop busy. A spring
 * string is aimed that hair inside its limit, so that rounding never
 * leaves it past the limit (a check of 1.01 sees 1.01 at most); a taut
 * string past its hold is taken to its rest length anyway. */
#define OVER 1e-9

/* Whether string i, not released, is over `limit` × rest (positions) or
 * at it and lengthening (velocities, rate > 0), and if so its direction u
 * and the row's right-hand side. */
static int string_row(const mr_world *w, int i, double limit, int velocities, double u[3],
                      double *rhs) {
  const mr_string *s = &MR_AT(*MR_FORCES(w, STRINGS), mr_string, i);
  const double *xp = &w->x[3 * s->puppet_particle], *vp = &w->v[3 * s->puppet_particle];
  const double *xf = &w->x[3 * s->frame_particle], *vf = &w->v[3 * s->frame_particle];
  double d[3] = { xp[0] - xf[0], xp[1] - xf[1], xp[2] - xf[2] };
  double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  /* A taut string past its hold is brought back to its rest length,
   * positions only: its lengthening speed is stopped by the next step's
   * impulse (eq. 9) or its resting row. */
  const double max = s->taut ? s->rest + mr_taut_hold(w, i) : s->rest * limit;
  int held = s->taut ? !velocities : w->has_string_correction;
  if (!held || w->string_released[i] || !(len > 0) || w->inv_mass[s->puppet_particle] == 0.0)
    return 0;
  for (int k = 0; k < 3; k++) u[k] = d[k] / len;
  double rate = u[0] * (vp[0] - vf[0]) + u[1] * (vp[1] - vf[1]) + u[2] * (vp[2] - vf[2]);
  const double over = s->taut ? max * (1.0 + OVER) : max;
  if (velocities ? !(len >= max * (1.0 - 1e-6) && rate > 0) : !(len > over)) return 0;
  *rhs = velocities ? -rate : -(len - (s->taut ? s->rest : max * (1.0 - OVER)));
  return 1;
}

/* Appends a row for each string string_row holds, from row r on; how
 * many. */
static int string_rows(mr_world *w, double limit, int velocities, int r) {
  const int strings = MR_FORCES(w, STRINGS)->n;
  int added = 0;
  for (int i = 0; i < strings; i++) {
    double u[3], rhs;
    if (!string_row(w, i, limit, velocities, u, &rhs)) continue;
    const int particle = MR_AT(*MR_FORCES(w, STRINGS), mr_string, i).puppet_particle;
    if (mr_jac_begin_row(&w->J) < 0 || mr_jac_add(&w->J, particle, u) != 0) return -1;
    w->rhs[r + added] = rhs;
    w->row_contact[r + added] = -1;
    w->string_of_row[added++] = i;
  }
  return added;
}

/* Positions with nothing to do: no string over its length, and the
 * constraints within the ATS's lower threshold. Told before any row is
 * built, which most steps need not (Fig. 10: 1 368 of 2 022 rounds).
 * `known`: a bound on the constraints' deviation of this state, or NaN. */
static int positions_hold(mr_world *w, double limit, double known) {
  const int strings = MR_FORCES(w, STRINGS)->n;
  for (int i = 0; i < strings; i++) {
    double u[3], rhs;
    if (string_row(w, i, limit, 0, u, &rhs)) return 0;
  }
  return mr_constraint_row_count(w) == 0 || known <= w->def.deviation_low ||
         !(mr_constraints_deviation(w, w->t, w->x) > w->def.deviation_low);
}

/* How deep contact c may be when the correction is done: as deep as the
 * slop, or as deep as it was when the correction began, and no deeper.
 * Measured against the start, not against the round before: a round's
 * Newton step is linear, and the puppets it turns far took a held contact
 * 19.7 mm deep (two puppets at the control limits, spring strings held at
 * 1 %), where "as deep as it already is" then kept it, 6.3 mm deep at the
 * step's end. */
static double allowed(const mr_world *w, const mr_contact *c) {
  return fmin(-w->def.contact_slop, mr_contact_gap(w, c, w->scratch.x_held));
}

/* The contacts the projection holds (positions only), from row r on: each
 * goes to the slop when it is shallower, stays where it is down to how
 * deep it may be (allowed), and is taken back to that when deeper; the
 * first held_deep are taken back to the slop and MR_SINK_MAX. How many
 * rows. */
static int held_rows(mr_world *w, int r) {
  const double slop = w->def.contact_slop;
  int added = 0;
  for (int k = 0; k < w->held.n; k++) {
    const mr_contact *c = &w->held.c[k];
    double chi, chidot, jdqd;
    if (mr_contact_row(w, c, w->x, w->v, &chi, &chidot, &jdqd) != 0) return -1;
    w->rhs[r + added] = k < w->held_deep ? -(slop + MR_SINK_MAX) - chi /* to −slop − sink */
                                         : fmax(allowed(w, c) - chi, fmin(0.0, -slop - chi));
    w->row_contact[r + added++] = k;
  }
  return added;
}

static int is_held(const mr_world *w, const mr_contact *c) {
  for (int k = 0; k < w->held.n; k++)
    if (w->held.c[k].kind == c->kind && w->held.c[k].a == c->a && w->held.c[k].b == c->b) return 1;
  return 0;
}

/* The most contacts one projection holds: a pile of puppets touches in a
 * few tens of places. Past it the projection is taken as it comes. */
#define HELD_MAX 256
/* Deeper than that by a rounding is not deeper, m. */
#define DEEPER 1e-9

/* The string rows pull a puppet towards its frames and the links follow,
 * and none of them knows the contacts: a puppet pressed against another or
 * a floor was pushed into it (1.3 mm past the slop, two puppets whose
 * frames jumped at the control limits). The contacts the projection just
 * took past the slop and deeper than they may be (allowed) are added to
 * the held set, to be projected again with them (a taut string over by as
 * much, which the projection has just shortened, would be held from
 * lengthening). How many, or −1. */
static int newly_deep(mr_world *w) {
  const double slop = w->def.contact_slop;
  if (mr_contacts_detect(w, w->x, -slop, &w->held_found) != 0) return -1;
  int added = 0;
  for (int i = 0; i < w->held_found.n && w->held.n < HELD_MAX; i++) {
    const mr_contact *c = &w->held_found.c[i];
    if (is_held(w, c)) continue;
    if (!(mr_contact_gap(w, c, w->x) < allowed(w, c) - DEEPER)) continue;
    if (mr_contact_push(&w->held, c->kind, c->a, c->b, 0.0, 0.0) != 0) return -1;
    added++;
  }
  return added;
}

/* Contacts the step left deeper than the slop and MR_SINK_MAX, into the
 * held set as its first held_deep. A contact touching at a step's start is
 * held at the level of accelerations only, and a step that sinks it past
 * that depth is retried shorter, but not below the floor step (step.c):
 * inside a pile of five puppets one crept 1.56 mm deep that way, a little
 * further at each floor step. Taken back out to that depth after each
 * step, with the links and the strings, it stays there (0.86 mm at most
 * along a step). Looked for only when the step went that deep somewhere
 * (step_deepest): a detection of its own is not free in a pile. −1 when
 * out of memory. */
static int deep_contacts(mr_world *w) {
  const double limit = w->def.contact_slop + MR_SINK_MAX;
  w->held_deep = 0;
  if (!(w->step_deepest > limit) || !mr_colliders(w)) return 0;
  if (mr_contacts_detect(w, w->x, -limit, &w->held_found) != 0) return -1;
  for (int i = 0; i < w->held_found.n && w->held.n < HELD_MAX; i++) {
    const mr_contact *c = &w->held_found.c[i];
    if (c->kind == MR_CONTACT_STRING) continue; /* an over-length: string_rows */
    if (mr_contact_push(&w->held, c->kind, c->a, c->b, 0.0, 0.0) != 0) return -1;
  }
  w->held_deep = w->held.n;
  return 0;
}

/* Applies the solved projection; positions are taken back, and 0
 * returned, when it pushed a contact too deep (newly_deep). A held contact
 * the round's linear step left deeper than it may be is taken back by the
 * next iteration's rows (held_rows); another round from here at once
 * instead reset puppets wedged by their strings, whose contacts cannot all
 * be met. 1, 0 or −1. */
static int apply(mr_world *w, int velocities) {
  if (velocities || !mr_colliders(w)) {
    mr_project_apply(w, velocities ? w->v : w->x);
    return 1;
  }
  const size_t bytes = (size_t)(3 * w->n) * sizeof(double);
  if (!w->held_from) { /* no position has moved yet: this is the start */
    memcpy(w->scratch.x_held, w->x, bytes);
    w->held_from = 1;
  }
  double *before = w->scratch.xs;
  memcpy(before, w->x, bytes);
  mr_project_apply(w, w->x);
  int deep = newly_deep(w);
  if (deep != 0) memcpy(w->x, before, bytes);
  return deep < 0 ? -1 : deep == 0;
}

/* One projection of the constraints and the rows string_rows adds: 1, or
 * 0 when there is nothing to do, or −1. Positions: nothing to do once no
 * string is over and the constraints hold within the ATS's lower
 * threshold (Newton moves the strings' ends along straight lines, so a
 * large correction leaves the links long to second order, and the rounds
 * go on until they hold too). Velocities: always, after positions moved,
 * so that the links' rates agree with their new directions.
 *
 * A string pulls and never pushes: a row whose multiplier would lengthen
 * its string is released and the rest solved again, as a contact that
 * would pull is (eq. 9), so the strings act as the inequalities they are.
 * A contact the projection would push too deep is held at its bound
 * instead (newly_deep), for the rest of this projection: an equality
 * there, which at worst keeps two sides at the slop that the projection
 * would have parted a hair, for the next step's contacts to part. Each
 * round releases a string or holds a new contact, so the rounds end. */
static int project(mr_world *w, double limit, int velocities, double known) {
  int strings = MR_FORCES(w, STRINGS)->n;
  memset(w->string_released, 0, (size_t)strings);
  w->held.n = 0;
  w->held_deep = 0;
  if (!velocities && deep_contacts(w) != 0) return -1;
  if (!velocities && w->held_deep == 0 && positions_hold(w, limit, known)) return 0;
  for (int round = 0; round <= strings + w->held.n; round++) {
    int nc = mr_project_rows(w, w->t, w->x, w->v, strings + w->held.n);
    if (nc < 0) return -1;
    for (int i = 0; i < nc; i++) w->rhs[i] = velocities ? -w->row_cdot[i] : -w->row_c[i];
    int ns = string_rows(w, limit, velocities, nc);
    int nh = ns < 0 ? 0 : held_rows(w, nc + ns); /* none in velocities */
    if (ns < 0 || nh < 0) return -1;
    if (nc + ns + nh == 0 || (ns + nh == 0 && !velocities &&
                              !(mr_constraints_deviation(w, w->t, w->x) > w->def.deviation_low)))
      return 0;
    if (mr_solve_rows(w, 1) != 0) return -1;
    int pushed = 0;
    for (int k = 0; k < ns; k++) /* Δx_p = u·μ/m: μ > 0 lengthens */
      if (w->lambda[nc + k] > 0) {
        w->string_released[w->string_of_row[k]] = 1;
        pushed = 1;
      }
    if (pushed) continue;
    int done = apply(w, velocities);
    if (done != 0) return done;
  }
  return 0;
}

/* The rounds can end with a string a hair over its limit (3.5e-6 of its
 * rest on hard case 19, in 1 479 of its steps): solved with the links, its
 * row nearly depends on theirs and its multiplier comes out lengthening,
 * so it is released, and the links solved without it leave it as it was.
 * A residue within the ATS's lower threshold of its rest is taken up
 * along the string alone: its puppet end moves by micrometres, which
 * leaves the links within that threshold. A larger one stays with the
 * rounds (moving one end far is what tore limbs, above). Whether any
 * string was taken up. */
static int take_up_residue(mr_world *w, double limit) {
  const int strings = MR_FORCES(w, STRINGS)->n;
  int moved = 0;
  memset(w->string_released, 0, (size_t)strings);
  for (int i = 0; i < strings; i++) {
    const mr_string *s = &MR_AT(*MR_FORCES(w, STRINGS), mr_string, i);
    double u[3], rhs;
    if (!string_row(w, i, limit, 0, u, &rhs) || !(-rhs <= w->def.deviation_low * s->rest)) continue;
    double *xp = &w->x[3 * s->puppet_particle];
    for (int k = 0; k < 3; k++) xp[k] += rhs * u[k];
    moved = 1;
  }
  return moved;
}

int mr_strings_correct(mr_world *w, double deviation) {
  /* The pass counter is the string-correction effect's: it counts only when
   * that effect is declared. A world of taut strings without it comes here
   * too, to hold its taut strings at rest length, but that hold is the
   * position half of the taut strings' own constraint (taut_string.c, the
   * STRINGS effect, whose detection, rows and impulses count under no pass
   * either): its spring strings are left uncorrected (string_rows). */
  if (w->has_string_correction) w->pass_calls[MR_PASS_STRING_CORRECTION]++;
  int strings = MR_FORCES(w, STRINGS)->n, cap = w->cap_string_work;
  if (strings == 0) return 0;
  if (mr_grow((void **)&w->string_released, &cap, strings, sizeof *w->string_released) != 0)
    return -1;
  cap = w->cap_string_work;
  if (mr_grow((void **)&w->string_of_row, &cap, strings, sizeof *w->string_of_row) != 0) return -1;
  w->cap_string_work = cap;
  const double limit = 1.0 + w->def.string_max_stretch;
  int moved = 0;
  w->held_from = 0;
  for (int it = 0; it < w->def.string_correction_iterations; it++) {
    if (project(w, limit, 0, moved ? NAN : deviation) <= 0) break;
    moved = 1;
  }
  if ((moved || w->has_string_correction) && take_up_residue(w, limit)) moved = 1;
  if (moved) project(w, limit, 1, NAN);
  return 0;
}

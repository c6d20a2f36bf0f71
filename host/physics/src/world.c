/* The world: creation from a definition, particles, errors, read-out,
 * counters and the state hash. */
#include "internal.h"

/* Near-singular constraint sets (a chain pulled straight between two
 * pins, a flat square kicked out of its plane, a ring closed on a braced
 * square, a light joint between heavy parts): a row whose independent part
 * is below this share of its own effective mass (sin² of its angle to the
 * span of the others) gets a compliance on that direction alone, bounding
 * its multiplier; see host/physics/README.md, "Near-singular constraints". */
#define MR_REG_TOL 1e-4

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *mr_status_name(mr_status s) {
  switch (s) {
  case MR_OK:
    return "ok";
  case MR_DIVERGED:
    return "diverged";
  case MR_DEPENDENT:
    return "dependent constraints";
  case MR_ERR_ARG:
    return "bad argument";
  case MR_ERR_NOMEM:
    return "out of memory";
  case MR_ERR_ID:
    return "unknown id";
  case MR_ERR_NONFINITE:
    return "not finite";
  case MR_ERR_DEGENERATE:
    return "degenerate";
  case MR_ERR_NOT_DECLARED:
    return "effect not declared";
  case MR_ERR_TIME:
    return "time goes backwards";
  case MR_ERR_LIMIT:
    return "step limit";
  case MR_ERR_SOLVER:
    return "solver failed";
  }
  return "unknown status";
}

/* ------------------------------------------------------------ name tables */

#define MR_NAME_(id, stem, name) name,
static const char *const effect_names[MR_EFFECT_COUNT] = { MR_EFFECTS(MR_NAME_) };
static const char *const pass_names[MR_PASS_COUNT] = { "frames",
                                                       MR_FORCE_KINDS(MR_NAME_) "constraints",
                                                       "solve",
                                                       "planes",
                                                       "self-collision",
                                                       "puppet-collision",
                                                       "string-correction" };
#undef MR_NAME_
#define MR_NAME_(id, name) name,
static const char *const integrator_names[MR_INTEGRATOR_COUNT] = { MR_INTEGRATORS(MR_NAME_) };
#undef MR_NAME_

/* Index of name in names[0..n), '_' matching '-'; -1 if absent. */
static int find_name(const char *const *names, int n, const char *name) {
  if (!name) return -1;
  for (int i = 0; i < n; i++) {
    const char *a = names[i], *b = name;
    while (*a && (*a == *b || (*a == '-' && *b == '_'))) {
      a++;
      b++;
    }
    if (*a == '\0' && *b == '\0') return i;
  }
  return -1;
}

const char *mr_effect_name(uint32_t effect) {
  for (int i = 0; i < MR_EFFECT_COUNT; i++)
    if (effect == 1u << i) return effect_names[i];
  return "unknown";
}

int mr_effect_parse(const char *name, uint32_t *out) {
  int i = find_name(effect_names, MR_EFFECT_COUNT, name);
  if (i < 0 || !out) return -1;
  *out = 1u << i;
  return 0;
}

const char *mr_pass_name(mr_pass p) {
  return (unsigned)p < MR_PASS_COUNT ? pass_names[p] : "unknown";
}

int mr_pass_parse(const char *name, mr_pass *out) {
  int i = find_name(pass_names, MR_PASS_COUNT, name);
  if (i < 0 || !out) return -1;
  *out = (mr_pass)i;
  return 0;
}

const char *mr_integrator_name(mr_integrator i) {
  return (unsigned)i < MR_INTEGRATOR_COUNT ? integrator_names[i] : "unknown";
}

int mr_integrator_parse(const char *name, mr_integrator *out) {
  int i = find_name(integrator_names, MR_INTEGRATOR_COUNT, name);
  if (i < 0 || !out) return -1;
  *out = (mr_integrator)i;
  return 0;
}

mr_world_def mr_default_world_def(void) {
  mr_world_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.gravity[1] = -9.81;
  d.effects = MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS;
  d.integrator = MR_INTEGRATOR_RK4;
  /* §7: bounds 0.01–0.05 s, thresholds 0.01 %–1 %, average step ≈ 0.02 s. */
  d.dt_initial = 0.02;
  d.dt_min = 0.01;
  d.dt_max = 0.05;
  d.deviation_low = 1e-4;
  d.deviation_high = 1e-2;
  d.deviation_length = 1.0;
  d.divergence_bound = 0.5;
  d.max_steps_per_call = 1000000;
  /* A local error of 1 % of a metre or of a metre per second per step is
   * rejected, below 0.01 % Δt grows: a puppet a metre tall swinging at a
   * few m/s. At the paper's bounds the puppet's steps stay where the
   * deviation put them (README, "Error control"). */
  d.error_length = 1.0;
  d.error_speed = 1.0;
  /* Puppets and their strings move at a few m/s, a thrown one at up to
   * 40; a light part pinched between a part striking at 40 m/s and its
   * own taut string can take the striker's energy and leave at over
   * 200 m/s (a 12 g ball from a 0.54 kg rod: up to 268). A runaway passes
   * any bound within a few steps. */
  d.max_speed = 1000.0;
  d.solver = MR_SOLVE_LDLT;
  d.solver_tolerance = 1e-10;
  d.solver_max_iterations = 1000;
  /* C̈ + kd Ċ + ks C = 0 with kd = 2√ks: critically damped, ω = 10/s, well
   * inside RK4's stability region at the 0.05 s upper bound (ω·Δt = 0.5). */
  d.ks = 100.0;
  d.kd = 20.0;
  d.drag = 0.1;
  d.contact_slop = 1e-4;
  d.rest_speed = 0.05;
  d.string_max_stretch = 0.1;
  d.string_correction_iterations = 10;
  return d;
}

mr_particle_def mr_default_particle_def(void) {
  mr_particle_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.mass = 1.0;
  d.frame = -1;
  return d;
}

int mr_finite3(const double v[3]) {
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

mr_status mr_fail(mr_world *w, mr_status s, const char *fmt, ...) {
  if (w) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(w->err, sizeof w->err, fmt, ap);
    va_end(ap);
  }
  return s;
}

int mr_grow(void **data, int *cap, int need, size_t elem) {
  if (need <= *cap) return 0;
  int c = *cap ? *cap : 16;
  while (c < need) c *= 2;
  void *p = realloc(*data, (size_t)c * elem);
  if (!p) return -1;
  memset((char *)p + (size_t)*cap * elem, 0, (size_t)(c - *cap) * elem);
  *data = p;
  *cap = c;
  return 0;
}

static mr_status bad_cookie(mr_world *w, const char *what) {
  return mr_fail(w, MR_ERR_ARG,
                 "%s: the definition was not made by its mr_default_..._def() maker (start from "
                 "the maker and change fields, never from {0})",
                 what);
}

mr_status mr_add_check(mr_world *w, const void *def, uint32_t cookie, uint32_t effect,
                       const char *what) {
  if (!w || !def) return mr_fail(w, MR_ERR_ARG, "%s: NULL argument", what);
  if (cookie != MR_DEF_COOKIE) return bad_cookie(w, what);
  if (effect && !(w->def.effects & effect))
    return mr_fail(w, MR_ERR_NOT_DECLARED, "%s: the world does not declare this effect", what);
  return MR_OK;
}

mr_status mr_add_push(mr_world *w, mr_list *list, const void *elem, size_t size, int *out_id,
                      const char *what) {
  if (mr_grow(&list->data, &list->cap, list->n + 1, size) != 0)
    return mr_fail(w, MR_ERR_NOMEM, "%s: out of memory", what);
  memcpy((char *)list->data + (size_t)list->n * size, elem, size);
  if (out_id) *out_id = list->n;
  list->n++;
  w->dirty = 1;
  return MR_OK;
}

int mr_check_particle(mr_world *w, int id, const char *what) {
  if (id < 0 || id >= w->n) {
    mr_fail(w, MR_ERR_ID, "%s: particle %d does not exist (world has %d)", what, id, w->n);
    return -1;
  }
  return 0;
}

static mr_status def_error(char *msg, size_t msg_size, mr_status s, const char *text) {
  if (msg && msg_size) snprintf(msg, msg_size, "mr_world_def: %s", text);
  return s;
}

/* Every field of a world definition in range. MR_OK or the first failure. */
static mr_status check_world_def(const mr_world_def *def, char *msg, size_t msg_size) {
  const double scalars[] = { def->dt_initial,
                             def->dt_min,
                             def->dt_max,
                             def->dt_floor,
                             def->deviation_low,
                             def->deviation_high,
                             def->deviation_length,
                             def->divergence_bound,
                             def->solver_tolerance,
                             def->ks,
                             def->kd,
                             def->drag,
                             def->contact_slop,
                             def->rest_speed,
                             def->string_max_stretch,
                             def->error_length,
                             def->error_speed,
                             def->max_speed };
  for (size_t i = 0; i < sizeof scalars / sizeof scalars[0]; i++)
    if (!isfinite(scalars[i]))
      return def_error(msg, msg_size, MR_ERR_NONFINITE,
                       "a time step, threshold or gain is NaN or Inf");
  if (!mr_finite3(def->gravity))
    return def_error(msg, msg_size, MR_ERR_NONFINITE, "gravity is NaN or Inf");
  if (!(def->dt_min > 0 && def->dt_min <= def->dt_max))
    return def_error(msg, msg_size, MR_ERR_ARG, "need 0 < dt_min <= dt_max");
  if (def->dt_floor < 0 || def->dt_floor > def->dt_min)
    return def_error(msg, msg_size, MR_ERR_ARG, "need 0 <= dt_floor <= dt_min");
  if (!(def->dt_initial > 0)) return def_error(msg, msg_size, MR_ERR_ARG, "need dt_initial > 0");
  if (!(def->deviation_low > 0 && def->deviation_low <= def->deviation_high))
    return def_error(msg, msg_size, MR_ERR_ARG, "need 0 < deviation_low <= deviation_high");
  if (!(def->deviation_length > 0) || !(def->divergence_bound > def->deviation_high))
    return def_error(msg, msg_size, MR_ERR_ARG,
                     "need deviation_length > 0 and divergence_bound > deviation_high");
  if (def->ks < 0 || def->kd < 0 || def->drag < 0 || def->contact_slop <= 0 ||
      def->rest_speed < 0 || def->string_max_stretch < 0 || def->solver_tolerance <= 0)
    return def_error(msg, msg_size, MR_ERR_ARG,
                     "ks, kd, drag, rest_speed and string_max_stretch must be >= 0, "
                     "contact_slop and solver_tolerance > 0");
  if (def->error_length < 0 || def->error_speed < 0 || !(def->max_speed > 0))
    return def_error(msg, msg_size, MR_ERR_ARG,
                     "error_length and error_speed must be >= 0, max_speed > 0");
  if (def->max_steps_per_call < 1 || def->solver_max_iterations < 1 ||
      def->string_correction_iterations < 0)
    return def_error(msg, msg_size, MR_ERR_ARG,
                     "max_steps_per_call and solver_max_iterations must be >= 1");
  if ((unsigned)def->integrator >= MR_INTEGRATOR_COUNT)
    return def_error(msg, msg_size, MR_ERR_ARG, "unknown integrator");
  if ((unsigned)def->solver >= MR_SOLVE_METHOD_COUNT)
    return def_error(msg, msg_size, MR_ERR_ARG, "unknown solver method");
  if (def->effects & ~(uint32_t)MR_EFFECT_ALL)
    return def_error(msg, msg_size, MR_ERR_ARG, "unknown effect bits");
  return MR_OK;
}

mr_status mr_world_create(const mr_world_def *def, mr_world **out_world, char *msg,
                          size_t msg_size) {
  if (out_world) *out_world = NULL;
  if (!def || !out_world)
    return def_error(msg, msg_size, MR_ERR_ARG, "def and out_world must not be NULL");
  if (def->cookie != MR_DEF_COOKIE)
    return def_error(msg, msg_size, MR_ERR_ARG,
                     "not made by mr_default_world_def() (start from the maker, never from {0})");
  mr_status st = check_world_def(def, msg, msg_size);
  if (st != MR_OK) return st;

  mr_world *w = calloc(1, sizeof *w);
  if (!w) return def_error(msg, msg_size, MR_ERR_NOMEM, "out of memory");
  w->def = *def;
  w->solver = mr_solver_create();
  if (!w->solver) {
    free(w);
    return def_error(msg, msg_size, MR_ERR_NOMEM, "out of memory");
  }
  w->opts = mr_default_solve_def();
  w->opts.method = def->solver;
  w->opts.tol = def->solver_tolerance;
  w->opts.max_iter = def->solver_max_iterations;
  w->opts.reg_tol = MR_REG_TOL;
  w->dt_next = fmin(fmax(def->dt_initial, def->dt_min), def->dt_max);
  w->frame_state_t = NAN; /* no frame placed yet */
  w->dirty = 1;           /* derived data and scratch are built at the first step */
  w->stats.min_dt = INFINITY;
  w->stats.min_dt_landing = INFINITY;
  w->stats.stable_dt = INFINITY;
  w->stable_dt = INFINITY;
  w->drag_rate_cap = INFINITY;
  w->has_frames = (def->effects & MR_EFFECT_FRAMES) != 0;
  w->has_solve = (def->effects & (MR_EFFECT_CONSTRAINTS | MR_EFFECT_PLANES |
                                  MR_EFFECT_SELF_COLLISION | MR_EFFECT_PUPPET_COLLISION)) != 0;
  w->has_string_correction =
      (def->effects & MR_EFFECT_STRING_CORRECTION) && (def->effects & MR_EFFECT_STRINGS);
  if (mr_forces_build_passes(w) != 0 || mr_collide_build_passes(w) != 0) {
    mr_world_destroy(w);
    return def_error(msg, msg_size, MR_ERR_ARG, "too many passes");
  }
  *out_world = w;
  return MR_OK;
}

mr_status mr_world_get_def(const mr_world *w, mr_world_def *out) {
  if (w == NULL || out == NULL) return MR_ERR_ARG;
  *out = w->def;
  return MR_OK;
}

void mr_world_destroy(mr_world *w) {
  if (!w) return;
  void *arrays[] = { w->x,
                     w->v,
                     w->mass,
                     w->inv_mass,
                     w->radius,
                     w->x_start,
                     w->v_start,
                     w->local,
                     w->puppet,
                     w->frame,
                     w->frame_state,
                     w->kin_placed,
                     w->puppet_mass,
                     w->carrier,
                     w->part_adjacent,
                     w->built_overlaps,
                     w->tree_stack,
                     w->trees,
                     w->nodes,
                     w->leaf_c,
                     w->contact_active,
                     w->contact_pre,
                     w->probe_valid,
                     w->rhs,
                     w->lambda,
                     w->row_c,
                     w->row_cdot,
                     w->row_bias,
                     w->row_jv,
                     w->row_contact,
                     w->fric_points,
                     w->fric_work,
                     w->reached,
                     w->row_reached,
                     w->x1,
                     w->v1,
                     w->scratch.x0,
                     w->scratch.v0,
                     w->scratch.xs,
                     w->scratch.vs,
                     w->scratch.k,
                     w->scratch.force,
                     w->scratch.constraint_force,
                     w->scratch.acc_try,
                     w->scratch.impact_momentum,
                     w->scratch.impact_dv,
                     w->scratch.v_try,
                     w->scratch.x_held };
  for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) free(arrays[i]);
  for (int i = 0; i < w->curves.n; i++) {
    free(MR_AT(w->curves, mr_curve, i).times);
    free(MR_AT(w->curves, mr_curve, i).points);
  }
  mr_list *lists[] = { &w->frames, &w->kin,    &w->distances, &w->pins,
                       &w->curves, &w->planes, &w->parts,     &w->leaves };
  for (size_t i = 0; i < sizeof lists / sizeof lists[0]; i++) free(lists[i]->data);
  for (int i = 0; i < MR_FORCE_KIND_COUNT; i++) free(w->forces[i].data);
  mr_contact_list_free(&w->contacts);
  mr_contact_list_free(&w->probe);
  mr_contact_list_free(&w->measured);
  mr_contact_list_free(&w->held);
  mr_contact_list_free(&w->held_found);
  mr_eval_memo_free(&w->memo);
  free(w->string_released);
  free(w->string_of_row);
  mr_jac_free(&w->J);
  mr_jac_free(&w->island_J);
  void *blocks[] = { w->island_of,    w->island_parent, w->island_local, w->island_mass,
                     w->island_start, w->island_key,    w->island_rows,  w->island_contact,
                     w->island_b,     w->island_x };
  for (size_t i = 0; i < sizeof blocks / sizeof blocks[0]; i++) free(blocks[i]);
  mr_csr_free(&w->A);
  mr_solver_destroy(w->solver);
  free(w);
}

const char *mr_world_last_error(const mr_world *w) {
  return w ? w->err : "no world";
}

/* Grows every per-particle array to hold n + 1 particles. x1 and v1 trade
 * places with x and v on every accepted step, so they grow with them. */
static int grow_particles(mr_world *w) {
  struct {
    void **p;
    size_t size;
  } arr[] = {
    { (void **)&w->x, 3 * sizeof(double) },       { (void **)&w->v, 3 * sizeof(double) },
    { (void **)&w->x1, 3 * sizeof(double) },      { (void **)&w->v1, 3 * sizeof(double) },
    { (void **)&w->x_start, 3 * sizeof(double) }, { (void **)&w->v_start, 3 * sizeof(double) },
    { (void **)&w->local, 3 * sizeof(double) },   { (void **)&w->mass, sizeof(double) },
    { (void **)&w->inv_mass, sizeof(double) },    { (void **)&w->radius, sizeof(double) },
    { (void **)&w->puppet, sizeof(int) },         { (void **)&w->frame, sizeof(int) }
  };
  int cap = w->cap_n;
  for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) {
    cap = w->cap_n;
    if (mr_grow(arr[i].p, &cap, w->n + 1, arr[i].size) != 0) return -1;
  }
  w->cap_n = cap;
  return 0;
}

mr_status mr_world_add_particle(mr_world *w, const mr_particle_def *def, int *out_id) {
  mr_status st = MR_ADD_CHECK(w, def, 0, "mr_world_add_particle");
  if (st != MR_OK) return st;
  int id = w->n;
  if (!mr_finite3(def->position) || !mr_finite3(def->velocity) || !isfinite(def->radius) ||
      !isfinite(def->mass))
    return mr_fail(w, MR_ERR_NONFINITE,
                   "particle %d: position, velocity, mass or radius is NaN or Inf", id);
  if (def->radius < 0)
    return mr_fail(w, MR_ERR_ARG, "particle %d: radius %g is negative", id, def->radius);
  if (def->puppet < 0)
    return mr_fail(w, MR_ERR_ARG, "particle %d: puppet id %d is negative", id, def->puppet);
  if (def->frame >= 0) {
    if (def->frame >= w->frames.n)
      return mr_fail(w, MR_ERR_ID, "particle %d: frame %d does not exist", id, def->frame);
  } else if (def->frame != -1) {
    return mr_fail(w, MR_ERR_ID, "particle %d: frame %d is neither -1 nor a frame id", id,
                   def->frame);
  } else if (!(def->mass > 0)) {
    return mr_fail(w, MR_ERR_ARG, "particle %d: mass %g must be > 0", id, def->mass);
  }
  if (grow_particles(w) != 0 ||
      (def->frame >= 0 && mr_grow(&w->kin.data, &w->kin.cap, w->kin.n + 1, sizeof(int)) != 0))
    return mr_fail(w, MR_ERR_NOMEM, "particle %d: out of memory", id);
  int kin = def->frame >= 0;
  for (int k = 0; k < 3; k++) {
    w->x[3 * id + k] = def->position[k];
    w->v[3 * id + k] = kin ? 0.0 : def->velocity[k];
    w->local[3 * id + k] = 0.0;
  }
  w->mass[id] = kin ? 0.0 : def->mass;
  w->inv_mass[id] = kin ? 0.0 : 1.0 / def->mass;
  w->radius[id] = def->radius;
  w->puppet[id] = def->puppet;
  w->frame[id] = def->frame;
  if (kin) {
    /* local = R(q)ᵀ (x − p) for the frame's pose at the world's time. */
    mr_pose pose;
    double vel[3], om[3], d[3];
    mr_frame_eval(&MR_AT(w->frames, mr_frame, def->frame), w->t, &pose, vel, om);
    for (int k = 0; k < 3; k++) d[k] = def->position[k] - pose.position[k];
    mr_pose_unrotate(pose.orientation, d, &w->local[3 * id]);
    MR_AT(w->kin, int, w->kin.n++) = id;
    w->n = id + 1;
    if (w->has_frames) mr_frame_place_one(w, id);
  }
  memcpy(&w->x_start[3 * id], &w->x[3 * id], 3 * sizeof(double));
  memcpy(&w->v_start[3 * id], &w->v[3 * id], 3 * sizeof(double));
  w->n = id + 1;
  w->dirty = 1;
  if (out_id) *out_id = id;
  return MR_OK;
}

int mr_world_particle_count(const mr_world *w) {
  return w ? w->n : 0;
}

mr_status mr_world_particle_state(const mr_world *w, int id, double pos[3], double vel[3]) {
  if (!w) return MR_ERR_ARG;
  if (id < 0 || id >= w->n) return MR_ERR_ID;
  for (int k = 0; k < 3; k++) {
    if (pos) pos[k] = w->x[3 * id + k];
    if (vel) vel[k] = w->v[3 * id + k];
  }
  return MR_OK;
}

int mr_world_positions(const mr_world *w, double *xyz, int count) {
  if (!w || !xyz || count <= 0) return 0;
  int m = count < w->n ? count : w->n;
  memcpy(xyz, w->x, (size_t)m * 3 * sizeof(double));
  return m;
}

mr_status mr_world_set_particle_state(mr_world *w, int id, const double pos[3],
                                      const double vel[3]) {
  if (!w || !pos || !vel)
    return mr_fail(w, MR_ERR_ARG, "mr_world_set_particle_state: NULL argument");
  if (mr_check_particle(w, id, "mr_world_set_particle_state") != 0) return MR_ERR_ID;
  if (!mr_finite3(pos) || !mr_finite3(vel))
    return mr_fail(w, MR_ERR_NONFINITE, "mr_world_set_particle_state: particle %d: NaN or Inf", id);
  if (w->frame[id] >= 0)
    return mr_fail(w, MR_ERR_ARG, "mr_world_set_particle_state: particle %d is carried by frame %d",
                   id, w->frame[id]);
  memcpy(&w->x[3 * id], pos, 3 * sizeof(double));
  memcpy(&w->v[3 * id], vel, 3 * sizeof(double));
  if (!w->started) {
    memcpy(&w->x_start[3 * id], pos, 3 * sizeof(double));
    memcpy(&w->v_start[3 * id], vel, 3 * sizeof(double));
  }
  return MR_OK;
}

double mr_world_time(const mr_world *w) {
  return w ? w->t : 0.0;
}

double mr_world_next_dt(const mr_world *w) {
  return w ? w->dt_next : 0.0;
}

mr_status mr_world_stats(const mr_world *w, mr_stats *out) {
  if (!w || !out) return MR_ERR_ARG;
  *out = w->stats;
  if (w->stats.steps == 0) out->min_dt = 0.0;
  return MR_OK;
}

uint64_t mr_world_pass_calls(const mr_world *w, mr_pass p) {
  if (!w || (unsigned)p >= MR_PASS_COUNT) return 0;
  return w->pass_calls[p];
}

static uint64_t fnv1a(uint64_t h, const void *data, size_t len) {
  const unsigned char *b = data;
  for (size_t i = 0; i < len; i++) {
    h ^= b[i];
    h *= 1099511628211ull;
  }
  return h;
}

uint64_t mr_world_state_hash(const mr_world *w) {
  uint64_t h = 14695981039346656037ull;
  if (!w) return h;
  h = fnv1a(h, &w->t, sizeof w->t);
  if (w->n > 0) {
    h = fnv1a(h, w->x, (size_t)w->n * 3 * sizeof(double));
    h = fnv1a(h, w->v, (size_t)w->n * 3 * sizeof(double));
  }
  return h;
}

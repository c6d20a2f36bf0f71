/* A headless run: the control track sampled at the scene's frame rate,
 * the world stepped one ATS step at a time in between (§4.5, §4.6), and the
 * numbers `marionette sim` prints gathered on the way. */
#include "mr_sim.h"
#include "mr_theater.h"
#include "theater_internal.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Steps closer than this to a frame time land on it instead of leaving a
 * sliver of a step behind. */
#define LAND_S 1e-9

mr_sim_def mr_default_sim_def(void) {
  mr_sim_def o;
  memset(&o, 0, sizeof o);
  o.cookie = MR_DEF_COOKIE;
  o.present = MR_PRESENT_SCENE;
  return o;
}

const char *mr_present_mode_name(mr_present_mode m) {
  switch (m) {
  case MR_PRESENT_LAND:
    return "land";
  case MR_PRESENT_INTERPOLATE:
    return "interpolate";
  default:
    return "scene";
  }
}

int mr_present_mode_parse(const char *name, mr_present_mode *out) {
  if (name == NULL || out == NULL) return -1;
  if (strcmp(name, "land") == 0)
    *out = MR_PRESENT_LAND;
  else if (strcmp(name, "interpolate") == 0)
    *out = MR_PRESENT_INTERPOLATE;
  else
    return -1;
  return 0;
}

static bool state_finite(const double *xyz, int n) {
  for (int i = 0; i < 3 * n; i++)
    if (!isfinite(xyz[i])) return false;
  return true;
}

static double max_speed(const mr_scene_world *sw) {
  double m = 0;
  for (size_t i = 0; i < sw->n_particles; i++) {
    double v[3];
    if (mr_world_particle_state(sw->world, sw->particle_ids[i], NULL, v) == MR_OK)
      m = fmax(m, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  }
  return m;
}

/* A string's length: from its control point to its particle. */
static double string_length(const mr_scene_world *sw, const mr_string_def *str) {
  double a[3], b[3];
  if (mr_world_particle_state(sw->world, str->frame_particle, a, NULL) != MR_OK ||
      mr_world_particle_state(sw->world, str->puppet_particle, b, NULL) != MR_OK)
    return NAN;
  double d[3] = { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* Each force's string rest length: the file's, else the length at the
 * start, as the physics takes it; 0 for other forces. */
static void string_rests(const mr_scene *s, const mr_scene_world *sw, double *rest) {
  for (size_t i = 0; i < s->n_forces; i++) {
    const mr_string_def *str = &s->forces[i].def.string;
    rest[i] = s->forces[i].kind != MR_EFFECT_STRINGS ? 0.0
              : str->rest_length >= 0                ? str->rest_length
                                                     : string_length(sw, str);
  }
}

/* How far the most stretched string is past its rest length, as a ratio
 * of its length to its rest. A string of rest 0 has no ratio. */
static double string_stretch(const mr_scene *s, const mr_scene_world *sw, const double *rest) {
  double m = 0;
  for (size_t i = 0; i < s->n_forces; i++)
    if (rest[i] > 0) m = fmax(m, string_length(sw, &s->forces[i].def.string) / rest[i]);
  return m;
}

typedef struct watcher {
  const mr_scene_expect *e;
  const mr_scene_world *sw;
  double *anchor; /* watched positions at `settle` */
  bool anchored;
} watcher;

static void watch(watcher *w, double t, mr_sim_result *r) {
  const mr_scene_expect *e = w->e;
  if (e->n_watch == 0 || !(t >= e->settle)) return;
  for (size_t k = 0; k < e->n_watch; k++) {
    double p[3], v[3];
    mr_world_particle_state(w->sw->world, e->watch[k], p, v);
    if (!w->anchored) {
      memcpy(&w->anchor[3 * k], p, sizeof p);
      continue;
    }
    double d[3] = { p[0] - w->anchor[3 * k], p[1] - w->anchor[3 * k + 1],
                    p[2] - w->anchor[3 * k + 2] };
    r->creep = fmax(r->creep, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    r->jitter = fmax(r->jitter, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  }
  w->anchored = true;
}

/* Each frame heads for its track's pose at time t (§6.2). */
static void place_frames(const mr_scene *s, mr_scene_world *sw, double t) {
  for (size_t k = 0; k < sw->n_frames; k++) {
    mr_pose goal;
    mr_scene_frame_pose_at(s, k, t, &goal);
    mr_theater_head_frame(s, sw, k, goal, t);
  }
}

/* The same at the end of a step the ATS chose in a run without frames,
 * arriving at the track's own rates there (mr_theater_track_frame). Runs
 * in frames keep the parabola's slopes for now: landing on frame times,
 * the track's rates moved the wedged puppets of hard case 30 onto a path
 * that resets (a squeeze, host/physics/README.md); interpolating, they
 * parted the walk from the landed one by 36 mm (theater_present), as the
 * two presentations then follow two paths. */
static void place_frames_at_step(const mr_scene *s, mr_scene_world *sw, double t) {
  for (size_t k = 0; k < sw->n_frames; k++) mr_theater_track_frame(s, sw, k, t);
}

static mr_scene_status run_fail(const mr_scene *s, mr_scene_error *err, mr_scene_status st,
                                const char *msg, double t) {
  err->status = st;
  snprintf(err->message, sizeof err->message, "%.280s at t = %.6f s", msg, t);
  snprintf(err->text, sizeof err->text, "%s: %s", s->path, err->message);
  return st;
}

/* One run in progress: the world, where the result gathers, and the
 * running sums the means are made from at the end. */
typedef struct run {
  const mr_scene *s;
  const mr_sim_def *opts;
  mr_sim_result *r;
  mr_scene_world sw;
  double duration, fps, dt_max;
  double *xyz;  /* positions, to check every state is finite */
  double *rest; /* per force: a string's rest length, else 0 */
  int n;
  watcher w;
  double sum_dt, sum_err2;
  uint64_t at_upper;
  double t;         /* world time reached */
  bool interpolate; /* frames between steps (sim.present) */
  mr_interp ip;
  double sum_lead;
  mr_scene_error *err; /* where a failure inside a frame goes */
  mr_scene_status rc;  /* a failure inside a frame */
} run;

static mr_scene_status run_open(run *u, mr_scene_error *err) {
  const mr_scene *s = u->s;
  mr_scene_status rc = mr_scene_build(s, &u->sw, err);
  if (rc != MR_SCENE_OK) return rc;
  u->duration = u->opts && u->opts->duration > 0 ? u->opts->duration : s->duration;
  u->fps = u->opts && u->opts->fps > 0 ? u->opts->fps : s->fps;
  u->dt_max = s->world.dt_max;
  mr_present_mode mode = u->opts ? u->opts->present : MR_PRESENT_SCENE;
  u->interpolate = u->fps > 0 &&
                   (mode == MR_PRESENT_INTERPOLATE || (mode == MR_PRESENT_SCENE && s->interpolate));
  const double *from = u->opts ? u->opts->start_state : NULL;
  for (size_t i = 0; from != NULL && i < u->sw.n_particles; i++)
    if (mr_world_set_particle_state(u->sw.world, u->sw.particle_ids[i], from + 6 * i,
                                    from + 6 * i + 3) != MR_OK) {
      char msg[300];
      snprintf(msg, sizeof msg, "the start state of particle %s: %s", s->particles[i].name,
               mr_world_last_error(u->sw.world));
      return run_fail(s, err, MR_SCENE_ERR_VALUE, msg, 0);
    }
  u->n = mr_world_particle_count(u->sw.world);
  u->xyz = calloc((size_t)(u->n > 0 ? u->n : 1) * 3, sizeof *u->xyz);
  if (u->xyz != NULL) mr_world_positions(u->sw.world, u->xyz, u->n);
  if (mr_interp_open(&u->ip, u->n) != 0)
    return run_fail(s, err, MR_SCENE_ERR_NOMEM, "out of memory", 0);
  u->rest = calloc(s->n_forces ? s->n_forces : 1, sizeof *u->rest);
  if (u->rest != NULL) string_rests(s, &u->sw, u->rest);
  double *anchor = calloc(s->expect.n_watch ? 3 * s->expect.n_watch : 1, sizeof *anchor);
  u->w = (watcher){ &s->expect, &u->sw, anchor, false };
  if (u->xyz == NULL || u->rest == NULL || anchor == NULL)
    return run_fail(s, err, MR_SCENE_ERR_NOMEM, "out of memory", 0);
  return MR_SCENE_OK;
}

static void run_close(run *u) {
  mr_interp_close(&u->ip);
  free(u->xyz);
  free(u->rest);
  free(u->w.anchor);
  mr_scene_world_free(&u->sw);
}

/* Folds one step call into the result and returns its trace row. */
static mr_sim_step record(run *u, const mr_step_report *rep) {
  mr_sim_result *r = u->r;
  mr_stats stats;
  mr_world_stats(u->sw.world, &stats);
  mr_sim_step row = {
    mr_world_time(u->sw.world), stats.last_dt,    stats.last_error, rep->steps, rep->rejected,
    rep->divergences,           max_speed(&u->sw)
  };
  mr_world_positions(u->sw.world, u->xyz, u->n);
  if (!state_finite(u->xyz, u->n) || !isfinite(row.error) || !isfinite(row.max_speed))
    r->finite = false;
  r->string_stretch = fmax(r->string_stretch, string_stretch(u->s, &u->sw, u->rest));
  if (isfinite(row.max_speed)) r->max_speed = fmax(r->max_speed, row.max_speed);
  /* The world's own account covers every step of the call and the paths
   * between their ends, where they went deeper than the slop. */
  r->max_penetration =
      fmax(fmax(r->max_penetration, mr_world_penetration(u->sw.world)), stats.max_penetration);
  r->steps += (uint64_t)rep->steps;
  r->rejected += (uint64_t)rep->rejected;
  if (rep->divergences > 0 && r->resets == 0)
    snprintf(r->first_reset, sizeof r->first_reset, "%s", mr_world_last_error(u->sw.world));
  r->resets += (uint64_t)rep->divergences;
  r->collisions += (uint64_t)rep->collisions;
  if (rep->dependent > r->dependent_rows) r->dependent_rows = rep->dependent;
  if (rep->steps > 0 && isfinite(row.dt)) {
    u->sum_dt += row.dt * rep->steps;
    r->dt_max = fmax(r->dt_max, row.dt);
    if (row.dt >= u->dt_max * (1 - 1e-9)) u->at_upper += (uint64_t)rep->steps;
  }
  if (isfinite(row.error)) {
    r->max_deviation = fmax(r->max_deviation, row.error);
    u->sum_err2 += row.error * row.error * rep->steps;
  }
  return row;
}

/* One step call towards target (landing on it when land); fails only when
 * the physics stopped outright or the run passed its step guard. */
static mr_scene_status step_once(run *u, double target, bool land, double *t, mr_scene_error *err) {
  mr_step_report rep;
  memset(&rep, 0, sizeof rep);
  mr_status st =
      land ? mr_world_step_to(u->sw.world, target, &rep) : mr_world_step(u->sw.world, &rep);
  u->r->last_status = st;
  if (st < 0) {
    char msg[400];
    snprintf(msg, sizeof msg, "the physics stopped (%s): %s", mr_status_name(st),
             mr_world_last_error(u->sw.world));
    return run_fail(u->s, err, MR_SCENE_ERR_BUILD, msg, *t);
  }
  mr_sim_step row = record(u, &rep);
  if (u->r->steps + u->r->rejected > (uint64_t)u->s->max_steps) {
    char msg[300];
    snprintf(msg, sizeof msg,
             "stopped after %" PRIu64 " step tries, past sim.max_steps (%ld); the time step "
             "settings ask for more steps than a run may take",
             u->r->steps + u->r->rejected, u->s->max_steps);
    return run_fail(u->s, err, MR_SCENE_ERR_BUILD, msg, row.t);
  }
  *t = row.t;
  watch(&u->w, *t, u->r);
  if (u->opts && u->opts->on_step) u->opts->on_step(u->opts->user, &row);
  return MR_SCENE_OK;
}

/* Steps from *t to `end`, one ATS step at a time so the trace sees each;
 * the step that would pass `end` lands on it instead. Without a frame
 * rate the track is sampled at the end of every step, so the ATS alone
 * chooses Δt (§4.5). */
static mr_scene_status step_to(run *u, double *t, double end, bool sample_each,
                               mr_scene_error *err) {
  mr_scene_status rc = MR_SCENE_OK;
  while (*t < end - LAND_S && rc == MR_SCENE_OK) {
    double target = *t + mr_world_next_dt(u->sw.world);
    bool land = target > end - LAND_S;
    if (land) target = end;
    if (sample_each) place_frames_at_step(u->s, &u->sw, target);
    rc = step_once(u, target, land, t, err);
  }
  return rc;
}

/* Steps from *t at the ATS's own Δt until a step passes `end` (the
 * interpolated presentation), the frames heading for the track's pose at
 * each step's end; only the run's own end is landed on. */
static mr_scene_status step_past(run *u, double *t, double end, mr_scene_error *err) {
  mr_scene_status rc = MR_SCENE_OK;
  while (*t < end - LAND_S && rc == MR_SCENE_OK) {
    double target = *t + mr_world_next_dt(u->sw.world);
    bool land = target > u->duration - LAND_S;
    if (land) target = u->duration;
    place_frames(u->s, &u->sw, target);
    mr_interp_mark(&u->ip, u->sw.world);
    rc = step_once(u, target, land, t, err);
  }
  return rc;
}

/* The frame at t as presented, to the caller's hook. */
static void frame_out(run *u, double t) {
  const double *xyz = u->xyz;
  if (u->interpolate) {
    xyz = mr_interp_at(&u->ip, u->sw.world, t);
    u->sum_lead += u->ip.lead;
    u->r->lead_max = fmax(u->r->lead_max, u->ip.lead);
  }
  if (u->opts != NULL && u->opts->on_frame != NULL) u->opts->on_frame(u->opts->user, t, xyz, u->n);
}

/* The scheduler's advance hook: the frame at time t (k/fps, §4.6) is
 * sampled from the track and the world stepped to land on it, as in the
 * theater, or past it when frames are interpolated. Nonzero ends the run:
 * its end reached, or a failure (kept in u->rc). */
static int advance_frame(void *user, double t, mr_frame_work *work) {
  run *u = user;
  double now = mr_world_time(u->sw.world), t_frame = fmin(t, u->duration);
  uint64_t steps = u->r->steps, rejected = u->r->rejected, resets = u->r->resets;
  if (u->interpolate) {
    u->rc = step_past(u, &now, t_frame, u->err);
  } else if (t_frame > now + LAND_S) {
    place_frames(u->s, &u->sw, t_frame);
    u->rc = step_to(u, &now, t_frame, false, u->err);
  }
  if (u->rc == MR_SCENE_OK) frame_out(u, t_frame);
  work->steps = u->r->steps - steps;
  work->rejected = u->r->rejected - rejected;
  work->resets = u->r->resets - resets;
  u->t = now;
  /* Ends with the frame at the run's end: interpolated frames may find
   * the physics there before them. */
  return u->rc != MR_SCENE_OK || !(t_frame < u->duration - LAND_S);
}

static void present_nothing(void *user, double t) {
  (void)user, (void)t;
}

/* The frames, paced by the theater's scheduler on a virtual clock: the
 * same loop as a show, only as fast as the physics goes. */
static mr_scene_status run_frames(run *u) {
  mr_virtual_clock vc = { 0.0 };
  mr_clock clock = mr_clock_virtual(&vc);
  mr_scheduler_def def = mr_default_scheduler_def();
  def.fps = u->fps;
  mr_scheduler_hooks hooks = { advance_frame, present_nothing, u };
  mr_scheduler *sch = NULL;
  char msg[200];
  if (mr_scheduler_create(&def, &clock, &hooks, &sch, msg, sizeof msg) != MR_THEATER_OK)
    return run_fail(u->s, u->err, MR_SCENE_ERR_BUILD, msg, 0);
  while (mr_scheduler_tick(sch) == MR_THEATER_OK) {
  }
  mr_scheduler_stats st;
  mr_scheduler_get_stats(sch, &st);
  u->r->frames = st.frames_simulated;
  u->r->fps = u->fps;
  u->r->interpolated = u->interpolate;
  if (u->interpolate && st.frames_simulated > 0)
    u->r->lead_mean = u->sum_lead / (double)st.frames_simulated;
  mr_scheduler_destroy(sch);
  return u->rc;
}

static void run_finish(run *u, double t) {
  mr_sim_result *r = u->r;
  r->sim_time = t;
  mr_stats st;
  mr_world_stats(u->sw.world, &st);
  r->dt_min = isfinite(st.min_dt) && st.steps > 0 ? st.min_dt : 0.0;
  r->dt_min_landing = isfinite(st.min_dt_landing) ? st.min_dt_landing : 0.0;
  r->stable_dt = isfinite(st.stable_dt) ? st.stable_dt : 0.0;
  r->corrections = st.corrections;
  r->softened_forces = st.softened_forces;
  if (r->steps > 0) {
    r->dt_mean = u->sum_dt / (double)r->steps;
    r->rms_deviation = sqrt(u->sum_err2 / (double)r->steps);
    r->at_upper_fraction = (double)u->at_upper / (double)r->steps;
  }
  for (int p = 0; p < MR_PASS_COUNT; p++)
    r->pass_calls[p] = mr_world_pass_calls(u->sw.world, (mr_pass)p);
  r->hash = mr_world_state_hash(u->sw.world);
}

mr_scene_status mr_sim_run(const mr_scene *s, const mr_sim_def *opts, mr_sim_result *r,
                           mr_scene_error *err) {
  memset(r, 0, sizeof *r);
  r->finite = true;
  r->dt_min = INFINITY;
  if (opts != NULL && opts->cookie != MR_DEF_COOKIE) {
    err->status = MR_SCENE_ERR_VALUE;
    snprintf(err->message, sizeof err->message, "the sim def was not made by mr_default_sim_def");
    snprintf(err->text, sizeof err->text, "%s: %s", s->path, err->message);
    return err->status;
  }
  run u;
  memset(&u, 0, sizeof u);
  u.s = s;
  u.opts = opts;
  u.r = r;
  mr_scene_status rc = run_open(&u, err);
  if (rc != MR_SCENE_OK) {
    run_close(&u);
    return rc;
  }
  /* A run that cannot finish within the guard is refused before it
   * starts, not after millions of steps: it needs at least duration/dt_max
   * steps, and with a frame rate at least one per frame. */
  double least = fmax(u.duration / u.dt_max, u.fps > 0 ? u.duration * u.fps : 0.0);
  if (least > (double)s->max_steps) {
    char msg[300];
    snprintf(msg, sizeof msg,
             "refused: %g s at steps of at most %g s needs at least %.3g steps, past "
             "sim.max_steps (%ld); raise dt_max or max_steps, or shorten the run",
             u.duration, u.dt_max, least, s->max_steps);
    rc = run_fail(s, err, MR_SCENE_ERR_BUILD, msg, 0);
    run_close(&u);
    return rc;
  }
  u.t = mr_world_time(u.sw.world);
  u.err = err;
  watch(&u.w, u.t, r);
  if (u.fps > 0)
    rc = run_frames(&u);
  else
    rc = step_to(&u, &u.t, u.duration, true, err);
  run_finish(&u, u.t);
  for (size_t i = 0; opts != NULL && opts->end_state != NULL && i < u.sw.n_particles; i++)
    mr_world_particle_state(u.sw.world, u.sw.particle_ids[i], opts->end_state + 6 * i,
                            opts->end_state + 6 * i + 3);
  run_close(&u);
  return rc;
}

int mr_sim_check(const mr_scene *s, const mr_sim_result *r, char *msg, size_t msg_size) {
  const mr_scene_expect *e = &s->expect;
  if (e->has_load_error) {
    snprintf(msg, msg_size, "expected the load to fail with \"%s\", but the scene loaded",
             e->load_error);
    return -1;
  }
  if (e->finite && !r->finite) {
    snprintf(msg, msg_size, "expected a finite state throughout, got NaN or Inf");
    return -1;
  }
  if (!isnan(e->max_deviation) && !(r->max_deviation <= e->max_deviation)) {
    snprintf(msg, msg_size, "expected max deviation <= %g, got %g", e->max_deviation,
             r->max_deviation);
    return -1;
  }
  if (e->resets_min >= 0 && r->resets < (uint64_t)e->resets_min) {
    snprintf(msg, msg_size, "expected at least %ld resets, got %llu", e->resets_min,
             (unsigned long long)r->resets);
    return -1;
  }
  if (e->resets_max >= 0 && r->resets > (uint64_t)e->resets_max) {
    snprintf(msg, msg_size, "expected at most %ld resets, got %llu", e->resets_max,
             (unsigned long long)r->resets);
    return -1;
  }
  if (!isnan(e->min_mean_dt) && !(r->dt_mean >= e->min_mean_dt)) {
    snprintf(msg, msg_size, "expected mean dt >= %g s, got %g s", e->min_mean_dt, r->dt_mean);
    return -1;
  }
  if (!isnan(e->min_string_stretch) && !(r->string_stretch >= e->min_string_stretch)) {
    snprintf(msg, msg_size, "expected a string stretched to >= %g x its rest length, got %.9g x",
             e->min_string_stretch, r->string_stretch);
    return -1;
  }
  if (!isnan(e->max_string_stretch) && !(r->string_stretch <= e->max_string_stretch)) {
    snprintf(msg, msg_size, "expected every string within %g x its rest length, got %.9g x",
             e->max_string_stretch, r->string_stretch);
    return -1;
  }
  if (!isnan(e->max_speed) && !(r->max_speed <= e->max_speed)) {
    snprintf(msg, msg_size, "expected speeds <= %g m/s, got %g m/s", e->max_speed, r->max_speed);
    return -1;
  }
  if (!isnan(e->max_penetration) && !(r->max_penetration <= e->max_penetration)) {
    snprintf(msg, msg_size, "expected penetration <= %g m, got %g m", e->max_penetration,
             r->max_penetration);
    return -1;
  }
  if (!isnan(e->creep) && !(r->creep <= e->creep)) {
    snprintf(msg, msg_size, "expected creep <= %g m after %g s, got %g m", e->creep, e->settle,
             r->creep);
    return -1;
  }
  if (!isnan(e->jitter) && !(r->jitter <= e->jitter)) {
    snprintf(msg, msg_size, "expected speeds <= %g m/s after %g s (no jitter), got %g m/s",
             e->jitter, e->settle, r->jitter);
    return -1;
  }
  /* The pin holds for a run of the scene's own length only. */
  if (e->has_state_hash && r->sim_time == s->duration && r->hash != e->state_hash) {
    snprintf(msg, msg_size, "expected state hash 0x%016" PRIx64 ", got 0x%016" PRIx64,
             e->state_hash, r->hash);
    return -1;
  }
  if (msg_size > 0) msg[0] = '\0';
  return 0;
}

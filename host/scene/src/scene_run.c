/* A headless run: the control track sampled at the scene's frame rate,
 * the world stepped one ATS step at a time in between (§4.5, §4.6), and the
 * numbers `marionette sim` prints gathered on the way. */
#include "mr_scene_world.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Steps closer than this to a frame time land on it instead of leaving a
 * sliver of a step behind. */
#define LAND_S 1e-9

static bool state_finite(const double *xyz, int n) {
  for (int i = 0; i < 3 * n; i++)
    if (!isfinite(xyz[i]))
      return false;
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

/* How far the most stretched string is past its rest length, as a ratio:
 * the distance from its control point to its particle over its rest. Only
 * strings whose file states a rest length above 0 have a ratio. */
static double string_stretch(const mr_scene *s, const mr_scene_world *sw) {
  double m = 0;
  for (size_t i = 0; i < s->n_strings; i++) {
    const mr_scene_string *str = &s->strings[i];
    double a[3], b[3];
    if (!(str->rest > 0))
      continue;
    if (mr_world_particle_state(sw->world, sw->control_ids[str->control], a, NULL) != MR_OK ||
        mr_world_particle_state(sw->world, sw->particle_ids[str->particle], b, NULL) != MR_OK)
      continue;
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    m = fmax(m, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / str->rest);
  }
  return m;
}

typedef struct watcher {
  const mr_scene_expect *e;
  const mr_scene_world *sw;
  double *anchor; /* watched positions at `settle` */
  bool anchored;
} watcher;

static void watch(watcher *w, double t, mr_scene_run_result *r) {
  const mr_scene_expect *e = w->e;
  if (e->n_watch == 0 || !(t >= e->settle))
    return;
  for (size_t k = 0; k < e->n_watch; k++) {
    double p[3], v[3];
    mr_world_particle_state(w->sw->world, w->sw->particle_ids[e->watch[k]], p, v);
    if (!w->anchored) {
      memcpy(&w->anchor[3 * k], p, sizeof p);
      continue;
    }
    double d[3] = {p[0] - w->anchor[3 * k], p[1] - w->anchor[3 * k + 1],
                   p[2] - w->anchor[3 * k + 2]};
    r->creep = fmax(r->creep, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    r->jitter = fmax(r->jitter, sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  }
  w->anchored = true;
}

/* The frame heads for the track's pose at time t, reached at t (§6.2). */
static void place_frame(const mr_scene *s, mr_scene_world *sw, double t) {
  mr_scene_pose pose;
  mr_scene_control_pose_at(s, t, &pose);
  mr_pose goal = mr_scene_pose_to_physics(&pose);
  mr_world_set_frame_target(sw->world, sw->frame, &goal, t);
}

static mr_scene_status run_fail(const mr_scene *s, mr_scene_error *err, mr_scene_status st,
                                const char *msg, double t) {
  err->status = st;
  snprintf(err->message, sizeof err->message, "%.280s at t = %.6f s", msg, t);
  snprintf(err->text, sizeof err->text, "%s: %s", s->path, err->message);
  return st;
}

mr_scene_status mr_scene_run(const mr_scene *s, const mr_scene_run_opts *opts,
                             mr_scene_run_result *r, mr_scene_error *err) {
  memset(r, 0, sizeof *r);
  r->finite = true;
  r->dt_min = INFINITY;
  mr_scene_world sw;
  mr_scene_status rc = mr_scene_build(s, &sw, err);
  if (rc != MR_SCENE_OK)
    return rc;
  double duration = opts && opts->duration > 0 ? opts->duration : s->duration;
  double fps = s->fps;
  mr_world_def def = mr_default_world_def();
  double dt_max = isnan(s->settings.dt_max) ? def.dt_max : s->settings.dt_max;
  int n = mr_world_particle_count(sw.world);
  double *xyz = malloc((size_t)(n > 0 ? n : 1) * 3 * sizeof *xyz);
  double *anchor = calloc(s->expect.n_watch ? 3 * s->expect.n_watch : 1, sizeof *anchor);
  if (xyz == NULL || anchor == NULL) {
    free(xyz);
    free(anchor);
    mr_scene_world_free(&sw);
    return run_fail(s, err, MR_SCENE_ERR_NOMEM, "out of memory", 0);
  }
  watcher w = {&s->expect, &sw, anchor, false};
  double sum_dt = 0, sum_err2 = 0;
  uint64_t at_upper = 0;
  double t = mr_world_time(sw.world);
  watch(&w, t, r);
  /* Without a frame rate the track is sampled at the end of every step, so
   * the ATS alone chooses Δt (§4.5). With one, steps land on the frame
   * times k/fps (§4.6) and the frame moves linearly between samples, as in
   * the theater. Frame times are k/fps, not a running sum, so long runs land
   * exactly. */
  long frame_k = 0;
  double t_frame = -1.0;
  while (t < duration - LAND_S && rc == MR_SCENE_OK) {
    double target = t + mr_world_next_dt(sw.world);
    double end = duration;
    if (fps > 0) {
      if (!(t_frame > t + LAND_S)) {
        frame_k++;
        t_frame = fmin((double)frame_k / fps, duration);
        if (sw.frame >= 0)
          place_frame(s, &sw, t_frame);
      }
      end = t_frame;
    }
    /* One ATS step at a time, so the trace sees each; the step that would
     * pass a frame time or the end lands on it instead. */
    bool land = target > end - LAND_S;
    if (land)
      target = end;
    if (fps <= 0 && sw.frame >= 0)
      place_frame(s, &sw, target);
    mr_step_report rep;
    memset(&rep, 0, sizeof rep);
    mr_status st = land ? mr_world_step_to(sw.world, target, &rep) : mr_world_step(sw.world, &rep);
    r->last_status = st;
    if (st < 0) {
      char msg[400];
      snprintf(msg, sizeof msg, "the physics stopped (%s): %s", mr_status_name(st),
               mr_world_last_error(sw.world));
      rc = run_fail(s, err, MR_SCENE_ERR_BUILD, msg, t);
      break;
    }
    t = mr_world_time(sw.world);
    mr_stats stats;
    mr_world_stats(sw.world, &stats);
    mr_scene_step row = {t, stats.last_dt, stats.last_error, rep.steps, rep.rejected,
                         rep.divergences > 0, 0};
    mr_world_positions(sw.world, xyz, n);
    if (!state_finite(xyz, n) || !isfinite(row.error))
      r->finite = false;
    row.max_speed = max_speed(&sw);
    r->string_stretch = fmax(r->string_stretch, string_stretch(s, &sw));
    if (!isfinite(row.max_speed))
      r->finite = false;
    r->steps += (uint64_t)rep.steps;
    r->rejected += (uint64_t)rep.rejected;
    if (rep.divergences > 0 && r->resets == 0)
      snprintf(r->first_reset, sizeof r->first_reset, "%s", mr_world_last_error(sw.world));
    r->resets += (uint64_t)rep.divergences;
    r->collisions += (uint64_t)rep.collisions;
    if (rep.dependent > r->dependent_rows)
      r->dependent_rows = rep.dependent;
    if (rep.steps > 0 && isfinite(row.dt)) {
      sum_dt += row.dt * rep.steps;
      r->dt_min = fmin(r->dt_min, row.dt);
      r->dt_max = fmax(r->dt_max, row.dt);
      if (row.dt >= dt_max * (1 - 1e-9))
        at_upper += (uint64_t)rep.steps;
    }
    if (isfinite(row.error)) {
      r->max_deviation = fmax(r->max_deviation, row.error);
      sum_err2 += row.error * row.error * rep.steps;
    }
    watch(&w, t, r);
    if (opts && opts->on_step)
      opts->on_step(opts->user, &row);
  }
  r->sim_time = t;
  if (r->steps > 0) {
    r->dt_mean = sum_dt / (double)r->steps;
    r->rms_deviation = sqrt(sum_err2 / (double)r->steps);
    r->at_upper_fraction = (double)at_upper / (double)r->steps;
  } else {
    r->dt_min = 0;
  }
  for (int p = 0; p < MR_PASS_COUNT; p++)
    r->pass_calls[p] = mr_world_pass_calls(sw.world, (mr_pass)p);
  r->hash = mr_world_state_hash(sw.world);
  free(xyz);
  free(anchor);
  mr_scene_world_free(&sw);
  return rc;
}

int mr_scene_check(const mr_scene *s, const mr_scene_run_result *r, char *why, size_t size) {
  const mr_scene_expect *e = &s->expect;
  if (e->has_load_error) {
    snprintf(why, size, "expected the load to fail with \"%s\", but the scene loaded",
             e->load_error);
    return -1;
  }
  if (e->finite && !r->finite) {
    snprintf(why, size, "expected a finite state throughout, got NaN or Inf");
    return -1;
  }
  if (!isnan(e->max_deviation) && !(r->max_deviation <= e->max_deviation)) {
    snprintf(why, size, "expected max deviation <= %g, got %g", e->max_deviation,
             r->max_deviation);
    return -1;
  }
  if (e->resets_min >= 0 && r->resets < (uint64_t)e->resets_min) {
    snprintf(why, size, "expected at least %ld resets, got %llu", e->resets_min,
             (unsigned long long)r->resets);
    return -1;
  }
  if (e->resets_max >= 0 && r->resets > (uint64_t)e->resets_max) {
    snprintf(why, size, "expected at most %ld resets, got %llu", e->resets_max,
             (unsigned long long)r->resets);
    return -1;
  }
  if (!isnan(e->min_mean_dt) && !(r->dt_mean >= e->min_mean_dt)) {
    snprintf(why, size, "expected mean dt >= %g s, got %g s", e->min_mean_dt, r->dt_mean);
    return -1;
  }
  if (!isnan(e->min_string_stretch) && !(r->string_stretch >= e->min_string_stretch)) {
    snprintf(why, size, "expected a string stretched to >= %g x its rest length, got %g x",
             e->min_string_stretch, r->string_stretch);
    return -1;
  }
  if (!isnan(e->creep) && !(r->creep <= e->creep)) {
    snprintf(why, size, "expected creep <= %g m after %g s, got %g m", e->creep, e->settle,
             r->creep);
    return -1;
  }
  if (!isnan(e->jitter) && !(r->jitter <= e->jitter)) {
    snprintf(why, size, "expected speeds <= %g m/s after %g s (no jitter), got %g m/s",
             e->jitter, e->settle, r->jitter);
    return -1;
  }
  if (size > 0)
    why[0] = '\0';
  return 0;
}

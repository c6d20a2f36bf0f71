/* A live show: glove → control mapping → control frame → physics, paced by
 * the frame scheduler (§4.6, §6.2). */
#include "mr_show.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mr_control.h"
#include "mr_io.h"
#include "theater_internal.h"

typedef struct show {
  const mr_scene *scene;
  mr_scene_world sw;
  mr_glove *glove;
  mr_control *control;
  mr_scheduler *sch;
  mr_clock clock;
  const mr_show_hooks *hooks;
  mr_pose target; /* where the control frame heads */
  double duration;
  uint64_t samples_seen;
  mr_rec_writer take;
  bool recording, take_open;
  char take_error[320];
  mr_scene_error *err;
  mr_scene_status rc;
} show;

mr_show_def mr_default_show_def(void) {
  mr_show_def d = { MR_SHOW_COOKIE, MR_POLICY_SKIP, 0.0, 0.0, NULL };
  return d;
}

static mr_scene_status fail(show *s, mr_scene_status st, const char *msg) {
  s->err->status = st;
  snprintf(s->err->message, sizeof s->err->message, "%.300s", msg);
  snprintf(s->err->text, sizeof s->err->text, "%s: %s", s->scene->path, s->err->message);
  s->rc = st;
  return st;
}

/* The glove's newest values, if any came, through the mapping. */
static void read_glove(show *s, double now) {
  mr_glove_poll(s->glove, now, 0);
  mr_glove_reading r;
  mr_glove_latest(s->glove, &r);
  if (r.samples == s->samples_seen || mr_glove_state_get(s->glove) != MR_GLOVE_LIVE) return;
  s->samples_seen = r.samples;
  /* Read at the start of this frame's work: the latency counters run from
   * here to the frame's presentation, on the show's clock. */
  mr_scheduler_note_input(s->sch, s->clock.now(s->clock.self));
  mr_pose pose;
  if (mr_control_update(s->control, r.values, r.host_t, &pose, NULL) == MR_CONTROL_OK)
    s->target = pose;
}

/* The glove's bytes into the take, stamped with show time. */
static void record(void *user, double now, const uint8_t *bytes, size_t len) {
  show *s = user;
  if (!s->recording) return;
  mr_io_err err;
  uint64_t t_ns = now > 0 ? (uint64_t)llround(now * 1e9) : 0;
  if (mr_rec_writer_add(&s->take, t_ns, bytes, len, &err) != 0) {
    snprintf(s->take_error, sizeof s->take_error, "%s", err.msg);
    s->recording = false;
  }
}

static int advance(void *user, double t, mr_frame_work *work) {
  show *s = user;
  read_glove(s, t);
  mr_world *w = s->sw.world;
  if (t > mr_world_time(w)) {
    if (s->sw.frame >= 0) mr_theater_head_frame(s->scene, &s->sw, s->target, t);
    mr_step_report rep;
    memset(&rep, 0, sizeof rep);
    mr_status st = mr_world_step_to(w, t, &rep);
    if (st < 0) {
      char msg[400];
      snprintf(msg, sizeof msg, "the physics stopped (%s): %s at t = %.3f s", mr_status_name(st),
               mr_world_last_error(w), t);
      fail(s, MR_SCENE_ERR_BUILD, msg);
      return 1;
    }
    work->steps = (uint64_t)rep.steps;
    work->rejected = (uint64_t)rep.rejected;
    work->resets = (uint64_t)rep.divergences;
  }
  if (s->hooks != NULL && s->hooks->frame_done != NULL)
    s->hooks->frame_done(s->hooks->user, t, mr_world_state_hash(w));
  /* Stopping ends the show after this frame: the scheduler counts it as
   * simulated, and it was. */
  if (s->hooks != NULL && s->hooks->stop != NULL && s->hooks->stop(s->hooks->user)) return 1;
  if (s->duration > 0) return t >= s->duration;
  return mr_glove_take_done(s->glove) && mr_glove_state_get(s->glove) == MR_GLOVE_LOST;
}

static void present(void *user, double t) {
  show *s = user;
  if (s->hooks == NULL || s->hooks->present == NULL) return;
  mr_show_frame f = { t, s->target, s->glove, s->sch, s->sw.world };
  s->hooks->present(s->hooks->user, &f);
}

/* The scene's mappings, or the paper's default about its start pose. */
static int make_control(show *s) {
  mr_mapping_def defs[MR_CONTROL_MAX_MAPPINGS];
  int n = 0;
  for (size_t i = 0; i < s->scene->n_mappings && n < MR_CONTROL_MAX_MAPPINGS; i++)
    defs[n++] = s->scene->mappings[i].def;
  if (n == 0) {
    defs[0] = mr_default_mapping_def();
    defs[0].neutral = s->scene->control_pose;
    n = 1;
  }
  char msg[200];
  if (mr_control_create(defs, n, &s->control, msg, sizeof msg) != MR_CONTROL_OK) {
    fail(s, MR_SCENE_ERR_VALUE, msg);
    return -1;
  }
  return 0;
}

static int open_parts(show *s, const char *source, const mr_show_def *def) {
  char msg[400];
  if (mr_scene_build(s->scene, &s->sw, s->err) != MR_SCENE_OK) return -1;
  mr_glove_def gd = mr_default_glove_def();
  snprintf(gd.source, sizeof gd.source, "%s", source);
  if (mr_glove_create(&gd, &s->glove, msg, sizeof msg) != MR_GLOVE_OK) {
    fail(s, MR_SCENE_ERR_VALUE, msg);
    return -1;
  }
  if (make_control(s) != 0) return -1;
  if (def->record_path != NULL) {
    mr_io_err err;
    if (mr_rec_writer_open(&s->take, def->record_path, GP_SPEC_HASH, mr_io_unix_ns(), &err) != 0) {
      fail(s, MR_SCENE_ERR_IO, err.msg);
      return -1;
    }
    s->recording = s->take_open = true;
    mr_glove_set_tap(s->glove, record, s);
  }
  mr_scheduler_def sd = mr_default_scheduler_def();
  sd.policy = def->policy;
  sd.fps = def->fps > 0 ? def->fps : s->scene->fps > 0 ? s->scene->fps : 60.0;
  mr_scheduler_hooks h = { advance, present, s };
  if (mr_scheduler_create(&sd, &s->clock, &h, &s->sch, msg, sizeof msg) != MR_THEATER_OK) {
    fail(s, MR_SCENE_ERR_VALUE, msg);
    return -1;
  }
  return 0;
}

static void close_parts(show *s) {
  if (s->take_open) {
    mr_io_err err;
    if (mr_rec_writer_close(&s->take, &err) != 0 && s->rc == MR_SCENE_OK)
      fail(s, MR_SCENE_ERR_IO, err.msg);
    s->take_open = s->recording = false;
  }
  mr_scheduler_destroy(s->sch);
  mr_control_destroy(s->control);
  mr_glove_destroy(s->glove);
  mr_scene_world_free(&s->sw);
}

mr_scene_status mr_show_run(const mr_scene *scene, const char *glove_source, const mr_show_def *def,
                            const mr_clock *clock, const mr_show_hooks *hooks,
                            mr_show_result *result, mr_scene_error *err) {
  show s;
  memset(&s, 0, sizeof s);
  memset(result, 0, sizeof *result);
  memset(err, 0, sizeof *err);
  s.scene = scene;
  s.err = err;
  s.hooks = hooks;
  s.target = scene->control_pose;
  if (def == NULL || def->cookie != MR_SHOW_COOKIE || clock == NULL || glove_source == NULL) {
    fail(&s, MR_SCENE_ERR_VALUE, "expected a show definition, a clock and a glove source");
    return s.rc;
  }
  s.clock = *clock;
  s.duration = def->duration;
  if (open_parts(&s, glove_source, def) == 0)
    while (mr_scheduler_tick(s.sch) == MR_THEATER_OK) {
    }
  if (s.sch != NULL) mr_scheduler_stats_get(s.sch, &result->frames);
  if (s.glove != NULL) {
    mr_glove_counters_get(s.glove, &result->glove);
    result->glove_state = mr_glove_state_get(s.glove);
    mr_glove_reading r;
    mr_glove_latest(s.glove, &r);
    result->samples = r.samples;
  }
  close_parts(&s);
  if (s.rc == MR_SCENE_OK && s.take_error[0] != '\0') fail(&s, MR_SCENE_ERR_IO, s.take_error);
  return s.rc != MR_SCENE_OK ? s.rc : err->status;
}

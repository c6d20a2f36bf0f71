/* A live show: gloves → control mapping → control frames → physics, paced
 * by the frame scheduler (§4.6, §6.2). */
#include "mr_show.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mr_control.h"
#include "mr_io.h"
#include "show_internal.h"
#include "theater_internal.h"

mr_show_def mr_default_show_def(void) {
  mr_show_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.policy = MR_POLICY_SKIP;
  d.present = MR_PRESENT_SCENE;
  d.punch_in = d.punch_out = -1.0;
  return d;
}

static void tell(mr_show_error *e, const mr_scene *scene, mr_show_status st, const char *msg) {
  e->status = st;
  snprintf(e->message, sizeof e->message, "%.390s", msg);
  snprintf(e->text, sizeof e->text, "%s: %s", scene ? scene->path : "show", e->message);
}

/* The first error is the one told: what follows from it is not news. */
static mr_show_status fail(show *s, mr_show_status st, const char *msg) {
  if (s->err.status == MR_SHOW_OK) tell(&s->err, s->scene, st, msg);
  return st;
}

static bool uid_matches(const mr_scene_glove_bind *b, const gp_info *info) {
  for (int w = 0; w < b->uid_words && w < 3; w++)
    if (info->uid[w] != b->uid[w]) return false;
  return true;
}

static bool claimed(const show *s, int g) {
  for (size_t k = 0; k < s->n_frames; k++)
    if (s->frames[k].glove == g) return true;
  return false;
}

/* Frame k's glove under its binding, or -1 while none matches. By hand, a
 * glove no other frame took is preferred, so two right-hand puppets take
 * two right-hand gloves. */
static int find_glove(const show *s, size_t k) {
  const mr_scene_glove_bind *b = &s->scene->frames[k].glove;
  if (b->by == MR_SCENE_BIND_ORDER) return b->order < (int)s->n_gloves ? b->order : -1;
  int any = -1;
  for (size_t g = 0; g < s->n_gloves; g++) {
    const gp_info *info = mr_glove_info(s->gloves[g].glove);
    if (info == NULL) continue;
    bool match = b->by == MR_SCENE_BIND_UID ? uid_matches(b, info) : info->hand == b->hand;
    if (!match) continue;
    if (!claimed(s, (int)g)) return (int)g;
    if (any < 0) any = (int)g;
  }
  return any;
}

/* Frame k's glove's newest values, if any came, through its mapping. */
static bool read_frame(show *s, size_t k) {
  show_frame *f = &s->frames[k];
  if (f->glove < 0 && (f->glove = find_glove(s, k)) < 0) return false;
  const show_glove *sg = &s->gloves[f->glove];
  mr_glove_reading r;
  bool on = mr_layer_read(&s->layers[f->glove], sg->glove, &r);
  if (r.samples == f->samples_seen || !on) return false;
  f->samples_seen = r.samples;
  /* The mapping's filters run on show time: a glove read on its own
   * clock's pace (slow motion) is read at this frame's time. */
  double at = sg->paced ? s->t_now : r.host_t;
  mr_pose pose;
  mr_channel_state states[MR_CONTROL_CHANNELS];
  if (mr_control_update(f->control, r.values, at, &pose, states) == MR_CONTROL_OK) {
    f->target = pose;
    mr_show_tell_states(s, f, states);
  }
  return true;
}

/* Live gloves on the glove clock, takes (and a take beneath) on show
 * time. */
static void read_gloves(show *s, double now) {
  s->t_now = now;
  for (size_t g = 0; g < s->n_gloves; g++) {
    show_glove *sg = &s->gloves[g];
    sg->paced = s->glove_clock.now != NULL && !mr_glove_is_take(sg->glove);
    sg->now = sg->paced ? s->glove_clock.now(s->glove_clock.self) : now;
    mr_glove_poll(sg->glove, sg->now, 0);
    mr_layer_poll(&s->layers[g], now);
    mr_show_tell_glove(s, g, sg->now);
  }
  bool fresh = false;
  for (size_t k = 0; k < s->n_frames; k++) fresh |= read_frame(s, k);
  /* Read at the start of this frame's work: the latency counters run from
   * here to the frame's presentation, on the show's clock. */
  const mr_clock *lc = s->glove_clock.now != NULL ? &s->glove_clock : &s->clock;
  if (fresh) mr_scheduler_note_input(s->sch, lc->now(lc->self));
}

/* A glove's bytes into its take, stamped with the show time of the frame
 * that read them (the glove's own `now` may run at another pace). */
static void record(void *user, double glove_now, const uint8_t *bytes, size_t len) {
  show_glove *g = user;
  (void)glove_now;
  if (!g->recording) return;
  double now = *g->show_t;
  mr_io_error err;
  uint64_t t_ns = now > 0 ? (uint64_t)llround(now * 1e9) : 0;
  if (mr_rec_writer_add(&g->take, t_ns, bytes, len, &err) != 0) {
    snprintf(g->take_error, sizeof g->take_error, "%s", err.msg);
    g->recording = false;
  }
}

/* Over when every glove is a take that has ended. */
static bool takes_over(const show *s) {
  for (size_t g = 0; g < s->n_gloves; g++) {
    const mr_glove *gl = s->gloves[g].glove;
    if (mr_layer_over(&s->layers[g])) continue;
    if (!mr_glove_take_done(gl) || mr_glove_get_state(gl) != MR_GLOVE_LOST) return false;
  }
  return true;
}

static const char *mapping_name(const show *s) {
  int m = s->n_frames > 0 && s->frames[0].control ? mr_control_selected(s->frames[0].control) : 0;
  return s->scene->n_mappings > 0 ? s->scene->mappings[m].def.name : "default";
}

void mr_show_snapshot(const show *s, mr_show_frame *f) {
  if (s == NULL || f == NULL || f->n_frames != s->n_frames || f->n_particles != s->ip.n) return;
  f->t = mr_world_time(s->sw.world);
  f->hash = 0;
  mr_scheduler_get_stats(s->sch, &f->stats);
  for (size_t k = 0; k < s->n_frames; k++) {
    f->target[k] = s->frames[k].target;
    f->glove_of[k] = s->frames[k].glove;
    if (mr_world_frame_pose(s->sw.world, s->sw.frames[k], &f->pose[k]) != MR_OK)
      f->pose[k] = s->frames[k].target;
  }
  f->n_gloves = s->n_gloves;
  for (size_t g = 0; g < s->n_gloves; g++) {
    const mr_glove *gl = s->gloves[g].glove;
    mr_show_glove_view *v = &f->gloves[g];
    v->state = mr_glove_get_state(gl);
    mr_glove_latest(gl, &v->reading);
    mr_glove_get_counters(gl, &v->counters);
    v->clock_offset = mr_glove_clock_offset(gl);
    mr_glove_describe(gl, s->gloves[g].paced ? s->gloves[g].now : f->t, v->describe,
                      sizeof v->describe);
    v->layered = s->layers[g].take != NULL;
    v->armed = s->layers[g].armed;
  }
  f->recording = s->punch.recording;
  f->punch_in = s->punch.punch_in;
  f->punch_out = s->punch.punch_out;
  memcpy(f->xyz, s->ip.frame, 3 * (size_t)s->ip.n * sizeof *f->xyz);
  snprintf(f->mapping, sizeof f->mapping, "%s", mapping_name(s));
}

/* The snapshot of the frame at t, for a hook. */
static mr_show_frame *view(show *s, double t) {
  mr_show_snapshot(s, &s->scratch);
  s->scratch.t = t;
  return &s->scratch;
}

/* The world to time t: the frames head for their gloves' poses and the
 * last step lands on t (the paper's), or, interpolating, steps at the
 * ATS's own Δt run until one passes t, the frames heading for their
 * poses at each step's end. Fails only when the physics stopped. */
static int step_world(show *s, double t, mr_frame_work *work) {
  mr_world *w = s->sw.world;
  while (t > mr_world_time(w) + 1e-9) {
    double end = s->interpolate ? mr_world_time(w) + mr_world_next_dt(w) : t;
    for (size_t k = 0; k < s->n_frames; k++)
      mr_theater_follow_glove(s->scene, &s->sw, k, &s->frames[k].follow, s->frames[k].target, end);
    mr_interp_mark(&s->ip, w);
    mr_step_report rep;
    memset(&rep, 0, sizeof rep);
    mr_status st = s->interpolate ? mr_world_step(w, &rep) : mr_world_step_to(w, t, &rep);
    if (st < 0) {
      char msg[400];
      snprintf(msg, sizeof msg, "the physics stopped (%s): %s at t = %.3f s", mr_status_name(st),
               mr_world_last_error(w), t);
      fail(s, MR_SHOW_ERR_PHYSICS, msg);
      return -1;
    }
    work->steps += (uint64_t)rep.steps;
    work->rejected += (uint64_t)rep.rejected;
    work->resets += (uint64_t)rep.divergences;
  }
  mr_interp_at(&s->ip, w, t);
  s->sum_lead += s->ip.lead;
  s->lead_max = fmax(s->lead_max, s->ip.lead);
  s->frames_stepped++;
  return 0;
}

/* The next mapping for every frame, told once. */
static void switch_mapping(show *s) {
  char line[120];
  for (size_t k = 0; k < s->n_frames; k++) {
    mr_control *c = s->frames[k].control;
    int n = s->scene->n_mappings > 0 ? (int)s->scene->n_mappings : 1;
    mr_control_select(c, (mr_control_selected(c) + 1) % n);
  }
  int i = s->n_frames > 0 ? mr_control_selected(s->frames[0].control) : 0;
  snprintf(line, sizeof line, "mapping '%s' (%d of %zu)",
           s->scene->n_mappings > 0 ? s->scene->mappings[i].def.name : "default", i + 1,
           s->scene->n_mappings > 0 ? s->scene->n_mappings : 1);
  mr_show_note(s, line);
}

/* The reset hook: the scene's particles back at their start, at rest,
 * and each frame placed at its start pose at once. A particle the physics
 * holds (pinned, on a frame) refuses the new state and stays as it is. */
static void reset_puppets(show *s) {
  mr_world *w = s->sw.world;
  const double rest[3] = { 0, 0, 0 };
  for (size_t i = 0; i < s->sw.n_particles; i++) {
    int id = s->sw.particle_ids[i];
    mr_world_set_particle_state(w, id, &s->start_xyz[3 * (size_t)id], rest);
  }
  for (size_t k = 0; k < s->n_frames; k++) {
    s->frames[k].target = s->scene->frames[k].pose;
    mr_world_set_frame_target(w, s->sw.frames[k], &s->scene->frames[k].pose, mr_world_time(w));
  }
  mr_show_note(s, "reset: the puppets are back where they started");
}

void mr_show_reset(show *s) {
  if (s != NULL) s->resets_asked++;
}

void mr_show_next_mapping(show *s) {
  if (s != NULL) s->mappings_asked++;
}

/* --- layers: arming and punches (issue 23) ------------------------------ */

void mr_show_arm(show *s, size_t glove, unsigned armed) {
  if (s != NULL && glove < s->n_gloves) mr_punch_ask_arm(&s->punch, glove, armed);
}

void mr_show_punch(show *s) {
  if (s != NULL) s->punch.punches_asked++;
}

static void note_hook(void *user, const char *line) {
  mr_show_note(user, line);
}

static int advance(void *user, double t, mr_frame_work *work) {
  show *s = user;
  for (; s->resets_asked > 0; s->resets_asked--) reset_puppets(s);
  for (; s->mappings_asked > 0; s->mappings_asked--) switch_mapping(s);
  mr_punch_asks(&s->punch, s->layers, s->n_gloves, t, note_hook, s);
  read_gloves(s, t);
  if (step_world(s, t, work) != 0) return 1;
  if (s->hooks.frame_done != NULL) {
    mr_show_frame *f = view(s, t);
    f->hash = mr_world_state_hash(s->sw.world);
    s->hooks.frame_done(s->hooks.user, f);
  }
  /* Stopping ends the show after this frame: the scheduler counts it as
   * simulated, and it was. */
  if (s->hooks.stop != NULL && s->hooks.stop(s->hooks.user)) return 1;
  if (s->punch.punched_out) return 1;
  if (s->duration > 0) return t >= s->duration;
  return takes_over(s);
}

static void present(void *user, double t) {
  show *s = user;
  if (s->hooks.present != NULL) s->hooks.present(s->hooks.user, view(s, t));
}

/* Each frame's control: the scene's mappings, or the paper's default, about
 * that frame's start pose. */
static int make_controls(show *s, const char *mapping) {
  int start = -1;
  if (mapping != NULL) {
    for (size_t i = 0; i < s->scene->n_mappings && start < 0; i++)
      if (strcmp(s->scene->mappings[i].def.name, mapping) == 0) start = (int)i;
    if (start < 0) {
      char msg[400];
      int n = snprintf(msg, sizeof msg, "no mapping '%.40s' in the scene; it has:", mapping);
      for (size_t i = 0; i < s->scene->n_mappings && n > 0 && (size_t)n < sizeof msg; i++)
        n += snprintf(msg + n, sizeof msg - (size_t)n, "%s %s", i ? "," : "",
                      s->scene->mappings[i].def.name);
      if (s->scene->n_mappings == 0) snprintf(msg + n, sizeof msg - (size_t)n, " only the default");
      return fail(s, MR_SHOW_ERR_MAPPING, msg), -1;
    }
  }
  /* n_frames counts the frames held, which close_parts destroys. */
  s->frames = calloc(s->scene->n_frames ? s->scene->n_frames : 1, sizeof *s->frames);
  if (s->frames == NULL) return fail(s, MR_SHOW_ERR_NOMEM, "out of memory"), -1;
  s->n_frames = s->scene->n_frames;
  for (size_t k = 0; k < s->n_frames; k++) {
    mr_mapping_def defs[MR_CONTROL_MAX_MAPPINGS];
    int n = 0;
    for (size_t i = 0; i < s->scene->n_mappings && n < MR_CONTROL_MAX_MAPPINGS; i++)
      defs[n++] = s->scene->mappings[i].def;
    if (n == 0) defs[n++] = mr_default_mapping_def();
    for (int i = 0; i < n; i++) defs[i].neutral = s->scene->frames[k].pose;
    s->frames[k].glove = -1;
    s->frames[k].target = s->scene->frames[k].pose;
    char msg[200];
    if (mr_control_create(defs, n, &s->frames[k].control, msg, sizeof msg) != MR_CONTROL_OK)
      return fail(s, MR_SHOW_ERR_MAPPING, msg), -1;
    if (start >= 0) mr_control_select(s->frames[k].control, start);
  }
  return 0;
}

static int open_glove(show *s, const mr_show_def *def, size_t i) {
  const char *source = def->gloves[i], *take_path = def->record[i];
  char msg[400];
  show_glove *g = &s->gloves[i];
  mr_glove_def gd = mr_default_glove_def();
  snprintf(gd.source, sizeof gd.source, "%s", source);
  if (mr_glove_create(&gd, &g->glove, msg, sizeof msg) != MR_GLOVE_OK)
    return fail(s, MR_SHOW_ERR_GLOVE, msg), -1;
  g->show_t = &s->t_now;
  if (mr_layer_open(&s->layers[i], def->beneath[i], def->armed[i], msg, sizeof msg) != 0)
    return fail(s, MR_SHOW_ERR_GLOVE, msg), -1;
  if (take_path == NULL) return 0;
  mr_io_error err;
  /* The take names the scene it was performed on, so that a program
   * playing it on another scene can say so (marionette export). */
  if (mr_rec_writer_open_scene(&g->take, take_path, GP_SPEC_HASH, mr_io_unix_ns(),
                               mr_world_state_hash(s->sw.world), &err) != 0)
    return fail(s, MR_SHOW_ERR_TAKE, err.msg), -1;
  g->recording = g->take_open = true;
  mr_glove_set_tap(g->glove, record, g);
  return 0;
}

static int open_parts(show *s, const mr_show_def *def) {
  char msg[400];
  mr_scene_error se;
  if (mr_scene_build(s->scene, &s->sw, &se) != MR_SCENE_OK)
    return fail(s, MR_SHOW_ERR_SCENE, se.message), -1;
  s->interpolate = def->present == MR_PRESENT_INTERPOLATE ||
                   (def->present == MR_PRESENT_SCENE && s->scene->interpolate);
  if (mr_interp_open(&s->ip, mr_world_particle_count(s->sw.world)) != 0)
    return fail(s, MR_SHOW_ERR_NOMEM, "out of memory"), -1;
  mr_interp_mark(&s->ip, s->sw.world);
  mr_interp_at(&s->ip, s->sw.world, 0.0);
  int n = mr_world_particle_count(s->sw.world);
  if ((s->start_xyz = calloc((size_t)(n > 0 ? n : 1) * 3, sizeof(double))) == NULL)
    return fail(s, MR_SHOW_ERR_NOMEM, "out of memory"), -1;
  mr_world_positions(s->sw.world, s->start_xyz, n);
  for (size_t i = 0; i < def->n_gloves; i++) {
    s->n_gloves = i + 1;
    s->sources[i] = def->gloves[i];
    if (open_glove(s, def, i) != 0) return -1;
  }
  if (make_controls(s, def->mapping) != 0) return -1;
  if (mr_show_frame_make(s, &s->scratch) != 0)
    return fail(s, MR_SHOW_ERR_NOMEM, "out of memory"), -1;
  mr_scheduler_def sd = mr_default_scheduler_def();
  sd.policy = def->policy;
  if (def->max_catch_up > 0) sd.max_catch_up = def->max_catch_up;
  sd.latency_clock = s->glove_clock;
  sd.fps = def->fps > 0 ? def->fps : s->scene->fps > 0 ? s->scene->fps : 60.0;
  mr_scheduler_hooks h = { advance, present, s };
  if (mr_scheduler_create(&sd, &s->clock, &h, &s->sch, msg, sizeof msg) != MR_THEATER_OK) {
    fail(s, MR_SHOW_ERR_ARG, msg);
    return -1;
  }
  return 0;
}

static void close_parts(show *s) {
  for (size_t i = 0; i < s->n_gloves; i++) {
    show_glove *g = &s->gloves[i];
    if (g->take_open) {
      mr_io_error err;
      if (mr_rec_writer_close(&g->take, &err) != 0) fail(s, MR_SHOW_ERR_TAKE, err.msg);
      g->take_open = g->recording = false;
    }
    if (g->take_error[0] != '\0') fail(s, MR_SHOW_ERR_TAKE, g->take_error);
    /* A replayed take that is damaged: the reader's line, naming the file. */
    mr_io_status gst;
    const char *why = mr_glove_last_error(g->glove, &gst);
    if (s->err.status == MR_SHOW_OK && mr_glove_is_take(g->glove) && mr_io_failed(gst)) {
      fail(s, MR_SHOW_ERR_GLOVE, why);
      snprintf(s->err.text, sizeof s->err.text, "%s", why);
    }
    mr_glove_destroy(g->glove);
    mr_layer_close(&s->layers[i]);
  }
  for (size_t k = 0; k < s->n_frames; k++) mr_control_destroy(s->frames[k].control);
  free(s->frames);
  mr_scheduler_destroy(s->sch);
  mr_interp_close(&s->ip);
  mr_show_frame_free(&s->scratch);
  free(s->start_xyz);
  mr_scene_world_free(&s->sw);
}

static void gather(const show *s, mr_show_result *result) {
  if (s->ended)
    result->frames = s->end_stats;
  else if (s->sch != NULL)
    mr_scheduler_get_stats(s->sch, &result->frames);
  result->interpolated = s->interpolate;
  result->lead_mean = s->frames_stepped > 0 ? s->sum_lead / (double)s->frames_stepped : 0.0;
  result->lead_max = s->lead_max;
  result->n_gloves = s->n_gloves;
  for (size_t i = 0; i < s->n_gloves; i++) {
    const mr_glove *g = s->gloves[i].glove;
    mr_show_glove_result *o = &result->glove[i];
    if (g == NULL) continue;
    mr_glove_get_counters(g, &o->counters);
    o->state = mr_glove_get_state(g);
    mr_glove_reading r;
    mr_glove_latest(g, &r);
    o->samples = r.samples;
    o->over_net = mr_glove_net_counters(g, &o->net);
    /* At the glove's own time: show time, or the glove clock's for a live
     * glove read at its own pace (slow motion), which the show time would
     * put before the glove's last news. */
    double at = s->gloves[i].paced ? s->gloves[i].now : result->frames.sim_time;
    mr_glove_describe(g, at, o->describe, sizeof o->describe);
  }
  result->glove_of = calloc(s->n_frames > 0 ? s->n_frames : 1, sizeof *result->glove_of);
  if (result->glove_of != NULL) {
    result->n_frames = s->n_frames;
    for (size_t k = 0; k < s->n_frames; k++) result->glove_of[k] = s->frames[k].glove;
  }
  snprintf(result->mapping, sizeof result->mapping, "%s", s->frames ? mapping_name(s) : "default");
  result->punch_in = s->punch.punch_in;
  result->punch_out = s->punch.punch_out;
  memcpy(result->punched, s->punch.punched, sizeof result->punched);
}

void mr_show_result_free(mr_show_result *r) {
  if (r == NULL) return;
  free(r->glove_of);
  r->glove_of = NULL;
  r->n_frames = 0;
}

int mr_show_frame_make(const show *s, mr_show_frame *out) {
  if (s == NULL || out == NULL) return -1;
  return mr_show_frame_alloc(out, s->n_frames, s->ip.n);
}

mr_show_status mr_show_create(const mr_scene *scene, const mr_show_def *def, const mr_clock *clock,
                              const mr_show_hooks *hooks, mr_show **out, mr_show_error *err) {
  if (err != NULL) memset(err, 0, sizeof *err);
  if (out != NULL) *out = NULL;
  show *s = calloc(1, sizeof *s);
  if (s == NULL) {
    if (err != NULL) tell(err, scene, MR_SHOW_ERR_NOMEM, "out of memory");
    return MR_SHOW_ERR_NOMEM;
  }
  s->scene = scene;
  if (hooks != NULL) s->hooks = *hooks;
  if (scene == NULL || out == NULL || def == NULL || def->cookie != MR_DEF_COOKIE ||
      clock == NULL || def->n_gloves == 0 || def->n_gloves > MR_SHOW_MAX_GLOVES) {
    fail(s, MR_SHOW_ERR_ARG, "expected a scene, a show definition with 1 to 8 gloves, and a clock");
  } else {
    for (size_t i = 0; i < def->n_gloves; i++)
      if (def->gloves[i] == NULL) fail(s, MR_SHOW_ERR_ARG, "expected a glove source");
  }
  if (s->err.status == MR_SHOW_OK) {
    s->clock = *clock;
    s->duration = def->duration;
    s->glove_clock = def->glove_clock;
    mr_punch_init(&s->punch, def->punch_in, def->punch_out);
    open_parts(s, def);
  }
  if (s->err.status != MR_SHOW_OK) {
    mr_show_status st = s->err.status;
    if (err != NULL) *err = s->err;
    if (s->scene != NULL) close_parts(s);
    free(s);
    return st;
  }
  *out = s;
  return MR_SHOW_OK;
}

mr_show_status mr_show_tick(show *s) {
  if (s == NULL) return MR_SHOW_ERR_ARG;
  if (s->err.status != MR_SHOW_OK) return s->err.status;
  if (s->ended) return MR_SHOW_ENDED;
  if (mr_scheduler_tick(s->sch) == MR_THEATER_OK) return MR_SHOW_OK;
  /* Wall time stops with the show, not with whoever destroys it later (a
   * window may still be drawing its last frame). */
  mr_scheduler_get_stats(s->sch, &s->end_stats);
  s->ended = true;
  return s->err.status != MR_SHOW_OK ? s->err.status : MR_SHOW_ENDED;
}

mr_show_status mr_show_destroy(show *s, mr_show_result *result, mr_show_error *err) {
  if (result != NULL) memset(result, 0, sizeof *result);
  if (err != NULL) memset(err, 0, sizeof *err);
  if (s == NULL) return MR_SHOW_ERR_ARG;
  if (result != NULL) gather(s, result);
  close_parts(s);
  mr_show_status st = s->err.status;
  if (err != NULL) *err = s->err;
  free(s);
  return st;
}

mr_show_status mr_show_run(const mr_scene *scene, const mr_show_def *def, const mr_clock *clock,
                           const mr_show_hooks *hooks, mr_show_result *result, mr_show_error *err) {
  if (result != NULL) memset(result, 0, sizeof *result);
  mr_show *s = NULL;
  mr_show_status st = mr_show_create(scene, def, clock, hooks, &s, err);
  if (st != MR_SHOW_OK) return st;
  while ((st = mr_show_tick(s)) == MR_SHOW_OK) {
  }
  return mr_show_destroy(s, result, err);
}

/* The frame scheduler (§4.6). Frame j has simulated time j/fps. It is
 * computed in the tick that starts at wall time t0 + j/fps and presented at
 * the start of the next tick, one frame period later: one frame of delay,
 * by design, so that a frame is always whole when it is shown.
 *
 * When a tick starts a period or more late (the last render took too long),
 * the frame waiting to be shown is already stale. The paper's policy
 * (skip) drops it, and simulates every frame whose time has come, up to
 * max_catch_up, showing only the newest: simulated time stays within one
 * frame of wall time, and the lag beyond the cap is given up rather than
 * chased, so the loop never spirals. The slow policy shows every frame and
 * moves the wall origin instead: simulated time falls behind, and the
 * real-time factor says by how much. */
#include "mr_theater.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Latency histogram: 0.1 ms bins up to 2 s, the last bin for anything
 * longer. Fixed, so a long show allocates nothing as it runs. */
#define LAT_BIN  1e-4
#define LAT_BINS 20000

struct mr_scheduler {
  mr_scheduler_def def;
  mr_clock clock;
  mr_scheduler_hooks hooks;
  double period;
  bool started, pending;
  double t0, first_wall;
  uint64_t next; /* the next frame to compute */
  double pending_t, pending_input;
  double input_first; /* the first sample noted since the last frame was computed, or NAN */
  mr_scheduler_stats st;
  uint64_t lat_count;
  uint32_t lat[LAT_BINS];
};

const char *mr_policy_name(mr_policy p) {
  return p == MR_POLICY_SKIP ? "skip" : p == MR_POLICY_SLOW ? "slow" : "unknown";
}

int mr_policy_parse(const char *name, mr_policy *out) {
  if (name == NULL || out == NULL) return -1;
  if (strcmp(name, "skip") == 0)
    *out = MR_POLICY_SKIP;
  else if (strcmp(name, "slow") == 0)
    *out = MR_POLICY_SLOW;
  else
    return -1;
  return 0;
}

mr_scheduler_def mr_default_scheduler_def(void) {
  mr_scheduler_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.fps = 60.0;
  d.policy = MR_POLICY_SKIP;
  d.max_catch_up = 5;
  return d;
}

mr_theater_status mr_scheduler_create(const mr_scheduler_def *def, const mr_clock *clock,
                                      const mr_scheduler_hooks *hooks, mr_scheduler **out,
                                      char *msg, size_t msg_size) {
  char dummy[8];
  if (msg == NULL || msg_size == 0) {
    msg = dummy;
    msg_size = sizeof dummy;
  }
  if (out != NULL) *out = NULL;
  if (def == NULL || clock == NULL || hooks == NULL || out == NULL || clock->now == NULL ||
      clock->wait_until == NULL || hooks->advance == NULL || hooks->present == NULL) {
    snprintf(msg, msg_size,
             "expected a definition, a clock with now and wait_until, and the "
             "advance and present hooks");
    return MR_THEATER_ERR_ARG;
  }
  if (def->cookie != MR_DEF_COOKIE) {
    snprintf(msg, msg_size, "the scheduler definition was not made by mr_default_scheduler_def");
    return MR_THEATER_ERR_ARG;
  }
  if (!(def->fps >= 1 && def->fps <= 10000) || def->max_catch_up < 1 ||
      (def->policy != MR_POLICY_SKIP && def->policy != MR_POLICY_SLOW)) {
    snprintf(msg, msg_size,
             "expected fps between 1 and 10000, max_catch_up >= 1 and policy skip or slow, got "
             "%g, %d, %d",
             def->fps, def->max_catch_up, (int)def->policy);
    return MR_THEATER_ERR_ARG;
  }
  mr_scheduler *s = calloc(1, sizeof *s);
  if (s == NULL) {
    snprintf(msg, msg_size, "out of memory");
    return MR_THEATER_ERR_ARG;
  }
  s->def = *def;
  s->clock = *clock;
  s->hooks = *hooks;
  s->period = 1.0 / def->fps;
  s->input_first = NAN;
  *out = s;
  return MR_THEATER_OK;
}

void mr_scheduler_destroy(mr_scheduler *s) {
  free(s);
}

void mr_scheduler_note_input(mr_scheduler *s, double t) {
  if (s != NULL && isfinite(t) && !(s->input_first <= t)) s->input_first = t;
}

static void record_latency(mr_scheduler *s, double lat) {
  long bin = lat <= 0 ? 0 : (long)(lat / LAT_BIN);
  if (bin >= LAT_BINS) bin = LAT_BINS - 1;
  s->lat[bin]++;
  s->lat_count++;
}

/* The latency below which a fraction q of the samples fall: the upper
 * edge of the bin that holds it. */
static double latency_quantile(const mr_scheduler *s, double q) {
  if (s->lat_count == 0) return 0.0;
  uint64_t need = (uint64_t)ceil(q * (double)s->lat_count), seen = 0;
  for (long b = 0; b < LAT_BINS; b++) {
    seen += s->lat[b];
    if (seen >= need && seen > 0) return (double)(b + 1) * LAT_BIN;
  }
  return (double)LAT_BINS * LAT_BIN;
}

/* Frame j's time is j/fps, computed afresh, never a running sum: a long
 * show lands on its frame times exactly. */
static double frame_time(const mr_scheduler *s, uint64_t j) {
  return (double)j / s->def.fps;
}

static double slot(const mr_scheduler *s, uint64_t j) {
  return s->t0 + frame_time(s, j);
}

/* Shows the frame computed last, or drops it when it is stale. */
static void present_pending(mr_scheduler *s, double now) {
  if (!s->pending) return;
  s->pending = false;
  if (s->def.policy == MR_POLICY_SKIP && now >= slot(s, s->next) + s->period) {
    s->st.frames_skipped++;
    return;
  }
  s->hooks.present(s->hooks.user, s->pending_t);
  s->st.frames_presented++;
  s->st.last_present_wall = now;
  s->st.last_present_sim = s->pending_t;
  if (isfinite(s->pending_input)) {
    const mr_clock *lc = &s->def.latency_clock;
    record_latency(s, (lc->now != NULL ? lc->now(lc->self) : now) - s->pending_input);
  }
}

/* The frames to simulate this tick: every one whose slot has begun, from
 * the next, at most max_catch_up; the rest of the lag is given up. */
static uint64_t frames_due(mr_scheduler *s, double now) {
  if (s->def.policy == MR_POLICY_SLOW) return 1;
  double behind = floor((now - slot(s, s->next)) / s->period + 1e-9);
  uint64_t due = behind > 0 ? (uint64_t)behind + 1 : 1;
  if (due > (uint64_t)s->def.max_catch_up) {
    double drop = (double)(due - (uint64_t)s->def.max_catch_up) * s->period;
    s->t0 += drop;
    s->st.dropped_time += drop;
    due = (uint64_t)s->def.max_catch_up;
  }
  return due;
}

mr_theater_status mr_scheduler_tick(mr_scheduler *s) {
  if (s == NULL) return MR_THEATER_ERR_ARG;
  double now = s->clock.now(s->clock.self);
  if (!s->started) {
    s->started = true;
    s->t0 = s->first_wall = now;
  }
  s->st.ticks++;
  /* The slow policy is never late: the wall origin follows. */
  if (s->def.policy == MR_POLICY_SLOW && now > slot(s, s->next)) s->t0 += now - slot(s, s->next);
  present_pending(s, now);
  now = s->clock.now(s->clock.self);
  uint64_t due = frames_due(s, now);
  for (uint64_t i = 0; i < due; i++) {
    mr_frame_work w = { 0, 0, 0 };
    double t = frame_time(s, s->next);
    int stop = s->hooks.advance(s->hooks.user, t, &w);
    s->st.steps += w.steps;
    s->st.rejected += w.rejected;
    s->st.resets += w.resets;
    s->st.frames_simulated++;
    s->st.sim_time = t;
    s->next++;
    if (stop != 0) return MR_THEATER_STOPPED; /* the frame it reached still counts */
    if (i + 1 < due) s->st.frames_skipped++;  /* simulated, never shown */
  }
  s->pending = true;
  s->pending_t = s->st.sim_time;
  s->pending_input = s->input_first;
  s->input_first = NAN;
  s->clock.wait_until(s->clock.self, slot(s, s->next));
  return MR_THEATER_OK;
}

void mr_scheduler_get_stats(const mr_scheduler *s, mr_scheduler_stats *out) {
  if (s == NULL || out == NULL) return;
  *out = s->st;
  double now = s->started ? s->clock.now(s->clock.self) : 0.0;
  out->wall_time = s->started ? now - s->first_wall : 0.0;
  out->real_time_factor = out->wall_time > 0 ? out->sim_time / out->wall_time : 1.0;
  out->latency_p50 = latency_quantile(s, 0.50);
  out->latency_p99 = latency_quantile(s, 0.99);
}

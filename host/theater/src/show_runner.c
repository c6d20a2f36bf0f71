/* The show on a thread of its own, or on the caller's (mr_show_runner.h).
 *
 * Ownership: the show, its scaled clock and the writer's side of the
 * triple buffer belong to the thread that ticks; the reader's side and the
 * sent counts to the caller's. They meet only in the command queue, the
 * triple buffer's exchange and the atomics below. */
#define _POSIX_C_SOURCE 200809L
#include "mr_show_runner.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mr_handoff.h"

struct mr_show_runner {
  mr_show_runner_def def;
  mr_clock base;
  mr_scaled_clock clock;
  bool base_is_wall;
  mr_show *show;
  mr_show_hooks hooks; /* the caller's */
  mr_cmdq *queue;
  mr_show_frame slots[3];
  mr_triple frames;
  bool have_front;
  bool quit; /* the ticking thread's */
  pthread_t thread;
  bool thread_started;
  atomic_bool done;
  mr_show_status end; /* written before done is set */
  uint64_t sent[MR_SHOW_CMD_COUNT];
  atomic_uint_fast64_t applied[MR_SHOW_CMD_COUNT];
};

mr_show_runner_def mr_default_show_runner_def(void) {
  mr_show_runner_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.threaded = true;
  d.slow_rate = 0.25;
  d.queue = 64;
  d.poll = 0.004;
  d.speed = 1.0;
  return d;
}

bool mr_show_speed_valid(double speed) {
  return speed == 1.0 || speed == 0.5 || speed == 0.25;
}

double mr_show_speed_next(double speed) {
  return speed > 0.75 ? 0.5 : speed > 0.375 ? 0.25 : 1.0;
}

/* A queued command: its kind in the low byte, an argument above (ARM:
 * the glove, then the channels' bits). */
enum { CMD_BITS = 8 };

static void apply(mr_show_runner *r, int queued) {
  mr_scaled_clock *c = &r->clock;
  int cmd = queued & ((1 << CMD_BITS) - 1), arg = queued >> CMD_BITS;
  switch (cmd) {
  case MR_SHOW_CMD_PAUSE:
    mr_scaled_clock_pause(c, !c->paused);
    break;
  case MR_SHOW_CMD_STEP:
    mr_scaled_clock_step(c);
    break;
  case MR_SHOW_CMD_SLOW:
    mr_scaled_clock_set_rate(c, c->rate < 1.0 ? 1.0 : r->def.slow_rate);
    break;
  case MR_SHOW_CMD_RESET:
    mr_show_reset(r->show);
    break;
  case MR_SHOW_CMD_NEXT_MAPPING:
    mr_show_next_mapping(r->show);
    break;
  case MR_SHOW_CMD_QUIT:
    r->quit = true;
    break;
  case MR_SHOW_CMD_SPEED:
    mr_scaled_clock_set_rate(c, mr_show_speed_next(c->rate));
    break;
  case MR_SHOW_CMD_ARM:
    mr_show_arm(r->show, (size_t)(arg >> CMD_BITS), (unsigned)arg & 0xffu);
    break;
  case MR_SHOW_CMD_PUNCH:
    mr_show_punch(r->show);
    break;
  default:
    return;
  }
  atomic_fetch_add_explicit(&r->applied[cmd], 1, memory_order_relaxed);
}

/* Every command queued, done in order; whether there was one. */
static bool apply_queued(mr_show_runner *r) {
  int cmd;
  bool any = false;
  while (mr_cmdq_pop(r->queue, &cmd)) {
    apply(r, cmd);
    any = true;
  }
  return any;
}

/* The scaled clock's wait: commands are done as they come. Threaded on
 * the wall clock, the thread sleeps on the queue itself, so a command
 * wakes it at once; on a virtual clock it waits on that clock, and paused
 * sleeps until a command comes. One thread: the caller's pump every poll
 * seconds. */
static int idle(void *user, double deadline) {
  mr_show_runner *r = user;
  if (apply_queued(r)) return r->quit;
  if (r->quit) return 1;
  if (r->def.threaded) {
    if (r->base_is_wall || !isfinite(deadline))
      mr_cmdq_wait(r->queue, deadline);
    else
      r->base.wait_until(r->base.self, deadline);
    return 0;
  }
  if (r->def.pump != NULL) r->def.pump(r->def.user);
  if (apply_queued(r)) return r->quit;
  double slice = r->base.now(r->base.self) + r->def.poll;
  r->base.wait_until(r->base.self, deadline < slice ? deadline : slice);
  return 0;
}

/* Every simulated frame goes into the writer's slot and is published;
 * then the caller's hook sees it. */
static void frame_done(void *user, const mr_show_frame *f) {
  mr_show_runner *r = user;
  mr_show_frame_copy(&r->slots[mr_triple_back(&r->frames)], f);
  mr_triple_publish(&r->frames);
  if (r->hooks.frame_done != NULL) r->hooks.frame_done(r->hooks.user, f);
}

static void present(void *user, const mr_show_frame *f) {
  mr_show_runner *r = user;
  if (r->hooks.present != NULL) r->hooks.present(r->hooks.user, f);
}

static int stop(void *user) {
  mr_show_runner *r = user;
  return r->quit || (r->hooks.stop != NULL && r->hooks.stop(r->hooks.user));
}

static void note(void *user, const char *line) {
  mr_show_runner *r = user;
  if (r->hooks.note != NULL) r->hooks.note(r->hooks.user, line);
}

mr_show_status mr_show_runner_tick(mr_show_runner *r) {
  if (r == NULL) return MR_SHOW_ERR_ARG;
  if (atomic_load_explicit(&r->done, memory_order_acquire)) return r->end;
  if (!r->def.threaded && r->def.pump != NULL) r->def.pump(r->def.user);
  apply_queued(r);
  /* After a quit the tick still runs: its frame asks stop, which ends the
   * show there, as Ctrl-C always did. */
  mr_show_status st = mr_show_tick(r->show);
  if (st != MR_SHOW_OK) {
    r->end = st;
    atomic_store_explicit(&r->done, true, memory_order_release);
  }
  return st;
}

static void *physics_thread(void *arg) {
  mr_show_runner *r = arg;
  while (mr_show_runner_tick(r) == MR_SHOW_OK) {
  }
  return NULL;
}

static void runner_free(mr_show_runner *r) {
  for (int i = 0; i < 3; i++) mr_show_frame_free(&r->slots[i]);
  mr_cmdq_destroy(r->queue);
  free(r);
}

static mr_show_status refuse(mr_show_error *err, mr_show_status st, const char *msg) {
  if (err != NULL) {
    err->status = st;
    snprintf(err->message, sizeof err->message, "%s", msg);
    snprintf(err->text, sizeof err->text, "show: %s", msg);
  }
  return st;
}

mr_show_status mr_show_runner_start(const mr_scene *scene, const mr_show_def *def,
                                    const mr_clock *base, const mr_show_hooks *hooks,
                                    const mr_show_runner_def *rd, mr_show_runner **out,
                                    mr_show_error *err) {
  if (err != NULL) memset(err, 0, sizeof *err);
  if (out == NULL || base == NULL || rd == NULL || rd->cookie != MR_DEF_COOKIE ||
      !(rd->slow_rate > 0) || rd->queue == 0 || !(rd->poll > 0) || !mr_show_speed_valid(rd->speed))
    return refuse(err, MR_SHOW_ERR_ARG,
                  "expected a runner definition made by mr_default_show_runner_def, a clock and "
                  "a place for the runner");
  *out = NULL;
  mr_show_runner *r = calloc(1, sizeof *r);
  if (r == NULL || mr_cmdq_create(rd->queue, &r->queue) != 0) {
    free(r);
    return refuse(err, MR_SHOW_ERR_NOMEM, "out of memory");
  }
  r->def = *rd;
  r->base = *base;
  r->base_is_wall = mr_clock_is_wall(base);
  if (hooks != NULL) r->hooks = *hooks;
  mr_scaled_clock_init(&r->clock, base);
  mr_scaled_clock_set_rate(&r->clock, rd->speed);
  r->clock.idle = idle;
  r->clock.user = r;
  mr_clock show_clock = mr_clock_scaled(&r->clock);
  /* Live gloves on the show's pace: at rate 1 that is show time. */
  mr_show_def paced = *def;
  if (paced.glove_clock.now == NULL) paced.glove_clock = mr_clock_paced(&r->clock);
  def = &paced;
  /* A frame is made for a hook only when someone reads it. */
  mr_show_hooks h = { r->hooks.present != NULL ? present : NULL, stop, frame_done, note, r };
  mr_show_status st = mr_show_create(scene, def, &show_clock, &h, &r->show, err);
  if (st != MR_SHOW_OK) {
    runner_free(r);
    return st;
  }
  for (int i = 0; i < 3; i++)
    if (mr_show_frame_make(r->show, &r->slots[i]) != 0) st = MR_SHOW_ERR_NOMEM;
  mr_triple_init(&r->frames);
  if (st == MR_SHOW_OK && rd->threaded) {
    if (pthread_create(&r->thread, NULL, physics_thread, r) != 0)
      st = MR_SHOW_ERR_THREAD;
    else
      r->thread_started = true;
  }
  if (st != MR_SHOW_OK) {
    mr_show_destroy(r->show, NULL, NULL);
    runner_free(r);
    return refuse(err, st,
                  st == MR_SHOW_ERR_NOMEM ? "out of memory" : "cannot start the physics thread");
  }
  *out = r;
  return MR_SHOW_OK;
}

void mr_show_runner_send(mr_show_runner *r, mr_show_cmd cmd) {
  if (r == NULL || cmd < 0 || cmd >= MR_SHOW_CMD_COUNT) return;
  r->sent[cmd]++;
  mr_cmdq_push(r->queue, (int)cmd);
}

void mr_show_runner_send_arm(mr_show_runner *r, size_t glove, unsigned armed) {
  if (r == NULL || glove >= MR_SHOW_MAX_GLOVES) return;
  r->sent[MR_SHOW_CMD_ARM]++;
  int arg = (int)(glove << CMD_BITS | (armed & 0xffu));
  mr_cmdq_push(r->queue, MR_SHOW_CMD_ARM | arg << CMD_BITS);
}

bool mr_show_runner_latest(mr_show_runner *r, const mr_show_frame **frame) {
  bool fresh = r != NULL && mr_triple_take(&r->frames);
  if (fresh) r->have_front = true;
  *frame = r != NULL && r->have_front ? &r->slots[mr_triple_front(&r->frames)] : NULL;
  return fresh;
}

bool mr_show_runner_done(mr_show_runner *r) {
  return r == NULL || atomic_load_explicit(&r->done, memory_order_acquire);
}

void mr_show_runner_counts(mr_show_runner *r, uint64_t *sent, uint64_t *done) {
  for (int i = 0; i < MR_SHOW_CMD_COUNT; i++) {
    if (sent != NULL) sent[i] = r->sent[i];
    if (done != NULL) done[i] = atomic_load_explicit(&r->applied[i], memory_order_relaxed);
  }
}

mr_show_status mr_show_runner_finish(mr_show_runner *r, mr_show_result *result,
                                     mr_show_error *err) {
  if (r == NULL) return refuse(err, MR_SHOW_ERR_ARG, "expected a runner");
  if (r->thread_started) pthread_join(r->thread, NULL);
  /* Commands sent after the end are done still, so that none is lost. */
  apply_queued(r);
  mr_show_status st = mr_show_destroy(r->show, result, err);
  runner_free(r);
  return st;
}

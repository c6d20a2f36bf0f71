/* A watcher's side of a show's state: the link's messages decoded,
 * checked and counted. Owned by the caller's thread; the network is
 * libmosquitto's thread, behind mr_net's queue. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mr_net.h"
#include "mr_state.h"
#include "net_internal.h"

struct mr_state_in {
  mr_state_in_def def;
  mr_net *net;
  uint8_t *buf;
  size_t cap;
  float *pose;
  uint16_t *q;
  double *poses, *xyz;
  size_t pose_cap, q_cap; /* values */
  uint32_t scene_id;
  bool have_scene, have_seq, scene_since; /* scene_since: a SCENE since the last FRAME */
  uint32_t next_seq;
  mr_state_in_counters c;
};

mr_state_in_def mr_default_state_in_def(void) {
  mr_state_in_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.max_scene = MR_STATE_DEFAULT_SCENE;
  d.queue_messages = 1024;
  d.connect_wait_ms = 3000;
  return d;
}

int mr_state_in_open(const mr_state_in_def *def, mr_state_in **out, mr_io_error *err) {
  *out = NULL;
  if (def == NULL || def->cookie != MR_DEF_COOKIE || def->url == NULL ||
      def->max_scene < MR_NET_MAX_MESSAGE)
    return mr_net_err(err, MR_IO_ERR_ARG,
                      "expected a definition made by mr_default_state_in_def, with a URL and "
                      "max_scene of 16384 bytes or more");
  mr_state_in *in = calloc(1, sizeof *in);
  if (in == NULL) return mr_net_err(err, MR_IO_ERR_SYSTEM, "out of memory");
  in->def = *def;
  in->cap = def->max_scene;
  in->buf = malloc(in->cap);
  mr_net_def nd = mr_default_net_def();
  snprintf(nd.url, sizeof nd.url, "%s", def->url);
  snprintf(nd.name, sizeof nd.name, "watch");
  nd.role = MR_NET_WATCHER;
  nd.max_message = def->max_scene;
  nd.queue_messages = def->queue_messages;
  nd.connect_wait_ms = def->connect_wait_ms;
  if (in->buf == NULL) {
    mr_state_in_close(in);
    return mr_net_err(err, MR_IO_ERR_SYSTEM, "out of memory");
  }
  if (mr_net_open(&nd, &in->net, err) != 0) {
    mr_state_in_close(in);
    return -1;
  }
  *out = in;
  return 0;
}

/* Room for a frame of n_frames and n_points; -1 when memory runs out. */
static int make_room(mr_state_in *in, size_t n_frames, size_t n_points) {
  if (n_frames * 7 > in->pose_cap) {
    size_t n = n_frames * 7;
    float *p = realloc(in->pose, n * sizeof *p);
    double *d = p != NULL ? realloc(in->poses, n * sizeof *d) : NULL;
    if (p != NULL) in->pose = p;
    if (d == NULL) return -1;
    in->poses = d;
    in->pose_cap = n;
  }
  if (n_points * 3 > in->q_cap) {
    size_t n = n_points * 3;
    uint16_t *q = realloc(in->q, n * sizeof *q);
    double *d = q != NULL ? realloc(in->xyz, n * sizeof *d) : NULL;
    if (q != NULL) in->q = q;
    if (d == NULL) return -1;
    in->xyz = d;
    in->q_cap = n;
  }
  return 0;
}

static uint64_t wall_us(void) {
  struct timespec ts;
  clock_gettime(CLOCK_REALTIME, &ts);
  return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

/* A FRAME into ev: true when it is one to hand out. */
static bool take_frame(mr_state_in *in, size_t len, mr_state_event *ev) {
  mr_state_frame *m = &ev->frame;
  memset(m, 0, sizeof *m);
  /* n_frames and n_points sit at fixed places: room for them first. */
  if (len < MR_STATE_FRAME_FIXED) return in->c.corrupt++, false;
  size_t n_frames = in->buf[29], n_points = (size_t)in->buf[30] | ((size_t)in->buf[31] << 8);
  if (make_room(in, n_frames, n_points) != 0) return in->c.corrupt++, false;
  m->pose = in->pose;
  m->pose_cap = in->pose_cap;
  m->q = in->q;
  m->q_cap = in->q_cap;
  if (mr_state_frame_decode(in->buf, len, m) != MR_STATE_OK) return in->c.corrupt++, false;
  if (in->have_scene && m->scene_id != in->scene_id) return in->c.stale++, false;
  if (in->have_seq && m->seq < in->next_seq && !in->scene_since) return in->c.stale++, false;
  /* After a SCENE a show restarted counts from 0 again (not stale, above);
   * a gap forward is the same show's loss all the same, as across a broker
   * restart, after which the show publishes its SCENE again. */
  if (in->have_seq && m->seq > in->next_seq) in->c.lost += m->seq - in->next_seq;
  in->have_seq = true;
  in->scene_since = false;
  in->next_seq = m->seq + 1;
  for (size_t i = 0; i < (size_t)m->n_frames * 7; i++) in->poses[i] = (double)m->pose[i];
  for (size_t i = 0; i < m->n_points; i++) mr_state_point(m, i, in->xyz + 3 * i);
  ev->kind = MR_STATE_GOT_FRAME;
  ev->t = (double)m->t_us * 1e-6;
  ev->lag = ((double)wall_us() - (double)m->sent_us) * 1e-6;
  ev->poses = in->poses;
  ev->xyz = in->xyz;
  in->c.frames++;
  return true;
}

/* One message of len bytes into ev: true when there is an event. */
static bool take_message(mr_state_in *in, size_t len, mr_state_event *ev) {
  uint8_t type = 0;
  uint32_t hash = 0;
  mr_state_status st = mr_state_peek(in->buf, len, &type, &hash);
  if (st == MR_STATE_ERR_HASH) {
    in->c.refused++;
    ev->kind = MR_STATE_REFUSED;
    ev->type = type;
    ev->hash = hash;
    return true;
  }
  if (st != MR_STATE_OK) return in->c.corrupt++, false;
  if (type == MR_STATE_FRAME) return take_frame(in, len, ev);
  if (type != MR_STATE_SCENE || mr_state_scene_decode(in->buf, len, &ev->scene) != MR_STATE_OK)
    return in->c.corrupt++, false;
  in->scene_id = (uint32_t)ev->scene.scene_hash;
  in->have_scene = true;
  in->scene_since = true;
  in->c.scenes++;
  ev->kind = MR_STATE_GOT_SCENE;
  return true;
}

mr_io_status mr_state_in_read(mr_state_in *in, int timeout_ms, mr_state_event *ev,
                              mr_io_error *err) {
  memset(ev, 0, sizeof *ev);
  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  for (;;) {
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    long spent = (long)(now.tv_sec - t0.tv_sec) * 1000 + (now.tv_nsec - t0.tv_nsec) / 1000000;
    int left = timeout_ms > spent ? timeout_ms - (int)spent : 0;
    size_t got = 0;
    mr_io_status st = mr_net_read(in->net, in->buf, in->cap, left, &got, NULL, err);
    if (st == MR_IO_TIMEOUT) return MR_IO_OK;
    if (st == MR_IO_HANGUP) {
      in->c.broker_lost++;
      ev->kind = MR_STATE_BROKER_LOST;
      return MR_IO_OK;
    }
    if (st != MR_IO_OK) return st;
    in->c.messages++;
    in->c.bytes += got;
    if (take_message(in, got, ev)) return MR_IO_OK;
  }
}

void mr_state_in_get_counters(mr_state_in *in, mr_state_in_counters *out) {
  memset(out, 0, sizeof *out);
  if (in == NULL) return;
  *out = in->c;
  mr_net_counters nc;
  mr_net_get_counters(in->net, &nc);
  out->oversized = nc.oversized;
  out->queue_full = nc.queue_full;
  out->empty = nc.empty;
}

void mr_state_in_close(mr_state_in *in) {
  if (in == NULL) return;
  mr_net_close(in->net);
  free(in->buf);
  free(in->pose);
  free(in->q);
  free(in->poses);
  free(in->xyz);
  free(in);
}

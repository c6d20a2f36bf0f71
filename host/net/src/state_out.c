/* A show's state out to a broker: its scene retained on TOPIC/scene, its
 * frames on TOPIC. Owned by one thread (the one that simulates); the
 * network is libmosquitto's thread, behind mr_net, and a frame it cannot
 * take at once is dropped, never waited for. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mr_net.h"
#include "mr_state.h"
#include "net_internal.h"

struct mr_state_out {
  mr_state_out_def def;
  mr_net *net;
  uint8_t *scene_msg; /* the SCENE, encoded once */
  size_t scene_len;
  uint32_t scene_id;
  uint64_t connects; /* the link's connections when the scene was last published */
  uint32_t seq;
  float *pose;
  uint16_t *q;
  uint8_t *buf;
  size_t buf_cap;
  mr_state_out_counters c;
};

mr_state_out_def mr_default_state_out_def(void) {
  mr_state_out_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.fps = 60.0;
  d.max_unsent = 16;
  d.connect_wait_ms = 3000;
  return d;
}

static int encode_scene(mr_state_out *o, mr_io_error *err) {
  const mr_state_bundle *b = o->def.scene;
  mr_state_scene s;
  memset(&s, 0, sizeof s);
  s.scene_hash = mr_state_bundle_hash(b->data, b->size);
  s.fps = (float)o->def.fps;
  s.n_frames = (uint8_t)o->def.n_frames;
  s.n_points = (uint16_t)o->def.n_points;
  s.n_files = b->n_files;
  s.size = (uint32_t)b->size;
  s.files = b->data;
  o->scene_len = mr_state_scene_size(&s);
  o->scene_msg = malloc(o->scene_len);
  if (o->scene_msg == NULL) return mr_net_err(err, MR_IO_ERR_SYSTEM, "out of memory");
  mr_state_scene_encode(&s, o->scene_msg, o->scene_len);
  o->scene_id = (uint32_t)s.scene_hash;
  o->c.scene_bytes = o->scene_len;
  return 0;
}

/* The SCENE, retained: at the start and after every reconnection (a
 * broker restarted without persistence has forgotten it). */
static int publish_scene(mr_state_out *o, mr_io_error *err) {
  mr_net_counters nc;
  mr_net_get_counters(o->net, &nc);
  if (nc.connects == o->connects) return 0;
  if (mr_net_publish_retained(o->net, MR_NET_SCENE, o->scene_msg, o->scene_len, err) != 0)
    return -1;
  o->connects = nc.connects;
  o->c.scenes++;
  return 0;
}

int mr_state_out_open(const mr_state_out_def *def, mr_state_out **out, mr_io_error *err) {
  *out = NULL;
  if (def == NULL || def->cookie != MR_DEF_COOKIE || def->url == NULL || def->scene == NULL ||
      def->scene->n_files == 0 || def->n_frames < 0 || def->n_frames > MR_STATE_MAX_FRAMES ||
      def->n_points < 0 || def->n_points > MR_STATE_MAX_POINTS || !(def->fps > 0) ||
      def->max_unsent < 1)
    return mr_net_err(err, MR_IO_ERR_ARG,
                      "expected a definition made by mr_default_state_out_def, with a URL, a scene "
                      "of one file or more, up to 255 control frames and 65535 particles");
  mr_state_out *o = calloc(1, sizeof *o);
  if (o == NULL) return mr_net_err(err, MR_IO_ERR_SYSTEM, "out of memory");
  o->def = *def;
  mr_state_frame probe = { .n_frames = (uint8_t)def->n_frames,
                           .n_points = (uint16_t)def->n_points };
  o->buf_cap = mr_state_frame_size(&probe);
  o->pose = calloc((size_t)def->n_frames * 7 + 1, sizeof *o->pose);
  o->q = calloc((size_t)def->n_points * 3 + 1, sizeof *o->q);
  o->buf = malloc(o->buf_cap);
  if (o->pose == NULL || o->q == NULL || o->buf == NULL) {
    mr_state_out_close(o);
    return mr_net_err(err, MR_IO_ERR_SYSTEM, "out of memory");
  }
  if (encode_scene(o, err) != 0) {
    mr_state_out_close(o);
    return -1;
  }
  mr_net_def nd = mr_default_net_def();
  snprintf(nd.url, sizeof nd.url, "%s", def->url);
  snprintf(nd.name, sizeof nd.name, "show");
  nd.role = MR_NET_SHOW;
  nd.connect_wait_ms = def->connect_wait_ms;
  /* The larger of the scene and a frame (2 700 particles and more make a
   * frame larger than a glove's messages). */
  nd.max_message = o->scene_len > o->buf_cap ? o->scene_len : o->buf_cap;
  if (nd.max_message < MR_NET_MAX_MESSAGE) nd.max_message = MR_NET_MAX_MESSAGE;
  nd.max_unsent = def->max_unsent;
  if (mr_net_open(&nd, &o->net, err) != 0 || publish_scene(o, err) != 0) {
    mr_state_out_close(o);
    return -1;
  }
  *out = o;
  return 0;
}

static uint64_t wall_us(void) {
  struct timespec ts;
  clock_gettime(CLOCK_REALTIME, &ts);
  return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

int mr_state_out_frame(mr_state_out *o, double t, const double *poses, const double *xyz,
                       mr_io_error *err) {
  mr_state_frame m;
  memset(&m, 0, sizeof m);
  m.scene_id = o->scene_id;
  m.seq = o->seq++;
  m.t_us = t > 0 ? (uint64_t)llround(t * 1e6) : 0;
  m.n_frames = (uint8_t)o->def.n_frames;
  m.n_points = (uint16_t)o->def.n_points;
  for (size_t i = 0; i < (size_t)o->def.n_frames * 7; i++) o->pose[i] = (float)poses[i];
  m.pose = o->pose;
  mr_state_quantise(xyz, (size_t)o->def.n_points, m.origin, m.step, o->q);
  m.q = o->q;
  o->c.frames++;
  mr_io_error e;
  /* A reconnection: the scene again first (its failure is the frame's). */
  if (publish_scene(o, &e) == 0) {
    m.sent_us = wall_us();
    size_t len = mr_state_frame_encode(&m, o->buf, o->buf_cap);
    if (mr_net_publish(o->net, MR_NET_DATA, o->buf, len, &e) == 0) {
      o->c.sent++;
      o->c.bytes += len;
      return 0;
    }
  }
  if (e.status == MR_IO_TIMEOUT) {
    o->c.dropped_behind++;
  } else if (e.status == MR_IO_HANGUP) {
    o->c.dropped_away++;
  } else {
    if (err != NULL) *err = e;
    return -1;
  }
  return 1;
}

void mr_state_out_get_counters(const mr_state_out *o, mr_state_out_counters *out) {
  memset(out, 0, sizeof *out);
  if (o != NULL) *out = o->c;
}

void mr_state_out_close(mr_state_out *o) {
  if (o == NULL) return;
  if (o->net != NULL) {
    /* The show is over: no scene for watchers who come later. */
    if (mr_net_publish_retained(o->net, MR_NET_SCENE, "", 0, NULL) == 0) mr_net_flush(o->net, 500);
    mr_net_close(o->net);
  }
  free(o->scene_msg);
  free(o->pose);
  free(o->q);
  free(o->buf);
  free(o);
}

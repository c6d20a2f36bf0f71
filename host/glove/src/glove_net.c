/* A glove over an MQTT broker (mr_net): its frames come as messages on
 * TOPIC and TOPIC/reply, its commands go on TOPIC/cmd. The link reconnects
 * by itself; a loss of the broker is a loss of the glove, held as any. */
#include <stdio.h>
#include <string.h>

#include "glove_internal.h"

static bool is_loopback(const char *host) {
  return strcmp(host, "localhost") == 0 || strncmp(host, "127.", 4) == 0 ||
         strcmp(host, "::1") == 0;
}

mr_io_status mr_glove_net_check(const char *source, mr_glove_source_report *out) {
  mr_net_url u;
  mr_io_error err;
  if (mr_net_url_parse(source, &u, &err) != 0) {
    snprintf(out->msg, sizeof out->msg, "%s", err.msg);
    return err.status;
  }
  if (!u.tls && u.user[0] && !is_loopback(u.host))
    snprintf(out->note, sizeof out->note,
             "%.200s: plain mqtt:// sends the password in the clear beyond this machine (use "
             "mqtts://)",
             source);
  return MR_IO_OK;
}

int mr_glove_net_open(mr_glove *g, mr_io_error *err) {
  mr_net_def d = mr_default_net_def();
  snprintf(d.url, sizeof d.url, "%s", g->def.source);
  snprintf(d.name, sizeof d.name, "glove");
  d.role = MR_NET_RECEIVER;
  /* The show polls on: a broker slow to answer costs it one second once,
   * and the link goes on connecting meanwhile (the glove is silent, then
   * lost, as any). */
  d.connect_wait_ms = 1000;
  d.background = true;
  g->net_failed = false;
  return mr_net_open(&d, &g->net, err);
}

/* A message that does not end its last frame (garbage, or a publisher
 * that splits frames) is ended here, by the host's delimiter, so that it
 * costs one error and not the next message's first frame as well. The
 * delimiter is not counted as a byte received. */
static int feed_message(mr_glove *g, const uint8_t *buf, size_t got, double now) {
  if (g->tap != NULL) g->tap(g->tap_user, now, buf, got);
  int taken = mr_glove_feed(g, buf, got, now);
  if (buf[got - 1] != 0) {
    if (g->tap != NULL) g->tap(g->tap_user, now, (const uint8_t *)"", 1);
    taken += mr_glove_feed(g, (const uint8_t *)"", 1, now);
    g->dec.c.bytes--;
  }
  return taken;
}

bool mr_glove_net_read(mr_glove *g, double now, int timeout_ms, int *taken) {
  static const int most = 512; /* messages a poll takes: 2 s of a 250 Hz glove */
  uint8_t buf[MR_NET_MAX_MESSAGE];
  for (int round = 0; round < most; round++) {
    size_t got = 0;
    mr_io_error err;
    mr_io_status st =
        mr_net_read(g->net, buf, sizeof buf, round == 0 ? timeout_ms : 0, &got, NULL, &err);
    if (st == MR_IO_OK) {
      g->last_bytes = now;
      g->give_up_at = 0;
      *taken += feed_message(g, buf, got, now);
      continue;
    }
    if (st == MR_IO_TIMEOUT) return false;
    if (st == MR_IO_HANGUP) {
      mr_glove_mark_lost(g, now, "the broker went away; reconnecting", false);
    } else {
      g->net_failed = true; /* refused: opened again, from the start */
      mr_glove_mark_lost(g, now, err.msg, false);
    }
    return true;
  }
  return false;
}

void mr_glove_net_note(const mr_glove *g, char *out, size_t size) {
  char a[MR_NET_NAME_MAX + 64], b[MR_NET_NAME_MAX + 64];
  if (size > 0) out[0] = '\0';
  if (!mr_glove_net_publishers(g, a, b, sizeof a)) return;
  snprintf(out, size, "; two publishers on the topic: %s and %s", a, b);
}

bool mr_glove_net_counters(const mr_glove *g, mr_net_counters *out) {
  if (out != NULL) memset(out, 0, sizeof *out);
  if (g == NULL || g->net == NULL || out == NULL) return false;
  mr_net_get_counters(g->net, out);
  return true;
}

bool mr_glove_net_publishers(const mr_glove *g, char *first, char *second, size_t size) {
  return g != NULL && g->net != NULL && mr_net_publishers(g->net, first, second, size);
}

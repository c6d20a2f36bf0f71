/* A local glove relayed to a broker (gd_relay.h). The relay moves whole
 * frames, unchanged: it looks inside a frame only to tell an answer from
 * a sample, and forwards a frame it cannot read to TOPIC as it is, for
 * the receiver's decoder to count. */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gd_relay.h"
#include "gp.h"
#include "mr_net.h"

/* A run without a delimiter this long goes out as it is: no frame is. */
enum { PENDING_MAX = 4096 };

struct gd_relay {
  mr_net *net;
  uint8_t pending[PENDING_MAX];
  size_t pending_len;
  uint8_t data[MR_NET_MAX_MESSAGE], reply[MR_NET_MAX_MESSAGE];
  size_t data_len, reply_len;
  bool down;                 /* the broker is away: told once */
  uint64_t dropped;          /* messages not sent while it was */
  uint64_t commands, unsent; /* commands relayed down, and not */
};

int gd_relay_open(gd_relay **out, const char *url) {
  *out = NULL;
  gd_relay *r = calloc(1, sizeof *r);
  if (r == NULL) {
    fprintf(stderr, "glove-dump: out of memory\n");
    return 1;
  }
  mr_net_def d = mr_default_net_def();
  if (strlen(url) >= sizeof d.url) {
    fprintf(stderr, "glove-dump: --publish URL is longer than %zu characters\n", sizeof d.url - 1);
    free(r);
    return 2;
  }
  snprintf(d.url, sizeof d.url, "%s", url);
  snprintf(d.name, sizeof d.name, "glove-dump");
  d.role = MR_NET_RELAY;
  mr_io_error err;
  if (mr_net_open(&d, &r->net, &err) != 0) {
    fprintf(stderr, "glove-dump: %s%s\n", err.msg,
            err.status == MR_IO_ERR_SPEC ? " (see --help)" : "");
    free(r);
    return err.status == MR_IO_ERR_SPEC ? 2 : 1;
  }
  /* The stamp a reader names when two publishers share a topic. */
  fprintf(stderr, "glove-dump: %s: relaying as %s\n", mr_net_where(r->net), mr_net_id(r->net));
  *out = r;
  return 0;
}

/* An answer to a command goes on TOPIC/reply. */
static bool is_answer(const uint8_t *frame, size_t len) {
  uint8_t raw[GP_MAX_WIRE];
  if (len == 0 || len > GP_MAX_WIRE) return false;
  int n = gp_cobs_decode(frame, len, raw, sizeof raw);
  return n > 0 && (raw[0] == GP_ACK || raw[0] == GP_NACK || raw[0] == GP_STATUS);
}

static void send(gd_relay *r, mr_net_topic topic, uint8_t *buf, size_t *len) {
  mr_io_error err;
  if (*len == 0) return;
  if (mr_net_publish(r->net, topic, buf, *len, &err) != 0) r->dropped++;
  *len = 0;
}

/* One frame with its delimiter into the message for its topic. */
static void add_frame(gd_relay *r, const uint8_t *frame, size_t len) {
  bool answer = is_answer(frame, len - 1);
  uint8_t *buf = answer ? r->reply : r->data;
  size_t *used = answer ? &r->reply_len : &r->data_len;
  mr_net_topic topic = answer ? MR_NET_REPLY : MR_NET_DATA;
  if (*used + len > MR_NET_MAX_MESSAGE) send(r, topic, buf, used);
  memcpy(buf + *used, frame, len);
  *used += len;
}

void gd_relay_bytes(gd_relay *r, const uint8_t *bytes, size_t len) {
  for (size_t i = 0; i < len; i++) {
    r->pending[r->pending_len++] = bytes[i];
    /* An empty frame (delimiters in a row) carries nothing. */
    if (bytes[i] == 0 && r->pending_len == 1) {
      r->pending_len = 0;
    } else if (bytes[i] == 0 || r->pending_len == PENDING_MAX) {
      add_frame(r, r->pending, r->pending_len);
      r->pending_len = 0;
    }
  }
  send(r, MR_NET_DATA, r->data, &r->data_len);
  send(r, MR_NET_REPLY, r->reply, &r->reply_len);
}

/* A loss of the broker and its return, each told once. */
static void tell(gd_relay *r) {
  bool up = mr_net_connected(r->net);
  if (up == !r->down) return;
  r->down = !up;
  if (r->down)
    fprintf(stderr,
            "glove-dump: %s: the broker went away; reconnecting (frames meanwhile are "
            "dropped)\n",
            mr_net_where(r->net));
  else
    fprintf(stderr, "glove-dump: %s: reconnected\n", mr_net_where(r->net));
}

int gd_relay_poll(gd_relay *r, mr_glove *g) {
  static uint8_t buf[MR_NET_MAX_MESSAGE];
  for (int round = 0; round < 64; round++) {
    size_t got = 0;
    mr_io_error err;
    mr_io_status st = mr_net_read(r->net, buf, sizeof buf, 0, &got, NULL, &err);
    if (st == MR_IO_OK) {
      char msg[400];
      if (mr_glove_send_raw(g, buf, got, msg, sizeof msg) == 0)
        r->commands++;
      else
        r->unsent++;
      continue;
    }
    if (mr_io_failed(st)) {
      fprintf(stderr, "glove-dump: %s\n", err.msg);
      return 1;
    }
    if (st == MR_IO_TIMEOUT) break;
  }
  tell(r);
  return 0;
}

void gd_relay_close(gd_relay *r, FILE *report) {
  if (r == NULL) return;
  mr_net_counters c;
  mr_net_get_counters(r->net, &c);
  if (report != NULL)
    fprintf(report,
            "relay_sent=%llu\nrelay_dropped=%llu\nrelay_commands=%llu\nrelay_commands_unsent=%llu\n"
            "relay_losses=%llu\n",
            (unsigned long long)c.sent, (unsigned long long)r->dropped,
            (unsigned long long)r->commands, (unsigned long long)r->unsent,
            (unsigned long long)c.losses);
  mr_net_close(r->net);
  free(r);
}

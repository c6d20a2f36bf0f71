/* What runs on libmosquitto's network thread: the broker's answers and
 * the messages it delivers. Each callback takes the lock, changes the
 * shared part of the link (net_internal.h) and wakes a waiting reader;
 * nothing else of the link is touched here. */
#include <errno.h>
#include <mosquitto.h>
#include <mqtt_protocol.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "net_internal.h"

/* A publisher silent this long is gone: its successor is no second one. */
#define PUBLISHER_GONE_NS 3000000000ull

static void wake(mr_net *n) {
  pthread_cond_broadcast(&n->cv);
  pthread_mutex_unlock(&n->mu);
}

/* Under mu: the link is refused for good. */
static void refuse(mr_net *n, const char *what, const char *why) {
  if (n->refused) return;
  n->refused = true;
  n->answered = true;
  snprintf(n->fatal, sizeof n->fatal, "%.120s: %.150s%s%.200s", n->where, what, why[0] ? ": " : "",
           why);
}

static void on_connect(struct mosquitto *m, void *user, int rc, int flags,
                       const mosquitto_property *props) {
  mr_net *n = user;
  (void)flags;
  (void)props;
  pthread_mutex_lock(&n->mu);
  if (rc != 0) {
    char what[200];
    if (n->url.user[0])
      snprintf(what, sizeof what, "the broker refused user %.100s", n->url.user);
    else
      snprintf(what, sizeof what, "the broker refused an anonymous client");
    char why[200];
    snprintf(why, sizeof why, "%s%s", mosquitto_reason_string(rc),
             n->url.user[0] ? " (check the password: password-file= or MR_MQTT_PASSWORD)" : "");
    refuse(n, what, why);
    wake(n);
    mosquitto_disconnect(m); /* no retries: the answer would be the same */
    return;
  }
  n->connected = true;
  n->probe_due = true;
  n->c.connects++;
  n->written = n->c.sent; /* what a lost connection had queued is gone */
  /* The session is clean: every connection subscribes again. */
  char *subs[2];
  int count = 0;
  if (n->def.role == MR_NET_RELAY) {
    subs[count++] = n->topic[MR_NET_CMD];
  } else if (n->def.role == MR_NET_WATCHER) {
    subs[count++] = n->topic[MR_NET_DATA];
    subs[count++] = n->topic[MR_NET_SCENE];
  } else if (n->def.role == MR_NET_RECEIVER) {
    subs[count++] = n->topic[MR_NET_DATA];
    subs[count++] = n->topic[MR_NET_REPLY];
  }
  if (count == 0) {
    n->answered = true; /* a show's publisher reads nothing: the CONNACK is the answer */
    wake(n);
    return;
  }
  pthread_mutex_unlock(&n->mu);
  mosquitto_subscribe_multiple(m, NULL, count, subs, 1, 0, NULL);
}

static void on_subscribe(struct mosquitto *m, void *user, int mid, int count, const int *granted,
                         const mosquitto_property *props) {
  mr_net *n = user;
  (void)m;
  (void)mid;
  (void)props;
  pthread_mutex_lock(&n->mu);
  for (int i = 0; i < count; i++) {
    if (granted[i] < 0x80) continue;
    char what[300];
    snprintf(what, sizeof what, "the broker refused to let %.60s read %.80s",
             n->url.user[0] ? n->url.user : "an anonymous client",
             n->def.role == MR_NET_RELAY ? n->topic[MR_NET_CMD] : n->url.topic);
    refuse(n, what, mosquitto_reason_string(granted[i]));
  }
  n->answered = true;
  wake(n);
}

static void on_disconnect(struct mosquitto *m, void *user, int rc,
                          const mosquitto_property *props) {
  mr_net *n = user;
  (void)m;
  (void)props;
  /* The network thread's own errno, read at once: why a socket failed. */
  int sys_errno = errno;
  const char *sys = rc == MOSQ_ERR_ERRNO && sys_errno != 0 ? strerror(sys_errno) : NULL;
  pthread_mutex_lock(&n->mu);
  if (n->connected) {
    n->connected = false;
    n->c.losses++;
    n->lost_pending++;
  } else if (!n->answered) {
    /* Closed before the broker answered: a TLS handshake that failed (the
     * log said), a socket's error, or without either only what is known:
     * no broker answered there. */
    char why[300]; /* the longest 210 */
    snprintf(why, sizeof why,
             "no MQTT answer from %.60s:%d (no broker running there, the network not reaching "
             "it, or a server of another kind%s)",
             n->url.host, n->url.port, n->url.tls ? "" : ", perhaps one that wants mqtts://");
    refuse(n, "the connection closed before the broker answered",
           n->last_log[0] ? n->last_log
           : sys != NULL  ? sys
                          : why);
  }
  wake(n);
}

static void on_publish(struct mosquitto *m, void *user, int mid, int rc,
                       const mosquitto_property *props) {
  mr_net *n = user;
  (void)m;
  (void)mid;
  (void)props;
  pthread_mutex_lock(&n->mu);
  n->written++;
  if (rc < 0x80) {
    wake(n); /* mr_net_flush may be waiting */
    return;
  }
  n->c.send_refused++;
  char what[300];
  snprintf(what, sizeof what, "the broker refused to let %.60s publish to %.80s",
           n->url.user[0] ? n->url.user : "an anonymous client", n->url.topic);
  refuse(n, what, mosquitto_reason_string(rc));
  wake(n);
}

/* The stamp of a message, or NULL. */
static const char *stamp_of(const mosquitto_property *props, char **name, char **value) {
  const mosquitto_property *p = props;
  bool skip = false;
  while ((p = mosquitto_property_read_string_pair(p, MQTT_PROP_USER_PROPERTY, name, value, skip)) !=
         NULL) {
    skip = true;
    bool ours = strcmp(*name, "mr-publisher") == 0;
    free(*name);
    *name = NULL;
    if (ours) return *value;
    free(*value);
    *value = NULL;
  }
  return NULL;
}

/* Under mu: who sent a data message. */
static void track(mr_net *n, const char *stamp) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  uint64_t now = (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
  net_publisher *first = &n->pub[0];
  if (stamp == NULL) {
    n->c.unstamped++;
  } else if (strcmp(first->name, stamp) == 0) {
    first->last_ns = now;
  } else if (first->name[0] == '\0' || now - first->last_ns > PUBLISHER_GONE_NS) {
    snprintf(first->name, sizeof first->name, "%s", stamp);
    first->last_ns = now;
  } else {
    n->c.foreign++;
    n->two = true;
    snprintf(n->pub[1].name, sizeof n->pub[1].name, "%s", stamp);
    n->pub[1].last_ns = now;
  }
}

static void on_message(struct mosquitto *m, void *user, const struct mosquitto_message *msg,
                       const mosquitto_property *props) {
  mr_net *n = user;
  (void)m;
  int topic = -1;
  for (int t = 0; t < 4; t++)
    if (strcmp(msg->topic, n->topic[t]) == 0) topic = t;
  char *name = NULL, *value = NULL;
  const char *stamp = stamp_of(props, &name, &value);
  pthread_mutex_lock(&n->mu);
  if (topic == MR_NET_DATA) track(n, stamp);
  uint8_t *copy = NULL;
  if (msg->payloadlen <= 0)
    n->c.empty++;
  else if ((size_t)msg->payloadlen > n->def.max_message)
    n->c.oversized++;
  else if (n->count >= n->def.queue_messages)
    n->c.queue_full++;
  else if (topic >= 0 && (copy = malloc((size_t)msg->payloadlen)) != NULL) {
    memcpy(copy, msg->payload, (size_t)msg->payloadlen);
    net_msg *slot = &n->ring[(n->head + n->count) % n->def.queue_messages];
    slot->data = copy;
    slot->len = (size_t)msg->payloadlen;
    slot->topic = (mr_net_topic)topic;
    n->count++;
  }
  wake(n);
  free(value);
}

static void on_log(struct mosquitto *m, void *user, int level, const char *line) {
  mr_net *n = user;
  (void)m;
  if (!(level & (MOSQ_LOG_ERR | MOSQ_LOG_WARNING))) return;
  /* OpenSSL's lines read "OpenSSL Error[0]: error:0A000086:SSL
   * routines::certificate verify failed": the words after the last
   * colon say it. */
  const char *say = strstr(line, "OpenSSL") ? strrchr(line, ':') : NULL;
  pthread_mutex_lock(&n->mu);
  if (say != NULL)
    snprintf(n->last_log, sizeof n->last_log, "TLS: %s", say + 1);
  else
    snprintf(n->last_log, sizeof n->last_log, "%s", line);
  /* A handshake that fails before the broker answered fails the same way
   * on every try: told at once, not after the wait. */
  if (say != NULL && !n->answered)
    refuse(n, "the TLS handshake failed",
           strstr(say, "verify failed") != NULL
               ? "certificate verify failed (is cafile= the CA that signed the broker's?)"
               : say + 1);
  wake(n);
}

void mr_net_set_callbacks(mr_net *n) {
  mosquitto_connect_v5_callback_set(n->mosq, on_connect);
  mosquitto_subscribe_v5_callback_set(n->mosq, on_subscribe);
  mosquitto_disconnect_v5_callback_set(n->mosq, on_disconnect);
  mosquitto_publish_v5_callback_set(n->mosq, on_publish);
  mosquitto_message_v5_callback_set(n->mosq, on_message);
  mosquitto_log_callback_set(n->mosq, on_log);
}

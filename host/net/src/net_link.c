/* A link to a broker: opened on the caller's thread, run on libmosquitto's
 * (net_callbacks.c), read and written through the queue and the lock. */
#include <errno.h>
#include <mosquitto.h>
#include <mqtt_protocol.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "net_internal.h"

int mr_net_err(mr_io_error *err, mr_io_status status, const char *fmt, ...) {
  if (err != NULL) {
    va_list ap;
    err->status = status;
    err->sys_errno = 0;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
  }
  return -1;
}

mr_net_def mr_default_net_def(void) {
  mr_net_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  snprintf(d.name, sizeof d.name, "mr");
  d.queue_messages = MR_NET_DEFAULT_QUEUE;
  d.connect_wait_ms = 3000;
  d.keepalive_s = 5;
  d.background = false;
  d.max_message = MR_NET_MAX_MESSAGE;
  d.max_unsent = 0;
  return d;
}

static pthread_once_t lib_once = PTHREAD_ONCE_INIT;
static void lib_init(void) {
  mosquitto_lib_init();
}

/* The password: password-file's first line, else MR_MQTT_PASSWORD. */
static int read_password(const mr_net *n, char *out, size_t size, mr_io_error *err) {
  out[0] = '\0';
  if (n->url.password_file[0] == '\0') {
    const char *env = getenv("MR_MQTT_PASSWORD");
    if (env != NULL) snprintf(out, size, "%s", env);
    return 0;
  }
  FILE *f = fopen(n->url.password_file, "r");
  if (f == NULL)
    return mr_net_err(err, MR_IO_ERR_SPEC, "%s: password-file %s: %s", n->where,
                      n->url.password_file, strerror(errno));
  if (fgets(out, (int)size, f) == NULL) out[0] = '\0';
  fclose(f);
  out[strcspn(out, "\r\n")] = '\0';
  return 0;
}

static int setup(mr_net *n, mr_io_error *err) {
  char password[256];
  if (read_password(n, password, sizeof password, err) != 0) return -1;
  n->mosq = mosquitto_new(n->id, true, n);
  if (n->mosq == NULL) return mr_net_err(err, MR_IO_ERR_SYSTEM, "%s: out of memory", n->where);
  mosquitto_int_option(n->mosq, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V5);
  int rc = MOSQ_ERR_SUCCESS;
  if (n->url.user[0])
    rc = mosquitto_username_pw_set(n->mosq, n->url.user, password[0] ? password : NULL);
  memset(password, 0, sizeof password);
  if (rc == MOSQ_ERR_SUCCESS && n->url.tls) {
    if (n->url.cafile[0])
      rc = mosquitto_tls_set(n->mosq, n->url.cafile, NULL, NULL, NULL, NULL);
    else
      rc = mosquitto_int_option(n->mosq, MOSQ_OPT_TLS_USE_OS_CERTS, 1);
  }
  if (rc != MOSQ_ERR_SUCCESS)
    return mr_net_err(err, MR_IO_ERR_SPEC, "%s: %s%s", n->where, mosquitto_strerror(rc),
                      n->url.cafile[0] ? " (is cafile= a readable PEM file?)" : "");
  /* A lost broker is tried again once a second: back within 2 s of its
   * return (DESIGN, issue 24 item 5). */
  mosquitto_reconnect_delay_set(n->mosq, 1, 1, false);
  mr_net_set_callbacks(n);
  return 0;
}

/* Waits for the broker's answer to the connection. 0, or -1 with err. */
static int await_answer(mr_net *n, mr_io_error *err) {
  struct timespec until;
  clock_gettime(CLOCK_REALTIME, &until);
  until.tv_sec += n->def.connect_wait_ms / 1000;
  until.tv_nsec += (long)(n->def.connect_wait_ms % 1000) * 1000000L;
  if (until.tv_nsec >= 1000000000L) {
    until.tv_sec++;
    until.tv_nsec -= 1000000000L;
  }
  pthread_mutex_lock(&n->mu);
  while (!n->answered && pthread_cond_timedwait(&n->cv, &n->mu, &until) == 0) {
  }
  int rc = 0;
  if (n->refused)
    rc = mr_net_err(err, MR_IO_ERR_SYSTEM, "%s", n->fatal);
  else if (!n->answered && !n->def.background)
    rc = mr_net_err(err, MR_IO_ERR_SYSTEM, "%s: no answer from the broker within %d ms%s%s",
                    n->where, n->def.connect_wait_ms, n->last_log[0] ? ": " : "", n->last_log);
  pthread_mutex_unlock(&n->mu);
  return rc;
}

static int connect_now(mr_net *n, mr_io_error *err) {
  errno = 0;
  /* Asynchronous: a port that refuses says so at once, and a host that
   * does not answer costs connect_wait_ms, not the kernel's minutes. */
  int rc =
      mosquitto_connect_bind_async(n->mosq, n->url.host, n->url.port, n->def.keepalive_s, NULL);
  if (rc == MOSQ_ERR_ERRNO)
    return mr_net_err(err, MR_IO_ERR_SYSTEM, "%s: cannot connect to %s:%d: %s", n->where,
                      n->url.host, n->url.port, strerror(errno));
  if (rc != MOSQ_ERR_SUCCESS) {
    /* A handshake that failed at once was told by the log (on_log). */
    pthread_mutex_lock(&n->mu);
    if (n->refused)
      mr_net_err(err, MR_IO_ERR_SYSTEM, "%s", n->fatal);
    else
      mr_net_err(err, rc == MOSQ_ERR_EAI ? MR_IO_ERR_SPEC : MR_IO_ERR_SYSTEM,
                 "%s: cannot connect to %s:%d: %s", n->where, n->url.host, n->url.port,
                 n->last_log[0] ? n->last_log : mosquitto_strerror(rc));
    pthread_mutex_unlock(&n->mu);
    return -1;
  }
  if (mosquitto_loop_start(n->mosq) != MOSQ_ERR_SUCCESS)
    return mr_net_err(err, MR_IO_ERR_SYSTEM, "%s: cannot start the network thread", n->where);
  n->loop_started = true;
  return await_answer(n, err);
}

static void name_link(mr_net *n) {
  char host[64] = "";
  gethostname(host, sizeof host - 1);
  host[sizeof host - 1] = '\0';
  /* One process may hold many links (a benchmark's watchers): each past
   * the first gets a number of its own, as a broker takes one connection
   * per client id. */
  static atomic_int links;
  int k = atomic_fetch_add(&links, 1);
  if (k == 0)
    snprintf(n->id, sizeof n->id, "%.40s-%.60s-%ld", n->def.name, host, (long)getpid());
  else
    snprintf(n->id, sizeof n->id, "%.40s-%.60s-%ld-%d", n->def.name, host, (long)getpid(), k + 1);
  const char *q = strchr(n->def.url, '?');
  int len = q ? (int)(q - n->def.url) : (int)strlen(n->def.url);
  snprintf(n->where, sizeof n->where, "%.*s", len, n->def.url);
  snprintf(n->topic[MR_NET_DATA], MR_NET_TOPIC_MAX + 8, "%s", n->url.topic);
  snprintf(n->topic[MR_NET_CMD], MR_NET_TOPIC_MAX + 8, "%s/cmd", n->url.topic);
  snprintf(n->topic[MR_NET_REPLY], MR_NET_TOPIC_MAX + 8, "%s/reply", n->url.topic);
  snprintf(n->topic[MR_NET_SCENE], MR_NET_TOPIC_MAX + 8, "%s/scene", n->url.topic);
}

int mr_net_open(const mr_net_def *def, mr_net **out, mr_io_error *err) {
  *out = NULL;
  if (def == NULL || def->cookie != MR_DEF_COOKIE || def->queue_messages < 1 ||
      def->connect_wait_ms < 1 || def->keepalive_s < 5 || def->max_message < 1 ||
      def->max_message > (size_t)1 << 28 || def->max_unsent < 0)
    return mr_net_err(err, MR_IO_ERR_ARG,
                      "expected a link definition made by mr_default_net_def, with "
                      "queue_messages >= 1, connect_wait_ms >= 1, keepalive_s >= 5, "
                      "max_message 1..256 MiB and max_unsent >= 0");
  mr_net *n = calloc(1, sizeof *n);
  if (n == NULL) return mr_net_err(err, MR_IO_ERR_SYSTEM, "out of memory");
  n->def = *def;
  n->def.url[MR_NET_URL_MAX - 1] = '\0';
  n->def.name[MR_NET_NAME_MAX - 1] = '\0';
  pthread_mutex_init(&n->mu, NULL);
  pthread_cond_init(&n->cv, NULL);
  if (mr_net_url_parse(n->def.url, &n->url, err) != 0) {
    mr_net_close(n);
    return -1;
  }
  name_link(n);
  pthread_once(&lib_once, lib_init);
  n->ring = calloc((size_t)n->def.queue_messages, sizeof *n->ring);
  if (n->ring == NULL) {
    mr_net_close(n);
    return mr_net_err(err, MR_IO_ERR_SYSTEM, "out of memory");
  }
  if (setup(n, err) != 0 || connect_now(n, err) != 0) {
    mr_net_close(n);
    return -1;
  }
  *out = n;
  return 0;
}

/* Under mu: the next message out of the queue into buf. */
static void take(mr_net *n, uint8_t *buf, size_t cap, size_t *got, mr_net_topic *topic) {
  net_msg *m = &n->ring[n->head];
  size_t len = m->len < cap ? m->len : cap;
  memcpy(buf, m->data, len);
  *got = len;
  if (topic != NULL) *topic = m->topic;
  n->c.messages++;
  n->c.bytes += len;
  free(m->data);
  m->data = NULL;
  n->head = (n->head + 1) % n->def.queue_messages;
  n->count--;
}

mr_io_status mr_net_read(mr_net *n, uint8_t *buf, size_t cap, int timeout_ms, size_t *got,
                         mr_net_topic *topic, mr_io_error *err) {
  *got = 0;
  if (n == NULL || buf == NULL || cap < n->def.max_message) {
    mr_net_err(err, MR_IO_ERR_ARG, "expected a link and a buffer of %zu bytes",
               n != NULL ? n->def.max_message : (size_t)MR_NET_MAX_MESSAGE);
    return MR_IO_ERR_ARG;
  }
  struct timespec until;
  clock_gettime(CLOCK_REALTIME, &until);
  long long ns = (long long)until.tv_nsec + (long long)(timeout_ms > 0 ? timeout_ms : 0) * 1000000;
  until.tv_sec += (time_t)(ns / 1000000000);
  until.tv_nsec = (long)(ns % 1000000000);
  mr_io_status st = MR_IO_TIMEOUT;
  pthread_mutex_lock(&n->mu);
  for (;;) {
    /* Messages that came before a loss are handed out before it. */
    if (n->count > 0) {
      take(n, buf, cap, got, topic);
      st = MR_IO_OK;
    } else if (n->lost_pending > 0) {
      n->lost_pending--;
      st = MR_IO_HANGUP;
    } else if (n->refused) {
      mr_net_err(err, MR_IO_ERR_SYSTEM, "%s", n->fatal);
      st = MR_IO_ERR_SYSTEM;
    } else if (timeout_ms != 0 &&
               (timeout_ms < 0 ? pthread_cond_wait(&n->cv, &n->mu)
                               : pthread_cond_timedwait(&n->cv, &n->mu, &until)) == 0) {
      continue;
    }
    break;
  }
  pthread_mutex_unlock(&n->mu);
  return st;
}

static int publish(mr_net *n, mr_net_topic topic, const void *data, size_t len, bool retain,
                   mr_io_error *err) {
  if (n == NULL || (int)topic < 0 || topic > MR_NET_SCENE || (len == 0 && !retain) ||
      len > n->def.max_message)
    return mr_net_err(err, MR_IO_ERR_ARG, "expected a link, a topic and 1..%zu bytes",
                      n != NULL ? n->def.max_message : (size_t)MR_NET_MAX_MESSAGE);
  pthread_mutex_lock(&n->mu);
  bool up = n->connected && !n->refused;
  /* Samples go at QoS 0; the first data message of a connection goes at
   * QoS 1, so that a broker whose ACL refuses it says so (a QoS 0 message
   * refused is dropped without a word). */
  int qos = topic != MR_NET_DATA || n->probe_due || retain ? 1 : 0;
  bool full = up && qos == 0 && n->def.max_unsent > 0 &&
              n->c.sent - n->written >= (uint64_t)n->def.max_unsent;
  if (full) n->c.send_dropped++;
  if (up && !full && topic == MR_NET_DATA) n->probe_due = false;
  pthread_mutex_unlock(&n->mu);
  if (!up) return mr_net_err(err, MR_IO_HANGUP, "%s: not connected", n->where);
  if (full) return mr_net_err(err, MR_IO_TIMEOUT, "%s: the network is behind", n->where);
  mosquitto_property *props = NULL;
  mosquitto_property_add_string_pair(&props, MQTT_PROP_USER_PROPERTY, "mr-publisher", n->id);
  int rc = mosquitto_publish_v5(n->mosq, NULL, n->topic[topic], (int)len, data, qos, retain, props);
  mosquitto_property_free_all(&props);
  if (rc != MOSQ_ERR_SUCCESS)
    return mr_net_err(err, MR_IO_ERR_SYSTEM, "%s: %s", n->where, mosquitto_strerror(rc));
  pthread_mutex_lock(&n->mu);
  n->c.sent++;
  pthread_mutex_unlock(&n->mu);
  return 0;
}

int mr_net_publish(mr_net *n, mr_net_topic topic, const void *data, size_t len, mr_io_error *err) {
  return publish(n, topic, data, len, false, err);
}

int mr_net_publish_retained(mr_net *n, mr_net_topic topic, const void *data, size_t len,
                            mr_io_error *err) {
  return publish(n, topic, data, len, true, err);
}

bool mr_net_flush(mr_net *n, int timeout_ms) {
  if (n == NULL) return true;
  struct timespec until;
  clock_gettime(CLOCK_REALTIME, &until);
  long long ns = (long long)until.tv_nsec + (long long)(timeout_ms > 0 ? timeout_ms : 0) * 1000000;
  until.tv_sec += (time_t)(ns / 1000000000);
  until.tv_nsec = (long)(ns % 1000000000);
  pthread_mutex_lock(&n->mu);
  while (n->connected && n->written < n->c.sent &&
         pthread_cond_timedwait(&n->cv, &n->mu, &until) == 0) {
  }
  bool done = n->written >= n->c.sent;
  pthread_mutex_unlock(&n->mu);
  return done;
}

bool mr_net_connected(mr_net *n) {
  if (n == NULL) return false;
  pthread_mutex_lock(&n->mu);
  bool up = n->connected;
  pthread_mutex_unlock(&n->mu);
  return up;
}

void mr_net_get_counters(mr_net *n, mr_net_counters *out) {
  memset(out, 0, sizeof *out);
  if (n == NULL) return;
  pthread_mutex_lock(&n->mu);
  *out = n->c;
  pthread_mutex_unlock(&n->mu);
}

bool mr_net_publishers(mr_net *n, char *first, char *second, size_t size) {
  if (n == NULL) return false;
  pthread_mutex_lock(&n->mu);
  bool two = n->two;
  if (two) {
    snprintf(first, size, "%s", n->pub[0].name);
    snprintf(second, size, "%s", n->pub[1].name);
  }
  pthread_mutex_unlock(&n->mu);
  return two;
}

const char *mr_net_id(const mr_net *n) {
  return n != NULL ? n->id : "";
}

const char *mr_net_where(const mr_net *n) {
  return n != NULL ? n->where : "";
}

void mr_net_close(mr_net *n) {
  if (n == NULL) return;
  if (n->mosq != NULL) {
    mosquitto_disconnect(n->mosq);
    if (n->loop_started) mosquitto_loop_stop(n->mosq, false);
    mosquitto_destroy(n->mosq);
  }
  for (int i = 0; n->ring != NULL && i < n->count; i++)
    free(n->ring[(n->head + i) % n->def.queue_messages].data);
  free(n->ring);
  pthread_cond_destroy(&n->cv);
  pthread_mutex_destroy(&n->mu);
  free(n);
}

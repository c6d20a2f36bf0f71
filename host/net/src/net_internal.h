/* Shared between mr_net's files; not part of the public API. */
#ifndef NET_INTERNAL_H
#define NET_INTERNAL_H

#include <pthread.h>

#include "mr_net.h"

#if defined(__GNUC__)
#define MR_NET_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define MR_NET_PRINTF(a, b)
#endif

/* Fills *err (if not NULL) and returns -1. */
int mr_net_err(mr_io_error *err, mr_io_status status, const char *fmt, ...) MR_NET_PRINTF(3, 4);

/* A received message, waiting for the caller. */
typedef struct net_msg {
  uint8_t *data;
  size_t len;
  mr_net_topic topic;
} net_msg;

/* A publisher seen on the data topic, by its stamp. */
typedef struct net_publisher {
  char name[MR_NET_NAME_MAX + 64];
  uint64_t last_ns;
} net_publisher;

struct mr_net {
  /* Set by mr_net_open, read-only after: both threads read them. */
  mr_net_def def;
  mr_net_url url;
  struct mosquitto *mosq;
  char id[MR_NET_NAME_MAX + 64];
  char where[MR_NET_URL_MAX];
  char topic[4][MR_NET_TOPIC_MAX + 8];
  bool loop_started;

  /* Everything below is shared with the network thread: under mu. */
  pthread_mutex_t mu;
  pthread_cond_t cv;
  net_msg *ring;
  int head, count;
  bool connected;
  bool answered;    /* this connection's CONNACK and SUBACK came (or a refusal) */
  bool refused;     /* for good: fatal says why */
  bool probe_due;   /* the next data message goes at QoS 1, to learn the ACL's answer */
  int lost_pending; /* losses not yet told by mr_net_read */
  char fatal[480];
  char last_log[200]; /* libmosquitto's last error line (a TLS failure) */
  mr_net_counters c;
  uint64_t written; /* publishes the network thread wrote (or had answered) */
  net_publisher pub[2];
  bool two;
};

/* net_callbacks.c: installs the network thread's callbacks on n->mosq. */
void mr_net_set_callbacks(mr_net *n);

#endif

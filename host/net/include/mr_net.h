/* mr_net: a glove over an MQTT broker (host/net/README.md).
 *
 * A link is one client of a broker, named by a URL:
 *
 *   mqtt://[USER@]HOST[:PORT]/TOPIC[?OPTION&...]     plain TCP, port 1883
 *   mqtts://[USER@]HOST[:PORT]/TOPIC[?OPTION&...]    TLS, port 8883
 *
 * with the options
 *   cafile=PATH          the CA that signed the broker's certificate (mqtts;
 *                        without it the system's CAs in /etc/ssl/certs)
 *   password-file=PATH   the password, the file's first line; without it
 *                        the environment's MR_MQTT_PASSWORD, if set. Never
 *                        on the command line, where ps shows it.
 *
 * A glove's messages go on three topics: TOPIC carries its frames (SAMPLE,
 * INFO) at QoS 0, TOPIC/cmd the host's commands down to it at QoS 1,
 * TOPIC/reply its answers (ACK, NACK, STATUS) at QoS 1. Every message
 * holds whole COBS frames of the glove protocol, unchanged, and is stamped
 * with an MQTT v5 user property "mr-publisher" naming the client that sent
 * it, so that two publishers on one glove topic show.
 *
 * The network runs on libmosquitto's own thread. What it receives goes to
 * the caller through a bounded queue under a lock; the caller's thread
 * owns everything else. The link reconnects by itself after a loss, once
 * a second. Nothing here prints or aborts.
 */
#ifndef MR_NET_H
#define MR_NET_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_def.h"
#include "mr_io.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
  MR_NET_URL_MAX = 1024,
  MR_NET_TOPIC_MAX = 200,
  MR_NET_NAME_MAX = 64,
  /* The largest message taken; a longer one is dropped whole and counted
   * (a glove's frames are tens of bytes, a relay's message a few of them). */
  MR_NET_MAX_MESSAGE = 16384,
  MR_NET_DEFAULT_QUEUE = 1024 /* messages waiting for the caller */
};

/* A URL taken apart. */
typedef struct mr_net_url {
  bool tls;
  int port;
  char user[128];
  char host[256];
  char topic[MR_NET_TOPIC_MAX];
  char cafile[256];
  char password_file[256];
} mr_net_url;

/* True for a string that names a broker (mqtt:// or mqtts://). */
bool mr_net_is_url(const char *s);

/* Parses url: 0, or -1 with err (MR_IO_ERR_SPEC) saying what is wrong. */
int mr_net_url_parse(const char *url, mr_net_url *out, mr_io_error *err);

/* The topics a link uses. */
typedef enum mr_net_topic {
  MR_NET_DATA = 0, /* TOPIC: the glove's frames */
  MR_NET_CMD,      /* TOPIC/cmd: commands down to the glove */
  MR_NET_REPLY,    /* TOPIC/reply: the glove's answers */
  MR_NET_SCENE     /* TOPIC/scene: a show's scene, retained (mr_state.h) */
} mr_net_topic;

/* What the link does on the topic. */
typedef enum mr_net_role {
  MR_NET_RECEIVER = 0, /* reads DATA and REPLY, sends CMD: a host's glove */
  MR_NET_RELAY,        /* reads CMD, sends DATA and REPLY: a glove's relay */
  MR_NET_SHOW,         /* reads nothing, sends DATA and SCENE: a show's state */
  MR_NET_WATCHER       /* reads DATA and SCENE: a show's audience */
} mr_net_role;

typedef struct mr_net_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_net_def() */
  char url[MR_NET_URL_MAX];
  mr_net_role role;
  /* The client's name, the start of its MQTT client id and its stamp on
   * every message (a pid and the host's name are added); default "mr". */
  char name[MR_NET_NAME_MAX];
  int queue_messages;  /* received messages held for the caller; default 1024 */
  int connect_wait_ms; /* how long an open waits for the broker's answer; default 3000 */
  /* An open that has no answer within connect_wait_ms succeeds all the
   * same, and the link goes on trying in the background (a show's glove:
   * the show never waits longer). Default false: the open fails. */
  bool background;
  int keepalive_s; /* default 5: a dead broker is found within 1.5 times this */
  /* The longest message taken or sent; default MR_NET_MAX_MESSAGE (a
   * show's scene with its models is larger). mr_net_read's cap must be
   * at least this. */
  size_t max_message;
  /* DATA messages handed to the network thread and not yet written to
   * the socket, at the most: past it mr_net_publish drops the message
   * (counted in send_dropped) rather than queue it, so that a publisher
   * never waits for the network. Default 0: no bound. */
  int max_unsent;
} mr_net_def;
mr_net_def mr_default_net_def(void);

typedef struct mr_net_counters {
  uint64_t messages;     /* received and handed on */
  uint64_t bytes;        /* in those messages */
  uint64_t oversized;    /* longer than MR_NET_MAX_MESSAGE: dropped */
  uint64_t queue_full;   /* dropped because the caller fell behind */
  uint64_t empty;        /* messages of no bytes: dropped */
  uint64_t unstamped;    /* without an mr-publisher property (taken) */
  uint64_t foreign;      /* from a second publisher while the first one sends */
  uint64_t sent;         /* messages published */
  uint64_t send_refused; /* publishes the broker refused */
  uint64_t send_dropped; /* DATA not sent: max_unsent were waiting for the socket */
  uint64_t connects;     /* connections the broker accepted */
  uint64_t losses;       /* connections lost (each reconnected by itself) */
} mr_net_counters;

typedef struct mr_net mr_net;

/* Connects to the broker, waits up to def->connect_wait_ms for it to accept,
 * subscribes to the role's topics and starts the network thread (with
 * def->background, a broker that has not answered yet is no failure: its
 * refusal, if it comes, is told by mr_net_read). 0, or -1
 * with err saying why in a user's words: MR_IO_ERR_SPEC for a URL that does
 * not parse or a password file that cannot be read; MR_IO_ERR_SYSTEM for a
 * broker that is not there, refused the user or password, failed the TLS
 * handshake, or refused a subscription (the ACL). */
int mr_net_open(const mr_net_def *def, mr_net **out, mr_io_error *err);

/* One received message, waiting up to timeout_ms (negative: forever):
 * MR_IO_OK with *got bytes (cap must be at least the def's max_message) and
 * *topic (may be NULL); MR_IO_TIMEOUT; MR_IO_HANGUP once for each loss of
 * the broker (the link reconnects by itself: keep reading); a failure
 * (MR_IO_ERR_SYSTEM) when the broker refused the link for good, with err
 * saying why. */
mr_io_status mr_net_read(mr_net *n, uint8_t *buf, size_t cap, int timeout_ms, size_t *got,
                         mr_net_topic *topic, mr_io_error *err);

/* Publishes len bytes on topic, at QoS 0 for DATA, else 1. 0, or -1 with
 * err: status MR_IO_HANGUP while the broker is away (the message is
 * dropped, not kept), MR_IO_TIMEOUT when max_unsent messages wait for the
 * socket (dropped and counted), a failure otherwise. A refusal by
 * the broker (its ACL) comes back later, as a failure of mr_net_read. */
int mr_net_publish(mr_net *n, mr_net_topic topic, const void *data, size_t len, mr_io_error *err);

/* The same, retained by the broker for clients that subscribe later (QoS
 * 1): a show's scene. An empty message (len 0) clears what was retained. */
int mr_net_publish_retained(mr_net *n, mr_net_topic topic, const void *data, size_t len,
                            mr_io_error *err);

/* Waits up to timeout_ms until every message published so far is
 * written to the broker (QoS 0) or answered (QoS 1): true, else false
 * (the time ran out, or the broker went away). */
bool mr_net_flush(mr_net *n, int timeout_ms);

/* True while the broker has the link. */
bool mr_net_connected(mr_net *n);

void mr_net_get_counters(mr_net *n, mr_net_counters *out);

/* Two publishers on the topic: fills first and second (MR_NET_NAME_MAX +
 * 64 bytes each) with their stamps and returns true; false while one
 * publisher (or none) is seen. A publisher silent for 3 s is gone: the one
 * that follows it (a relay restarted) is no second publisher. */
bool mr_net_publishers(mr_net *n, char *first, char *second, size_t size);

/* This link's own stamp (its client id). */
const char *mr_net_id(const mr_net *n);
/* The URL without its options, for messages. */
const char *mr_net_where(const mr_net *n);

/* Disconnects, stops the thread and frees; NULL is allowed. */
void mr_net_close(mr_net *n);

#ifdef __cplusplus
}
#endif

#endif /* MR_NET_H */

/* A real mosquitto for one test: its own config in the test's folder, a
 * listener on a free 127.0.0.1 port found at run time, no persistence. */
#ifndef TEST_BROKER_H
#define TEST_BROKER_H

#include <sys/types.h>

typedef struct tb_broker {
  pid_t pid;
  int port;
  char conf[600], log[600];
} tb_broker;

/* Writes dir/NAME.conf (the listener, no persistence, then extra, a
 * config's lines; may be NULL) and starts mosquitto (its path) on it, on
 * port (0: a free one). Returns once the port takes connections: 0, or -1
 * after printing why (the broker's log). */
int tb_broker_start(tb_broker *b, const char *mosquitto, const char *dir, const char *name,
                    int port, const char *extra);

/* Stops it: SIGTERM, or SIGKILL when kill_it (a crash), and waits. */
void tb_broker_stop(tb_broker *b, int kill_it);

/* Stops every broker still running (a test that failed midway left it):
 * a teardown. Returns 0, for cmocka. */
int tb_broker_stop_all(void **state);

/* Publishes len bytes on topic as a client of no stamp: 0 or -1. */
int tb_publish(int port, const char *topic, const void *data, int len);
/* The same, retained by the broker when retain is nonzero. */
int tb_publish_retained(int port, const char *topic, const void *data, int len, int retain);

#endif

/* tb_broker (broker.h). */
#include <mosquitto.h>
#include <netinet/in.h>
#include <pwd.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "broker.h"
#include "proc.h"

/* The brokers running, so that a test that fails midway leaves none. */
static pid_t running[16];

static void track(pid_t pid, pid_t was) {
  for (int i = 0; i < 16; i++)
    if (running[i] == was) {
      running[i] = pid;
      return;
    }
}

static int free_port(void) {
  int s = socket(AF_INET, SOCK_STREAM, 0);
  struct sockaddr_in a = { .sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
  socklen_t len = sizeof a;
  if (s < 0) return -1;
  if (bind(s, (struct sockaddr *)&a, sizeof a) != 0 ||
      getsockname(s, (struct sockaddr *)&a, &len) != 0) {
    close(s);
    return -1;
  }
  close(s);
  return ntohs(a.sin_port);
}

static int takes_connections(int port) {
  int s = socket(AF_INET, SOCK_STREAM, 0);
  struct sockaddr_in a = { .sin_family = AF_INET,
                           .sin_addr.s_addr = htonl(INADDR_LOOPBACK),
                           .sin_port = htons((uint16_t)port) };
  int ok = s >= 0 && connect(s, (struct sockaddr *)&a, sizeof a) == 0;
  if (s >= 0) close(s);
  return ok;
}

int tb_broker_start(tb_broker *b, const char *mosquitto, const char *dir, const char *name,
                    int port, const char *extra) {
  char file[64];
  b->port = port > 0 ? port : free_port();
  snprintf(file, sizeof file, "%s.conf", name);
  snprintf(b->conf, sizeof b->conf, "%s", tt_path(dir, file));
  snprintf(file, sizeof file, "%s.log", name);
  snprintf(b->log, sizeof b->log, "%s", tt_path(dir, file));
  FILE *f = fopen(b->conf, "w");
  if (f == NULL || b->port <= 0) return -1;
  /* Run as root, mosquitto becomes user "mosquitto", who cannot read the
   * test's folder: it stays who runs the test. */
  struct passwd *pw = getpwuid(getuid());
  fprintf(f, "listener %d 127.0.0.1\npersistence false\nuser %s\n%s", b->port,
          pw != NULL ? pw->pw_name : "root", extra != NULL ? extra : "allow_anonymous true\n");
  fclose(f);
  const char *argv[] = { mosquitto, "-c", b->conf, NULL };
  b->pid = tt_spawn(argv, NULL, b->log);
  if (b->pid > 0) track(b->pid, 0);
  for (int i = 0; b->pid > 0 && i < 500; i++) {
    if (takes_connections(b->port)) return 0;
    struct timespec ts = { 0, 10000000 };
    nanosleep(&ts, NULL);
  }
  char *said = tt_read_file(b->log, NULL);
  fprintf(stderr, "mosquitto did not start on port %d:\n%s\n", b->port, said ? said : "");
  return -1;
}

void tb_broker_stop(tb_broker *b, int kill_it) {
  if (b->pid <= 0) return;
  kill(b->pid, kill_it ? SIGKILL : SIGTERM);
  tt_wait(b->pid, 10);
  track(0, b->pid);
  b->pid = 0;
}

int tb_broker_stop_all(void **state) {
  (void)state;
  for (int i = 0; i < 16; i++)
    if (running[i] > 0) {
      tb_broker b = { .pid = running[i] };
      tb_broker_stop(&b, 1);
    }
  return 0;
}

int tb_publish(int port, const char *topic, const void *data, int len) {
  return tb_publish_retained(port, topic, data, len, 0);
}

int tb_publish_retained(int port, const char *topic, const void *data, int len, int retain) {
  mosquitto_lib_init();
  struct mosquitto *m = mosquitto_new(NULL, true, NULL);
  int rc = m != NULL && mosquitto_connect(m, "127.0.0.1", port, 5) == MOSQ_ERR_SUCCESS &&
                   mosquitto_publish(m, NULL, topic, len, data, 1, retain != 0) == MOSQ_ERR_SUCCESS
               ? 0
               : -1;
  /* Bounded: the message out and its PUBACK in, then away. */
  for (int i = 0; rc == 0 && i < 200 && mosquitto_want_write(m); i++) mosquitto_loop(m, 50, 1);
  for (int i = 0; rc == 0 && i < 4; i++) mosquitto_loop(m, 25, 1);
  if (m != NULL) {
    mosquitto_disconnect(m);
    mosquitto_loop(m, 25, 1);
    mosquitto_destroy(m);
  }
  return rc;
}

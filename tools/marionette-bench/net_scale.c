/* Section net (issue 24, item 6): a show's state through a real mosquitto
 * on loopback, started here with its own config. In this process: a glove
 * relay publishing SAMPLEs at 250 Hz (its device time the wall clock, so
 * a sample's age can be read anywhere in the process), the humanoid's
 * show reading that glove through the broker on the wall clock at 60 fps
 * and publishing every frame (host/net/STATE.md), and W watchers decoding
 * every frame. Figures: bytes a frame and a second; glove sample to
 * watcher frame latency, p50 and p99 (the newest sample a frame used,
 * from the moment the relay sent it to the moment a watcher decoded the
 * frame); the broker's CPU from /proc/PID/stat, with 1 and with 200
 * watchers. */
#define _POSIX_C_SOURCE 200809L
#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <netinet/in.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "gp_glove.h"
#include "mr_net.h"
#include "mr_show.h"
#include "mr_state.h"
#include "state_pub.h"

extern char **environ;

enum { MAX_FRAMES = 60 * 40, MAX_WATCHERS = 200 };

typedef struct net_run {
  int port;
  double t0;     /* CLOCK_REALTIME at the start: the relay's device time is now - t0 */
  double length; /* s of show */
  mr_net *relay;
  atomic_int stop;
  mr_state_out *out;
  const mr_scene *scene;
  double poses[7 * 8];
  pthread_mutex_t mu;
  double sample_sent[MAX_FRAMES]; /* by seq: when the newest sample it used was sent */
  mr_show_status show_rc;
} net_run;

static double real_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_REALTIME, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void nap(double s) {
  struct timespec ts = { (time_t)s, (long)((s - floor(s)) * 1e9) };
  nanosleep(&ts, NULL);
}

/* A free loopback port: bound to 0, named, let go. */
static int free_port(void) {
  int fd = socket(AF_INET, SOCK_STREAM, 0);
  struct sockaddr_in a = { .sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
  socklen_t len = sizeof a;
  int port = -1;
  if (fd >= 0 && bind(fd, (struct sockaddr *)&a, sizeof a) == 0 &&
      getsockname(fd, (struct sockaddr *)&a, &len) == 0)
    port = ntohs(a.sin_port);
  if (fd >= 0) close(fd);
  return port;
}

static pid_t start_broker(const bench *b, int port) {
  char conf[1024], log[1024];
  snprintf(conf, sizeof conf, "%s/net-broker.conf", b->out);
  snprintf(log, sizeof log, "%s/net-broker.log", b->out);
  FILE *f = fopen(conf, "w");
  if (f == NULL) return -1;
  fprintf(f,
          "listener %d 127.0.0.1\nallow_anonymous true\npersistence false\n"
          "max_queued_messages 10000\n",
          port);
  fclose(f);
  char *argv[] = { MOSQUITTO_PATH, "-c", conf, NULL };
  /* Its log (stderr) into out/net-broker.log, not among the figures. */
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 2, log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 2, 1);
  pid_t pid;
  int spawned = posix_spawn(&pid, argv[0], &fa, NULL, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  if (spawned != 0) return -1;
  for (int i = 0; i < 300; i++) { /* up within 3 s */
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in a = { .sin_family = AF_INET,
                             .sin_port = htons((uint16_t)port),
                             .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
    int up = connect(fd, (struct sockaddr *)&a, sizeof a) == 0;
    close(fd);
    if (up) return pid;
    nap(0.01);
  }
  kill(pid, SIGTERM);
  waitpid(pid, NULL, 0);
  return -1;
}

/* The broker's CPU time so far, s (utime + stime of /proc/PID/stat). */
static double broker_cpu(pid_t pid) {
  char path[64], line[2048];
  snprintf(path, sizeof path, "/proc/%d/stat", (int)pid);
  FILE *f = fopen(path, "r");
  if (f == NULL) return NAN;
  size_t n = fread(line, 1, sizeof line - 1, f);
  fclose(f);
  line[n] = '\0';
  const char *p = strrchr(line, ')'); /* past the command's name */
  unsigned long long ut = 0, st = 0;
  if (p == NULL ||
      sscanf(p + 2, "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %llu %llu", &ut, &st) != 2)
    return NAN;
  return (double)(ut + st) / (double)sysconf(_SC_CLK_TCK);
}

/* The glove relay: INFO, then SAMPLEs at 250 Hz stamped with the wall
 * clock, until told to stop. */
static void *relay_main(void *arg) {
  net_run *r = arg;
  gp_info info = gp_default_glove_info();
  gp_glove_info_set_rate(&info, 250);
  uint8_t wire[GP_MAX_WIRE];
  double next = real_now(), next_info = next;
  for (uint16_t seq = 0; !atomic_load(&r->stop); seq++) {
    double now = real_now();
    if (now >= next_info) {
      size_t n = gp_glove_info_encode(&info, wire, sizeof wire);
      mr_net_publish(r->relay, MR_NET_DATA, wire, n, NULL);
      next_info += 1.0;
    }
    double phase = 3.14159265358979 * (now - r->t0); /* 0.5 Hz */
    uint16_t ch[GP_SAMPLE_CH_COUNT];
    for (unsigned k = 0; k < GP_SAMPLE_CH_COUNT; k++)
      ch[k] = gp_glove_value_count(0.5 + 0.4 * sin(phase + k));
    gp_sample s = gp_glove_sample(seq, gp_glove_time_us(now - r->t0), ch);
    size_t n = gp_glove_sample_encode(&s, GP_SPEC_HASH, wire, sizeof wire);
    mr_net_publish(r->relay, MR_NET_DATA, wire, n, NULL);
    next += 0.004;
    if (next > now) nap(next - now);
  }
  return NULL;
}

/* On the show's thread: the frame out, and the send time of the newest
 * sample it used, by its seq. */
static void frame_done(void *user, const mr_show_frame *f) {
  net_run *r = user;
  mr_state_out_counters c;
  mr_state_out_get_counters(r->out, &c);
  uint64_t seq = c.frames;
  for (size_t k = 0; k < f->n_frames && k < 8; k++) {
    memcpy(r->poses + 7 * k, f->pose[k].position, 3 * sizeof(double));
    memcpy(r->poses + 7 * k + 3, f->pose[k].orientation, 4 * sizeof(double));
  }
  mr_state_out_frame(r->out, f->t, r->poses, f->xyz, NULL);
  const mr_glove_reading *g = &f->gloves[0].reading;
  pthread_mutex_lock(&r->mu);
  if (seq < MAX_FRAMES) r->sample_sent[seq] = g->samples > 0 ? r->t0 + g->device_t : NAN;
  pthread_mutex_unlock(&r->mu);
}

static void *show_main(void *arg) {
  net_run *r = arg;
  char glove[300];
  snprintf(glove, sizeof glove, "mqtt://127.0.0.1:%d/glove/bench", r->port);
  mr_show_def d = mr_default_show_def();
  d.gloves[0] = glove;
  d.n_gloves = 1;
  d.fps = 60;
  d.duration = r->length;
  mr_clock clock = mr_clock_wall();
  mr_show_hooks h = { NULL, NULL, frame_done, NULL, r };
  mr_show_result res;
  mr_show_error err;
  r->show_rc = mr_show_run(r->scene, &d, &clock, &h, &res, &err);
  atomic_store(&r->stop, 1); /* the relay stops, and the watchers drain */
  if (r->show_rc != MR_SHOW_OK) fprintf(stderr, "marionette-bench: net: %s\n", err.text);
  mr_show_result_free(&res);
  return NULL;
}

/* What the watchers saw. */
typedef struct seen {
  double *lat;
  size_t n_lat, cap;
  uint64_t frames, lost, corrupt, bytes;
} seen;

/* Every watcher's messages read, round after round, until the show's
 * thread ends; the latencies of the frames whose sample is known. */
static void watch_all(net_run *r, mr_state_in **w, int n, seen *s) {
  double end = real_now() + r->length + 5.0;
  while (real_now() < end) {
    int got = 0;
    for (int i = 0; i < n; i++) {
      mr_state_event ev;
      while (mr_state_in_read(w[i], 0, &ev, NULL) == MR_IO_OK && ev.kind != MR_STATE_NOTHING) {
        got++;
        if (ev.kind != MR_STATE_GOT_FRAME || ev.frame.seq >= MAX_FRAMES) continue;
        double now = real_now();
        pthread_mutex_lock(&r->mu);
        double sent = r->sample_sent[ev.frame.seq];
        pthread_mutex_unlock(&r->mu);
        if (isfinite(sent) && sent > 0 && s->n_lat < s->cap) s->lat[s->n_lat++] = now - sent;
      }
    }
    if (got == 0) {
      /* The show over, what is still on its way has half a second. */
      if (atomic_load(&r->stop) && end > real_now() + 0.5) end = real_now() + 0.5;
      nap(0.0005);
    }
  }
  for (int i = 0; i < n; i++) {
    mr_state_in_counters c;
    mr_state_in_get_counters(w[i], &c);
    s->frames += c.frames;
    s->lost += c.lost;
    s->corrupt += c.corrupt;
    s->bytes += c.bytes;
  }
}

/* Bytes of one FRAME's PUBLISH packet on the wire: the fixed header, the
 * topic, the properties (the mr-publisher stamp, "show-HOST-PID") and
 * the payload. */
static size_t wire_bytes(size_t payload, const char *topic) {
  char host[64] = "";
  gethostname(host, sizeof host - 1);
  size_t stamp = strlen("show--") + strlen(host) + 7;
  size_t props = 1 + 1 + 2 + strlen("mr-publisher") + 2 + stamp;
  size_t rest = 2 + strlen(topic) + props + payload;
  return 1 + (rest < 128 ? 1 : rest < 16384 ? 2 : 3) + rest;
}

/* The links of one run: W watchers, the relay and the show's publisher. */
static int open_links(net_run *r, mr_state_in **w, int n, const mr_state_bundle *files) {
  char url[300];
  snprintf(url, sizeof url, "mqtt://127.0.0.1:%d/show/bench", r->port);
  for (int i = 0; i < n; i++) {
    mr_state_in_def d = mr_default_state_in_def();
    d.url = url;
    d.max_scene = 1 << 20;
    d.connect_wait_ms = 10000;
    mr_io_error err;
    if (mr_state_in_open(&d, &w[i], &err) != 0)
      return fprintf(stderr, "marionette-bench: net: watcher %d: %s\n", i, err.msg), -1;
  }
  mr_net_def nd = mr_default_net_def();
  snprintf(nd.url, sizeof nd.url, "mqtt://127.0.0.1:%d/glove/bench", r->port);
  nd.role = MR_NET_RELAY;
  mr_io_error err;
  if (mr_net_open(&nd, &r->relay, &err) != 0)
    return fprintf(stderr, "marionette-bench: net: relay: %s\n", err.msg), -1;
  size_t n_points = 0;
  mr_scene_error se;
  free(mr_scene_start_positions(r->scene, &n_points, &se));
  mr_state_out_def od = mr_default_state_out_def();
  od.url = url;
  od.scene = files;
  od.fps = 60;
  od.n_frames = (int)r->scene->n_frames;
  od.n_points = (int)n_points;
  if (mr_state_out_open(&od, &r->out, &err) != 0)
    return fprintf(stderr, "marionette-bench: net: publisher: %s\n", err.msg), -1;
  return 0;
}

/* One run with n watchers: the figures said, the broker's CPU share
 * (of one core) in *cpu. 0 or -1. */
static int net_phase(bench *b, pid_t broker, net_run *r, int n, const mr_state_bundle *files,
                     double *cpu) {
  static mr_state_in *w[MAX_WATCHERS];
  memset(w, 0, sizeof w);
  int rc = open_links(r, w, n, files);
  seen s = { .cap = (size_t)n * MAX_FRAMES };
  s.lat = malloc(s.cap * sizeof *s.lat);
  pthread_t relay, show;
  if (rc == 0 && s.lat != NULL) {
    nap(1.0); /* the scene's fan-out to the watchers done before the count starts */
    double cpu0 = broker_cpu(broker), wall0 = real_now();
    r->t0 = wall0;
    atomic_store(&r->stop, 0);
    pthread_create(&relay, NULL, relay_main, r);
    pthread_create(&show, NULL, show_main, r);
    watch_all(r, w, n, &s);
    pthread_join(show, NULL);
    pthread_join(relay, NULL);
    *cpu = (broker_cpu(broker) - cpu0) / (real_now() - wall0);
    mr_state_out_counters c;
    mr_state_out_get_counters(r->out, &c);
    bench_sort(s.lat, (int)s.n_lat);
    double p50 = s.n_lat ? s.lat[(s.n_lat - 1) / 2] : NAN;
    double p99 = s.n_lat ? s.lat[(size_t)floor(0.99 * (double)(s.n_lat - 1))] : NAN;
    double per = c.sent ? (double)c.bytes / (double)c.sent : 0;
    if (n == 1) {
      size_t wire = wire_bytes((size_t)lround(per), "show/bench");
      bench_say(b,
                "net: humanoid at 60 fps: %.0f bytes a frame (%zu on the wire), %.1f kB/s "
                "(%.1f kB/s on the wire) to each watcher (target <= 64 kB/s); scene %zu bytes, "
                "once a watcher\n",
                per, wire, per * 60 / 1e3, (double)wire * 60 / 1e3, c.scene_bytes);
    }
    bench_say(b,
              "net: %d watcher%s: glove -> watcher p50 %.1f ms, p99 %.1f ms (%zu frames); "
              "received %llu of %llu sent x %d, lost %llu, dropped by the show %llu; broker "
              "CPU %.1f %% of a core\n",
              n, n == 1 ? "" : "s", p50 * 1e3, p99 * 1e3, s.n_lat, (unsigned long long)s.frames,
              (unsigned long long)c.sent, n, (unsigned long long)s.lost,
              (unsigned long long)(c.dropped_behind + c.dropped_away), 100 * *cpu);
    rc = r->show_rc == MR_SHOW_OK && c.sent > 0 ? 0 : -1;
  }
  mr_state_out_close(r->out);
  r->out = NULL;
  mr_net_close(r->relay);
  r->relay = NULL;
  for (int i = 0; i < n; i++) mr_state_in_close(w[i]);
  free(s.lat);
  return rc;
}

int bench_net(bench *b) {
  mr_scene scene;
  if (bench_load(b, "host/scenes/humanoid.yaml", &scene) != 0) return -1;
  mr_state_bundle files;
  memset(&files, 0, sizeof files);
  char msg[700];
  if (mr_app_scene_files(&scene, &files, msg, sizeof msg) != 0) {
    fprintf(stderr, "marionette-bench: net: %s\n", msg);
    mr_scene_free(&scene);
    return -1;
  }
  static net_run r;
  memset(&r, 0, sizeof r);
  pthread_mutex_init(&r.mu, NULL);
  r.scene = &scene;
  r.length = b->quick ? 4.0 : 10.0;
  r.port = free_port();
  pid_t broker = r.port > 0 ? start_broker(b, r.port) : -1;
  int rc = -1;
  double cpu1 = 0, cpu200 = 0;
  if (broker < 0) {
    fprintf(stderr, "marionette-bench: net: cannot start %s\n", MOSQUITTO_PATH);
  } else {
    bench_progress("net", "mosquitto on 127.0.0.1:%d; 1 watcher, then %d, %.0f s each", r.port,
                   MAX_WATCHERS, r.length);
    rc = net_phase(b, broker, &r, 1, &files, &cpu1);
    if (rc == 0) rc = net_phase(b, broker, &r, MAX_WATCHERS, &files, &cpu200);
    if (rc == 0)
      bench_say(b, "net: broker CPU a watcher: %.3f %% of a core ((%.1f %% - %.1f %%) / %d)\n",
                100 * (cpu200 - cpu1) / (MAX_WATCHERS - 1), 100 * cpu200, 100 * cpu1,
                MAX_WATCHERS - 1);
    kill(broker, SIGTERM);
    waitpid(broker, NULL, 0);
  }
  pthread_mutex_destroy(&r.mu);
  mr_state_bundle_free(&files);
  mr_scene_free(&scene);
  return rc;
}

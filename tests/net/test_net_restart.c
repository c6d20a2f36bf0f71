/* The broker killed and started again on its port while a show publishes
 * and a watcher watches (both real processes, the broker a real
 * mosquitto without persistence): the show goes on, the publisher is
 * back within 2 s with its scene retained again, and the watcher holds
 * its pose through the gap, counts it as losses and watches on. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <mosquitto.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "broker.h"
#include "proc.h"

static const char *glove_gen, *marionette, *mosquitto;

#define HUMANOID MR_SOURCE_DIR "/host/scenes/humanoid.yaml"

/* The number of a "key: N ..." line of a summary; fails without it. */
static long long num(const char *text, const char *key) {
  char v[200];
  if (tt_field(text, key, v, sizeof v) != 0) fail_msg("no '%s' in:\n%s", key, text);
  return atoll(v);
}

/* The seq of the first and the last frame in a watcher's --dump. */
static void seqs_of(const char *path, long long *first, long long *last) {
  char *text = tt_read_file(path, NULL);
  assert_non_null(text);
  *first = atoll(text);
  for (char *line = text; *line != '\0';) {
    *last = atoll(line);
    char *end = strchr(line, '\n');
    if (end == NULL) break;
    line = end + 1;
  }
  free(text);
}

/* A client of the test's own on TOPIC and TOPIC/scene: when the first
 * frame and the first non-empty scene came, written on libmosquitto's
 * thread and read once its loop stopped; the frames so far, read while
 * it runs. */
typedef struct probe {
  struct mosquitto *m;
  const char *topic;
  double first_frame, first_scene; /* 0: none */
  atomic_int frames;
} probe;

static void probe_message(struct mosquitto *m, void *user, const struct mosquitto_message *msg) {
  (void)m;
  probe *p = user;
  bool scene = strstr(msg->topic, "/scene") != NULL;
  double *when = scene ? &p->first_scene : &p->first_frame;
  if (msg->payloadlen > 0 && *when == 0) *when = tt_now_s();
  if (!scene) atomic_fetch_add(&p->frames, 1);
}

static void probe_connected(struct mosquitto *m, void *user, int rc) {
  probe *p = user;
  char all[200];
  snprintf(all, sizeof all, "%s/#", p->topic); /* TOPIC/scene */
  if (rc == 0) {
    mosquitto_subscribe(m, NULL, p->topic, 0);
    mosquitto_subscribe(m, NULL, all, 0);
  }
}

static void probe_start(probe *p, int port) {
  mosquitto_lib_init();
  p->m = mosquitto_new(NULL, true, p);
  assert_non_null(p->m);
  mosquitto_connect_callback_set(p->m, probe_connected);
  mosquitto_message_callback_set(p->m, probe_message);
  assert_int_equal(mosquitto_connect(p->m, "127.0.0.1", port, 5), MOSQ_ERR_SUCCESS);
  assert_int_equal(mosquitto_loop_start(p->m), MOSQ_ERR_SUCCESS);
}

static void probe_stop(probe *p) {
  mosquitto_disconnect(p->m);
  mosquitto_loop_stop(p->m, false);
  mosquitto_destroy(p->m);
}

/* The show publishes 10 s; a second after its first frame the broker is
 * killed, and 1.5 s later started again on its port. */
static void a_broker_restart_mid_show_is_weathered_by_the_show_and_its_watcher(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  char url[200], take_src[600], pngs[600], dump[600];
  snprintf(url, sizeof url, "mqtt://127.0.0.1:%d/show/r", b.port);
  snprintf(take_src, sizeof take_src, "file:%s", tt_path(dir, "glove.bin"));
  snprintf(pngs, sizeof pngs, "%s", tt_path(dir, "pictures"));
  snprintf(dump, sizeof dump, "%s", tt_path(dir, "watch.dump"));
  const char *gen_argv[] = { glove_gen, "-o", take_src + 5, "--fast", "-d", "12", NULL };
  assert_int_equal(tt_run(gen_argv, NULL, NULL, 30), 0);
  /* Drawn (160x90, into PNGs every 1000th) so that held pictures count;
   * until the show is over (SIGINT), each frame's seq in the dump. */
  const char *watch_argv[] = { marionette, "watch",  url,        "--headless", "-o",
                               pngs,       "--size", "160x90",   "--every",    "1000",
                               "--dump",   dump,     "--no-mp4", "-q",         NULL };
  pid_t watch = tt_spawn(watch_argv, tt_path(dir, "watch.out"), tt_path(dir, "watch.err"));
  tt_sleep_s(1.0);
  const char *run_argv[] = { marionette, "run",        HUMANOID, "--glove", take_src, "--publish",
                             url,        "--headless", "--time", "10",      "-q",     NULL };
  pid_t show = tt_spawn(run_argv, tt_path(dir, "run.out"), tt_path(dir, "run.err"));
  /* The show publishing (however long it took to start), then 1 s of it. */
  probe first = { .topic = "show/r" };
  probe_start(&first, b.port);
  for (double t0 = tt_now_s(); atomic_load(&first.frames) == 0 && tt_now_s() - t0 < 20;)
    tt_sleep_s(0.05);
  assert_true(atomic_load(&first.frames) > 0);
  probe_stop(&first);
  tt_sleep_s(1.0);
  int port = b.port;
  tb_broker_stop(&b, 1);
  tt_sleep_s(1.5);
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker2", port, NULL), 0);
  double back = tt_now_s();
  probe p = { .topic = "show/r" };
  probe_start(&p, port);
  tt_sleep_s(2.0);
  probe_stop(&p);
  /* A watcher that comes after the restart gets the scene again. */
  const char *late_argv[] = { marionette, "watch",  url, "--headless", "--time",
                              "1",        "--wait", "3", "-q",         NULL };
  assert_int_equal(tt_run(late_argv, tt_path(dir, "late.out"), tt_path(dir, "late.err"), 30), 0);
  assert_int_equal(tt_wait(show, 60), 0);
  tt_sleep_s(0.5); /* the show's last frames through */
  kill(watch, SIGINT);
  assert_int_equal(tt_wait(watch, 60), 0);
  tb_broker_stop(&b, 0);

  if (!(p.first_frame > 0 && p.first_frame - back <= 2.0))
    fail_msg("the show's first frame %.2f s after the broker's return (<= 0: none)",
             p.first_frame > 0 ? p.first_frame - back : -1.0);
  assert_true(p.first_scene > 0);
  char *run_out = tt_read_file(tt_path(dir, "run.out"), NULL);
  char *watch_out = tt_read_file(tt_path(dir, "watch.out"), NULL);
  char *late_out = tt_read_file(tt_path(dir, "late.out"), NULL);
  /* The show went on: 10 s simulated, the frames while away dropped. */
  assert_true(num(run_out, "simulated") >= 9);
  long long sent = num(run_out, "published frames");
  char v[200];
  assert_int_equal(tt_field(run_out, "publish dropped", v, sizeof v), 0);
  long long behind = 0, away = 0;
  assert_int_equal(sscanf(v, "%lld (network behind), %lld", &behind, &away), 2);
  assert_true(away > 30); /* 1.5 s at 60 fps, less the reconnection's */
  assert_true(num(run_out, "published scene") > 0);
  assert_non_null(strstr(run_out, "sent 2 times"));
  /* The watcher: every frame from its first received or counted lost, the
   * show's last one received (after the gap: it watched on), the gap held. */
  long long received = num(watch_out, "frames received"), lost = num(watch_out, "frames lost");
  long long first_seq = -1, last_seq = -1;
  seqs_of(dump, &first_seq, &last_seq);
  if (received + lost != last_seq - first_seq + 1 || last_seq != sent + behind + away - 1 ||
      lost < away)
    fail_msg("received %lld + lost %lld, seq %lld..%lld; the show's frames %lld (%lld away):\n%s",
             received, lost, first_seq, last_seq, sent + behind + away, away, watch_out);
  assert_int_equal(num(watch_out, "broker losses"), 1);
  assert_int_equal(tt_field(watch_out, "pictures", v, sizeof v), 0);
  long long pictures = 0, held = 0;
  assert_int_equal(sscanf(v, "%lld (%lld held", &pictures, &held), 2);
  assert_true(held > 20); /* the gap: 1.5 s and more of the last pose */
  assert_true(pictures > held);
  assert_non_null(strstr(late_out, "scene: humanoid ("));
  assert_true(num(late_out, "frames received") > 20);
  free(run_out);
  free(watch_out);
  free(late_out);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  if (argc < 4) {
    fprintf(stderr, "usage: %s GLOVE-GEN MARIONETTE MOSQUITTO\n", argv[0]);
    return 2;
  }
  glove_gen = argv[1];
  marionette = argv[2];
  mosquitto = argv[3];
  signal(SIGPIPE, SIG_IGN);
  const struct CMUnitTest tests[] = {
    cmocka_unit_test_teardown(a_broker_restart_mid_show_is_weathered_by_the_show_and_its_watcher,
                              tb_broker_stop_all),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* A show's state over a broker, end to end: glove-gen on a pty, relayed by
 * glove-dump --publish through a real mosquitto (each test's own, on a
 * free 127.0.0.1 port) to `marionette run --publish`, whose frames go
 * through a relay in this process (which drops and corrupts the frames
 * it is told to) to `marionette watch --headless`. Every wait is bounded. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <mosquitto.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "broker.h"
#include "mr_state.h"
#include "proc.h"

static const char *glove_gen, *glove_dump, *marionette, *mosquitto;

#define HUMANOID MR_SOURCE_DIR "/host/scenes/humanoid.yaml"

static const char *url_of(const tb_broker *b, const char *topic) {
  static char url[4][300];
  static int k;
  k = (k + 1) % 4;
  snprintf(url[k], sizeof url[k], "mqtt://127.0.0.1:%d/%s", b->port, topic);
  return url[k];
}

/* ---- The relay: show/in -> show/out, dropping and corrupting by seq ---- */

typedef struct relay {
  struct mosquitto *m;
  const uint32_t *drop, *corrupt;
  size_t n_drop, n_corrupt;
  int dropped, corrupted, passed; /* read after the loop stopped */
} relay;

static bool listed(const uint32_t *list, size_t n, uint32_t seq) {
  for (size_t i = 0; i < n; i++)
    if (list[i] == seq) return true;
  return false;
}

/* On libmosquitto's thread; the test reads the counts once it stopped. */
static void relay_message(struct mosquitto *m, void *user, const struct mosquitto_message *msg) {
  relay *r = user;
  bool scene = strstr(msg->topic, "/scene") != NULL;
  uint8_t buf[4096];
  if (scene || msg->payloadlen > (int)sizeof buf || msg->payloadlen < 13) {
    mosquitto_publish(m, NULL, scene ? "show/out/scene" : "show/out", msg->payloadlen, msg->payload,
                      1, msg->retain);
    return;
  }
  memcpy(buf, msg->payload, (size_t)msg->payloadlen);
  uint32_t seq =
      (uint32_t)buf[9] | (uint32_t)buf[10] << 8 | (uint32_t)buf[11] << 16 | (uint32_t)buf[12] << 24;
  if (listed(r->drop, r->n_drop, seq)) {
    r->dropped++;
    return;
  }
  if (listed(r->corrupt, r->n_corrupt, seq)) {
    buf[msg->payloadlen / 2] ^= 0x40;
    r->corrupted++;
  } else {
    r->passed++;
  }
  mosquitto_publish(m, NULL, "show/out", msg->payloadlen, buf, 0, false);
}

static void relay_connected(struct mosquitto *m, void *user, int rc) {
  (void)user;
  if (rc == 0) mosquitto_subscribe(m, NULL, "show/in/#", 0); /* show/in and show/in/scene */
}

static void relay_start(relay *r, int port) {
  mosquitto_lib_init();
  r->m = mosquitto_new(NULL, true, r);
  assert_non_null(r->m);
  mosquitto_connect_callback_set(r->m, relay_connected);
  mosquitto_message_callback_set(r->m, relay_message);
  assert_int_equal(mosquitto_connect(r->m, "127.0.0.1", port, 5), MOSQ_ERR_SUCCESS);
  assert_int_equal(mosquitto_loop_start(r->m), MOSQ_ERR_SUCCESS);
  tt_sleep_s(0.3); /* subscribed before the show starts */
}

static void relay_stop(relay *r) {
  mosquitto_disconnect(r->m);
  mosquitto_loop_stop(r->m, false);
  mosquitto_destroy(r->m);
}

/* ---- Both sides' particles ---- */

typedef struct line_set {
  double *t;
  double **v; /* values after t on each line */
  size_t *n, count;
} line_set;

static void read_lines(const char *path, int skip, line_set *s) {
  char *text = tt_read_file(path, NULL);
  assert_non_null(text);
  memset(s, 0, sizeof *s);
  for (char *save = NULL, *l = strtok_r(text, "\n", &save); l != NULL;
       l = strtok_r(NULL, "\n", &save)) {
    s->t = realloc(s->t, (s->count + 1) * sizeof *s->t);
    s->v = realloc(s->v, (s->count + 1) * sizeof *s->v);
    s->n = realloc(s->n, (s->count + 1) * sizeof *s->n);
    double *vals = NULL;
    size_t n = 0;
    char *p = l, *end = NULL;
    for (int k = 0; k < skip; k++) strtod(p, &end), p = end; /* seq */
    s->t[s->count] = strtod(p, &end);
    for (p = end;; p = end) {
      double x = strtod(p, &end);
      if (end == p) break;
      vals = realloc(vals, (n + 1) * sizeof *vals);
      vals[n++] = x;
    }
    s->v[s->count] = vals;
    s->n[s->count++] = n;
  }
  free(text);
}

static void free_lines(line_set *s) {
  for (size_t i = 0; i < s->count; i++) free(s->v[i]);
  free(s->t);
  free(s->v);
  free(s->n);
}

/* Every frame the watcher dumped (seq t sx sy sz xyz...) is the show's
 * frame of the same time (t xyz...) within the quantisation step. */
static size_t check_within_step(const char *show_path, const char *dump_path) {
  line_set show, got;
  read_lines(show_path, 0, &show);
  read_lines(dump_path, 1, &got);
  size_t j = 0;
  for (size_t i = 0; i < got.count; i++) {
    while (j < show.count && show.t[j] < got.t[i] - 5e-7) j++;
    assert_true(j < show.count);
    assert_true(fabs(show.t[j] - got.t[i]) < 5e-7);
    assert_int_equal(got.n[i], 3 + show.n[j]);
    const double *step = got.v[i];
    for (size_t k = 0; k < show.n[j]; k++) {
      double err = fabs(got.v[i][3 + k] - show.v[j][k]);
      /* The step, plus the printing of both files to 9 digits. */
      if (err > step[k % 3] + 1e-7 * (1 + fabs(show.v[j][k])))
        fail_msg("t %.6f value %zu: %.9g against %.9g, step %g", got.t[i], k, got.v[i][3 + k],
                 show.v[j][k], step[k % 3]);
    }
  }
  size_t n = got.count;
  free_lines(&show);
  free_lines(&got);
  return n;
}

/* The number of a "key: N ..." line of a summary, or -1. */
/* A glove take of secs seconds, made by glove-gen in dir: its source
 * ("file:PATH") into src. */
static void glove_take(const char *dir, const char *secs, char *src, size_t size) {
  assert_true((size_t)snprintf(src, size, "file:%s", tt_path(dir, "glove.bin")) < size);
  const char *gen_argv[] = { glove_gen, "-o", src + strlen("file:"), "--fast", "-d", secs, NULL };
  assert_int_equal(tt_run(gen_argv, NULL, NULL, 30), 0);
}

static long long num(const char *text, const char *key) {
  char v[200];
  return tt_field(text, key, v, sizeof v) == 0 ? atoll(v) : -1;
}

static void expect_kv(const char *text, const char *key, long long want) {
  long long v = num(text, key);
  if (v != want) fail_msg("expected %s: %lld, got %lld in:\n%s", key, want, v, text);
}

/* The whole chain: the watcher's particles are the show's within the
 * quantisation step on every frame it received, its losses are exactly
 * the frames the relay dropped or corrupted, its corrupt count the
 * corrupted ones, and it drew frames. */
static void
a_watcher_sees_the_shows_particles_within_a_step_and_exactly_the_induced_losses(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  static const uint32_t drop[] = { 40, 41, 42, 90 }, corrupt[] = { 60, 120 };
  relay r = { .drop = drop, .n_drop = 4, .corrupt = corrupt, .n_corrupt = 2 };
  relay_start(&r, b.port);
  const char *gen_extra[] = { "--duration", "8", "--uid", "5A", NULL };
  pid_t gen = tt_glove_on_pty(glove_gen, dir, gen_extra, source, sizeof source);
  assert_true(gen > 0);
  const char *relay_argv[] = { glove_dump, "-q", "--publish", url_of(&b, "glove/1"), source, NULL };
  pid_t gd = tt_spawn(relay_argv, NULL, tt_path(dir, "relay.err"));
  char pngs[600], dump[600], parts[600];
  snprintf(pngs, sizeof pngs, "%s", tt_path(dir, "pictures"));
  snprintf(dump, sizeof dump, "%s", tt_path(dir, "watch.dump"));
  snprintf(parts, sizeof parts, "%s", tt_path(dir, "run.particles"));
  const char *watch_argv[] = { marionette,   "watch",  url_of(&b, "show/out"),
                               "--headless", "--time", "60",
                               "--dump",     dump,     "-o",
                               pngs,         "--size", "160x90",
                               "--every",    "20",     "--no-mp4",
                               "-q",         NULL };
  pid_t watch = tt_spawn(watch_argv, tt_path(dir, "watch.out"), tt_path(dir, "watch.err"));
  tt_sleep_s(0.5);
  const char *run_argv[] = { marionette,
                             "run",
                             HUMANOID,
                             "--glove",
                             url_of(&b, "glove/1"),
                             "--publish",
                             url_of(&b, "show/in"),
                             "--particles",
                             parts,
                             "--headless",
                             "--time",
                             "4",
                             "-q",
                             NULL };
  assert_int_equal(tt_run(run_argv, tt_path(dir, "run.out"), tt_path(dir, "run.err"), 60), 0);
  /* The watcher ends a moment after the show's last frame, not at a time
   * of its own: under the sanitizers the show's start alone can take
   * seconds, and a watcher that left first would miss its last frames. */
  tt_sleep_s(1.0);
  kill(watch, SIGINT);
  assert_int_equal(tt_wait(watch, 60), 0);
  relay_stop(&r);
  char *run_out = tt_read_file(tt_path(dir, "run.out"), NULL);
  char *watch_out = tt_read_file(tt_path(dir, "watch.out"), NULL);
  long long published = num(run_out, "published frames");
  assert_true(published > 200); /* 60 fps for 4 s */
  assert_int_equal(r.dropped, 4);
  assert_int_equal(r.corrupted, 2);
  expect_kv(watch_out, "frames lost", 6);
  expect_kv(watch_out, "messages corrupt", 2);
  expect_kv(watch_out, "frames received", published - 6);
  size_t dumped = check_within_step(parts, dump);
  assert_int_equal((long long)dumped, published - 6);
  assert_true(num(watch_out, "png frames") > 0);
  free(run_out);
  free(watch_out);
  tt_wait(gen, 30);
  tt_wait(gd, 30);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

/* A watcher started while the show runs gets the retained scene, builds
 * it and watches: the show's scene by name, frames received, none lost;
 * asked for a contact sheet alone (no -o), it draws and writes just that. */
static void a_watcher_that_joins_late_gets_the_retained_scene(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  char take_src[600];
  glove_take(dir, "6", take_src, sizeof take_src);
  const char *run_argv[] = {
    marionette, "run", HUMANOID, "--glove", take_src, "--publish", url_of(&b, "show/late"),
    "--time",   "4",   "-q",     NULL
  };
  pid_t show = tt_spawn(run_argv, tt_path(dir, "run.out"), tt_path(dir, "run.err"));
  tt_sleep_s(1.5);
  /* Its sheet alone, without -o: that file is written, and no frame. */
  char sheet[600];
  snprintf(sheet, sizeof sheet, "%s", tt_path(dir, "late-sheet.png"));
  const char *watch_argv[] = { marionette,   "watch",  url_of(&b, "show/late"),
                               "--headless", "--time", "1.5",
                               "--wait",     "3",      "--sheet",
                               sheet,        "--size", "160x90",
                               "-q",         NULL };
  assert_int_equal(tt_run(watch_argv, tt_path(dir, "watch.out"), tt_path(dir, "watch.err"), 30), 0);
  char *out = tt_read_file(tt_path(dir, "watch.out"), NULL);
  assert_non_null(strstr(out, "scene: humanoid ("));
  assert_true(num(out, "frames received") > 30);
  expect_kv(out, "frames lost", 0);
  free(out);
  size_t png_len = 0;
  char *png = tt_read_file(sheet, &png_len);
  assert_non_null(png);
  assert_true(png_len > 8 && memcmp(png, "\x89PNG", 4) == 0);
  free(png);
  assert_int_not_equal(access(tt_path(dir, "frame_000000.png"), F_OK), 0);
  assert_int_equal(tt_wait(show, 30), 0);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

/* The watcher draws at the show's own rate, down to the slowest a scene
 * may ask for: a show of puppet.yaml at 1 frame a second is watched for
 * 3 s in at most 4 pictures (the first, then one a second), where the
 * watcher's own default, 60 a second, would draw a hundred or more. */
static void a_show_at_one_frame_a_second_is_watched_at_its_rate(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  char *text = tt_read_file(MR_SOURCE_DIR "/host/scenes/puppet.yaml", NULL);
  assert_non_null(text);
  char *sim = strstr(text, "\nsim:\n");
  assert_non_null(sim);
  char scene[600];
  snprintf(scene, sizeof scene, "%s", tt_path(dir, "slow.yaml"));
  FILE *f = fopen(scene, "w");
  assert_non_null(f);
  fprintf(f, "%.*s\nsim:\n  fps: 1\n%s", (int)(sim - text), text, sim + strlen("\nsim:\n"));
  fclose(f);
  free(text);
  char take_src[600];
  glove_take(dir, "8", take_src, sizeof take_src);
  const char *run_argv[] = {
    marionette,   "run",    scene, "--glove", take_src, "--publish", url_of(&b, "show/slow"),
    "--headless", "--time", "6",   "-q",      NULL
  };
  pid_t show = tt_spawn(run_argv, tt_path(dir, "run.out"), tt_path(dir, "run.err"));
  const char *watch_argv[] = {
    marionette, "watch",   url_of(&b, "show/slow"),   "--headless", "--time", "3",  "--wait",
    "5",        "--sheet", tt_path(dir, "sheet.png"), "--size",     "160x90", "-q", NULL
  };
  assert_int_equal(tt_run(watch_argv, tt_path(dir, "watch.out"), tt_path(dir, "watch.err"), 30), 0);
  char *out = tt_read_file(tt_path(dir, "watch.out"), NULL);
  assert_non_null(strstr(out, "scene: simple marionette ("));
  const long long pictures = num(out, "pictures");
  if (pictures < 1 || pictures > 4) fail_msg("expected 1 to 4 pictures in 3 s at 1 fps:\n%s", out);
  free(out);
  assert_int_equal(tt_wait(show, 30), 0);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

/* Garbage, frames cut short, an empty message and one over the
 * watcher's limit, all on the show's topic while it plays: each counted
 * where it belongs, the watcher unhurt and the show's frames all read. */
static void
garbage_and_oversized_state_messages_are_counted_and_the_watcher_watches_on(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  char take_src[600];
  glove_take(dir, "6", take_src, sizeof take_src);
  const char *watch_argv[] = { marionette,   "watch",  url_of(&b, "show/g"),
                               "--headless", "--time", "5",
                               "-q",         NULL };
  pid_t watch = tt_spawn(watch_argv, tt_path(dir, "watch.out"), tt_path(dir, "watch.err"));
  tt_sleep_s(0.3);
  const char *run_argv[] = {
    marionette,           "run",    HUMANOID, "--glove", take_src, "--publish",
    url_of(&b, "show/g"), "--time", "3",      "-q",      NULL
  };
  pid_t show = tt_spawn(run_argv, tt_path(dir, "run.out"), tt_path(dir, "run.err"));
  tt_sleep_s(1.5);
  uint8_t junk[64];
  for (size_t i = 0; i < sizeof junk; i++) junk[i] = (uint8_t)(i * 37 + 11);
  for (int i = 0; i < 3; i++) assert_int_equal(tb_publish(b.port, "show/g", junk, 20 + i), 0);
  junk[0] = MR_STATE_FRAME; /* a frame's start, cut short */
  assert_int_equal(tb_publish(b.port, "show/g", junk, 8), 0);
  assert_int_equal(tb_publish(b.port, "show/g", junk, 0), 0);
  size_t big = (size_t)MR_STATE_DEFAULT_SCENE + 1;
  uint8_t *huge = calloc(1, big);
  assert_int_equal(tb_publish(b.port, "show/g", huge, (int)big), 0);
  free(huge);
  assert_int_equal(tt_wait(show, 30), 0);
  assert_int_equal(tt_wait(watch, 30), 0);
  char *out = tt_read_file(tt_path(dir, "watch.out"), NULL);
  char *run_out = tt_read_file(tt_path(dir, "run.out"), NULL);
  expect_kv(out, "messages corrupt", 4);
  expect_kv(out, "messages oversized", 1);
  expect_kv(out, "frames lost", 0);
  expect_kv(out, "frames received", num(run_out, "published frames"));
  free(out);
  free(run_out);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

/* A scene of one small file, for the libraries' own tests. */
static mr_state_bundle one_file_scene(void) {
  mr_state_bundle files;
  memset(&files, 0, sizeof files);
  assert_int_equal(mr_state_bundle_add(&files, "s.yaml", "name: s\n", 8), 0);
  return files;
}

/* A scene published from another definition of the state messages is
 * refused with a line naming both hashes, and exit status 3. */
static void a_scene_of_another_spec_hash_is_refused_clearly(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  mr_state_bundle files = one_file_scene();
  mr_state_scene s = { .fps = 60, .n_files = 1, .size = (uint32_t)files.size, .files = files.data };
  s.scene_hash = mr_state_bundle_hash(files.data, files.size);
  uint8_t wire[256];
  size_t n = mr_state_scene_encode(&s, wire, sizeof wire);
  assert_true(n > 9);
  wire[1] ^= 0x5A; /* another hash, sealed again with a good CRC */
  uint32_t crc = mr_state_crc32c(wire, n - 4);
  for (int i = 0; i < 4; i++) wire[n - 4 + (size_t)i] = (uint8_t)(crc >> (8 * i));
  assert_int_equal(tb_publish_retained(b.port, "show/x/scene", wire, (int)n, 1), 0);
  const char *watch_argv[] = { marionette, "watch", url_of(&b, "show/x"), "--headless", "--wait",
                               "3",        NULL };
  const char *err_path = tt_path(dir, "watch.err");
  assert_int_equal(tt_run(watch_argv, NULL, err_path, 30), 3);
  char *said = tt_read_file(err_path, NULL);
  char want[80];
  snprintf(want, sizeof want, "this program's 0x%08X", MR_STATE_SPEC_HASH);
  if (strstr(said, "another definition") == NULL || strstr(said, want) == NULL)
    fail_msg("expected a refusal naming both hashes, got: %s", said);
  free(said);
  mr_state_bundle_free(&files);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

/* The sample edge bridge (host/net/examples/edge-bridge.conf), as it is:
 * a watcher on an edge broker bridged to the origin gets the retained
 * scene and every frame the show publishes to the origin. */
static void a_watcher_on_an_edge_bridged_to_the_origin_sees_every_frame(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tb_broker origin, edge;
  assert_int_equal(tb_broker_start(&origin, mosquitto, dir, "origin", 0, NULL), 0);
  char *sample = tt_read_file(MR_SOURCE_DIR "/host/net/examples/edge-bridge.conf", NULL);
  assert_non_null(sample);
  char *at = strstr(sample, "\naddress ORIGIN:1883"), conf[4096];
  assert_non_null(at);
  at += strlen("\naddress ");
  snprintf(conf, sizeof conf, "allow_anonymous true\n%.*s127.0.0.1:%d%s", (int)(at - sample),
           sample, origin.port, at + strlen("ORIGIN:1883"));
  free(sample);
  assert_int_equal(tb_broker_start(&edge, mosquitto, dir, "edge", 0, conf), 0);
  char take_src[600];
  glove_take(dir, "6", take_src, sizeof take_src);
  const char *watch_argv[] = { marionette,   "watch",  url_of(&edge, "show/e"),
                               "--headless", "--time", "5",
                               "-q",         NULL };
  pid_t watch = tt_spawn(watch_argv, tt_path(dir, "watch.out"), tt_path(dir, "watch.err"));
  tt_sleep_s(1.0); /* the bridge up, the watcher subscribed */
  const char *run_argv[] = {
    marionette, "run", HUMANOID, "--glove", take_src, "--publish", url_of(&origin, "show/e"),
    "--time",   "3",   "-q",     NULL
  };
  assert_int_equal(tt_run(run_argv, tt_path(dir, "run.out"), tt_path(dir, "run.err"), 30), 0);
  assert_int_equal(tt_wait(watch, 30), 0);
  char *out = tt_read_file(tt_path(dir, "watch.out"), NULL);
  char *run_out = tt_read_file(tt_path(dir, "run.out"), NULL);
  assert_non_null(strstr(out, "scene: humanoid ("));
  expect_kv(out, "frames received", num(run_out, "published frames"));
  expect_kv(out, "frames lost", 0);
  free(out);
  free(run_out);
  tb_broker_stop(&edge, 0);
  tb_broker_stop(&origin, 0);
  tt_rmdir(dir);
  free(dir);
}

/* Frames far larger than the socket takes, handed in as fast as a loop
 * goes: the publisher drops what it cannot hand on (counted), never
 * fails, and every frame is either sent or counted as dropped; with the
 * broker gone, the same. */
static void a_publisher_the_network_cannot_keep_up_with_drops_and_counts(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  mr_state_bundle files = one_file_scene();
  enum { POINTS = 30000, FRAMES = 400 };
  double *xyz = calloc(3 * POINTS, sizeof *xyz), pose[7] = { 0, 0, 0, 1, 0, 0, 0 };
  for (size_t i = 0; i < 3 * POINTS; i++) xyz[i] = 0.001 * (double)i;
  mr_state_out_def d = mr_default_state_out_def();
  d.url = url_of(&b, "show/big");
  d.scene = &files;
  d.n_frames = 1;
  d.n_points = POINTS;
  d.max_unsent = 2;
  mr_state_out *o = NULL;
  mr_io_error err;
  assert_int_equal(mr_state_out_open(&d, &o, &err), 0);
  /* The broker stopped (not gone): the socket's buffers fill and stay
   * full, so what is handed on waits for it; a publisher that waited
   * would hang here. */
  kill(b.pid, SIGSTOP);
  for (int i = 0; i < FRAMES; i++)
    assert_true(mr_state_out_frame(o, i / 60.0, pose, xyz, &err) >= 0);
  kill(b.pid, SIGCONT);
  mr_state_out_counters c;
  mr_state_out_get_counters(o, &c);
  assert_int_equal(c.frames, FRAMES);
  assert_true(c.dropped_behind > 0); /* 72 MB: far more than the socket holds */
  assert_true(c.sent > 0);
  assert_int_equal(c.sent + c.dropped_behind + c.dropped_away, FRAMES);
  tb_broker_stop(&b, 0);
  tt_sleep_s(0.5); /* the link has seen the broker go */
  for (int i = 0; i < 10; i++) assert_int_equal(mr_state_out_frame(o, 9.0, pose, xyz, &err), 1);
  mr_state_out_get_counters(o, &c);
  assert_true(c.dropped_away >= 10);
  assert_int_equal(c.sent + c.dropped_behind + c.dropped_away, FRAMES + 10);
  mr_state_out_close(o);
  mr_state_bundle_free(&files);
  free(xyz);
  tt_rmdir(dir);
  free(dir);
}

/* Frame i of the test show: two control frames, neither at the origin nor
 * upright, and three particles, moving from frame to frame. */
static void frame_values(int i, double pose[14], double xyz[9]) {
  const double k = 0.01 * i;
  const double p[14] = { -0.75 + k, 1.25, 0.5,  0.5, 0.5, -0.5, 0.5,
                         0.3,       1.1,  -0.2, 0.6, 0.0, 0.8,  0.0 };
  const double x[9] = { 0.1 + k, 0.9, -0.3, -0.2, 1.4, 0.05, 0.0, 0.2, 0.7 };
  memcpy(pose, p, sizeof p);
  memcpy(xyz, x, sizeof x);
}

/* The libraries alone, publisher to reader through a broker: a publisher
 * that may keep no frame waiting is refused, one that may keep one
 * publishes, and each frame comes back with every control pose as the
 * show gave it (as floats) and every particle within a millimetre (the
 * 16-bit grid over this frame is far finer), frame after frame. */
static void a_reader_gets_each_frames_poses_and_particles(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  mr_state_bundle files = one_file_scene();
  mr_state_out_def d = mr_default_state_out_def();
  d.url = url_of(&b, "show/lib");
  d.scene = &files;
  d.fps = 30;
  d.n_frames = 2;
  d.n_points = 3;
  mr_state_in_def id = mr_default_state_in_def();
  id.url = d.url;
  mr_state_in *in = NULL;
  mr_state_out *o = NULL;
  mr_io_error err;
  assert_int_equal(mr_state_in_open(&id, &in, &err), 0);
  d.max_unsent = 0; /* no frame may wait: refused */
  assert_int_equal(mr_state_out_open(&d, &o, &err), -1);
  assert_null(o);
  d.max_unsent = 1; /* one may: the fewest that can publish */
  assert_int_equal(mr_state_out_open(&d, &o, &err), 0);
  int got = 0;
  for (int i = 0; i < 300 && got < 3; i++) {
    double pose[14], xyz[9];
    frame_values(i, pose, xyz);
    assert_true(mr_state_out_frame(o, i / 30.0, pose, xyz, &err) >= 0);
    mr_state_event ev;
    assert_int_equal(mr_state_in_read(in, 20, &ev, &err), MR_IO_OK);
    if (ev.kind != MR_STATE_GOT_FRAME) continue;
    const int seq = (int)lround(ev.t * 30.0);
    double want[14], wxyz[9];
    frame_values(seq, want, wxyz);
    for (int j = 0; j < 14; j++)
      if (ev.poses[j] != (double)(float)want[j])
        fail_msg("frame %d: pose value %d is %.9g, published %.9g", seq, j, ev.poses[j], want[j]);
    for (int j = 0; j < 9; j++)
      if (fabs(ev.xyz[j] - wxyz[j]) > 1e-3)
        fail_msg("frame %d: particle value %d is %.6g, published %.6g", seq, j, ev.xyz[j], wxyz[j]);
    got++;
  }
  assert_int_equal(got, 3);
  mr_state_in_close(in);
  mr_state_out_close(o);
  mr_state_bundle_free(&files);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  if (argc < 5) {
    fprintf(stderr, "usage: %s GLOVE-GEN GLOVE-DUMP MARIONETTE MOSQUITTO\n", argv[0]);
    return 2;
  }
  glove_gen = argv[1];
  glove_dump = argv[2];
  marionette = argv[3];
  mosquitto = argv[4];
  signal(SIGPIPE, SIG_IGN);
  const struct CMUnitTest tests[] = {
    cmocka_unit_test_teardown(
        a_watcher_sees_the_shows_particles_within_a_step_and_exactly_the_induced_losses,
        tb_broker_stop_all),
    cmocka_unit_test_teardown(a_show_at_one_frame_a_second_is_watched_at_its_rate,
                              tb_broker_stop_all),
    cmocka_unit_test_teardown(a_watcher_that_joins_late_gets_the_retained_scene,
                              tb_broker_stop_all),
    cmocka_unit_test_teardown(
        garbage_and_oversized_state_messages_are_counted_and_the_watcher_watches_on,
        tb_broker_stop_all),
    cmocka_unit_test_teardown(a_scene_of_another_spec_hash_is_refused_clearly, tb_broker_stop_all),
    cmocka_unit_test_teardown(a_watcher_on_an_edge_bridged_to_the_origin_sees_every_frame,
                              tb_broker_stop_all),
    cmocka_unit_test_teardown(a_publisher_the_network_cannot_keep_up_with_drops_and_counts,
                              tb_broker_stop_all),
    cmocka_unit_test_teardown(a_reader_gets_each_frames_poses_and_particles, tb_broker_stop_all),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

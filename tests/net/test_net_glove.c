/* A glove over an MQTT broker, end to end: glove-gen on a pty, relayed by
 * glove-dump --publish through a real mosquitto (started by each test on a
 * free 127.0.0.1 port, its own config, no persistence) to `marionette
 * run`, glove-dump or an mr_glove in this process. Every wait is bounded. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <arpa/inet.h>
#include <math.h>
#include <netinet/in.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "broker.h"
#include "gp.h"
#include "mr_glove.h"
#include "proc.h"

static const char *glove_gen, *glove_dump, *marionette, *mosquitto, *mosquitto_passwd, *openssl;

#define PUPPET MR_SOURCE_DIR "/host/scenes/puppet.yaml"

static const char *url_of(const tb_broker *b, const char *user, const char *topic,
                          const char *query) {
  static char url[4][1000];
  static int k;
  k = (k + 1) % 4;
  snprintf(url[k], sizeof url[k], "mqtt://%s%s127.0.0.1:%d/%s%.700s", user ? user : "",
           user ? "@" : "", b->port, topic, query ? query : "");
  return url[k];
}

/* glove-gen on a pty for secs; its source in source. */
static pid_t start_gen(const char *dir, const char *secs, const char *uid, char *source,
                       size_t size) {
  const char *extra[] = { "--duration", secs, "--uid", uid, NULL };
  pid_t gen = tt_glove_on_pty(glove_gen, dir, extra, source, size);
  assert_true(gen > 0);
  return gen;
}

/* glove-dump relaying source to url, its stderr in dir/NAME.err. */
static pid_t start_relay(const char *dir, const char *source, const char *url, const char *name) {
  char err[64];
  snprintf(err, sizeof err, "%s.err", name);
  const char *argv[] = { glove_dump, "-q", "--publish", url, source, NULL };
  pid_t p = tt_spawn(argv, NULL, tt_path(dir, err));
  assert_true(p > 0);
  return p;
}

/* A SAMPLE frame with one bit of its payload flipped: a CRC error. */
static size_t bad_frame(uint8_t *wire, size_t cap) {
  gp_msg m;
  uint8_t raw[GP_MAX_WIRE];
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample.seq = 7;
  m.u.sample.ch[0] = 1000;
  size_t n = gp_frame_pack(&m, GP_SPEC_HASH, raw, sizeof raw);
  assert_true(n > 4);
  raw[3] ^= 0x10;
  size_t w = gp_cobs_encode(raw, n, wire, cap - 1);
  assert_true(w > 0);
  wire[w] = 0;
  return w + 1;
}

/* The show reads the glove through the broker: its samples drive it, and
 * the CRC errors it counts are the corrupt frames the test put on the
 * topic, no more (the relay lost nothing), with no loss of the glove. */
static void a_relayed_glove_drives_the_show_and_its_losses_are_the_induced_ones(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  pid_t gen = start_gen(dir, "5", "A1", source, sizeof source);
  pid_t relay = start_relay(dir, source, url_of(&b, NULL, "glove/1", NULL), "relay");
  const char *argv[] = { marionette, "run", PUPPET, "--glove", url_of(&b, NULL, "glove/1", NULL),
                         "--time",   "3",   "-q",   NULL };
  char out[600], err[600];
  snprintf(out, sizeof out, "%s", tt_path(dir, "run.out"));
  snprintf(err, sizeof err, "%s", tt_path(dir, "run.err"));
  pid_t show = tt_spawn(argv, out, err);
  tt_sleep_s(1.5);
  uint8_t wire[GP_MAX_WIRE + 1];
  size_t n = bad_frame(wire, sizeof wire);
  for (int i = 0; i < 4; i++) assert_int_equal(tb_publish(b.port, "glove/1", wire, (int)n), 0);
  /* Two messages longer than any message may be and three empty ones:
   * each kind counted apart in the show's summary. */
  static uint8_t big[20000];
  memset(big, 0x5a, sizeof big);
  for (int i = 0; i < 2; i++)
    assert_int_equal(tb_publish(b.port, "glove/1", big, (int)sizeof big), 0);
  for (int i = 0; i < 3; i++) assert_int_equal(tb_publish(b.port, "glove/1", big, 0), 0);
  assert_int_equal(tt_wait(show, 30), 0);
  char *summary = tt_read_file(out, NULL), *said = tt_read_file(err, NULL);
  if (strstr(summary, "glove crc errors: 4\n") == NULL)
    fail_msg("expected 4 crc errors in:\n%s\n%s", summary, said);
  assert_non_null(strstr(summary, "glove losses: 0\n"));
  /* The link's own counts: the 4 bad frames came as 4 messages of their
   * own and reached the decoder; the oversized and empty ones were dropped
   * before it, each counted under its own name. */
  if (strstr(summary, "glove broker drops: 2 oversized, 3 empty, 0 behind\n") == NULL)
    fail_msg("expected 2 oversized and 3 empty messages dropped in:\n%s", summary);
  assert_non_null(strstr(summary, "glove broker messages from a second publisher: 0\n"));
  assert_non_null(strstr(summary, "glove broker reconnects: 0\n"));
  char m[64];
  assert_int_equal(tt_field(summary, "glove broker messages", m, sizeof m), 0);
  assert_true(atoll(m) >= 4 + 100);
  char v[64];
  assert_int_equal(tt_field(summary, "glove samples", v, sizeof v), 0);
  assert_true(atoll(v) >= 400); /* 250 Hz for most of 3 s */
  free(summary);
  free(said);
  tt_wait(gen, 30);
  tt_wait(relay, 30);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

/* glove-dump reading url until it has been idle for idle s (its
 * counters in dir/NAME.counters, its stderr in dir/NAME.err). */
static pid_t start_reader(const char *dir, const char *url, const char *idle, const char *name) {
  char counters[64], err[64];
  snprintf(counters, sizeof counters, "%s.counters", name);
  snprintf(err, sizeof err, "%s.err", name);
  char cpath[600];
  snprintf(cpath, sizeof cpath, "%s", tt_path(dir, counters));
  const char *argv[] = { glove_dump, "-q", "--idle", idle, "--counters", cpath, url, NULL };
  pid_t p = tt_spawn(argv, NULL, tt_path(dir, err));
  assert_true(p > 0);
  return p;
}

static char *read_in(const char *dir, const char *name) {
  char *text = tt_read_file(tt_path(dir, name), NULL);
  assert_non_null(text);
  return text;
}

/* Messages that are no glove's frames (bytes that end no frame, longer
 * than any message may be, empty) are each counted, where they belong,
 * and the glove's own frames around them all arrive. */
static void garbage_and_oversized_messages_are_counted_and_the_glove_reads_on(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  const char *url = url_of(&b, NULL, "glove/2", NULL);
  pid_t reader = start_reader(dir, url, "1", "reader");
  pid_t gen = start_gen(dir, "2.5", "B2", source, sizeof source);
  pid_t relay = start_relay(dir, source, url, "relay");
  tt_sleep_s(1.0);
  static uint8_t junk[20000];
  for (size_t i = 0; i < sizeof junk; i++) junk[i] = (uint8_t)(1 + (i * 37 + 11) % 255);
  for (int i = 0; i < 3; i++) assert_int_equal(tb_publish(b.port, "glove/2", junk + i, 40), 0);
  for (int i = 0; i < 2; i++)
    assert_int_equal(tb_publish(b.port, "glove/2", junk, (int)sizeof junk), 0);
  assert_int_equal(tb_publish(b.port, "glove/2", junk, 0), 0);
  assert_int_equal(tt_wait(gen, 30), 0);
  assert_int_equal(tt_wait(relay, 30), 0);
  assert_int_equal(tt_wait(reader, 30), 0);
  char *c = read_in(dir, "reader.counters");
  assert_int_equal(tt_kv(c, "net_oversized"), 2);
  assert_int_equal(tt_kv(c, "net_empty"), 1);
  assert_int_equal(tt_kv(c, "net_unstamped"), 6);
  long long bad = tt_kv(c, "crc_errors") + tt_kv(c, "framing_errors") + tt_kv(c, "oversize") +
                  tt_kv(c, "unknown_type");
  if (bad != 3) fail_msg("expected 3 bad frames, one a message, in:\n%s", c);
  assert_int_equal(tt_kv(c, "lost"), 0);
  assert_int_equal(tt_kv(c, "spec_mismatch"), 0);
  assert_true(tt_kv(c, "frames") >= 500); /* 250 Hz for 2.5 s, INFO too */
  free(c);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

/* Two relays on one glove topic: the reader names both, by the stamps
 * that carry their process ids. */
static void a_second_publisher_on_a_glove_topic_is_reported(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), s1[300], s2[300], want[64];
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  const char *url = url_of(&b, NULL, "glove/3", NULL);
  pid_t reader = start_reader(dir, url, "1", "reader");
  pid_t g1 = start_gen(dir, "2", "C1", s1, sizeof s1);
  pid_t g2 = start_gen(dir, "2", "C2", s2, sizeof s2);
  pid_t r1 = start_relay(dir, s1, url, "relay1"), r2 = start_relay(dir, s2, url, "relay2");
  /* The show tells it too, though its glove stays live throughout. */
  const char *argv[] = { marionette, "run", PUPPET, "--glove", url, "--time", "2", "-q", NULL };
  char out[600], err[600];
  snprintf(out, sizeof out, "%s", tt_path(dir, "run.out"));
  snprintf(err, sizeof err, "%s", tt_path(dir, "run.err"));
  pid_t show = tt_spawn(argv, out, err);
  assert_int_equal(tt_wait(show, 30), 0);
  char *run_said = tt_read_file(err, NULL), *run_out = tt_read_file(out, NULL);
  if (strstr(run_said, "two publishers on its topic, glove-dump-") == NULL)
    fail_msg("the show did not tell of two publishers:\n%s", run_said);
  assert_int_equal(
      tt_field(run_out, "glove broker messages from a second publisher", want, sizeof want), 0);
  assert_true(atoll(want) > 0);
  free(run_said);
  free(run_out);
  tt_wait(g1, 30);
  tt_wait(g2, 30);
  tt_wait(r1, 30);
  tt_wait(r2, 30);
  assert_int_equal(tt_wait(reader, 30), 0);
  char *said = read_in(dir, "reader.err");
  const char *line = strstr(said, "two publishers on one glove topic: glove-dump-");
  if (line == NULL) fail_msg("no report of two publishers in:\n%s", said);
  snprintf(want, sizeof want, "-%ld", (long)r1);
  assert_non_null(strstr(line, want));
  snprintf(want, sizeof want, "-%ld", (long)r2);
  assert_non_null(strstr(line, want));
  free(said);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

static void run_ok(const char *const argv[]) {
  if (tt_run(argv, NULL, NULL, 60) != 0) fail_msg("%s %s failed", argv[0], argv[1]);
}

/* A CA and a certificate for 127.0.0.1 signed by it, in dir/NAME-*. */
static void make_ca(const char *dir, const char *name) {
  char ca_key[600], ca[600], key[600], csr[600], crt[600], ext[600], subj[64];
  snprintf(ca_key, sizeof ca_key, "%s-ca.key", tt_path(dir, name));
  snprintf(ca, sizeof ca, "%s-ca.crt", tt_path(dir, name));
  snprintf(key, sizeof key, "%s-server.key", tt_path(dir, name));
  snprintf(csr, sizeof csr, "%s-server.csr", tt_path(dir, name));
  snprintf(crt, sizeof crt, "%s-server.crt", tt_path(dir, name));
  snprintf(ext, sizeof ext, "%s-ext", tt_path(dir, name));
  snprintf(subj, sizeof subj, "/CN=%s test CA", name);
  FILE *f = fopen(ext, "w");
  assert_non_null(f);
  fputs("subjectAltName=IP:127.0.0.1\n", f);
  fclose(f);
  const char *a[] = {
    openssl,  "req",     "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1",
    "-nodes", "-keyout", ca_key,  "-out",    ca,   "-days",    "1",
    "-subj",  subj,      NULL
  };
  run_ok(a);
  const char *r[] = {
    openssl,         "req",     "-newkey", "ec",   "-pkeyopt", "ec_paramgen_curve:prime256v1",
    "-nodes",        "-keyout", key,       "-out", csr,        "-subj",
    "/CN=127.0.0.1", NULL
  };
  run_ok(r);
  const char *x[] = { openssl, "x509", "-req",   "-in",  csr,
                      "-CA",   ca,     "-CAkey", ca_key, "-CAcreateserial",
                      "-out",  crt,    "-days",  "1",    "-extfile",
                      ext,     NULL };
  run_ok(x);
}

/* A reader of an mqtts:// URL with query; its exit status, stderr in
 * *said. */
static int read_tls(const char *dir, const tb_broker *b, const char *query, char **said) {
  char url[700];
  assert_true(snprintf(url, sizeof url, "mqtts://127.0.0.1:%d/glove/4%s", b->port, query) <
              (int)sizeof url);
  pid_t p = start_reader(dir, url, "0.3", "tls");
  int st = tt_wait(p, 30);
  *said = read_in(dir, "tls.err");
  return st;
}

/* mqtts:// with the CA that signed the broker's certificate connects;
 * without a CA (the system's do not know it) or with another CA, or to a
 * broker without TLS, the TLS handshake is refused, in one line that says
 * so. */
static void tls_connects_with_its_ca_and_is_refused_without_it_or_with_another(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), extra[2000], query[700], *said;
  make_ca(dir, "good");
  make_ca(dir, "other");
  snprintf(extra, sizeof extra,
           "allow_anonymous true\ncafile %s-ca.crt\ncertfile %s-server.crt\nkeyfile "
           "%s-server.key\n",
           tt_path(dir, "good"), tt_path(dir, "good"), tt_path(dir, "good"));
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, extra), 0);
  snprintf(query, sizeof query, "?cafile=%s-ca.crt", tt_path(dir, "good"));
  assert_int_equal(read_tls(dir, &b, query, &said), 0);
  if (strstr(said, "nothing for 0.3 s, stopping") == NULL) fail_msg("%s", said);
  free(said);
  const char *refused = "the TLS handshake failed: certificate verify failed";
  assert_int_equal(read_tls(dir, &b, "", &said), 1);
  if (strstr(said, refused) == NULL) fail_msg("%s", said);
  free(said);
  snprintf(query, sizeof query, "?cafile=%s-ca.crt", tt_path(dir, "other"));
  assert_int_equal(read_tls(dir, &b, query, &said), 1);
  if (strstr(said, refused) == NULL) fail_msg("%s", said);
  free(said);
  tb_broker_stop(&b, 0);
  /* A broker that speaks no TLS hangs up on the handshake: the reason is
   * OpenSSL's own words, whole (on Debian 12's OpenSSL 3). */
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "plain", 0, "allow_anonymous true\n"), 0);
  snprintf(query, sizeof query, "?cafile=%s-ca.crt", tt_path(dir, "good"));
  assert_int_equal(read_tls(dir, &b, query, &said), 1);
  if (strstr(said, ": the TLS handshake failed: unexpected eof while reading\n") == NULL)
    fail_msg("%s", said);
  free(said);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

/* A broker with users and the sample ACL of host/net/examples/acl, as it
 * is: alice owns glove/alice, viewer may only read. */
static void start_secure(tb_broker *b, const char *dir) {
  char pw[600], extra[1400];
  snprintf(pw, sizeof pw, "%s", tt_path(dir, "passwords"));
  const char *c1[] = { mosquitto_passwd, "-c", "-b", pw, "alice", "s3cret", NULL };
  run_ok(c1);
  const char *c2[] = { mosquitto_passwd, "-b", pw, "viewer", "look", NULL };
  run_ok(c2);
  snprintf(extra, sizeof extra, "allow_anonymous false\npassword_file %s\nacl_file %s\n", pw,
           MR_SOURCE_DIR "/host/net/examples/acl");
  assert_int_equal(tb_broker_start(b, mosquitto, dir, "broker", 0, extra), 0);
}

/* The owner (its password from a file) relays its glove and the audience
 * reads it; a wrong password and a viewer that tries to publish to the
 * glove's topic are each refused, in one line naming the user and why.
 * The owner's password file is named by a path of one letter, relative
 * to the folder the relay is started in: the shortest path there is. */
static void a_wrong_password_and_a_viewer_publishing_are_refused(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300], here[600];
  tb_broker b;
  start_secure(&b, dir);
  FILE *f = fopen(tt_path(dir, "p"), "w");
  assert_non_null(f);
  fputs("s3cret\n", f);
  fclose(f);
  unsetenv("MR_MQTT_PASSWORD");
  pid_t gen = start_gen(dir, "2", "D1", source, sizeof source);
  assert_non_null(getcwd(here, sizeof here));
  assert_int_equal(chdir(dir), 0);
  pid_t relay =
      start_relay(dir, source, url_of(&b, "alice", "glove/alice", "?password-file=p"), "owner");
  assert_int_equal(chdir(here), 0);
  setenv("MR_MQTT_PASSWORD", "look", 1);
  const char *watch[] = {
    glove_dump, "-q", "--count", "100", "--idle", "5", url_of(&b, "viewer", "glove/alice", NULL),
    NULL
  };
  tt_output o;
  assert_int_equal(tt_capture((char *const *)watch, &o), 0);
  if (o.status != 0) fail_msg("the viewer could not read: %s", o.err);
  assert_true(tt_kv(o.err, "frames") >= 100);
  tt_output_free(&o);
  assert_int_equal(tt_wait(gen, 30), 0);
  assert_int_equal(tt_wait(relay, 30), 0);

  gen = start_gen(dir, "2", "D2", source, sizeof source);
  const char *drive[] = { glove_dump, "-q", "--publish", url_of(&b, "viewer", "glove/alice", NULL),
                          source,     NULL };
  assert_int_equal(tt_capture((char *const *)drive, &o), 0);
  assert_int_equal(o.status, 1);
  char want[300];
  snprintf(want, sizeof want,
           "glove-dump: mqtt://viewer@127.0.0.1:%d/glove/alice: the broker refused to let viewer "
           "publish to glove/alice: Not authorized\n",
           b.port);
  if (strstr(o.err, want) == NULL) fail_msg("expected '%s' in:\n%s", want, o.err);
  tt_output_free(&o);
  kill(gen, SIGTERM);
  tt_wait(gen, 30);

  setenv("MR_MQTT_PASSWORD", "wrong", 1);
  const char *wrong[] = { glove_dump,  "-q", "--publish", url_of(&b, "alice", "glove/alice", NULL),
                          "/dev/zero", NULL };
  assert_int_equal(tt_capture((char *const *)wrong, &o), 0);
  unsetenv("MR_MQTT_PASSWORD");
  assert_int_equal(o.status, 1);
  snprintf(want, sizeof want,
           "glove-dump: mqtt://alice@127.0.0.1:%d/glove/alice: the broker refused user alice: "
           "Not authorized (check the password: password-file= or MR_MQTT_PASSWORD)\n",
           b.port);
  if (strstr(o.err, want) == NULL) fail_msg("expected '%s' in:\n%s", want, o.err);
  tt_output_free(&o);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

/* Polls g for up to secs until it is in state want: the time it took, or
 * a negative number when it never was. */
static double poll_until(mr_glove *g, mr_glove_state want, double secs) {
  double t0 = tt_now_s();
  while (tt_now_s() - t0 < secs) {
    mr_glove_poll(g, tt_now_s(), 20);
    if (mr_glove_get_state(g) == want) return tt_now_s() - t0;
  }
  return -1;
}

/* The broker killed mid-show: the glove is lost and holds its last values
 * while the broker is away; back on the same port, the glove is live again
 * within 2 s of the broker's return, through the relay's reconnection and
 * its own. */
static void a_broker_restart_holds_the_pose_and_the_glove_is_back_within_2_s(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  const char *url = url_of(&b, NULL, "glove/5", NULL);
  pid_t gen = start_gen(dir, "8", "E1", source, sizeof source);
  pid_t relay = start_relay(dir, source, url, "relay");
  mr_glove_def d = mr_default_glove_def();
  snprintf(d.source, sizeof d.source, "%s", url);
  mr_glove *g = NULL;
  assert_int_equal(mr_glove_create(&d, &g, NULL, 0), MR_GLOVE_OK);
  assert_true(poll_until(g, MR_GLOVE_LIVE, 5) >= 0);
  poll_until(g, MR_GLOVE_LOST, 0.5); /* half a second of show */
  int port = b.port;
  tb_broker_stop(&b, 1);
  assert_true(poll_until(g, MR_GLOVE_LOST, 2) >= 0);
  mr_glove_reading held, later;
  mr_glove_latest(g, &held);
  assert_true(held.samples > 100);
  poll_until(g, MR_GLOVE_LIVE, 1.0); /* the broker away for a second */
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LOST);
  mr_glove_latest(g, &later);
  assert_memory_equal(held.values, later.values, sizeof held.values);
  assert_int_equal(later.samples, held.samples);
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker2", port, NULL), 0);
  double back = poll_until(g, MR_GLOVE_LIVE, 4);
  if (!(back >= 0 && back <= 2.0)) fail_msg("live again after %.2f s (negative: never)", back);
  mr_glove_counters c;
  mr_glove_get_counters(g, &c);
  assert_int_equal(c.losses, 1);
  mr_glove_destroy(g);
  kill(gen, SIGTERM);
  tt_wait(gen, 30);
  tt_wait(relay, 30);
  char *said = read_in(dir, "relay.err");
  if (strstr(said, "the broker went away; reconnecting") == NULL ||
      strstr(said, "reconnected") == NULL)
    fail_msg("%s", said);
  free(said);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

/* A show started while no broker listens: its glove waits, saying why
 * (the refused connection), and is connected within 2 s of the broker's
 * start and live once a relay publishes; so is the glove of a `marionette
 * run` started the same way, which drives its show. */
static void a_glove_started_before_its_broker_connects_once_the_broker_is_up(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "probe", 0, NULL), 0);
  int port = b.port; /* a free port, nothing listening on it once stopped */
  tb_broker_stop(&b, 0);
  const char *url = url_of(&b, NULL, "glove/early", NULL);
  const char *run_argv[] = { marionette,   "run",    PUPPET, "--glove", url,
                             "--headless", "--time", "7",    "-q",      NULL };
  pid_t show = tt_spawn(run_argv, tt_path(dir, "run.out"), tt_path(dir, "run.err"));
  mr_glove_def d = mr_default_glove_def();
  snprintf(d.source, sizeof d.source, "%s", url);
  mr_glove *g = NULL;
  assert_int_equal(mr_glove_create(&d, &g, NULL, 0), MR_GLOVE_OK);
  assert_true(poll_until(g, MR_GLOVE_LIVE, 1.5) < 0);
  char said[600];
  mr_glove_describe(g, tt_now_s(), said, sizeof said);
  if (strstr(said, "Connection refused") == NULL) fail_msg("%s", said);
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", port, NULL), 0);
  double up = tt_now_s();
  mr_net_counters nc = { 0 };
  while (tt_now_s() - up < 4 && nc.connects == 0) {
    mr_glove_poll(g, tt_now_s(), 20);
    mr_glove_net_counters(g, &nc);
  }
  double connected = tt_now_s() - up;
  if (nc.connects != 1 || connected > 2.0)
    fail_msg("%d connections %.2f s after the broker came", (int)nc.connects, connected);
  pid_t gen = start_gen(dir, "12", "E2", source, sizeof source);
  pid_t relay = start_relay(dir, source, url, "relay");
  assert_true(poll_until(g, MR_GLOVE_LIVE, 5) >= 0);
  mr_glove_destroy(g);
  assert_int_equal(tt_wait(show, 60), 0);
  char *out = read_in(dir, "run.out"), samples[64] = "";
  tt_field(out, "glove samples", samples, sizeof samples);
  if (strstr(out, "glove: live\n") == NULL || atoll(samples) < 200) fail_msg("%s", out);
  free(out);
  kill(gen, SIGTERM);
  tt_wait(gen, 30);
  tt_wait(relay, 30);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

/* A port where a server of another kind takes the connection and closes
 * it before any MQTT answer (no error number to tell): the glove says
 * that no MQTT answer came from there, and what that may mean. */
static void a_server_that_closes_without_an_mqtt_answer_is_named_as_no_broker(void **state) {
  (void)state;
  int ls = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK, 0);
  struct sockaddr_in a = { .sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
  socklen_t len = sizeof a;
  assert_int_equal(bind(ls, (struct sockaddr *)&a, sizeof a), 0);
  assert_int_equal(listen(ls, 4), 0);
  assert_int_equal(getsockname(ls, (struct sockaddr *)&a, &len), 0);
  tb_broker none = { .port = ntohs(a.sin_port) };
  mr_glove_def d = mr_default_glove_def();
  snprintf(d.source, sizeof d.source, "%s", url_of(&none, NULL, "glove/x", NULL));
  mr_glove *g = NULL;
  assert_int_equal(mr_glove_create(&d, &g, NULL, 0), MR_GLOVE_OK);
  char said[600], want[100];
  snprintf(want, sizeof want, "no MQTT answer from 127.0.0.1:%d (no broker running there",
           none.port);
  for (double t0 = tt_now_s(); tt_now_s() - t0 < 3;) {
    mr_glove_poll(g, tt_now_s(), 20);
    int c = accept(ls, NULL, NULL);
    if (c >= 0) close(c);
  }
  mr_glove_describe(g, tt_now_s(), said, sizeof said);
  if (strstr(said, want) == NULL) fail_msg("%s", said);
  mr_glove_destroy(g);
  close(ls);
}

/* `marionette calibrate` over the broker: its commands go down TOPIC/cmd
 * through the relay to the glove, the answers come back on TOPIC/reply,
 * and the range it saved on the glove is printed. */
static void calibration_commands_reach_a_relayed_glove_and_its_answers_come_back(void **state) {
  (void)state;
  char *dir = tt_tmpdir(), source[300];
  tb_broker b;
  assert_int_equal(tb_broker_start(&b, mosquitto, dir, "broker", 0, NULL), 0);
  const char *url = url_of(&b, NULL, "glove/6", NULL);
  pid_t gen = start_gen(dir, "6", "F1", source, sizeof source);
  pid_t relay = start_relay(dir, source, url, "relay");
  char *argv[] = { (char *)marionette, "calibrate", "--glove", (char *)url,
                   "--step-time",      "0.3",       NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  const char *saved = strstr(o.out, "saved on the glove (raw ADC counts):\n");
  if (saved == NULL) fail_msg("%s", o.out);
  unsigned lo = 0, hi = 0;
  assert_int_equal(sscanf(strstr(saved, "thumb"), "thumb %u .. %u", &lo, &hi), 2);
  assert_true(lo < hi && hi <= 4095);
  tt_output_free(&o);
  kill(gen, SIGTERM);
  tt_wait(gen, 30);
  tt_wait(relay, 30);
  char *said = read_in(dir, "relay.err");
  assert_true(tt_kv(said, "relay_commands") >= 2); /* CAL_START, CAL_SAVE at least */
  free(said);
  tb_broker_stop(&b, 0);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  if (argc < 7) {
    fprintf(stderr,
            "usage: %s GLOVE-GEN GLOVE-DUMP MARIONETTE MOSQUITTO MOSQUITTO_PASSWD OPENSSL\n",
            argv[0]);
    return 2;
  }
  glove_gen = argv[1];
  glove_dump = argv[2];
  marionette = argv[3];
  mosquitto = argv[4];
  mosquitto_passwd = argv[5];
  openssl = argv[6];
  signal(SIGPIPE, SIG_IGN);
  const struct CMUnitTest tests[] = {
    cmocka_unit_test_teardown(a_relayed_glove_drives_the_show_and_its_losses_are_the_induced_ones,
                              tb_broker_stop_all),
    cmocka_unit_test_teardown(garbage_and_oversized_messages_are_counted_and_the_glove_reads_on,
                              tb_broker_stop_all),
    cmocka_unit_test_teardown(a_second_publisher_on_a_glove_topic_is_reported, tb_broker_stop_all),
    cmocka_unit_test_teardown(tls_connects_with_its_ca_and_is_refused_without_it_or_with_another,
                              tb_broker_stop_all),
    cmocka_unit_test_teardown(a_wrong_password_and_a_viewer_publishing_are_refused,
                              tb_broker_stop_all),
    cmocka_unit_test_teardown(a_broker_restart_holds_the_pose_and_the_glove_is_back_within_2_s,
                              tb_broker_stop_all),
    cmocka_unit_test_teardown(calibration_commands_reach_a_relayed_glove_and_its_answers_come_back,
                              tb_broker_stop_all),
    cmocka_unit_test_teardown(a_glove_started_before_its_broker_connects_once_the_broker_is_up,
                              tb_broker_stop_all),
    cmocka_unit_test(a_server_that_closes_without_an_mqtt_answer_is_named_as_no_broker),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

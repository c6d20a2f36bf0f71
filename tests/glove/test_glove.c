/* A glove over a real pty: its INFO and calibrated values; a glove that
 * falls silent or is unplugged is lost, its port retried at least once a
 * second, and the stream resumes on a new pty without a restart; a glove
 * built from another protocol definition is shown as such. Losses and
 * retries run on the time the test passes in, a virtual clock. The port is
 * reached through a symlink, as the udev rule names a real glove. */
#define _DEFAULT_SOURCE /* symlink, mkdtemp */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mr_glove.h"
#include "mr_io.h"

typedef struct port {
  mr_io master;
  char dir[64], link[96];
} port;

/* A new pty, and the symlink pointed at its slave side. */
static void plug(port *p) {
  mr_io_error err;
  if (mr_io_open(&p->master, "pty", MR_IO_READ | MR_IO_WRITE, &err) != 0) fail_msg("%s", err.msg);
  unlink(p->link);
  assert_int_equal(symlink(mr_io_path(&p->master), p->link), 0);
}

static void unplug(port *p) {
  mr_io_close(&p->master);
  unlink(p->link);
}

static void send(port *p, const gp_msg *m, uint32_t hash) {
  uint8_t wire[GP_MAX_WIRE + 2];
  size_t n = gp_encode(m, hash, wire, sizeof wire);
  assert_true(n > 0);
  size_t sent = 0;
  mr_io_error err;
  assert_int_equal(mr_io_write(&p->master, wire, n, 1000, &sent, &err), MR_IO_OK);
  assert_int_equal(sent, n);
}

static void send_info(port *p, uint32_t hash) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_INFO;
  m.u.info.proto_major = 1;
  m.u.info.spec_hash = hash;
  m.u.info.uid[0] = 0xC0FFEE;
  m.u.info.hand = GP_HAND_LEFT;
  m.u.info.n_channels = 5;
  m.u.info.adc_bits = 12;
  m.u.info.frame_rate_hz = 100;
  m.u.info.cal_state = GP_CAL_VALID;
  for (int k = 0; k < 5; k++) {
    m.u.info.cal_min[k] = 1000;
    m.u.info.cal_max[k] = 3000;
  }
  send(p, &m, hash);
}

static void send_sample(port *p, uint16_t seq, uint32_t t_us, uint16_t raw) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample.seq = seq;
  m.u.sample.t_us = t_us;
  for (int k = 0; k < 5; k++) m.u.sample.ch[k] = (uint16_t)(raw + 100 * k);
  send(p, &m, GP_SPEC_HASH);
}

static mr_glove *glove_on(const char *source) {
  mr_glove_def d = mr_default_glove_def();
  snprintf(d.source, sizeof d.source, "%s", source);
  mr_glove *g = NULL;
  char msg[200];
  if (mr_glove_create(&d, &g, msg, sizeof msg) != MR_GLOVE_OK) fail_msg("%s", msg);
  return g;
}

/* Polls at `now` until a sample comes in or a second of real time passes:
 * the bytes cross a real pty. */
static int poll_for_samples(mr_glove *g, double now) {
  for (int i = 0; i < 100; i++) {
    int n = mr_glove_poll(g, now, 10);
    if (n > 0) return n;
  }
  return 0;
}

static void make_port(port *p) {
  snprintf(p->dir, sizeof p->dir, "/tmp/mr-glove-XXXXXX");
  assert_non_null(mkdtemp(p->dir));
  snprintf(p->link, sizeof p->link, "%s/glove", p->dir);
}

/* A new port behind a link, and a glove reading it through the link. */
static mr_glove *glove_on_new_port(port *p, char *source, size_t size) {
  make_port(p);
  plug(p);
  snprintf(source, size, "pty:%s", p->link);
  return glove_on(source);
}

static void send_sample_flags(port *p, uint16_t seq, uint32_t t_us, uint8_t flags) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample.seq = seq;
  m.u.sample.t_us = t_us;
  m.u.sample.flags = flags;
  for (int k = 0; k < 5; k++) m.u.sample.ch[k] = 2000;
  send(p, &m, GP_SPEC_HASH);
}

/* "ms late" as the theater shows it: the newest sample's host time past
 * its device time, less the clock offset. */
static double lateness(const mr_glove *g) {
  mr_glove_reading r;
  mr_glove_latest(g, &r);
  return r.host_t - r.device_t - mr_glove_clock_offset(g);
}

/* 100 Hz samples for `secs` of host time from `now`, device time from
 * t0_us, seq from *seq; each one read at its host time. */
static double stream(port *p, mr_glove *g, double now, double secs, uint32_t t0_us, uint16_t *seq) {
  for (int i = 0; i < (int)(secs * 100); i++) {
    send_sample_flags(p, (*seq)++, t0_us + 10000u * (uint32_t)i, 0);
    assert_true(poll_for_samples(g, now + 0.01 * i) > 0);
  }
  return now + secs;
}

/* A glove replugged on a new pty whose clock started again (its sequence
 * carries on and no START flag came: the reconnect alone must tell): the
 * lateness is below 100 ms again within a second, not the old offset's
 * 100 s. */
static void the_lateness_is_measured_afresh_after_a_replug(void **state) {
  (void)state;
  port p;
  char source[128];
  uint16_t seq = 1;
  mr_glove *g = glove_on_new_port(&p, source, sizeof source);
  mr_glove_poll(g, 10.0, 0);
  double now = stream(&p, g, 10.0, 0.5, 100000000u, &seq); /* device at 100 s */
  assert_true(fabs(lateness(g)) < 0.1);
  unplug(&p);
  for (int i = 0; i < 50 && mr_glove_get_state(g) != MR_GLOVE_LOST; i++) mr_glove_poll(g, now, 10);
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LOST);
  plug(&p);
  now += 2.0;
  for (int i = 0; i < 50 && mr_glove_get_state(g) == MR_GLOVE_LOST; i++) {
    mr_glove_poll(g, now, 10);
    send_sample_flags(&p, seq++, 0, 0);
    poll_for_samples(g, now);
  }
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LIVE);
  now = stream(&p, g, now, 1.0, 500000u, &seq); /* the device clock restarted */
  if (!(lateness(g) < 0.1)) fail_msg("%.3f s late a second after the replug", lateness(g));
  mr_glove_destroy(g);
  unplug(&p);
  rmdir(p.dir);
}

/* On one connection: a START flag after the device clock reached 3000 s
 * (more than 2^31 µs) is a restart, not a wrap, and a new INFO uid starts
 * the offset afresh too. */
static void a_restart_or_a_new_uid_starts_the_device_clock_afresh(void **state) {
  (void)state;
  port p;
  char source[128];
  uint16_t seq = 1;
  mr_glove *g = glove_on_new_port(&p, source, sizeof source);
  mr_glove_poll(g, 1.0, 0);
  send_info(&p, GP_SPEC_HASH);
  double now = stream(&p, g, 1.0, 0.2, 3000000000u, &seq);
  send_sample_flags(&p, 0, 1000, GP_SAMPLE_F_START);
  assert_true(poll_for_samples(g, now) > 0);
  mr_glove_reading r;
  mr_glove_latest(g, &r);
  if (!(fabs(r.device_t - 0.001) < 1e-9)) fail_msg("device time %.6f s, not 0.001", r.device_t);
  assert_true(fabs(lateness(g)) < 1e-9);

  /* Another glove's INFO: its clock is 50 s behind; the lateness must not
   * read 50 s. */
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_INFO;
  m.u.info.proto_major = 1;
  m.u.info.spec_hash = GP_SPEC_HASH;
  m.u.info.uid[0] = 0xBEEF;
  m.u.info.n_channels = 5;
  m.u.info.adc_bits = 12;
  send(&p, &m, GP_SPEC_HASH);
  seq = 5000;
  now = stream(&p, g, now + 60.0, 0.2, 10000000u, &seq);
  if (!(fabs(lateness(g)) < 0.1)) fail_msg("%.3f s late after a new uid", lateness(g));
  mr_glove_destroy(g);
  unplug(&p);
  rmdir(p.dir);
}

static void a_live_glove_is_read_calibrated_lost_and_found_again(void **state) {
  (void)state;
  port p;
  char source[128], line[300];
  mr_glove *g = glove_on_new_port(&p, source, sizeof source);
  double now = 10.0;
  mr_glove_poll(g, now, 0); /* opens the port */
  send_info(&p, GP_SPEC_HASH);
  send_sample(&p, 1, 5000000, 2000); /* device time 5 s */
  assert_true(poll_for_samples(g, now) > 0);
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LIVE);
  const gp_info *info = mr_glove_info(g);
  assert_non_null(info);
  assert_int_equal(info->uid[0], 0xC0FFEE);
  mr_glove_reading r;
  mr_glove_latest(g, &r);
  /* (raw − cal_min) / (cal_max − cal_min): 2000 → 0.5, 2100 → 0.55, ... */
  for (int k = 0; k < 5; k++) assert_true(fabs(r.values[k] - (0.5 + 0.05 * k)) < 1e-12);
  assert_true(r.device_t == 5.0 && r.host_t == now);
  assert_true(fabs(mr_glove_clock_offset(g) - 5.0) < 1e-12);
  mr_glove_describe(g, now, line, sizeof line);
  assert_non_null(strstr(line, ": live, uid 00C0FFEE, left hand, 100 Hz"));

  /* Unplugged: the read side hangs up, the glove is lost, its last values
   * held. */
  unplug(&p);
  for (int i = 0; i < 50 && mr_glove_get_state(g) != MR_GLOVE_LOST; i++)
    mr_glove_poll(g, now + 0.1, 10);
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LOST);
  mr_glove_latest(g, &r);
  assert_true(fabs(r.values[0] - 0.5) < 1e-12);
  mr_glove_describe(g, now + 0.6, line, sizeof line);
  assert_non_null(strstr(line, ": lost 0.5 s ago"));

  /* Retried every 0.5 s of the caller's clock while nothing is there. */
  mr_glove_counters c0, c1;
  mr_glove_get_counters(g, &c0);
  for (int i = 1; i <= 8; i++) mr_glove_poll(g, now + 0.1 + 0.25 * i, 0);
  mr_glove_get_counters(g, &c1);
  assert_int_equal(c1.open_failures - c0.open_failures, 4); /* 2 s: four tries */

  /* Plugged in again on a new pty: the stream resumes. */
  plug(&p);
  now += 3.0;
  int resumed = 0;
  for (int i = 0; i < 20 && !resumed; i++) {
    mr_glove_poll(g, now + 0.5 * i, 0);
    send_sample(&p, 2, 8000000, 2400);
    resumed = poll_for_samples(g, now + 0.5 * i) > 0;
  }
  assert_true(resumed);
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LIVE);
  mr_glove_latest(g, &r);
  assert_true(fabs(r.values[0] - 0.7) < 1e-12);
  mr_glove_get_counters(g, &c1);
  assert_int_equal(c1.opens, 2);
  assert_int_equal(c1.losses, 1);

  /* Silent for longer than lost_after while the port stays: lost too. */
  mr_glove_poll(g, now + 20.0, 0);
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LOST);
  mr_glove_destroy(g);
  unplug(&p);
  rmdir(p.dir);
}

/* A glove built from another definition: shown with both hashes. */
static void a_foreign_glove_is_a_spec_mismatch(void **state) {
  (void)state;
  port p;
  char source[128], line[300];
  mr_glove *g = glove_on_new_port(&p, source, sizeof source);
  mr_glove_poll(g, 1.0, 0);
  send_info(&p, 0x12345678u);
  int seen = 0;
  for (int i = 0; i < 100 && !seen; i++) {
    mr_glove_poll(g, 1.0, 10);
    seen = mr_glove_get_state(g) == MR_GLOVE_MISMATCH;
  }
  assert_true(seen);
  mr_glove_describe(g, 1.0, line, sizeof line);
  char want[300];
  snprintf(want, sizeof want,
           "glove on %s was built from protocol 0x12345678, this host speaks 0x%08X: reflash it",
           source, (unsigned)GP_SPEC_HASH);
  assert_string_equal(line, want);
  mr_glove_destroy(g);
  unplug(&p);
  rmdir(p.dir);
}

static void bad_sources_are_refused_by_name(void **state) {
  (void)state;
  mr_glove_def d = mr_default_glove_def();
  mr_glove *g = NULL;
  char msg[200];
  snprintf(d.source, sizeof d.source, "pty:");
  assert_int_equal(mr_glove_create(&d, &g, msg, sizeof msg), MR_GLOVE_ERR_ARG);
  assert_null(g);
  assert_string_equal(msg, "glove source 'pty:': expected serial:DEV[@BAUD], serial:auto, "
                           "pty:PATH, pty, file:PATH, take:PATH, -, tcp:HOST:PORT, "
                           "tcp-listen:[HOST:]PORT or mqtt[s]://[USER@]HOST[:PORT]/TOPIC");
  /* A broker's URL that cannot be is bad usage, said in its own words. */
  static const char *const urls[][2] = {
    { "mqtt://127.0.0.1", "mqtt://127.0.0.1: no topic (expected mqtt://HOST/TOPIC)" },
    { "mqtts://a:pw@h/t", "mqtts://a:pw@h/t: no password in the URL (ps shows it): use "
                          "MR_MQTT_PASSWORD or ?password-file=PATH" },
    { "mqtt://h:99999/t", "mqtt://h:99999/t: port '99999' is not 1..65535" },
    { "mqtt://h/g/#", "mqtt://h/g/#: the topic must be 1..190 characters without + or # and "
                      "not end in /" },
    { "mqtt://h/t?cafile=/x", "mqtt://h/t?cafile=/x: cafile= is for mqtts:// only" },
    { "mqtts://h/t?pass=x", "mqtts://h/t?pass=x: unknown option 'pass=x' (expected cafile=PATH "
                            "or password-file=PATH)" },
  };
  for (size_t i = 0; i < sizeof urls / sizeof urls[0]; i++) {
    mr_glove_source_report rep;
    assert_int_equal(mr_glove_source_check(urls[i][0], &rep), MR_IO_ERR_SPEC);
    assert_string_equal(rep.msg, urls[i][1]);
  }
  mr_glove_source_report rep;
  assert_int_equal(mr_glove_source_check("mqtts://bob@[::1]:8884/glove/bob?cafile=/ca.pem", &rep),
                   MR_IO_OK);
  assert_string_equal(rep.note, "");
  assert_int_equal(mr_glove_source_check("mqtt://bob@stage.example/glove/bob", &rep), MR_IO_OK);
  assert_non_null(strstr(rep.note, "sends the password in the clear"));
  /* Any user name, one letter long too, beyond this machine; none without
   * a user or on the loopback. */
  static const struct {
    const char *url;
    bool warned;
  } clear[] = { { "mqtt://b@stage.example/glove/b", true },
                { "mqtt://stage.example/glove/anyone", false },
                { "mqtt://bob@127.0.0.1/glove/bob", false },
                { "mqtt://bob@localhost/glove/bob", false },
                { "mqtt://bob@[::1]/glove/bob", false } };
  for (size_t i = 0; i < sizeof clear / sizeof clear[0]; i++) {
    assert_int_equal(mr_glove_source_check(clear[i].url, &rep), MR_IO_OK);
    if ((strstr(rep.note, "sends the password in the clear") != NULL) != clear[i].warned)
      fail_msg("%s: note '%s'", clear[i].url, rep.note);
  }
  d = mr_default_glove_def();
  d.retry_every = 5;
  assert_int_equal(mr_glove_create(&d, &g, msg, sizeof msg), MR_GLOVE_ERR_ARG);
  /* A port that is not there: connecting, and it says why. */
  g = glove_on("pty:/nonexistent/glove");
  mr_glove_poll(g, 0.0, 0);
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_CONNECTING);
  char line[300];
  mr_glove_describe(g, 0.0, line, sizeof line);
  assert_non_null(strstr(line, "glove on pty:/nonexistent/glove: connecting ("));
  mr_glove_destroy(g);
}

/* The definition's documented defaults, and its bounds, each side. */
static void a_glove_definition_is_checked_at_its_bounds(void **state) {
  (void)state;
  mr_glove_def d = mr_default_glove_def();
  assert_true(d.lost_after == 0.5 && d.retry_every == 0.5 && d.reconnect == 0.0);
  assert_true(d.cmd_timeout == 0.25 && d.cmd_tries == 5);
  assert_string_equal(d.source, "serial:auto");
  static const struct {
    double lost_after, retry_every, reconnect, cmd_timeout;
    int cmd_tries;
    mr_glove_status want;
  } cases[] = {
    { 0.5, 1.0, 0.0, 60.0, 100, MR_GLOVE_OK },
    { 0.0, 0.5, 0.0, 0.25, 5, MR_GLOVE_ERR_ARG },
    { 0.5, 1.01, 0.0, 0.25, 5, MR_GLOVE_ERR_ARG },
    { 0.5, 0.0, 0.0, 0.25, 5, MR_GLOVE_ERR_ARG },
    { 0.5, 0.5, 0.0, 0.0, 5, MR_GLOVE_ERR_ARG },
    { 0.5, 0.5, INFINITY, 0.25, 5, MR_GLOVE_ERR_ARG },
    { 0.5, 0.5, 0.0, 60.5, 5, MR_GLOVE_ERR_ARG },
    { 0.5, 0.5, 0.0, 0.25, 101, MR_GLOVE_ERR_ARG },
    { 0.5, 0.5, 0.0, 0.25, 0, MR_GLOVE_ERR_ARG },
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    d = mr_default_glove_def();
    snprintf(d.source, sizeof d.source, "pty:/nonexistent/glove");
    d.lost_after = cases[i].lost_after;
    d.retry_every = cases[i].retry_every;
    d.reconnect = cases[i].reconnect;
    d.cmd_timeout = cases[i].cmd_timeout;
    d.cmd_tries = cases[i].cmd_tries;
    mr_glove *g = NULL;
    assert_int_equal(mr_glove_create(&d, &g, NULL, 0), cases[i].want);
    mr_glove_destroy(g);
  }
  static const char *const names[] = { "connecting", "live", "lost", "spec mismatch" };
  const mr_glove_state states[] = { MR_GLOVE_CONNECTING, MR_GLOVE_LIVE, MR_GLOVE_LOST,
                                    MR_GLOVE_MISMATCH };
  for (int i = 0; i < 4; i++) assert_string_equal(mr_glove_state_name(states[i]), names[i]);
  assert_string_equal(mr_glove_state_name((mr_glove_state)9), "unknown");
}

/* A glove unplugged at t = 10 s with reconnect 1 s is retried until
 * 11 s and ends there, saying why; with reconnect < 0 it ends at the
 * hang-up itself. */
static void reconnect_bounds_how_long_an_unplugged_glove_is_retried(void **state) {
  (void)state;
  for (int give_up = 0; give_up <= 1; give_up++) {
    port p;
    make_port(&p);
    plug(&p);
    mr_glove_def d = mr_default_glove_def();
    snprintf(d.source, sizeof d.source, "pty:%s", p.link);
    d.reconnect = give_up ? 1.0 : -1.0;
    mr_glove *g = NULL;
    assert_int_equal(mr_glove_create(&d, &g, NULL, 0), MR_GLOVE_OK);
    mr_glove_poll(g, 10.0, 0);
    unplug(&p);
    for (int i = 0; i < 50 && mr_glove_get_state(g) != MR_GLOVE_LOST; i++)
      mr_glove_poll(g, 10.0, 10);
    assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LOST);
    if (give_up) {
      assert_false(mr_glove_ended(g));
      mr_glove_poll(g, 10.5, 0);
      mr_glove_poll(g, 10.75, 0);
      assert_false(mr_glove_ended(g));
      mr_glove_poll(g, 11.0, 0);
      assert_string_equal(mr_glove_last_error(g, NULL), "not back within 1 s");
    }
    assert_true(mr_glove_ended(g));
    mr_glove_destroy(g);
    rmdir(p.dir);
  }
}

/* An INFO of this build's spec with five channels and adc_bits bits. */
static gp_msg info_of(uint8_t adc_bits) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_INFO;
  m.u.info.proto_major = 1;
  m.u.info.spec_hash = GP_SPEC_HASH;
  m.u.info.n_channels = 5;
  m.u.info.adc_bits = adc_bits;
  return m;
}

/* An INFO whose numbers would make the calibration divide by zero or by
 * a negative span, or shift by 40 bits: the glove falls back to the ADC's
 * full scale, and every value stays a finite number. An ADC of 1, 11 or
 * 16 bits without a range gives its own full scale. */
static void an_info_that_would_make_nan_is_not_believed(void **state) {
  (void)state;
  port p;
  char source[128];
  mr_glove *g = glove_on_new_port(&p, source, sizeof source);
  mr_glove_poll(g, 1.0, 0);
  static const uint16_t spans[][2] = { { 2000, 2000 }, { 3000, 1000 } };
  static const uint8_t bits[] = { 0, 40 };
  for (int c = 0; c < 2; c++) {
    gp_msg m = info_of(bits[c]);
    m.u.info.cal_state = GP_CAL_VALID;
    for (int k = 0; k < 5; k++) {
      m.u.info.cal_min[k] = spans[c][0];
      m.u.info.cal_max[k] = spans[c][1];
    }
    send(&p, &m, GP_SPEC_HASH);
    send_sample(&p, (uint16_t)(c + 1), 1000u * (uint32_t)(c + 1), 2000);
    assert_true(poll_for_samples(g, 1.0 + c) > 0);
    mr_glove_reading r;
    mr_glove_latest(g, &r);
    for (int k = 0; k < 5; k++) {
      assert_true(isfinite(r.values[k]));
      assert_true(fabs(r.values[k] - (2000.0 + 100 * k) / 4095.0) < 1e-12);
    }
  }
  /* An ADC of 1..16 bits is believed, to its ends: its own full scale. */
  static const uint8_t good[] = { 1, 11, 16 };
  for (int c = 0; c < (int)(sizeof good / sizeof good[0]); c++) {
    gp_msg m = info_of(good[c]);
    send(&p, &m, GP_SPEC_HASH);
    send_sample(&p, (uint16_t)(c + 3), 1000u * (uint32_t)(c + 3), 2000);
    assert_true(poll_for_samples(g, 3.0 + c) > 0);
    mr_glove_reading r;
    mr_glove_latest(g, &r);
    const double full = (double)((1u << good[c]) - 1u);
    for (int k = 0; k < 5; k++)
      if (fabs(r.values[k] - (2000.0 + 100 * k) / full) > 1e-12)
        fail_msg("%d bits, finger %d: %.17g", good[c], k, r.values[k]);
  }
  mr_glove_destroy(g);
  unplug(&p);
  rmdir(p.dir);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(an_info_that_would_make_nan_is_not_believed),
    cmocka_unit_test(a_live_glove_is_read_calibrated_lost_and_found_again),
    cmocka_unit_test(a_foreign_glove_is_a_spec_mismatch),
    cmocka_unit_test(bad_sources_are_refused_by_name),
    cmocka_unit_test(a_glove_definition_is_checked_at_its_bounds),
    cmocka_unit_test(reconnect_bounds_how_long_an_unplugged_glove_is_retried),
    cmocka_unit_test(the_lateness_is_measured_afresh_after_a_replug),
    cmocka_unit_test(a_restart_or_a_new_uid_starts_the_device_clock_afresh),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

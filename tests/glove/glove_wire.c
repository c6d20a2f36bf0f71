/* What a glove sends, for the glove tests (glove_wire.h). */
#define _DEFAULT_SOURCE /* symlink, mkdtemp */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <math.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "glove_wire.h"
#include "mr_io.h"
#include "proc.h"

gp_msg gw_sample(uint16_t seq, uint32_t t_us, uint16_t flags, uint16_t raw) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_SAMPLE;
  m.u.sample.seq = seq;
  m.u.sample.t_us = t_us;
  m.u.sample.flags = flags;
  for (int k = 0; k < 5; k++) m.u.sample.ch[k] = (uint16_t)(raw + 100 * k);
  return m;
}

gp_msg gw_info(uint32_t uid, uint8_t cal_state, uint16_t cal_min, uint16_t cal_max,
               uint8_t adc_bits) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_INFO;
  m.u.info.proto_major = 1;
  m.u.info.spec_hash = GP_SPEC_HASH;
  m.u.info.uid[0] = uid;
  m.u.info.n_channels = 5;
  m.u.info.adc_bits = adc_bits;
  m.u.info.frame_rate_hz = 100;
  m.u.info.cal_state = cal_state;
  for (int k = 0; k < 5; k++) {
    m.u.info.cal_min[k] = cal_min;
    m.u.info.cal_max[k] = cal_max;
  }
  return m;
}

gp_msg gw_answer(uint8_t type, uint8_t tag, uint8_t cmd, uint8_t nack_reason) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = type;
  if (type == GP_NACK) {
    m.u.nack.tag = tag;
    m.u.nack.cmd = cmd;
    m.u.nack.reason = nack_reason;
  } else {
    m.u.ack.tag = tag;
    m.u.ack.cmd = cmd;
  }
  return m;
}

size_t gw_encode(const gp_msg *m, uint8_t *wire) {
  size_t n = gp_encode(m, GP_SPEC_HASH, wire, GP_MAX_WIRE);
  assert_true(n > 0);
  return n;
}

int gw_write(int fd, const void *buf, size_t len) {
  const uint8_t *p = buf;
  size_t done = 0;
  for (int spins = 0; done < len && spins < 200; spins++) {
    struct pollfd pf = { fd, POLLOUT, 0 };
    if (poll(&pf, 1, 10) <= 0) continue;
    ssize_t n = write(fd, p + done, len - done);
    if (n > 0)
      done += (size_t)n;
    else if (n < 0 && errno != EAGAIN && errno != EINTR)
      return -1;
  }
  return done == len ? 0 : -1;
}

size_t gw_send(int fd, const gp_msg *m) {
  uint8_t wire[GP_MAX_WIRE];
  size_t n = gw_encode(m, wire);
  return gw_write(fd, wire, n) == 0 ? n : 0;
}

void gw_port_plug(gw_port *p) {
  mr_io_error err;
  if (mr_io_open(&p->master, "pty", MR_IO_READ | MR_IO_WRITE, &err) != 0) fail_msg("%s", err.msg);
  unlink(p->link);
  assert_int_equal(symlink(mr_io_path(&p->master), p->link), 0);
}

void gw_port_make(gw_port *p) {
  snprintf(p->dir, sizeof p->dir, "/tmp/mr-glove-XXXXXX");
  assert_non_null(mkdtemp(p->dir));
  snprintf(p->link, sizeof p->link, "%s/glove", p->dir);
  snprintf(p->source, sizeof p->source, "pty:%s", p->link);
  gw_port_plug(p);
}

void gw_port_unplug(gw_port *p) {
  mr_io_close(&p->master);
  unlink(p->link);
}

void gw_port_remove(gw_port *p) {
  gw_port_unplug(p);
  rmdir(p->dir);
}

size_t gw_port_send(gw_port *p, const gp_msg *m) {
  size_t n = gw_send(p->master.fd, m);
  assert_true(n > 0);
  return n;
}

mr_glove *gw_glove(const char *source, double lost_after, double retry_every) {
  mr_glove_def d = mr_default_glove_def();
  snprintf(d.source, sizeof d.source, "%s", source);
  d.lost_after = lost_after;
  d.retry_every = retry_every;
  mr_glove *g = NULL;
  char msg[300];
  if (mr_glove_create(&d, &g, msg, sizeof msg) != MR_GLOVE_OK) fail_msg("%s", msg);
  return g;
}

int gw_poll_for_samples(mr_glove *g, double now) {
  for (int i = 0; i < 100; i++) {
    int n = mr_glove_poll(g, now, 10);
    if (n > 0) return n;
  }
  return 0;
}

char *gw_take(int count, double spacing, size_t *len) {
  const char *path = tt_tmp_file("glove_wire.mrec", "", 0);
  assert_non_null(path);
  mr_rec_writer w;
  mr_io_error err;
  assert_int_equal(mr_rec_writer_open(&w, path, GP_SPEC_HASH, 0, &err), 0);
  for (int i = 0; i < count; i++) {
    uint8_t wire[GP_MAX_WIRE];
    gp_msg m = gw_sample((uint16_t)(i + 1), (uint32_t)llround(i * spacing * 1e6), 0, 2000);
    size_t n = gw_encode(&m, wire);
    assert_int_equal(mr_rec_writer_add(&w, (uint64_t)llround(i * spacing * 1e9), wire, n, &err), 0);
  }
  assert_int_equal(mr_rec_writer_close(&w, &err), 0);
  char *bytes = tt_read_file(path, len);
  assert_non_null(bytes);
  return bytes;
}

double gw_lateness(const mr_glove *g) {
  mr_glove_reading r;
  mr_glove_latest(g, &r);
  return r.host_t - r.device_t - mr_glove_clock_offset(g);
}

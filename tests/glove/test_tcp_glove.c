/* TCP gloves over real sockets on 127.0.0.1. A `tcp:` glove whose server
 * drops it again and again (right after accept, before any byte, mid-frame,
 * with a reset, after a short stream), or goes away for a while and comes
 * back, connects again each time, gets samples again within a bound, reads
 * "ms late" below 100 ms within a second, and counts each loss once. A `tcp-listen:` glove serves one peer,
 * as documented: fifty peers that connect at once are each served or
 * closed, none is left hanging, and the served peer's samples arrive. The
 * glove runs on a virtual clock; the server is this test, on one thread. */
#define _DEFAULT_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "glove_wire.h"

enum { ROUNDS = 10, RATE_HZ = 100 };

/* How a connection ends. */
typedef enum drop {
  DROP_AFTER_FRAMES, /* a clean close after whole frames */
  DROP_MID_FRAME,    /* half a SAMPLE, then a close */
  DROP_RESET,        /* a reset (SO_LINGER 0) after whole frames */
  DROP_AT_ACCEPT,    /* closed right after accept, before any byte */
  DROP_SHORT_STREAM, /* twenty samples and half an INFO: fewer than the
                        decoder's sequence window */
} drop;

typedef struct server {
  int srv, conn, port;
  mr_glove *g;
  double now;          /* the glove's virtual clock, s */
  uint16_t seq;        /* the next SAMPLE's sequence number */
  uint64_t bytes_sent; /* every byte the server wrote */
  int cuts;            /* frames cut short by a drop */
  uint64_t losses;     /* losses the glove must have counted */
  int round;
} server;

/* A listening socket on 127.0.0.1: on *port, or on a free one when it is
 * 0 (then *port says which). */
static int listen_loopback(int *port) {
  int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0), one = 1;
  assert_true(fd >= 0);
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  struct sockaddr_in sa;
  memset(&sa, 0, sizeof sa);
  sa.sin_family = AF_INET;
  sa.sin_port = htons((uint16_t)*port);
  sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  assert_int_equal(bind(fd, (struct sockaddr *)&sa, sizeof sa), 0);
  assert_int_equal(listen(fd, 64), 0);
  socklen_t len = sizeof sa;
  assert_int_equal(getsockname(fd, (struct sockaddr *)&sa, &len), 0);
  *port = ntohs(sa.sin_port);
  return fd;
}

static mr_glove_counters counters(const mr_glove *g) {
  mr_glove_counters c;
  mr_glove_get_counters(g, &c);
  return c;
}

/* Polls the glove on its clock, 10 ms a step, until it has connected again
 * and the server took the connection. The virtual seconds it took. */
static double reconnect(server *s) {
  uint64_t opens = counters(s->g).opens;
  double t0 = s->now;
  for (int i = 0; i < 500 && counters(s->g).opens == opens; i++) {
    s->now += 0.01;
    mr_glove_poll(s->g, s->now, 0);
  }
  if (counters(s->g).opens != opens + 1)
    fail_msg("not connected again in %.2f s of the glove's clock", s->now - t0);
  struct pollfd p = { s->srv, POLLIN, 0 };
  assert_int_equal(poll(&p, 1, 2000), 1);
  s->conn = accept(s->srv, NULL, NULL);
  assert_true(s->conn >= 0);
  return s->now - t0;
}

static void send_counted(server *s, const gp_msg *m) {
  size_t n = gw_send(s->conn, m);
  assert_true(n > 0);
  s->bytes_sent += n;
}

/* `secs` of samples at 100 Hz, the device clock from t0_us, each read at its
 * device time plus a jitter of up to 4 ms on the glove's clock. */
static void stream(server *s, double secs, uint32_t t0_us, uint16_t first_flags) {
  double base = s->now;
  for (int i = 0; i < (int)(secs * RATE_HZ); i++) {
    gp_msg m = gw_sample(s->seq++, t0_us + 10000u * (uint32_t)i, i == 0 ? first_flags : 0,
                         (uint16_t)(1000 + i));
    send_counted(s, &m);
    s->now = base + 0.01 * i + 0.001 * (double)((i * 7) % 5);
    if (gw_poll_for_samples(s->g, s->now) == 0)
      fail_msg("round %d: sample %d (seq %u) of its connection was not taken", s->round, i,
               (unsigned)(s->seq - 1));
  }
  s->now = base + secs;
}

static void close_as(server *s, drop how) {
  if (how == DROP_MID_FRAME || how == DROP_SHORT_STREAM) {
    uint8_t wire[GP_MAX_WIRE];
    gp_msg m = how == DROP_MID_FRAME ? gw_sample(s->seq, 0, 0, 0)
                                     : gw_info(0xAB, GP_CAL_VALID, 1000, 3000, 12);
    size_t half = gw_encode(&m, wire) / 2;
    assert_int_equal(gw_write(s->conn, wire, half), 0);
    s->bytes_sent += half;
    s->cuts++;
  }
  if (how == DROP_RESET) {
    struct linger lg = { 1, 0 };
    setsockopt(s->conn, SOL_SOCKET, SO_LINGER, &lg, sizeof lg);
  }
  if (mr_glove_get_state(s->g) != MR_GLOVE_LOST) s->losses++;
  close(s->conn);
  s->conn = -1;
  /* The hang-up is seen at once: real waits, the clock held. */
  for (int i = 0; i < 200 && mr_glove_get_state(s->g) != MR_GLOVE_LOST; i++)
    mr_glove_poll(s->g, s->now, 10);
  assert_int_equal(mr_glove_get_state(s->g), MR_GLOVE_LOST);
  assert_int_equal(mr_glove_unfinished(s->g), 0);
}

/* How the glove's sequence goes on after a reconnect. */
typedef enum seq_mode {
  SEQ_START,   /* from 0 with a START flag (the glove booted again) */
  SEQ_RESTART, /* from 0 without one (its START frame was lost) */
  SEQ_CARRY    /* on from where it was (only the link was down) */
} seq_mode;

typedef struct round_plan {
  drop how;
  seq_mode seq;
  uint32_t t0_us; /* the device clock at the connection's first sample */
} round_plan;

/* Every drop after every kind of start, the device clock moved back by
 * more and by less than 2^31 us, and once across its wrap. */
static const round_plan plans[ROUNDS] = {
  { DROP_AT_ACCEPT, SEQ_START, 3000000000u },
  { DROP_AFTER_FRAMES, SEQ_RESTART, 10000000u },
  { DROP_SHORT_STREAM, SEQ_RESTART, 2500000000u },
  { DROP_MID_FRAME, SEQ_RESTART, 3000000000u },
  { DROP_RESET, SEQ_CARRY, 5000000u },
  { DROP_SHORT_STREAM, SEQ_START, 4000000000u },
  { DROP_AT_ACCEPT, SEQ_CARRY, 4294500000u },
  { DROP_MID_FRAME, SEQ_RESTART, 1000000u },
  { DROP_AFTER_FRAMES, SEQ_START, 2200000000u },
  { DROP_RESET, SEQ_CARRY, 0u },
};

/* One connection: connected again within retry_every and a step, samples
 * from the first one on, "ms late" below 100 ms after a second, and then
 * dropped as the plan says. */
static void one_connection(server *s, int round, double retry_every) {
  const round_plan *p = &plans[round];
  s->round = round;
  double took = reconnect(s);
  if (took > retry_every + 0.011)
    fail_msg("round %d: connected again after %.3f s, retry_every is %.2f s", round, took,
             retry_every);
  if (p->how == DROP_AT_ACCEPT) {
    close_as(s, p->how);
    reconnect(s);
  }
  if (p->seq != SEQ_CARRY) s->seq = 0;
  gp_msg info = gw_info(0x5EED, GP_CAL_VALID, 1000, 3000, 12);
  send_counted(s, &info);
  stream(s, p->how == DROP_SHORT_STREAM ? 0.2 : 1.0, p->t0_us,
         p->seq == SEQ_START ? GP_SAMPLE_F_START : 0);
  mr_glove_reading r;
  mr_glove_latest(s->g, &r);
  double want_t = (double)p->t0_us * 1e-6 + (p->how == DROP_SHORT_STREAM ? 0.19 : 0.99);
  if (!(fabs(r.device_t - want_t) < 1e-6 || fabs(r.device_t - want_t - 4294.967296) < 1e-6))
    fail_msg("round %d: device time %.6f s, expected %.6f s", round, r.device_t, want_t);
  if (!(gw_lateness(s->g) < 0.1))
    fail_msg("round %d: %.3f s late a second after the reconnect", round, gw_lateness(s->g));
  assert_true(gw_lateness(s->g) <= 0.0045); /* the jitter, no more */
  close_as(s, p->how);
}

/* The server gone for 3 s: every connection refused, tried once per
 * retry_every all along (the wait does not grow), and taken at the next
 * try once the server listens again on the same port. */
static void server_away_and_back(server *s, double retry_every) {
  close(s->srv);
  mr_glove_counters c0 = counters(s->g);
  for (int i = 1; i <= 300; i++) mr_glove_poll(s->g, s->now + 0.01 * i, 0);
  s->now += 3.0;
  int tries = (int)(counters(s->g).open_failures - c0.open_failures);
  int want = (int)(3.0 / retry_every);
  if (tries < want - 1 || tries > want)
    fail_msg("%d tries in 3 s with retry_every %.2f s", tries, retry_every);
  s->srv = listen_loopback(&s->port);
  s->round = ROUNDS;
  if (reconnect(s) > retry_every + 0.011) fail_msg("not back within retry_every");
  stream(s, 1.0, 123456789u, GP_SAMPLE_F_START);
  assert_true(gw_lateness(s->g) <= 0.0045);
  close_as(s, DROP_AFTER_FRAMES);
}

static void a_tcp_glove_gets_samples_again_after_every_reconnect(void **state) {
  (void)state;
  static const double retry[] = { 0.25, 0.5 };
  for (int r = 0; r < 2; r++) {
    server s;
    memset(&s, 0, sizeof s);
    s.srv = listen_loopback(&s.port);
    char source[64];
    snprintf(source, sizeof source, "tcp:127.0.0.1:%d", s.port);
    s.g = gw_glove(source, 0.5, retry[r]);
    s.now = 100.0;
    for (int round = 0; round < ROUNDS; round++) one_connection(&s, round, retry[r]);
    server_away_and_back(&s, retry[r]);
    mr_glove_counters c = counters(s.g);
    assert_int_equal(c.losses, s.losses);
    assert_int_equal(c.opens, ROUNDS + 3); /* two drops at accept, the server back */
    /* The host's own delimiter, which ends a cut frame, is not a byte
     * received; each cut frame is one error. */
    assert_int_equal(c.decoder.bytes, s.bytes_sent);
    assert_int_equal(c.decoder.framing_errors + c.decoder.crc_errors, (uint32_t)s.cuts);
    mr_glove_destroy(s.g);
    close(s.srv);
  }
}

enum { PEERS = 50 };

/* Where a peer of the listening glove stands, seen from its own end. */
typedef enum peer_state {
  PEER_WAITING, /* connecting, or connected and neither served nor closed */
  PEER_OPEN,    /* connected, nothing came back: served (or not yet refused) */
  PEER_CLOSED   /* the glove closed it: end of stream or a reset */
} peer_state;

static peer_state peer_look(int fd) {
  struct pollfd p = { fd, POLLIN | POLLOUT, 0 };
  if (poll(&p, 1, 0) != 1) return PEER_WAITING;
  int e = 0;
  socklen_t len = sizeof e;
  getsockopt(fd, SOL_SOCKET, SO_ERROR, &e, &len);
  if (e == ECONNREFUSED || e == ECONNRESET) return PEER_CLOSED;
  if (e != 0) fail_msg("a peer's connection failed: %s", strerror(e));
  if (!(p.revents & (POLLIN | POLLHUP))) return p.revents & POLLOUT ? PEER_OPEN : PEER_WAITING;
  char c;
  ssize_t n = recv(fd, &c, 1, MSG_PEEK);
  if (n == 0 || (n < 0 && errno == ECONNRESET)) return PEER_CLOSED;
  fail_msg("the glove sent a peer something");
  return PEER_WAITING;
}

static int connect_nonblocking(int port) {
  int fd = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  assert_true(fd >= 0);
  struct sockaddr_in sa;
  memset(&sa, 0, sizeof sa);
  sa.sin_family = AF_INET;
  sa.sin_port = htons((uint16_t)port);
  sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  int rc = connect(fd, (struct sockaddr *)&sa, sizeof sa);
  assert_true(rc == 0 || errno == EINPROGRESS);
  return fd;
}

/* Polls the glove (its clock held) until every peer is closed but one,
 * within 20 s of real time: the one it serves. Its index. */
static int settle(mr_glove *g, double now, const int *peers) {
  uint64_t end = mr_io_monotonic_ns() + 20000000000ull;
  int open = 0, closed = 0, served = -1;
  while (mr_io_monotonic_ns() < end) {
    mr_glove_poll(g, now, 10);
    open = closed = 0;
    for (int i = 0; i < PEERS; i++) {
      peer_state st = peer_look(peers[i]);
      closed += st == PEER_CLOSED;
      if (st == PEER_OPEN) {
        open++;
        served = i;
      }
    }
    if (closed == PEERS - 1 && open == 1) return served;
  }
  fail_msg("after 20 s: %d peers closed, %d connected and left open, %d connecting", closed, open,
           PEERS - closed - open);
  return -1;
}

/* Fifty peers at once on a listening glove, more than its backlog holds:
 * one is served, the 49 others are closed, none hangs. The served peer's
 * samples arrive; when it leaves, the next peer is served, and its clock,
 * which started again with the sequence carried on, is measured afresh. */
static void a_listening_glove_serves_one_of_fifty_peers_and_closes_the_rest(void **state) {
  (void)state;
  mr_glove *g = gw_glove("tcp-listen:127.0.0.1:0", 0.3, 0.2);
  double now = 50.0;
  mr_glove_poll(g, now, 0);
  const char *where = mr_glove_io_path(g);
  const char *colon = strrchr(where, ':');
  assert_non_null(colon);
  int port = atoi(colon + 1), peers[PEERS];
  for (int i = 0; i < PEERS; i++) peers[i] = connect_nonblocking(port);
  int served = settle(g, now, peers);
  uint16_t seq = 0;
  for (int i = 0; i < 50; i++) {
    gp_msg m = gw_sample(seq++, 100000000u + 10000u * (uint32_t)i, 0, 2000);
    assert_true(gw_send(peers[served], &m) > 0);
    if (gw_poll_for_samples(g, now + 0.01 * i) == 0) fail_msg("sample %d not taken", i);
  }
  now += 0.5;
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LIVE);
  assert_true(gw_lateness(g) < 1e-9);
  for (int i = 0; i < PEERS; i++) close(peers[i]);

  /* The next peer; the device clock went from 100 s back to 1 s. */
  for (int i = 0; i < 100 && mr_glove_get_state(g) != MR_GLOVE_LOST; i++) mr_glove_poll(g, now, 10);
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LOST);
  int next = connect_nonblocking(port);
  for (int i = 0; i < 100; i++) {
    gp_msg m = gw_sample(seq++, 1000000u + 10000u * (uint32_t)i, 0, 2000);
    if (i == 0) {
      struct pollfd p = { next, POLLOUT, 0 };
      assert_int_equal(poll(&p, 1, 2000), 1);
    }
    assert_true(gw_send(next, &m) > 0);
    if (gw_poll_for_samples(g, now + 0.01 * i) == 0) fail_msg("sample %d of the next peer", i);
  }
  if (!(gw_lateness(g) < 0.1)) fail_msg("%.3f s late with the next peer", gw_lateness(g));
  mr_glove_counters c = counters(g);
  assert_int_equal(c.opens, 1); /* one listening socket all along */
  assert_int_equal(c.losses, 1);
  close(next);
  mr_glove_destroy(g);
}

int main(void) {
  signal(SIGPIPE, SIG_IGN);
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_tcp_glove_gets_samples_again_after_every_reconnect),
    cmocka_unit_test(a_listening_glove_serves_one_of_fifty_peers_and_closes_the_rest),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

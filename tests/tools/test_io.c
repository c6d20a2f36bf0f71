/* The io layer on real descriptors: a link that goes away is a hang-up, not
 * a timeout, and whatever arrived before it is delivered first. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "mr_io.h"
#include "tools_proc.h"

#define BURST 3000

static void fill(uint8_t *b, size_t n, unsigned salt) {
  for (size_t i = 0; i < n; i++) b[i] = (uint8_t)((i * 13 + salt) | 1u);
}

/* Reads until something other than data; returns that status. */
static mr_io_status read_until_not_ok(mr_io *io, uint8_t *buf, size_t cap, size_t *total,
                                      int timeout_ms) {
  for (;;) {
    size_t got = 0;
    mr_io_error err;
    mr_io_status st = mr_io_read(io, buf + *total, cap - *total, timeout_ms, &got, &err);
    if (st != MR_IO_OK) return st;
    *total += got;
    if (*total == cap) return MR_IO_OK;
  }
}

/* The reader holds the slave side (as glove-dump does); the glove's side is
 * another process holding the master, which exits mid-stream. */
static void tools_io_pty_master_gone_is_hangup_and_keeps_what_was_read(void **state) {
  mr_io master, slave;
  mr_io_error err;
  int go[2];
  pid_t child;
  uint8_t sent[2 * BURST], got[4 * BURST];
  size_t total = 0;
  char spec[300];
  (void)state;
  fill(sent, BURST, 1);
  fill(sent + BURST, BURST, 2);
  tt_assert_io_ok(mr_io_open(&master, "pty", MR_IO_READ | MR_IO_WRITE, &err), err);
  assert_true(mr_io_is_pty_slave(mr_io_path(&master)));
  snprintf(spec, sizeof spec, "serial:%s@115200", mr_io_path(&master));
  tt_assert_io_ok(mr_io_open(&slave, spec, MR_IO_READ, &err), err);
  assert_int_equal(slave.kind, MR_IO_TTY);
  assert_int_equal(pipe(go), 0);
  child = fork();
  assert_true(child >= 0);
  if (child == 0) {
    char c;
    mr_io_close(&slave);
    close(go[1]);
    if (mr_io_write(&master, sent, BURST, 5000, NULL, &err) != MR_IO_OK) _exit(1);
    if (read(go[0], &c, 1) != 1) _exit(2);
    if (mr_io_write(&master, sent + BURST, BURST, 5000, NULL, &err) != MR_IO_OK) _exit(3);
    /* Closing the master drops what the slave has not read: wait for it. */
    if (mr_io_drain(&master, 10000, &err) != MR_IO_OK) _exit(4);
    _exit(0);
  }
  mr_io_close(&master);
  close(go[0]);
  /* The first burst, then a quiet link: a timeout, not a hang-up. */
  while (total < BURST) {
    size_t n = 0;
    assert_int_equal(mr_io_read(&slave, got + total, BURST - total, 10000, &n, &err), MR_IO_OK);
    total += n;
  }
  assert_int_equal(read_until_not_ok(&slave, got, sizeof got, &total, 50), MR_IO_TIMEOUT);
  assert_int_equal(total, BURST);
  assert_int_equal(write(go[1], "g", 1), 1);
  assert_int_equal(read_until_not_ok(&slave, got, sizeof got, &total, 10000), MR_IO_HANGUP);
  assert_int_equal(total, 2 * BURST);
  assert_memory_equal(got, sent, 2 * BURST);
  /* And it stays a hang-up. */
  assert_int_equal(read_until_not_ok(&slave, got, sizeof got, &total, 100), MR_IO_HANGUP);
  assert_int_equal(tt_wait(child, 30), 0);
  mr_io_close(&slave);
  close(go[1]);
}

/* The other way round: this process made the pty (as glove-gen does) and
 * a peer process opens the slave, writes, and exits. */
static void tools_io_pty_slave_gone_is_hangup_and_keeps_what_was_read(void **state) {
  mr_io master;
  mr_io_error err;
  pid_t child;
  uint8_t sent[BURST], got[2 * BURST];
  size_t total = 0;
  int go[2];
  (void)state;
  fill(sent, BURST, 3);
  tt_assert_io_ok(mr_io_open(&master, "pty", MR_IO_READ | MR_IO_WRITE, &err), err);
  /* No peer yet: waiting for one times out. */
  assert_int_equal(mr_io_wait_peer(&master, 30, &err), MR_IO_TIMEOUT);
  assert_int_equal(pipe(go), 0);
  child = fork();
  assert_true(child >= 0);
  if (child == 0) {
    mr_io slave;
    char c;
    close(go[1]);
    if (mr_io_open(&slave, mr_io_path(&master), MR_IO_READ | MR_IO_WRITE, &err) != 0) {
      fprintf(stderr, "child: %s\n", err.msg);
      _exit(1);
    }
    if (mr_io_write(&slave, sent, BURST / 2, 5000, NULL, &err) != MR_IO_OK) _exit(2);
    if (read(go[0], &c, 1) != 1) _exit(3);
    if (mr_io_write(&slave, sent + BURST / 2, BURST - BURST / 2, 5000, NULL, &err) != MR_IO_OK)
      _exit(4);
    _exit(0);
  }
  close(go[0]);
  assert_int_equal(mr_io_wait_peer(&master, 10000, &err), MR_IO_OK);
  while (total < BURST / 2) {
    size_t n = 0;
    assert_int_equal(mr_io_read(&master, got + total, BURST / 2 - total, 10000, &n, &err),
                     MR_IO_OK);
    total += n;
  }
  assert_int_equal(write(go[1], "g", 1), 1);
  /* The slave's last bytes stay readable on the master after it closed. */
  assert_int_equal(read_until_not_ok(&master, got, sizeof got, &total, 10000), MR_IO_HANGUP);
  assert_int_equal(total, BURST);
  assert_memory_equal(got, sent, BURST);
  assert_int_equal(tt_wait(child, 30), 0);
  /* Writing to a pty nobody holds is a hang-up too. */
  assert_int_equal(mr_io_write(&master, sent, 10, 100, NULL, &err), MR_IO_HANGUP);
  mr_io_close(&master);
  close(go[1]);
}

static void tools_io_tcp_peer_close_is_hangup(void **state) {
  mr_io srv;
  mr_io_error err;
  pid_t child;
  uint8_t sent[BURST], got[2 * BURST];
  size_t total = 0;
  char spec[64];
  (void)state;
  fill(sent, BURST, 4);
  tt_assert_io_ok(mr_io_open(&srv, "tcp-listen:127.0.0.1:0", MR_IO_READ, &err), err);
  assert_true(srv.port > 0);
  /* Nobody connects: a bounded wait, then a timeout. */
  assert_int_equal(mr_io_accept(&srv, 20, &err), MR_IO_TIMEOUT);
  snprintf(spec, sizeof spec, "tcp:127.0.0.1:%d", srv.port);
  child = fork();
  assert_true(child >= 0);
  if (child == 0) {
    mr_io cli;
    if (mr_io_open(&cli, spec, MR_IO_WRITE, &err) != 0) {
      fprintf(stderr, "child: %s\n", err.msg);
      _exit(1);
    }
    if (mr_io_write(&cli, sent, BURST, 5000, NULL, &err) != MR_IO_OK) _exit(2);
    mr_io_close(&cli);
    _exit(0);
  }
  assert_int_equal(read_until_not_ok(&srv, got, sizeof got, &total, 10000), MR_IO_HANGUP);
  assert_int_equal(total, BURST);
  assert_memory_equal(got, sent, BURST);
  assert_int_equal(tt_wait(child, 30), 0);
  mr_io_close(&srv);
}

/* Files and FIFOs end; they do not hang up. */
static void tools_io_file_and_fifo_end_with_eof(void **state) {
  char *dir = tt_tmpdir(), path[1100];
  uint8_t sent[BURST], got[2 * BURST];
  size_t total = 0;
  mr_io io;
  mr_io_error err;
  pid_t child;
  (void)state;
  assert_non_null(dir);
  fill(sent, BURST, 5);
  snprintf(path, sizeof path, "%s", tt_path(dir, "plain.bin"));
  tt_assert_io_ok(mr_io_open(&io, path, MR_IO_WRITE, &err), err);
  assert_int_equal(io.kind, MR_IO_FILE);
  assert_int_equal(mr_io_write(&io, sent, BURST, 1000, NULL, &err), MR_IO_OK);
  mr_io_close(&io);
  tt_assert_io_ok(mr_io_open(&io, path, MR_IO_READ, &err), err);
  assert_int_equal(read_until_not_ok(&io, got, sizeof got, &total, 1000), MR_IO_EOF);
  assert_int_equal(total, BURST);
  assert_memory_equal(got, sent, BURST);
  mr_io_close(&io);

  snprintf(path, sizeof path, "%s", tt_path(dir, "fifo"));
  assert_int_equal(mkfifo(path, 0600), 0);
  child = fork();
  assert_true(child >= 0);
  if (child == 0) {
    mr_io w;
    if (mr_io_open(&w, path, MR_IO_WRITE, &err) != 0 || w.kind != MR_IO_FIFO) {
      fprintf(stderr, "child: %s\n", err.msg);
      _exit(1);
    }
    if (mr_io_write(&w, sent, BURST, 5000, NULL, &err) != MR_IO_OK) _exit(2);
    _exit(0);
  }
  tt_assert_io_ok(mr_io_open(&io, path, MR_IO_READ, &err), err);
  assert_int_equal(io.kind, MR_IO_FIFO);
  total = 0;
  assert_int_equal(read_until_not_ok(&io, got, sizeof got, &total, 10000), MR_IO_EOF);
  assert_int_equal(total, BURST);
  assert_memory_equal(got, sent, BURST);
  mr_io_close(&io);
  assert_int_equal(tt_wait(child, 30), 0);
  tt_rmdir(dir);
  free(dir);
}

/* mr_io_drain returns only once the reader has every byte: closing a pty's
 * master discards what the slave side has not read yet (measured: nothing
 * of 11 KiB written is readable after the close), so a drain that returns
 * early loses the end of the stream. The reader here is slow on purpose and
 * keeps its count in shared memory, where the drain's caller can see it. */
static void tools_io_pty_drain_returns_once_the_reader_has_every_byte(void **state) {
  enum { TOTAL = 24000, STEP = 600 };
  static uint8_t sent[TOTAL];
  volatile size_t *read_so_far;
  mr_io master;
  mr_io_error err;
  pid_t child;
  (void)state;
  fill(sent, TOTAL, 5);
  read_so_far =
      mmap(NULL, sizeof *read_so_far, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  assert_true(read_so_far != MAP_FAILED);
  *read_so_far = 0;
  tt_assert_io_ok(mr_io_open(&master, "pty", MR_IO_WRITE, &err), err);
  child = fork();
  assert_true(child >= 0);
  if (child == 0) {
    mr_io slave;
    uint8_t buf[STEP];
    close(master.fd); /* only the parent holds the glove's side */
    if (mr_io_open(&slave, mr_io_path(&master), MR_IO_READ, &err) != 0) {
      fprintf(stderr, "child: %s\n", err.msg);
      _exit(1);
    }
    for (;;) {
      size_t n = 0;
      struct timespec ts = { 0, 5000000L };
      if (mr_io_read(&slave, buf, sizeof buf, 10000, &n, &err) != MR_IO_OK) break;
      *read_so_far += n;
      nanosleep(&ts, NULL);
    }
    _exit(0);
  }
  assert_int_equal(mr_io_write(&master, sent, TOTAL, 10000, NULL, &err), MR_IO_OK);
  /* The kernel holds at most about 12 KiB between the two sides. */
  assert_true(*read_so_far < TOTAL);
  assert_int_equal(mr_io_drain(&master, 20000, &err), MR_IO_OK);
  assert_int_equal(*read_so_far, TOTAL);
  mr_io_close(&master);
  assert_int_equal(tt_wait(child, 30), 0);
  munmap((void *)read_so_far, sizeof *read_so_far);
}

static void expect_open_fails(const char *spec, mr_io_status code, const char *names) {
  mr_io io;
  mr_io_error err;
  assert_int_equal(mr_io_open(&io, spec, MR_IO_READ, &err), -1);
  if (err.status != code)
    fail_msg("%s: code %d, expected %d (%s)", spec, err.status, code, err.msg);
  if (!strstr(err.msg, names)) fail_msg("%s: '%s' does not name '%s'", spec, err.msg, names);
}

static void tools_io_bad_specs_are_errors_that_name_them(void **state) {
  (void)state;
  expect_open_fails("", MR_IO_ERR_SPEC, "empty");
  expect_open_fails("tcp:localhost", MR_IO_ERR_SPEC, "tcp:localhost");
  expect_open_fails("tcp-listen:", MR_IO_ERR_SPEC, "tcp-listen:");
  /* A port past 65535 would otherwise wrap (99999 is 34463) to a port
   * nobody asked for. */
  expect_open_fails("tcp-listen:99999", MR_IO_ERR_SPEC, "99999");
  expect_open_fails("tcp:127.0.0.1:65536", MR_IO_ERR_SPEC, "65536");
  expect_open_fails("tcp:127.0.0.1:0", MR_IO_ERR_SPEC, "tcp:127.0.0.1:0");
  expect_open_fails("tcp:127.0.0.1:50x", MR_IO_ERR_SPEC, "50x");
  expect_open_fails("serial:/dev/ttyS0@fast", MR_IO_ERR_SPEC, "fast");
  expect_open_fails("serial:@9600", MR_IO_ERR_SPEC, "serial:@9600");
  expect_open_fails("/nonexistent/glove.bin", MR_IO_ERR_SYSTEM, "/nonexistent/glove.bin");
}

/* One failure, one message: a device that is not there reads the same
 * whether it was named as a path, a serial port (with or without a baud) or
 * a file, so the tools built on mr_io all say it one way. */
static void tools_io_a_missing_device_fails_with_one_message_for_every_spec(void **state) {
  const char *specs[] = { "/dev/ttyNOSUCH0", "serial:/dev/ttyNOSUCH0",
                          "serial:/dev/ttyNOSUCH0@9600", "file:/dev/ttyNOSUCH0" };
  (void)state;
  for (size_t i = 0; i < sizeof specs / sizeof specs[0]; i++) {
    mr_io io;
    mr_io_error err;
    assert_int_equal(mr_io_open(&io, specs[i], MR_IO_READ, &err), -1);
    if (err.status != MR_IO_ERR_SYSTEM || err.sys_errno != ENOENT ||
        strcmp(err.msg, "/dev/ttyNOSUCH0: cannot open: No such file or directory") != 0)
      fail_msg("%s: status %s, errno %d, message '%s'", specs[i], mr_io_status_name(err.status),
               err.sys_errno, err.msg);
  }
}

/* The library's one status type: every value has its own name, and only the
 * MR_IO_ERR_* values, below 0 as in every library (docs/conventions.md),
 * count as failures. */
static void tools_io_status_names_are_distinct_and_only_errors_fail(void **state) {
  (void)state;
  for (int a = MR_IO_ERR_ARG; a <= MR_IO_HANGUP; a++) {
    assert_int_equal(mr_io_failed((mr_io_status)a), a <= MR_IO_ERR_SYSTEM);
    assert_string_not_equal(mr_io_status_name((mr_io_status)a), "?");
    for (int b = MR_IO_ERR_ARG; b < a; b++)
      assert_string_not_equal(mr_io_status_name((mr_io_status)a),
                              mr_io_status_name((mr_io_status)b));
  }
}

static void tools_io_pty_slave_detection(void **state) {
  mr_io master;
  mr_io_error err;
  (void)state;
  tt_assert_io_ok(mr_io_open(&master, "pty", MR_IO_READ | MR_IO_WRITE, &err), err);
  assert_true(mr_io_is_pty_slave(mr_io_path(&master)));
  assert_false(mr_io_is_pty_slave("/dev/null"));
  assert_false(mr_io_is_pty_slave("/dev/ptmx"));
  assert_false(mr_io_is_pty_slave("/nonexistent"));
  mr_io_close(&master);
}

static void tools_io_serial_list_does_not_fail(void **state) {
  mr_serial_info ports[32];
  size_t n = 999;
  mr_io_error err;
  (void)state;
  assert_int_equal(mr_serial_list(ports, 32, &n, &err), 0);
  assert_true(n < 999);
  for (size_t i = 0; i < n && i < 32; i++) {
    assert_true(ports[i].name[0] != 0);
    if (!ports[i].is_usb) assert_int_equal(ports[i].usb_vid, -1);
  }
}

static void tools_io_clocks_tell_unix_time_and_never_go_back(void **state) {
  (void)state;
  uint64_t a = mr_io_monotonic_ns();
  struct timespec pause = { 0, 2000000 };
  nanosleep(&pause, NULL);
  uint64_t b = mr_io_monotonic_ns();
  assert_true(b >= a + 2000000u);
  uint64_t u = mr_io_unix_ns() / 1000000000u;
  uint64_t t = (uint64_t)time(NULL);
  assert_true(u + 1 >= t && u <= t + 1);
}

/* The listening socket's own address (getsockname; nothing is sent):
 * tcp-listen:PORT is the loopback only, with no word said; another
 * interface must be named, and then mr_io_spec_check says once that plain
 * TCP has no authentication. */
static void tools_io_tcp_listen_binds_the_loopback_unless_told(void **state) {
  static const struct {
    const char *spec, *addr;
    int noted;
  } cases[] = { { "tcp-listen:0", "127.0.0.1", 0 }, { "tcp-listen:0.0.0.0:0", "0.0.0.0", 1 } };
  (void)state;
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    mr_io io;
    mr_io_error err;
    char note[320];
    struct sockaddr_in sa;
    socklen_t len = sizeof sa;
    char addr[INET_ADDRSTRLEN];
    tt_assert_io_ok(mr_io_spec_check(cases[i].spec, MR_IO_READ, note, sizeof note, &err), err);
    if ((note[0] != '\0') != cases[i].noted || (cases[i].noted && !strstr(note, "authentication")))
      fail_msg("%s: note '%s'", cases[i].spec, note);
    tt_assert_io_ok(mr_io_open(&io, cases[i].spec, MR_IO_READ, &err), err);
    assert_int_equal(getsockname(io.listen_fd, (struct sockaddr *)&sa, &len), 0);
    assert_int_equal(sa.sin_family, AF_INET);
    assert_non_null(inet_ntop(AF_INET, &sa.sin_addr, addr, sizeof addr));
    if (strcmp(addr, cases[i].addr) != 0)
      fail_msg("%s listens on %s, not %s", cases[i].spec, addr, cases[i].addr);
    assert_int_equal(ntohs(sa.sin_port), io.port);
    mr_io_close(&io);
  }
}

/* tcp-listen: serves one peer at a time (as documented): 20 more that
 * connect meanwhile, one after another between reads, are each accepted
 * and closed at once (they read end
 * of stream within 2 s), and the first peer's bytes still come through. */
static void tools_io_tcp_listen_serves_one_peer_and_refuses_the_rest_cleanly(void **state) {
  mr_io srv;
  mr_io_error err;
  struct sockaddr_in sa;
  int extra[20], first;
  char buf[64];
  size_t got;
  (void)state;
  tt_assert_io_ok(mr_io_open(&srv, "tcp-listen:0", MR_IO_READ, &err), err);
  memset(&sa, 0, sizeof sa);
  sa.sin_family = AF_INET;
  sa.sin_port = htons((uint16_t)srv.port);
  sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  first = socket(AF_INET, SOCK_STREAM, 0);
  assert_int_equal(connect(first, (struct sockaddr *)&sa, sizeof sa), 0);
  assert_int_equal(write(first, "one", 3), 3);
  assert_int_equal(mr_io_read(&srv, buf, sizeof buf, 2000, &got, &err), MR_IO_OK);
  assert_int_equal(got, 3);
  for (int i = 0; i < 20; i++) {
    extra[i] = socket(AF_INET, SOCK_STREAM, 0);
    /* A backlog nobody empties would block connect for a minute: 2 s. */
    struct timeval tv = { 2, 0 };
    setsockopt(extra[i], SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
    if (connect(extra[i], (struct sockaddr *)&sa, sizeof sa) != 0)
      fail_msg("connection %d of 20 not taken: %s", i + 1, strerror(errno));
    mr_io_read(&srv, buf, sizeof buf, 0, &got, &err); /* as a show reads each frame */
  }
  assert_int_equal(write(first, "two", 3), 3);
  int closed = 0;
  for (int round = 0; round < 40 && closed < 20; round++) {
    mr_io_status st = mr_io_read(&srv, buf, sizeof buf, 50, &got, &err);
    assert_true(st == MR_IO_OK || st == MR_IO_TIMEOUT);
    closed = 0;
    for (int i = 0; i < 20; i++) {
      struct pollfd p = { extra[i], POLLIN, 0 };
      closed += poll(&p, 1, 0) == 1 && recv(extra[i], buf, 1, MSG_PEEK) == 0;
    }
  }
  if (closed != 20) fail_msg("%d of 20 extra connections closed", closed);
  assert_int_equal(write(first, "three", 5), 5);
  assert_int_equal(mr_io_read(&srv, buf, sizeof buf, 2000, &got, &err), MR_IO_OK);
  for (int i = 0; i < 20; i++) close(extra[i]);
  close(first);
  mr_io_close(&srv);
}

/* A peer that leaves with bytes still unread, while the next one is
 * already waiting to connect (a glove reconnecting at once): every byte of
 * the first comes through, then its hang-up, and the next is served on the
 * same port, not refused as a second peer of the first. */
static void
tools_io_tcp_listen_serves_the_next_peer_after_the_last_bytes_of_one_gone(void **state) {
  mr_io srv;
  mr_io_error err;
  struct sockaddr_in sa;
  uint8_t sent[BURST], got[2 * BURST];
  size_t total = 0;
  (void)state;
  fill(sent, BURST, 3);
  tt_assert_io_ok(mr_io_open(&srv, "tcp-listen:0", MR_IO_READ, &err), err);
  memset(&sa, 0, sizeof sa);
  sa.sin_family = AF_INET;
  sa.sin_port = htons((uint16_t)srv.port);
  sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  int first = socket(AF_INET, SOCK_STREAM, 0), next = socket(AF_INET, SOCK_STREAM, 0);
  assert_int_equal(connect(first, (struct sockaddr *)&sa, sizeof sa), 0);
  assert_int_equal(write(first, sent, BURST), BURST);
  close(first);
  assert_int_equal(connect(next, (struct sockaddr *)&sa, sizeof sa), 0);
  assert_int_equal(write(next, "next", 4), 4);
  assert_int_equal(read_until_not_ok(&srv, got, sizeof got, &total, 2000), MR_IO_HANGUP);
  assert_int_equal(total, BURST);
  assert_memory_equal(got, sent, BURST);
  assert_int_equal(mr_io_rearm(&srv), 0);
  total = 0;
  assert_int_equal(read_until_not_ok(&srv, got, 4, &total, 2000), MR_IO_OK);
  assert_memory_equal(got, "next", 4);
  close(next);
  mr_io_close(&srv);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_io_pty_master_gone_is_hangup_and_keeps_what_was_read),
    cmocka_unit_test(tools_io_pty_slave_gone_is_hangup_and_keeps_what_was_read),
    cmocka_unit_test(tools_io_pty_drain_returns_once_the_reader_has_every_byte),
    cmocka_unit_test(tools_io_clocks_tell_unix_time_and_never_go_back),
    cmocka_unit_test(tools_io_tcp_peer_close_is_hangup),
    cmocka_unit_test(tools_io_file_and_fifo_end_with_eof),
    cmocka_unit_test(tools_io_bad_specs_are_errors_that_name_them),
    cmocka_unit_test(tools_io_tcp_listen_binds_the_loopback_unless_told),
    cmocka_unit_test(tools_io_tcp_listen_serves_one_peer_and_refuses_the_rest_cleanly),
    cmocka_unit_test(tools_io_tcp_listen_serves_the_next_peer_after_the_last_bytes_of_one_gone),
    cmocka_unit_test(tools_io_a_missing_device_fails_with_one_message_for_every_spec),
    cmocka_unit_test(tools_io_status_names_are_distinct_and_only_errors_fail),
    cmocka_unit_test(tools_io_pty_slave_detection),
    cmocka_unit_test(tools_io_serial_list_does_not_fail),
  };
  signal(SIGPIPE, SIG_IGN);
  return cmocka_run_group_tests(tests, NULL, NULL);
}

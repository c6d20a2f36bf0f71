/* A take found on a stream by its magic, and a port listened to for a
 * glove, over real descriptors: a take written into a FIFO is played at
 * the times it was recorded at and then ends; a damaged one ends the glove
 * with its reader's message; a probe hears a glove announce itself however
 * late in its wait, tells a glove of another protocol definition, reports
 * silence, and refuses what is no port. */
#define _DEFAULT_SOURCE /* mkfifo, nanosleep */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "glove_wire.h"
#include "mr_io.h"
#include "proc.h"

/* A child that opens the FIFO for writing, writes len bytes and closes. */
static pid_t write_fifo(const char *fifo, const char *bytes, size_t len) {
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    int fd = open(fifo, O_WRONLY);
    if (fd < 0) _exit(1);
    _exit(gw_write(fd, bytes, len) == 0 && close(fd) == 0 ? 0 : 1);
  }
  return pid;
}

static void reap(pid_t pid) {
  int status = 0;
  assert_int_equal(waitpid(pid, &status, 0), pid);
  assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

/* A FIFO in a fresh folder, a take of `samples` SAMPLEs 0.1 s apart, and
 * a glove on the FIFO, lost after 0.5 s of its caller's time. */
typedef struct fifo_rig {
  char *dir, path[300], *bytes;
  size_t len;
  mr_glove *g;
} fifo_rig;

static void fifo_rig_make(fifo_rig *f, int samples) {
  f->dir = tt_tmpdir();
  snprintf(f->path, sizeof f->path, "%s", tt_path(f->dir, "glove.fifo"));
  assert_int_equal(mkfifo(f->path, 0600), 0);
  f->bytes = gw_take(samples, 0.1, &f->len);
  char source[300];
  snprintf(source, sizeof source, "file:%.240s", f->path);
  f->g = gw_glove(source, 0.5, 0.5);
}

static void fifo_rig_free(fifo_rig *f) {
  mr_glove_destroy(f->g);
  free(f->bytes);
  tt_rmdir(f->dir);
  free(f->dir);
}

/* Polls at `now` (real waits of 10 ms, a second at most) until `want`
 * SAMPLEs in all were taken; the count. */
static int poll_until(mr_glove *g, double now, int have, int want) {
  for (int i = 0; i < 100 && have < want; i++) have += mr_glove_poll(g, now, 10);
  return have;
}

static void a_take_down_a_fifo_is_found_by_its_magic_and_played_at_its_times(void **state) {
  (void)state;
  fifo_rig f;
  fifo_rig_make(&f, 5);
  mr_glove *g = f.g;
  pid_t writer = write_fifo(f.path, f.bytes, f.len);
  /* Chunks recorded at 0, 0.1, ... 0.4 s: at 0.05 s the first alone is
   * due, at 0.25 s three, at 0.45 s all five. */
  int taken = poll_until(g, 0.05, 0, 1);
  for (int i = 0; i < 20; i++) taken += mr_glove_poll(g, 0.05, 10);
  assert_int_equal(taken, 1);
  mr_glove_reading r;
  mr_glove_latest(g, &r);
  assert_int_equal(r.seq, 1);
  taken = poll_until(g, 0.25, taken, 3);
  for (int i = 0; i < 20; i++) taken += mr_glove_poll(g, 0.25, 10);
  assert_int_equal(taken, 3);
  taken = poll_until(g, 0.45, taken, 5);
  assert_int_equal(taken, 5);
  mr_glove_latest(g, &r);
  assert_int_equal(r.seq, 5);
  reap(writer);
  for (int i = 0; i < 100 && !mr_glove_take_done(g); i++) mr_glove_poll(g, 0.5, 10);
  assert_true(mr_glove_take_done(g));
  /* Lost once lost_after passed with nothing more, as the take ended. */
  mr_glove_poll(g, 1.5, 0);
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LOST);
  assert_string_equal(mr_glove_last_error(g, NULL), "the take ended");
  fifo_rig_free(&f);
}

/* A take's magic and then no header: the take's reader says what is wrong,
 * the glove ends there with that message, and nothing is played. */
static void a_damaged_take_down_a_fifo_ends_the_glove_with_its_readers_message(void **state) {
  (void)state;
  fifo_rig f;
  fifo_rig_make(&f, 1);
  mr_glove *g = f.g;
  pid_t writer = write_fifo(f.path, f.bytes, 12); /* the magic and 4 bytes of header */
  int taken = 0;
  for (int i = 0; i < 100 && !mr_glove_take_done(g); i++) taken += mr_glove_poll(g, 0.1, 10);
  reap(writer);
  assert_true(mr_glove_take_done(g));
  assert_int_equal(taken, 0);
  char why[300];
  snprintf(why, sizeof why, "%s", mr_glove_last_error(g, NULL));
  if (strstr(why, f.path) == NULL) fail_msg("the message does not name the FIFO: %s", why);
  mr_glove_poll(g, 1.0, 0);
  assert_int_equal(mr_glove_get_state(g), MR_GLOVE_LOST);
  assert_string_equal(mr_glove_last_error(g, NULL), why);
  fifo_rig_free(&f);
}

/* A child that writes one INFO (of the spec hash given) into the port
 * after `delay` s. */
static pid_t announce_later(gw_port *p, uint32_t spec_hash, uint32_t uid, double delay) {
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    struct timespec ts = { (time_t)delay, (long)((delay - (double)(time_t)delay) * 1e9) };
    nanosleep(&ts, NULL);
    gp_msg m = gw_info(uid, GP_CAL_VALID, 1000, 3000, 12);
    m.u.info.spec_hash = spec_hash;
    uint8_t wire[GP_MAX_WIRE];
    size_t n = gp_encode(&m, spec_hash, wire, GP_MAX_WIRE);
    _exit(n > 0 && gw_write(p->master.fd, wire, n) == 0 ? 0 : 1);
  }
  return pid;
}

/* The INFO comes 0.4 s into a wait of 2 s, after several empty reads: the
 * probe hears it, with the glove's uid; one of another protocol definition
 * is heard as foreign; silence over the wait is no glove, said so. */
static void a_probe_hears_a_glove_announce_itself_late_in_its_wait(void **state) {
  (void)state;
  gw_port p;
  gw_port_make(&p);
  const uint32_t hashes[2] = { GP_SPEC_HASH, GP_SPEC_HASH ^ 0x5A5A5A5Au };
  for (int c = 0; c < 2; c++) {
    pid_t child = announce_later(&p, hashes[c], 0xC0FFEE + (uint32_t)c, 0.4);
    gp_info info;
    memset(&info, 0, sizeof info);
    bool foreign = c == 0;
    char msg[300];
    int found = mr_glove_probe(p.source, 2.0, &info, &foreign, msg, sizeof msg);
    reap(child);
    if (found != 1) fail_msg("case %d: not found: %s", c, msg);
    assert_int_equal(info.uid[0], 0xC0FFEE + (uint32_t)c);
    assert_int_equal(info.spec_hash, hashes[c]);
    assert_int_equal(foreign, c == 1);
  }
  char msg[300];
  bool foreign = true;
  assert_int_equal(mr_glove_probe(p.source, 0.3, NULL, &foreign, msg, sizeof msg), 0);
  assert_false(foreign);
  char want[300];
  snprintf(want, sizeof want, "%s: no glove announced itself in 0.3 s", p.source);
  assert_string_equal(msg, want);
  gw_port_remove(&p);
}

static void a_probe_refuses_what_is_no_port(void **state) {
  (void)state;
  char msg[300];
  assert_int_equal(mr_glove_probe("serial:auto", 0.1, NULL, NULL, msg, sizeof msg), -1);
  assert_string_equal(msg, "glove source 'serial:auto': not a port to probe");
  assert_int_equal(mr_glove_probe(NULL, 0.1, NULL, NULL, msg, sizeof msg), -1);
  assert_string_equal(msg, "glove source '': not a port to probe");
  assert_int_equal(mr_glove_probe("pty:", 0.1, NULL, NULL, NULL, 300), -1);
}

int main(void) {
  signal(SIGPIPE, SIG_IGN);
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_take_down_a_fifo_is_found_by_its_magic_and_played_at_its_times),
    cmocka_unit_test(a_damaged_take_down_a_fifo_ends_the_glove_with_its_readers_message),
    cmocka_unit_test(a_probe_hears_a_glove_announce_itself_late_in_its_wait),
    cmocka_unit_test(a_probe_refuses_what_is_no_port),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

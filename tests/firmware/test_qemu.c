/* The QEMU image end to end: boots firmware/boards/qemu_netduinoplus2's
 * fw.elf under qemu-system-arm with USART1 on a pipe pair, decodes what it
 * sends with the protocol's decoder, and talks back to it. Every wait is
 * bounded; QEMU is killed at the end. A missing image fails the test. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "gp.h"

#define IMAGE      MR_FIRMWARE_OUT "/qemu_netduinoplus2/fw.elf"
#define MAX_FRAMES 20000

static pid_t qemu = -1;
static int to_qemu = -1, from_qemu = -1;
static gp_decoder dec;
static gp_msg msgs[MAX_FRAMES];
static size_t n_msgs;
static size_t n_samples;

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void start_qemu(void) {
  int in[2], out[2];
  assert_int_equal(pipe(in), 0);
  assert_int_equal(pipe(out), 0);
  qemu = fork();
  assert_true(qemu >= 0);
  if (qemu == 0) {
    dup2(in[0], 0);
    dup2(out[1], 1);
    close(in[1]);
    close(out[0]);
    execlp("qemu-system-arm", "qemu-system-arm", "-M", "netduinoplus2", "-nographic", "-monitor",
           "none", "-serial", "stdio", "-kernel", IMAGE, (char *)NULL);
    _exit(127);
  }
  close(in[0]);
  close(out[1]);
  to_qemu = in[1];
  from_qemu = out[0];
  gp_decoder_init(&dec, GP_SPEC_HASH);
}

static void stop_qemu(void) {
  if (qemu > 0) {
    kill(qemu, SIGTERM);
    int status;
    double until = now_s() + 5.0;
    while (waitpid(qemu, &status, WNOHANG) == 0) {
      if (now_s() > until) {
        kill(qemu, SIGKILL);
        waitpid(qemu, &status, 0);
        break;
      }
      nanosleep(&(struct timespec){ .tv_sec = 0, .tv_nsec = 10000000 }, NULL);
    }
    qemu = -1;
  }
  if (to_qemu >= 0) close(to_qemu);
  if (from_qemu >= 0) close(from_qemu);
  to_qemu = from_qemu = -1;
}

static int teardown(void **state) {
  (void)state;
  stop_qemu();
  return 0;
}

/* Reads and decodes until done() or the deadline; returns done()'s value. */
static int pump(double seconds, int (*done)(void)) {
  double until = now_s() + seconds;
  uint8_t buf[4096];
  while (!done()) {
    double left = until - now_s();
    if (left <= 0) return 0;
    struct pollfd p = { .fd = from_qemu, .events = POLLIN };
    int r = poll(&p, 1, (int)(left * 1000) + 1);
    if (r <= 0) continue;
    ssize_t n = read(from_qemu, buf, sizeof buf);
    if (n <= 0) return done(); /* QEMU went away */
    size_t off = 0;
    while (off < (size_t)n) {
      gp_msg m;
      gp_event ev = GP_EV_NONE;
      off += gp_decoder_feed(&dec, buf + off, (size_t)n - off, &m, &ev);
      if (ev == GP_EV_FRAME && n_msgs < MAX_FRAMES) {
        msgs[n_msgs++] = m;
        if (m.type == GP_SAMPLE) n_samples++;
      }
    }
  }
  return 1;
}

static void send_msg(const gp_msg *m) {
  uint8_t w[GP_MAX_WIRE];
  size_t n = gp_encode(m, GP_SPEC_HASH, w, sizeof w);
  assert_int_equal(write(to_qemu, w, n), (ssize_t)n);
}

static size_t mark;
static uint8_t want_tag;
static int first_sample(void) {
  return n_samples > 0;
}
static int enough_samples(void) {
  return n_samples >= 600;
}
static size_t find_after(size_t from, uint8_t type) {
  for (size_t i = from; i < n_msgs; i++)
    if (msgs[i].type == type) return i;
  return n_msgs;
}
static size_t find_ack(size_t from, uint8_t tag) {
  for (size_t i = from; i < n_msgs; i++)
    if (msgs[i].type == GP_ACK && msgs[i].u.ack.tag == tag) return i;
  return n_msgs;
}
static int ack_then(uint8_t type) {
  size_t a = find_ack(mark, want_tag);
  return a < n_msgs && find_after(a + 1, type) < n_msgs;
}
static int ack_info(void) {
  return ack_then(GP_INFO);
}
static size_t find_nack(size_t from, uint8_t tag) {
  for (size_t i = from; i < n_msgs; i++)
    if (msgs[i].type == GP_NACK && msgs[i].u.nack.tag == tag) return i;
  return n_msgs;
}
static int nacked(void) {
  return find_nack(mark, want_tag) < n_msgs;
}
static int ack_status(void) {
  return ack_then(GP_STATUS);
}
static int ack_and_60_samples(void) {
  size_t a = find_ack(mark, want_tag), n = 0;
  for (size_t i = a; i < n_msgs; i++) n += msgs[i].type == GP_SAMPLE;
  return a < n_msgs && n >= 60;
}

static void firmware_qemu_streams_and_answers(void **state) {
  (void)state;
  struct stat st;
  if (stat(IMAGE, &st) != 0)
    fail_msg("%s: no firmware image (build it with `make firmware`)", IMAGE);
  start_qemu();

  /* UART input before the firmware enables it is lost: wait for a frame. */
  assert_true(pump(20.0, first_sample));

  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = GP_GET_INFO;
  m.u.get_info.tag = 0x31;
  mark = n_msgs;
  want_tag = 0x31;
  send_msg(&m);
  assert_true(pump(10.0, ack_info));
  size_t info = find_after(find_ack(mark, 0x31), GP_INFO);
  assert_int_equal(msgs[info].u.info.spec_hash, GP_SPEC_HASH);
  assert_int_equal(msgs[info].u.info.cal_state, GP_CAL_DEFAULTS); /* no storage in QEMU */
  assert_int_equal(msgs[info].u.info.frame_rate_hz, 250);

  /* Garbage: non-zero noise, then a delimiter. */
  uint8_t junk[97];
  for (size_t i = 0; i < sizeof junk; i++) junk[i] = (uint8_t)(0x80 + (i * 37) % 120);
  junk[sizeof junk - 1] = 0;
  size_t garbage_at = n_msgs;
  assert_int_equal(write(to_qemu, junk, sizeof junk), (ssize_t)sizeof junk);
  assert_true(pump(20.0, enough_samples));
  /* Garbage gets silence: no tag in it can be trusted. */
  assert_int_equal(find_after(garbage_at, GP_ACK), n_msgs);
  assert_int_equal(find_after(garbage_at, GP_NACK), n_msgs);

  /* A rate the link cannot carry (1000 Hz at 115200 is 182 %) is refused
   * with the command's tag, and the stream keeps its 4 ms. */
  memset(&m, 0, sizeof m);
  m.type = GP_SET_RATE;
  m.u.set_rate.tag = 0x34;
  m.u.set_rate.frame_rate_hz = 1000;
  mark = n_msgs;
  want_tag = 0x34;
  send_msg(&m);
  assert_true(pump(10.0, nacked));
  size_t nack = find_nack(mark, 0x34);
  assert_int_equal(msgs[nack].u.nack.cmd, GP_SET_RATE);
  assert_int_equal(msgs[nack].u.nack.reason, GP_NACK_BAD_ARGUMENT);
  assert_int_equal(find_after(mark, GP_ACK), n_msgs);

  /* SET_RATE 500 Hz at 230400 baud (500 Hz needs more than 115200 can
   * carry in half its time; QEMU's USART has no speed, the pipe follows). */
  memset(&m, 0, sizeof m);
  m.type = GP_SET_RATE;
  m.u.set_rate.tag = 0x32;
  m.u.set_rate.frame_rate_hz = 500;
  m.u.set_rate.baud = 230400;
  mark = n_msgs;
  want_tag = 0x32;
  send_msg(&m);
  assert_true(pump(10.0, ack_and_60_samples));
  size_t ack = find_ack(mark, 0x32);
  assert_int_equal(msgs[ack].u.ack.cmd, GP_SET_RATE);
  /* The device clock says 2 ms between frames after the ACK, 4 ms before.
   * A busy host can make QEMU miss a tick now and then (the firmware
   * counts it as an overrun), so the rate is judged by the majority. */
  size_t before_4ms = 0, before = 0, after_2ms = 0, after = 0;
  uint32_t prev = 0;
  int have = 0;
  for (size_t i = 0; i < n_msgs; i++) {
    if (msgs[i].type != GP_SAMPLE) continue;
    if (have) {
      uint32_t d = msgs[i].u.sample.t_us - prev;
      if (i < ack) {
        before++;
        before_4ms += d == 4000u;
      } else {
        after++;
        after_2ms += d == 2000u;
      }
    }
    prev = msgs[i].u.sample.t_us;
    have = 1;
  }
  assert_true(before >= 500 && after >= 50);
  assert_true(before_4ms * 2 > before);
  assert_true(after_2ms * 2 > after);

  memset(&m, 0, sizeof m);
  m.type = GP_GET_STATUS;
  m.u.get_status.tag = 0x33;
  mark = n_msgs;
  want_tag = 0x33;
  send_msg(&m);
  assert_true(pump(10.0, ack_status));
  size_t st_i = find_after(find_ack(mark, 0x33), GP_STATUS);
  assert_true(msgs[st_i].u.status.cmd_errors >= 2);  /* the garbage, the refused rate */
  assert_true(msgs[st_i].u.status.adc_timeouts > 0); /* QEMU never sets EOC */
  stop_qemu();

  /* The whole stream: valid CRCs, no decoder errors, sequence numbers and
   * device timestamps strictly increasing, the spec announced. */
  assert_true(n_samples >= 500);
  assert_int_equal(dec.c.crc_errors + dec.c.framing_errors + dec.c.oversize + dec.c.unknown_type +
                       dec.c.spec_mismatch + dec.c.duplicates + dec.c.reordered +
                       dec.c.seq_restarts + dec.c.lost,
                   0);
  int seen = 0, infos = 0;
  uint16_t seq = 0;
  uint32_t t = 0;
  for (size_t i = 0; i < n_msgs; i++) {
    if (msgs[i].type == GP_INFO) {
      assert_int_equal(msgs[i].u.info.spec_hash, GP_SPEC_HASH);
      infos++;
    }
    if (msgs[i].type != GP_SAMPLE) continue;
    if (seen) {
      assert_int_equal((uint16_t)(msgs[i].u.sample.seq - seq), 1);
      assert_true(msgs[i].u.sample.t_us > t);
    }
    seq = msgs[i].u.sample.seq;
    t = msgs[i].u.sample.t_us;
    seen = 1;
  }
  assert_true(infos >= 2);
}

int main(void) {
  signal(SIGPIPE, SIG_IGN);
  const struct CMUnitTest tests[] = {
    cmocka_unit_test_teardown(firmware_qemu_streams_and_answers, teardown),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

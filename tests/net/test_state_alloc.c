/* The show's state over a broker when memory runs out: every allocation
 * of opening a publisher and a reader (tests/common/alloc.h) fails in
 * turn, against a real broker on 127.0.0.1. Each open fails with "out of
 * memory" and leaves nothing behind (the sanitizers' leak check), and
 * then the two open and a frame goes from one to the other. Nothing else
 * publishes meanwhile, so the allocations are this thread's alone. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "alloc.h"
#include "broker.h"
#include "mr_state.h"
#include "proc.h"

static const char *mosquitto;

typedef struct rig {
  char *dir;
  tb_broker b;
  char url[300];
  mr_state_bundle files;
} rig;

static void rig_make(rig *r) {
  memset(r, 0, sizeof *r);
  r->dir = tt_tmpdir();
  assert_non_null(r->dir);
  assert_int_equal(tb_broker_start(&r->b, mosquitto, r->dir, "broker", 0, NULL), 0);
  snprintf(r->url, sizeof r->url, "mqtt://127.0.0.1:%d/show/alloc", r->b.port);
  assert_int_equal(mr_state_bundle_add(&r->files, "s.yaml", "name: s\n", 8), 0);
}

static void rig_free(rig *r) {
  mr_state_bundle_free(&r->files);
  tb_broker_stop(&r->b, 0);
  tt_rmdir(r->dir);
  free(r->dir);
}

static mr_state_out_def out_def(rig *r) {
  mr_state_out_def d = mr_default_state_out_def();
  d.url = r->url;
  d.scene = &r->files;
  d.fps = 30;
  d.n_frames = 1;
  d.n_points = 2;
  return d;
}

/* Opens with each allocation failing in turn until an open needs no more;
 * open: 0 and *made, or -1 with err. Returns the allocations an open makes. */
typedef int (*opener)(rig *r, void **made, mr_io_error *err);
typedef void (*closer)(void *made);

static long each_allocation_failing(rig *r, opener open, closer close, const char *what) {
  long k = 1;
  for (;; k++) {
    void *made = NULL;
    mr_io_error err;
    memset(&err, 0, sizeof err);
    tt_alloc_count(k);
    int rc = open(r, &made, &err);
    const long n = tt_alloc_stop();
    if (rc == 0) {
      close(made);
      if (n < k) break;
      fail_msg("%s: allocation %ld of %ld failed, and it opened", what, k, n);
    }
    assert_null(made);
    if (strstr(err.msg, "out of memory") == NULL)
      fail_msg("%s, allocation %ld failing: \"%s\", expected out of memory", what, k, err.msg);
    assert_true(k < 1000);
  }
  print_message("%s: %ld allocations, each one failed in turn\n", what, k - 1);
  return k - 1;
}

static int open_out(rig *r, void **made, mr_io_error *err) {
  mr_state_out_def d = out_def(r);
  mr_state_out *o = NULL;
  int rc = mr_state_out_open(&d, &o, err);
  *made = o;
  return rc;
}

static void close_out(void *made) {
  mr_state_out_close(made);
}

static int open_in(rig *r, void **made, mr_io_error *err) {
  mr_state_in_def d = mr_default_state_in_def();
  d.url = r->url;
  mr_state_in *in = NULL;
  int rc = mr_state_in_open(&d, &in, err);
  *made = in;
  return rc;
}

static void close_in(void *made) {
  mr_state_in_close(made);
}

static void every_allocation_of_opening_a_publisher_or_a_reader_may_fail(void **state) {
  (void)state;
  rig r;
  rig_make(&r);
  /* Its own (the link, the frame's arrays, the scene message) and the
   * link's queue. */
  assert_true(each_allocation_failing(&r, open_out, close_out, "the publisher") >= 5);
  assert_true(each_allocation_failing(&r, open_in, close_in, "the reader") >= 4);
  /* Then both open, and a frame goes through. */
  mr_state_in_def id = mr_default_state_in_def();
  id.url = r.url;
  mr_state_in *in = NULL;
  mr_state_out *o = NULL;
  mr_io_error err;
  assert_int_equal(mr_state_in_open(&id, &in, &err), 0);
  mr_state_out_def d = out_def(&r);
  assert_int_equal(mr_state_out_open(&d, &o, &err), 0);
  const double pose[7] = { 0.1, 1.2, 0.0, 1, 0, 0, 0 }, xyz[6] = { 0.1, 0.2, 0.3, 0.4, 0.5, 0.6 };
  int frames = 0;
  for (int i = 0; i < 300 && frames == 0; i++) {
    assert_true(mr_state_out_frame(o, i / 30.0, pose, xyz, &err) >= 0);
    mr_state_event ev;
    assert_int_equal(mr_state_in_read(in, 20, &ev, &err), MR_IO_OK);
    if (ev.kind != MR_STATE_GOT_FRAME) continue;
    assert_true(fabs(ev.xyz[5] - 0.6) < 1e-3);
    frames++;
  }
  assert_int_equal(frames, 1);
  mr_state_out_close(o);
  mr_state_in_close(in);
  rig_free(&r);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s MOSQUITTO\n", argv[0]);
    return 2;
  }
  mosquitto = argv[1];
  signal(SIGPIPE, SIG_IGN);
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(every_allocation_of_opening_a_publisher_or_a_reader_may_fail),
  };
  return cmocka_run_group_tests(tests, NULL, tb_broker_stop_all);
}

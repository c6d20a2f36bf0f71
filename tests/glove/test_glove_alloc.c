/* A glove when memory runs out. Every allocation a glove makes from its
 * creation to the end of a take is failed in turn (tests/common/alloc.h),
 * for a take named as one ("take:") and for a take found by its magic on
 * a FIFO ("file:"): the creation fails with "out of memory", or the glove
 * ends with "out of memory" as its last error, or it did without and took
 * every sample. Never a crash, and nothing left behind (the sanitizers'
 * leak check runs over this test). */
#define _DEFAULT_SOURCE /* mkfifo */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "alloc.h"
#include "glove_wire.h"
#include "mr_io.h"
#include "proc.h"

enum { SAMPLES = 5 };

typedef struct tally {
  long tries, refused, ended, done_without;
} tally;

/* A child that opens the FIFO for writing, writes len bytes and closes
 * (it may find no reader: the glove was never made). */
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

/* The glove on source, played to the take's end with the k-th allocation
 * failing (0: none): the samples it took, or −1 when it was not made. */
static int play(const char *source, long k, char *why, size_t why_size) {
  mr_glove_def d = mr_default_glove_def();
  snprintf(d.source, sizeof d.source, "%s", source);
  mr_glove *g = NULL;
  tt_alloc_count(k);
  int taken = -1;
  if (mr_glove_create(&d, &g, why, why_size) == MR_GLOVE_OK) {
    taken = 0;
    for (int i = 0; i < 200 && !mr_glove_take_done(g); i++) taken += mr_glove_poll(g, 1e12, 10);
    snprintf(why, why_size, "%s", mr_glove_last_error(g, NULL));
  }
  tt_alloc_stop();
  mr_glove_destroy(g);
  return taken;
}

/* What the glove on source does with each allocation failing in turn;
 * fifo: the FIFO the take's bytes go down for each try, or NULL. */
static tally each_allocation_failing(const char *source, const char *fifo, const char *bytes,
                                     size_t len) {
  tally t = { 0 };
  char why[400];
  for (long k = 1;; k++) {
    pid_t writer = fifo ? write_fifo(fifo, bytes, len) : 0;
    const int taken = play(source, k, why, sizeof why);
    const long made = tt_allocations();
    if (writer > 0) {
      if (taken < 0) { /* nobody opened the FIFO: let the writer through */
        int fd = open(fifo, O_RDONLY | O_NONBLOCK);
        waitpid(writer, NULL, 0);
        if (fd >= 0) close(fd);
      } else {
        waitpid(writer, NULL, 0);
      }
    }
    if (made < k) { /* nothing failed: the glove's whole run */
      assert_int_equal(taken, SAMPLES);
      break;
    }
    t.tries++;
    if (taken < 0) {
      if (strstr(why, "out of memory") == NULL)
        fail_msg("%s, allocation %ld failing: not made, \"%s\"", source, k, why);
      t.refused++;
    } else if (taken == SAMPLES) {
      t.done_without++;
    } else if (strstr(why, "out of memory") != NULL) {
      t.ended++;
    } else {
      fail_msg("%s, allocation %ld failing: %d samples of %d, last error \"%s\"", source, k, taken,
               SAMPLES, why);
    }
    assert_true(k < 10000);
  }
  print_message("%s: %ld allocations failed in turn: %ld not made, %ld ended, %ld done without\n",
                source, t.tries, t.refused, t.ended, t.done_without);
  return t;
}

static void a_take_glove_when_each_allocation_fails(void **state) {
  (void)state;
  size_t len;
  char *bytes = gw_take(SAMPLES, 0.1, &len);
  char *dir = tt_tmpdir();
  assert_non_null(dir);
  const char *path = tt_path(dir, "five.mrec");
  FILE *f = fopen(path, "wb");
  assert_non_null(f);
  assert_int_equal(fwrite(bytes, 1, len, f), len);
  assert_int_equal(fclose(f), 0);
  char source[400];
  snprintf(source, sizeof source, "take:%.390s", path);
  tally t = each_allocation_failing(source, NULL, NULL, 0);
  /* The glove itself and the reader's buffer. */
  assert_true(t.refused >= 1 && t.ended >= 1);
  free(bytes);
  tt_rmdir(dir);
  free(dir);
}

static void a_take_down_a_fifo_when_each_allocation_fails(void **state) {
  (void)state;
  size_t len;
  char *bytes = gw_take(SAMPLES, 0.1, &len);
  char *dir = tt_tmpdir();
  assert_non_null(dir);
  char fifo[300], source[320];
  snprintf(fifo, sizeof fifo, "%s", tt_path(dir, "glove.fifo"));
  assert_int_equal(mkfifo(fifo, 0600), 0);
  snprintf(source, sizeof source, "file:%s", fifo);
  tally t = each_allocation_failing(source, fifo, bytes, len);
  /* The glove, the bytes read before the magic was known, the reader's. */
  assert_true(t.refused >= 1 && t.ended >= 2);
  free(bytes);
  tt_rmdir(dir);
  free(dir);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_take_glove_when_each_allocation_fails),
    cmocka_unit_test(a_take_down_a_fifo_when_each_allocation_fails),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

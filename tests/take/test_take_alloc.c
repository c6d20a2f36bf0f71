/* The take room when memory runs out. Each operation on a book of takes A
 * and B (opening it, adding a take, a punch, a split, a trim, smoothing,
 * an offset and scaling) runs with each of its allocations failing in
 * turn (tests/common/alloc.h): it fails with "out of memory" and the
 * book, read again from its folder, still holds A and B and nothing
 * else; or it did without and made its take. No data lost, never a
 * crash, and under the sanitizers nothing leaks. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "alloc.h"
#include "mr_take.h"
#include "proc.h"
#include "take_gen.h"
#include "take_rig.h"

/* One operation on b that makes the take "made" from "a" (and "b"). */
typedef int (*operation)(mr_take_book *b, mr_take_error *err);

static int op_add(mr_take_book *b, mr_take_error *err) {
  char path[MR_TAKE_PATH_MAX];
  take_path(b, "a", path);
  const char *paths[] = { path };
  return mr_take_book_add(b, "made", paths, 1, false, NULL, err);
}

static int op_punch(mr_take_book *b, mr_take_error *err) {
  mr_take_punch_def d = mr_default_take_punch_def();
  d.base = "a";
  d.over = "b";
  d.name = "made";
  d.arms[0] = (mr_take_arm){ 0, 1 };
  d.n_arms = 1;
  d.t_in = 1.0;
  d.t_out = 2.0;
  return mr_take_book_punch(b, &d, NULL, err);
}

static int op_split(mr_take_book *b, mr_take_error *err) {
  return mr_take_book_split(b, "a", 2.5, "made", "made2", NULL, err);
}

static int op_trim(mr_take_book *b, mr_take_error *err) {
  return mr_take_book_trim(b, "a", 1.0, 2.0, "made", NULL, err);
}

static int op_smooth(mr_take_book *b, mr_take_error *err) {
  mr_take_smooth_def d = mr_default_take_smooth_def();
  return mr_take_book_smooth(b, "a", &d, "made", NULL, err);
}

static int op_offset(mr_take_book *b, mr_take_error *err) {
  double offset[MR_TAKE_MAX_GLOVES][MR_TAKE_CHANNELS] = { { 0 } };
  offset[0][2] = 0.25;
  return mr_take_book_offset(b, "a", offset, "made", NULL, err);
}

static int op_scale(mr_take_book *b, mr_take_error *err) {
  return mr_take_book_scale(b, "a", 1.5, "made", NULL, err);
}

/* The take files in dir's book. */
static int take_files(const char *dir) {
  DIR *d = opendir(tt_path(dir, "book"));
  assert_non_null(d);
  int n = 0;
  for (struct dirent *e; (e = readdir(d)) != NULL;) n += strstr(e->d_name, ".mrec") != NULL;
  closedir(d);
  return n;
}

/* The book in dir, read again: A and B, and "made" when made; when not,
 * no file of it either. */
static void book_holds(const char *dir, bool made) {
  mr_take_book b;
  mr_take_error err;
  if (mr_take_book_open(tt_path(dir, "book"), false, &b, &err) != 0) fail_msg("%s", err.msg);
  assert_non_null(mr_take_book_find(&b, "a"));
  assert_non_null(mr_take_book_find(&b, "b"));
  if (made) {
    mr_take_rec r;
    load_take(&b, "made", &r);
    assert_true(r.n_frames > 10);
    mr_take_rec_free(&r);
  } else {
    assert_int_equal(b.n, 2);
    if (take_files(dir) != 2) fail_msg("%d take files in the book, not 2", take_files(dir));
  }
  mr_take_book_close(&b);
}

/* op with each of its allocations failing in turn; returns how many it
 * makes. */
static long each_allocation_failing(operation op, const char *what) {
  long k = 1, refused = 0;
  for (;; k++) {
    char *dir = tt_tmpdir();
    assert_non_null(dir);
    mr_take_book b;
    book_ab(dir, &b);
    mr_take_error err;
    memset(&err, 0, sizeof err);
    tt_alloc_count(k);
    int rc = op(&b, &err);
    const long n = tt_alloc_stop();
    mr_take_book_close(&b);
    if (rc != 0) {
      if (strstr(err.msg, "out of memory") == NULL)
        fail_msg("%s, allocation %ld failing: \"%s\", expected out of memory", what, k, err.msg);
      refused++;
    }
    book_holds(dir, rc == 0);
    tt_rmdir(tt_path(dir, "book"));
    tt_rmdir(dir);
    free(dir);
    if (rc == 0 && n < k) break;
    assert_true(k < 10000);
  }
  print_message("%s: %ld allocations, %ld refused it when they failed\n", what, k - 1, refused);
  assert_true(refused >= 1);
  return k - 1;
}

static void every_allocation_of_each_operation_may_fail(void **state) {
  (void)state;
  make_a();
  make_b();
  const struct {
    operation op;
    const char *what;
  } ops[] = { { op_add, "add" },    { op_punch, "punch" },   { op_split, "split" },
              { op_trim, "trim" },  { op_smooth, "smooth" }, { op_offset, "offset" },
              { op_scale, "scale" } };
  for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++)
    assert_true(each_allocation_failing(ops[i].op, ops[i].what) >= 2);
}

/* Opening a book whose list holds A and B. */
static void every_allocation_of_opening_a_book_may_fail(void **state) {
  (void)state;
  make_a();
  make_b();
  char *dir = tt_tmpdir();
  assert_non_null(dir);
  mr_take_book b;
  book_ab(dir, &b);
  mr_take_book_close(&b);
  long k = 1, refused = 0;
  for (;; k++) {
    mr_take_error err;
    memset(&err, 0, sizeof err);
    tt_alloc_count(k);
    int rc = mr_take_book_open(tt_path(dir, "book"), false, &b, &err);
    const long n = tt_alloc_stop();
    if (rc == 0) {
      assert_int_equal(b.n, 2);
      mr_take_book_close(&b);
      if (n < k) break;
      continue;
    }
    if (strstr(err.msg, "out of memory") == NULL)
      fail_msg("open, allocation %ld failing: \"%s\", expected out of memory", k, err.msg);
    refused++;
    assert_true(k < 10000);
  }
  print_message("open: %ld allocations, %ld refused it when they failed\n", k - 1, refused);
  assert_true(refused >= 2);
  book_holds(dir, false);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(every_allocation_of_opening_a_book_may_fail),
    cmocka_unit_test(every_allocation_of_each_operation_may_fail),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

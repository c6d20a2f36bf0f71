/* `marionette take` end to end, through the real program: its exit codes,
 * its messages (one line each), what list and show print, and a punch-in
 * whose stored take is byte for byte the merge built from the samples. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "proc.h"
#include "take_gen.h"

static const char *marionette;
static gen_take A, B, X;

/* Runs marionette take ARGS... (NULL-terminated) into *o. */
static void take(tt_output *o, ...) {
  char *argv[32] = { (char *)marionette, "take" };
  int n = 2;
  va_list ap;
  va_start(ap, o);
  for (char *a; n < 31 && (a = va_arg(ap, char *)) != NULL;) argv[n++] = a;
  va_end(ap);
  argv[n] = NULL;
  if (tt_capture(argv, o) != 0) fail_msg("cannot start %s", marionette);
}

/* The run ended with status, said nothing or one line on stderr, and its
 * stdout or stderr holds what. */
static void expect(tt_output *o, int status, const char *what) {
  if (o->status != status) fail_msg("status %d, want %d: %s%s", o->status, status, o->out, o->err);
  const char *nl = strchr(o->err, '\n');
  if (nl != NULL && nl[1] != '\0') fail_msg("more than one line on stderr: %s", o->err);
  if (what != NULL && strstr(o->out, what) == NULL && strstr(o->err, what) == NULL)
    fail_msg("'%s' not in: %s%s", what, o->out, o->err);
  tt_output_free(o);
}

static void make_ab(const char *dir) {
  gen_init(&A, 200, 3800, 0);
  A.n = 600;
  for (size_t i = 0; i < A.n; i++)
    for (int k = 0; k < 5; k++) A.ch[i][k] = (uint16_t)(200 + (k * 300 + i * 7) % 3600);
  gen_init(&B, 100, 4000, 0);
  B.n = 590;
  B.t0 = 0.015;
  for (size_t i = 0; i < B.n; i++)
    for (int k = 0; k < 5; k++) B.ch[i][k] = (uint16_t)(100 + (k * 500 + i * 13) % 3900);
  gen_write(&A, tt_path(dir, "a.mrec"));
  gen_write(&B, tt_path(dir, "b.mrec"));
}

static void the_take_command_adds_punches_lists_and_refuses_bad_input_with_one_line(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_ab(dir);
  char book[600], a[600], b[600], file[700];
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  snprintf(a, sizeof a, "%s", tt_path(dir, "a.mrec"));
  snprintf(b, sizeof b, "%s", tt_path(dir, "b.mrec"));
  tt_output o;
  take(&o, "add", book, a, NULL);
  expect(&o, 0, "made take-1");
  take(&o, "add", book, b, "--name", "over", NULL);
  expect(&o, 0, "made over");
  take(&o, "punch", book, "take-1", "over", "--arm", "0:index,0:2", "--in", "2", "--out", "4",
       NULL);
  expect(&o, 0, "made take-2");
  /* The stored take is the merge built here from A's and B's samples. */
  X = A;
  for (size_t i = 0; i < A.n; i++) {
    long j = gen_at(&B, A.read_ns[i]);
    if (A.read_ns[i] < 2000000000u || A.read_ns[i] >= 4000000000u || j < 0) continue;
    for (int k = 1; k <= 2; k++) X.ch[i][k] = gen_raw(&A, k, gen_value(&B, k, B.ch[j][k]));
  }
  gen_write(&X, tt_path(dir, "want.mrec"));
  size_t n_got, n_want;
  snprintf(file, sizeof file, "%s/t0003-g0.mrec", book);
  char *got = tt_read_file(file, &n_got), *want = tt_read_file(tt_path(dir, "want.mrec"), &n_want);
  assert_non_null(got);
  assert_int_equal(n_got, n_want);
  assert_memory_equal(got, want, n_want);
  free(got);
  free(want);
  take(&o, "split", book, "take-2", "--at", "3", NULL);
  expect(&o, 0, "made take-3 and take-4");
  take(&o, "delete", book, "over", NULL);
  expect(&o, 0, NULL);
  take(&o, "list", book, NULL);
  assert_null(strstr(o.out, "\nover ")); /* the deleted take's own line */
  assert_int_not_equal(strncmp(o.out, "over ", 5), 0);
  expect(&o, 0, "punch of take-1 by over on 0:index,0:middle from 2 to 4 s");
  take(&o, "list", book, "--all", NULL);
  expect(&o, 0, "(deleted)");
  take(&o, "show", book, "take-4", NULL);
  expect(&o, 0, "split of take-2 at 3 s, second part");
  /* Each way of making a take from the command line, with values of its
   * own: what show says of it is what the command line asked. */
  take(&o, "offset", book, "take-1", "--channel", "0:index=0.25", "--channel", "0:thumb=-0.1",
       "--name", "shifted", NULL);
  expect(&o, 0, "made shifted");
  take(&o, "show", book, "shifted", NULL);
  expect(&o, 0, "offset of take-1: 0:thumb=-0.1,0:index=0.25");
  take(&o, "scale", book, "take-1", "--factor", "2", "--name", "slow", NULL);
  expect(&o, 0, "made slow");
  take(&o, "show", book, "slow", NULL);
  expect(&o, 0, "scale of take-1 by 2");
  take(&o, "smooth", book, "take-1", "--channels", "0:ring", "--min-cutoff", "2", "--beta", "0.1",
       "--d-cutoff", "3", "--name", "calm", NULL);
  expect(&o, 0, "made calm");
  take(&o, "show", book, "calm", NULL);
  expect(&o, 0, "smooth of take-1, min-cutoff 2 Hz, beta 0.1, d-cutoff 3 Hz, on 0:ring");
  take(&o, "trim", book, "take-1", "--from", "0.5", "--to", "1.5", "--name", "short", NULL);
  expect(&o, 0, "made short");
  take(&o, "rename", book, "short", "shorter", NULL);
  expect(&o, 0, NULL);
  take(&o, "delete", book, "shorter", NULL);
  expect(&o, 0, NULL);
  take(&o, "restore", book, "shorter", NULL);
  expect(&o, 0, NULL);
  take(&o, "show", book, "shorter", NULL);
  expect(&o, 0, "trim of take-1 to [0.5, 1.5) s");
  /* Bad input: one line each, 2 for usage, 1 for what the book refuses. */
  take(&o, "punch", book, "take-1", "over", "--arm", "0:index", "--in", "4", "--out", "2", NULL);
  expect(&o, 1, "punch-in < punch-out");
  take(&o, "punch", book, "take-1", "nope", "--arm", "0:index", "--in", "1", "--out", "2", NULL);
  expect(&o, 1, "no take named 'nope'");
  take(&o, "scale", book, "take-1", "--factor", "-1", NULL);
  expect(&o, 1, "must be a number > 0");
  take(&o, "scale", book, "take-1", "--factor", "nan", NULL);
  expect(&o, 2, "--factor expects a number");
  take(&o, "split", book, "take-1", NULL);
  expect(&o, 2, "expects --at");
  take(&o, "offset", book, "take-1", "--channel", "1:thumb=0.1", NULL);
  expect(&o, 1, "channel 1:0: take 'take-1' has gloves 0..0");
  take(&o, "offset", book, "take-1", "shifted", "--channel", "0:thumb=0.1", NULL);
  expect(&o, 2, "usage: marionette take offset");
  take(&o, "offset", book, "take-1", "--channel", "0:thumb=soon", NULL);
  expect(&o, 2, "--channel expects a number");
  take(&o, "trim", book, "take-1", "--at", "1", NULL);
  expect(&o, 2, "does not take the option '--at'");
  take(&o, "juggle", book, NULL);
  expect(&o, 2, "unknown subcommand 'juggle'");
  take(&o, "rename", book, "take-1", "a/b", NULL);
  expect(&o, 1, "no '/'");
  take(&o, "list", tt_path(dir, "nobook"), NULL);
  expect(&o, 1, "takes.json");
  take(&o, "punch", "--help", NULL);
  expect(&o, 0, "usage: marionette take punch");
  tt_rmdir(book);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: take_cli MARIONETTE\n");
    return 2;
  }
  marionette = argv[1];
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_take_command_adds_punches_lists_and_refuses_bad_input_with_one_line),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

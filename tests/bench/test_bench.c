/* marionette-bench runs end to end: --help, bad options, the fixed runs of
 * `make bench-count`, and a --quick run that writes every output it
 * documents, stamped with the machine. It asserts that the figures exist
 * and are sane, never what they are: timings are the benchmark's to print. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "proc.h"

#define BENCH MR_BINARY_DIR "/tools/marionette-bench/marionette-bench"

static tt_output run(const char *a1, const char *a2, const char *a3, const char *a4) {
  char *argv[] = { BENCH, (char *)a1, (char *)a2, (char *)a3, (char *)a4, NULL };
  tt_output o;
  assert_int_equal(tt_capture(argv, &o), 0);
  return o;
}

static void help_names_every_section_and_option(void **state) {
  (void)state;
  tt_output o = run("--help", NULL, NULL, NULL);
  assert_int_equal(o.status, 0);
  const char *words[] = { "sweep",   "sec7",  "capacity", "load",  "latency",
                          "--quick", "--out", "--count",  "--only" };
  for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
    assert_non_null(strstr(o.out, words[i]));
  tt_output_free(&o);
  o = run("--fast", NULL, NULL, NULL);
  assert_int_equal(o.status, 2);
  assert_non_null(strstr(o.err, "--fast"));
  tt_output_free(&o);
}

static void count_runs_are_fixed_work(void **state) {
  (void)state;
  tt_output o = run("--count", "decode", NULL, NULL);
  assert_int_equal(o.status, 0);
  tt_output_free(&o);
  o = run("--count", "crowd", NULL, NULL); /* the capacity section's crowd loads and runs */
  assert_int_equal(o.status, 0);
  assert_int_equal(strlen(o.err), 0);
  tt_output_free(&o);
  o = run("--count", "nothing", NULL, NULL);
  assert_int_equal(o.status, 2); /* bad usage */
  assert_non_null(strstr(o.err, "'nothing'"));
  assert_non_null(strstr(o.err, "puppet, fig10, crowd, decode, sweep or render"));
  assert_int_equal(strlen(o.err), strcspn(o.err, "\n") + 1); /* one line */
  tt_output_free(&o);
}

/* A misspelt section would run nothing and exit 0, as if it had measured:
 * bad usage, exit 2, one line naming the bad name, and no output written. */
static void only_rejects_an_unknown_section(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  assert_non_null(dir);
  const char *bad[] = { "bogus", "sweep,bogus", "sec7,", "" };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    tt_output o = run("--only", bad[i], "--out", tt_path(dir, "out"));
    assert_int_equal(o.status, 2);
    assert_non_null(strstr(o.err, "unknown section"));
    if (i < 2) assert_non_null(strstr(o.err, "'bogus'"));
    assert_int_equal(strlen(o.err), strcspn(o.err, "\n") + 1); /* one line */
    assert_int_equal(strlen(o.out), 0);
    assert_int_not_equal(access(tt_path(dir, "out"), F_OK), 0); /* no work done */
    tt_output_free(&o);
  }
  tt_rmdir(dir);
  free(dir);
}

/* Rows of sweep.csv for a puppet, each with a finite, positive cost. */
/* The text after the k-th comma of a CSV line (no quoted commas here). */
static const char *csv_field(const char *line, int k) {
  for (int comma = 0; comma < k && line; comma++) line = strchr(line + 1, ',');
  assert_non_null(line);
  return line + 1;
}

/* Rows whose strings stretched past 1 % (string_stretch, column 25): each
 * must be off the front (front, column 29), however cheap or accurate. */
static int stretched_rows_are_off_the_front(const char *csv) {
  int rows = 0;
  for (const char *l = csv; l != NULL && *l; l = strchr(l, '\n'), l = l ? l + 1 : NULL) {
    if (*l == '#' || strncmp(l, "puppet,group,", 13) == 0) continue;
    if (!(strtod(csv_field(l, 24), NULL) > 1.01)) continue;
    assert_int_equal(atoi(csv_field(l, 28)), 0);
    rows++;
  }
  return rows;
}

static int sweep_rows(const char *csv, const char *puppet) {
  int rows = 0;
  size_t n = strlen(puppet);
  for (const char *l = csv; l != NULL && *l; l = strchr(l, '\n'), l = l ? l + 1 : NULL) {
    if (strncmp(l, puppet, n) != 0 || l[n] != ',' || strncmp(l + n, ",group,", 7) == 0)
      continue; /* another puppet's row, or the header */
    const char *last = l;
    for (int comma = 0; comma < 26 && last; comma++) last = strchr(last + 1, ',');
    assert_non_null(last); /* column 27: cpu_ms_per_sim_s */
    double cost = strtod(last + 1, NULL);
    assert_true(isfinite(cost) && cost > 0);
    rows++;
  }
  return rows;
}

/* The summary's section of one puppet, from `from` to `to` (or the end):
 * it says that the taut reference is not resolved exactly when halving
 * that reference's step moves it more than the default's error. */
static void said_unresolved_only_where_it_is(const char *from, const char *to) {
  const char *row = strstr(from, "\ndefault (the scene as written)");
  const char *ref = strstr(from, "halving its step moves the end effector");
  assert_true(row != NULL && ref != NULL && (to == NULL || ref < to));
  double cols[8], spring, taut;
  const char *p = row + strlen("\ndefault (the scene as written)");
  for (int k = 0; k < 8; k++) {
    char *end;
    cols[k] = strtod(p, &end);
    assert_true(end != p);
    p = *end == '%' ? end + 1 : end;
  }
  assert_int_equal(sscanf(ref,
                          "halving its step moves the end effector %lg m (spring strings), %lg m",
                          &spring, &taut),
                   2);
  const char *said = strstr(from, "the taut reference is not resolved");
  const int says = said != NULL && (to == NULL || said < to);
  print_message("default's error %.3g m, taut reference moved %.3g m: %s\n", cols[6], taut,
                says ? "said unresolved" : "resolved");
  assert_int_equal(says, taut > cols[6]);
}

/* Fig. 10 is judged in windows along its track (windows.c), and only it:
 * at least five in the quick run's 6 s, their references resolved (what
 * halving the step moves the hand, the median, below the default's
 * error), and the puppet's section has none. */
static void windows_only_on_the_chaotic_track(const char *fig10, const char *puppet) {
  const char *said = strstr(fig10, "the median over ");
  assert_true(said != NULL && said < puppet);
  int n = 0;
  double moved = NAN;
  const char *move = strstr(said, "moves the hand ");
  assert_int_equal(sscanf(said, "the median over %d windows", &n), 1);
  assert_true(move != NULL && sscanf(move, "moves the hand %lg m", &moved) == 1);
  const char *row = strstr(fig10, "\ndefault (the scene as written)");
  double cols[7];
  const char *p = row + strlen("\ndefault (the scene as written)");
  for (int k = 0; k < 7; k++) {
    char *end;
    cols[k] = strtod(p, &end);
    p = *end == '%' ? end + 1 : end;
  }
  print_message("%d windows, the reference resolved to %.3g m, the default's error %.3g m\n", n,
                moved, cols[6]);
  assert_true(n >= 5);
  assert_true(moved < cols[6]);
  assert_null(strstr(puppet, "the median over "));
}

static void quick_run_writes_every_output_with_the_machine(void **state) {
  (void)state;
#ifdef MR_BENCH_NATIVE_ONLY
  skip(); /* the native build runs it (tests/bench/CMakeLists.txt) */
#endif
  char *dir = tt_tmpdir();
  assert_non_null(dir);
  tt_output o = run("--quick", "--out", dir, NULL);
  assert_int_equal(o.status, 0);
  assert_non_null(strstr(o.out, "machine: "));
  assert_non_null(strstr(o.out, "cores"));
  assert_non_null(strstr(o.out, "default on the front: "));
  /* Where the taut reference moves more than the default's error when its
   * step is halved (Fig. 10 is chaotic, and over its 2 s horizon it may),
   * the summary says that the front ranks taut settings by chance, and
   * only there. */
  const char *fig10 = strstr(o.out, "\nstick-fig10 ("), *puppet = strstr(o.out, "\npuppet (");
  assert_non_null(fig10);
  assert_non_null(puppet);
  assert_true(fig10 < puppet);
  said_unresolved_only_where_it_is(fig10, puppet);
  said_unresolved_only_where_it_is(puppet, NULL);
  windows_only_on_the_chaotic_track(fig10, puppet);
  assert_non_null(strstr(o.out, "real-time puppets"));
  assert_non_null(strstr(o.out, "sample to frame: p50"));
  assert_non_null(strstr(o.out, "MuJoCo"));   /* the peer, or why it is not built */
  assert_non_null(strstr(o.err, "[sweep] ")); /* progress */
  char *csv = tt_read_file(tt_path(dir, "sweep.csv"), NULL);
  assert_non_null(csv);
  assert_non_null(strstr(csv, "puppet,group,setting,default,"));
  assert_true(sweep_rows(csv, "stick-fig10") >= 10);
  assert_true(sweep_rows(csv, "puppet") >= 10);
  /* Spring strings stretch 5-37 % on these tracks: shown, never on the front. */
  assert_true(stretched_rows_are_off_the_front(csv) >= 2);
  char *cap = tt_read_file(tt_path(dir, "capacity.csv"), NULL);
  assert_non_null(cap);
  assert_non_null(strstr(cap, "\n100,"));
  /* The crowd lying on a floor: a row for each count the quick run takes,
   * each a cost (the figures are the benchmark's to judge, not a test's). */
  assert_non_null(strstr(o.out, "lying on a floor with friction"));
  char *fl = tt_read_file(tt_path(dir, "capacity_floor.csv"), NULL);
  assert_non_null(fl);
  for (int k = 0; k < 3; k++) {
    char key[8];
    snprintf(key, sizeof key, "\n%d,", k == 0 ? 1 : k == 1 ? 4 : 16);
    const char *row = strstr(fl, key);
    double sim = 0, cost = 0;
    assert_non_null(row);
    assert_int_equal(sscanf(strchr(row + 1, ',') + 1, "%lf,%lf", &sim, &cost), 2);
    assert_true(sim > 0 && isfinite(cost) && cost > 0);
  }
  free(fl);
  char *summary = tt_read_file(tt_path(dir, "summary.txt"), NULL);
  assert_non_null(summary);
  assert_non_null(strstr(summary, "machine: "));
  if (system("command -v gnuplot >/dev/null 2>&1") == 0) {
    size_t len = 0;
    char *svg = tt_read_file(tt_path(dir, "sweep_puppet.svg"), &len);
    assert_non_null(svg);
    assert_non_null(strstr(svg, "<svg"));
    free(svg);
    assert_int_equal(access(tt_path(dir, "sweep_stick-fig10.png"), R_OK), 0);
  }
  free(csv);
  free(cap);
  free(summary);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(help_names_every_section_and_option),
    cmocka_unit_test(count_runs_are_fixed_work),
    cmocka_unit_test(only_rejects_an_unknown_section),
    cmocka_unit_test(quick_run_writes_every_output_with_the_machine),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

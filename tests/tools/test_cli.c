/* The programs' command lines: bad usage exits 2 with one line that names
 * the program by its name (not the path it was started by), one failure
 * reads the same in every tool, and glove-gen keeps binary off terminals. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tools_proc.h"

static const char *g_marionette = "marionette";

static int count_lines(const char *s) {
  int n = 0;
  for (; *s; s++) n += *s == '\n';
  return n;
}

/* Runs argv and checks its exit status and that stderr is exactly one line
 * starting "NAME: " and containing want. */
static void expect_one_line(const char *const argv[], const char *name, int status,
                            const char *want) {
  tt_output o;
  char prefix[64];
  assert_int_equal(tt_capture((char *const *)argv, &o), 0);
  snprintf(prefix, sizeof prefix, "%s: ", name);
  if (o.status != status || count_lines(o.err) != 1 || strncmp(o.err, prefix, strlen(prefix)) ||
      !strstr(o.err, want) || strstr(o.err, argv[0]))
    fail_msg("%s %s: exit %d (want %d), stderr '%s' (want one line '%s...%s...', without the "
             "program's path)",
             name, argv[1] ? argv[1] : "", o.status, status, o.err, prefix, want);
  tt_output_free(&o);
}

static void tools_cli_bad_usage_exits_2_with_one_line_naming_the_program(void **state) {
  const char *G = tt_glove_gen, *D = tt_glove_dump, *M = g_marionette;
  (void)state;
  {
    const char *a[] = { G, "--bogus", NULL };
    expect_one_line(a, "glove-gen", 2, "unknown option '--bogus'");
  }
  {
    const char *a[] = { G, "-x", NULL };
    expect_one_line(a, "glove-gen", 2, "unknown option '-x'");
  }
  {
    const char *a[] = { G, "--rate", NULL };
    expect_one_line(a, "glove-gen", 2, "'--rate' needs a value");
  }
  {
    const char *a[] = { G, "-n", "3", "-o", "tcp-listen:99999", NULL };
    expect_one_line(a, "glove-gen", 2, "99999");
  }
  {
    const char *a[] = { D, "--bogus", NULL };
    expect_one_line(a, "glove-dump", 2, "unknown option '--bogus'");
  }
  {
    /* Not 1: a port out of range is the user's usage, not a failure. */
    const char *a[] = { D, "tcp-listen:99999", NULL };
    expect_one_line(a, "glove-dump", 2, "99999");
  }
  {
    const char *a[] = { D, "tcp:localhost", NULL };
    expect_one_line(a, "glove-dump", 2, "tcp:HOST:PORT");
  }
  {
    const char *a[] = { D, "a.bin", "b.bin", NULL };
    expect_one_line(a, "glove-dump", 2, "one SOURCE only");
  }
  {
    const char *a[] = { M, NULL };
    expect_one_line(a, "marionette", 2, "expected a command");
  }
  {
    const char *a[] = { M, "bogus", NULL };
    expect_one_line(a, "marionette", 2, "unknown command 'bogus'");
  }
  {
    const char *a[] = { M, "sim", "--bogus", NULL };
    expect_one_line(a, "marionette", 2, "unknown option '--bogus'");
  }
}

/* A device that is not there is the user's usage (exit 2), found before
 * anything opens, and reads the same in every tool. */
static void tools_cli_a_missing_device_reads_the_same_in_every_tool(void **state) {
  const char *want = "/dev/ttyNOSUCH0: no such ";
  (void)state;
  {
    const char *a[] = { tt_glove_dump, "/dev/ttyNOSUCH0", NULL };
    expect_one_line(a, "glove-dump", 2, want);
  }
  {
    const char *a[] = { tt_glove_dump, "serial:/dev/ttyNOSUCH0@9600", NULL };
    expect_one_line(a, "glove-dump", 2, "serial:/dev/ttyNOSUCH0@9600: no such device");
  }
  {
    const char *a[] = { tt_glove_gen, "-n", "3", "-o", "serial:/dev/ttyNOSUCH0", NULL };
    expect_one_line(a, "glove-gen", 2, "serial:/dev/ttyNOSUCH0: no such device");
  }
}

/* Runs a bash pipeline to its end; stdout (the statuses it echoes) and
 * stderr in *o. */
static void pipeline(const char *script, tt_output *o) {
  const char *a[] = { "/bin/bash", "-c", script, NULL };
  assert_int_equal(tt_capture((char *const *)a, o), 0);
}

/* A reader that leaves after what it wanted (glove-dump -n, head, the end
 * of a show) is no failure of the writer: glove-gen exits 0, and
 * glove-dump piped into head ends quietly, exit 0, no "Broken pipe". */
static void tools_cli_a_reader_that_leaves_ends_the_writers_quietly_with_0(void **state) {
  char script[3000];
  tt_output o;
  (void)state;
  snprintf(script, sizeof script,
           "'%s' -q -r 1000 | '%s' -q -n 5 >/dev/null; echo \"${PIPESTATUS[*]}\"", tt_glove_gen,
           tt_glove_dump);
  pipeline(script, &o);
  if (strcmp(o.out, "0 0\n") != 0) fail_msg("glove-gen | glove-dump -n 5: statuses %s", o.out);
  tt_output_free(&o);
  snprintf(script, sizeof script,
           "'%s' -q --fast -n 5000 | '%s' | head -n 2 >/dev/null; echo \"${PIPESTATUS[*]}\"",
           tt_glove_gen, tt_glove_dump);
  pipeline(script, &o);
  if (strcmp(o.out, "0 0 0\n") != 0 || o.err[0] != '\0')
    fail_msg("glove-gen | glove-dump | head: statuses %s, stderr '%s' (want 0 0 0, nothing)", o.out,
             o.err);
  tt_output_free(&o);
}

/* --version: one line, the program's name and the project's version. */
static void tools_cli_each_tool_tells_its_version(void **state) {
  const char *tools[2][2] = { { tt_glove_gen, "glove-gen " }, { tt_glove_dump, "glove-dump " } };
  (void)state;
  for (int i = 0; i < 2; i++) {
    const char *a[] = { tools[i][0], "--version", NULL };
    tt_output o;
    assert_int_equal(tt_capture((char *const *)a, &o), 0);
    size_t n = strlen(tools[i][1]);
    if (o.status != 0 || strncmp(o.out, tools[i][1], n) != 0 || o.out[n] < '0' || o.out[n] > '9' ||
        count_lines(o.out) != 1 || o.err[0] != '\0')
      fail_msg("%s --version: exit %d, '%s'", tools[i][1], o.status, o.out);
    tt_output_free(&o);
  }
}

/* As gzip does: binary on a terminal garbles it, so glove-gen refuses, says
 * how to pipe it, exits 2, and writes nothing. */
static void tools_cli_glove_gen_refuses_to_write_binary_to_a_terminal(void **state) {
  int master = posix_openpt(O_RDWR | O_NOCTTY);
  char *dir = tt_tmpdir(), *err;
  const char *argv[] = { tt_glove_gen, "-n", "10", "--fast", NULL };
  (void)state;
  assert_non_null(dir);
  if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0 || !ptsname(master)) {
    perror("posix_openpt");
    skip();
  }
  assert_int_equal(tt_run(argv, ptsname(master), tt_path(dir, "err"), 30), 2);
  err = tt_read_file(tt_path(dir, "err"), NULL);
  assert_non_null(err);
  assert_int_equal(count_lines(err), 1);
  assert_non_null(strstr(err, "glove-gen: "));
  assert_non_null(strstr(err, "terminal"));
  assert_non_null(strstr(err, "glove-gen | glove-dump"));
  {
    /* Nothing reached the terminal (its master reads EIO or nothing once
     * the child has closed it). */
    char c;
    fcntl(master, F_SETFL, O_NONBLOCK);
    assert_true(read(master, &c, 1) <= 0);
  }
  {
    /* -o - on a pipe or file is fine: only the terminal is refused. */
    const char *ok[] = { tt_glove_gen, "-n", "10", "--fast", "-o", "-", NULL };
    assert_int_equal(tt_run(ok, tt_path(dir, "out.bin"), NULL, 30), 0);
  }
  close(master);
  free(err);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(tools_cli_bad_usage_exits_2_with_one_line_naming_the_program),
    cmocka_unit_test(tools_cli_a_missing_device_reads_the_same_in_every_tool),
    cmocka_unit_test(tools_cli_glove_gen_refuses_to_write_binary_to_a_terminal),
    cmocka_unit_test(tools_cli_a_reader_that_leaves_ends_the_writers_quietly_with_0),
    cmocka_unit_test(tools_cli_each_tool_tells_its_version),
  };
  tt_take_args(argc, argv);
  if (argc > 3) g_marionette = argv[3];
  return cmocka_run_group_tests(tests, NULL, NULL);
}

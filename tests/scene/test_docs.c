/* The sample output in host/scenes/FORMAT.md is what `marionette sim`
 * prints today: a doc that shows numbers must show numbers that come out.
 * Arguments: the marionette program. host/scenes/pin-hashes.sh
 * regenerates the sample. */
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

static char *marionette;

static char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  assert_non_null(f);
  char *buf = malloc(1 << 20);
  assert_non_null(buf);
  size_t n = fread(buf, 1, (1 << 20) - 1, f);
  buf[n] = '\0';
  fclose(f);
  return buf;
}

/* The text between the sample markers, without its code fence. */
static char *sample_of(const char *doc) {
  const char *begin = strstr(doc, "<!-- sample: begin -->\n```\n");
  const char *end = strstr(doc, "```\n<!-- sample: end -->");
  assert_non_null(begin);
  assert_non_null(end);
  begin += strlen("<!-- sample: begin -->\n```\n");
  assert_true(end >= begin);
  char *out = calloc((size_t)(end - begin) + 1, 1);
  assert_non_null(out);
  memcpy(out, begin, (size_t)(end - begin));
  return out;
}

/* Drops the `wall:` line, the one number that depends on the machine. */
static void drop_wall(char *text) {
  char *w = strstr(text, "\nwall: ");
  assert_non_null(w);
  char *eol = strchr(w + 1, '\n');
  assert_non_null(eol);
  memmove(w, eol, strlen(eol) + 1);
}

static void format_md_sample_is_what_sim_prints(void **state) {
  (void)state;
  assert_int_equal(chdir(MR_SOURCE_DIR), 0);
  char *doc = slurp("host/scenes/FORMAT.md");
  char *sample = sample_of(doc);
  char *argv[] = { marionette, "sim", "host/scenes/puppet.yaml", NULL };
  tt_output p;
  assert_int_equal(tt_capture(argv, &p), 0);
  assert_int_equal(p.status, 0);
  drop_wall(sample);
  drop_wall(p.out);
  if (strcmp(sample, p.out) != 0)
    fprintf(stderr,
            "FORMAT.md shows:\n%s\nsim prints:\n%s\n(host/scenes/pin-hashes.sh "
            "regenerates the sample)\n",
            sample, p.out);
  assert_string_equal(sample, p.out);
  tt_output_free(&p);
  free(sample);
  free(doc);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s PATH-TO-marionette\n", argv[0]);
    return 2;
  }
  marionette = argv[1];
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(format_md_sample_is_what_sim_prints),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Each board folder stands on its own: a board's sources take their
 * headers from their own folder, boards/common, the core, the protocol or
 * the generated protocol code, never from another board's folder. The
 * firmware's Makefile gives each board exactly those include paths; this
 * test catches a path that steps around them ("../other_board/x.h"). */
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cmocka.h>

#define BOARDS MR_SOURCE_DIR "/firmware/boards"

/* dir/name into out, or the test fails. */
static void join(char *out, size_t len, const char *dir, const char *name) {
  int n = snprintf(out, len, "%s/%s", dir, name);
  if (n < 0 || (size_t)n >= len) fail_msg("path too long: %s/%s", dir, name);
}

static int exists(const char *dir, const char *name) {
  char path[1024];
  struct stat st;
  join(path, sizeof path, dir, name);
  return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

static int source_file(const char *name) {
  size_t n = strlen(name);
  return n > 2 && name[n - 2] == '.' && (name[n - 1] == 'c' || name[n - 1] == 'h');
}

/* Checks every quoted #include of one file; returns the problems found. */
static unsigned check_file(const char *board_dir, const char *file) {
  static const char *const shared[] = { BOARDS "/common", MR_SOURCE_DIR "/firmware/core",
                                        MR_SOURCE_DIR "/protocol/include" };
  char path[1024], line[512];
  join(path, sizeof path, board_dir, file);
  FILE *f = fopen(path, "r");
  if (f == NULL) fail_msg("cannot open %s", path);
  unsigned bad = 0, ln = 0;
  while (fgets(line, sizeof line, f)) {
    ln++;
    char name[256];
    if (sscanf(line, " # include \"%255[^\"]\"", name) != 1) continue;
    int found = strchr(name, '/') == NULL &&
                (exists(board_dir, name) || strcmp(name, "gp_messages.h") == 0);
    for (size_t i = 0; !found && strchr(name, '/') == NULL && i < 3; i++)
      found = exists(shared[i], name);
    if (!found) {
      print_error("%s:%u: \"%s\" is not in the board's folder, common, core or protocol\n", path,
                  ln, name);
      bad++;
    }
  }
  fclose(f);
  return bad;
}

static void firmware_boards_take_headers_only_from_their_own_folder_or_common(void **state) {
  (void)state;
  DIR *boards = opendir(BOARDS);
  assert_non_null(boards);
  unsigned n_boards = 0, n_files = 0, bad = 0;
  struct dirent *b;
  while ((b = readdir(boards)) != NULL) {
    if (b->d_name[0] == '.') continue;
    char dir[1024];
    join(dir, sizeof dir, BOARDS, b->d_name);
    DIR *d = opendir(dir);
    if (d == NULL) continue;
    n_boards++;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
      if (!source_file(e->d_name)) continue;
      n_files++;
      bad += check_file(dir, e->d_name);
    }
    closedir(d);
  }
  closedir(boards);
  assert_int_equal(n_boards, 3); /* blackpill_f411, common, qemu_netduinoplus2 */
  assert_true(n_files >= 10);
  assert_int_equal(bad, 0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(firmware_boards_take_headers_only_from_their_own_folder_or_common),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

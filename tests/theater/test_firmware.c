/* The firmware in the loop: the glove's own firmware image, booted in QEMU
 * (netduinoplus2) with its USART on a pty, is read by `marionette run`: the
 * theater reads its INFO and takes its samples as from a glove on a serial
 * port. (QEMU never completes an ADC conversion, so the samples hold still
 * and the frame does not move; only the reading is tested here.) The image comes from `make firmware`; the test fails, never
 * skips, when it is missing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "proc.h"

#define IMAGE  MR_FIRMWARE_OUT "/qemu_netduinoplus2/fw.elf"
#define PUPPET MR_SOURCE_DIR "/host/scenes/puppet.yaml"

static const char *marionette;

/* QEMU names the pty it made on its standard output: "char device
 * redirected to /dev/pts/N". */
static int pty_of(const char *err_path, char *out, size_t size) {
  for (int i = 0; i < 200; i++) {
    char *text = tt_read_file(err_path, NULL);
    const char *at = text ? strstr(text, "redirected to ") : NULL;
    if (at != NULL) {
      at += strlen("redirected to ");
      size_t n = strcspn(at, " \n");
      snprintf(out, size, "pty:%.*s", (int)n, at);
      free(text);
      return 0;
    }
    free(text);
    usleep(50000);
  }
  return -1;
}

static void the_firmware_image_is_read_as_a_glove_by_the_theater(void **state) {
  (void)state;
  assert_int_equal(access(IMAGE, R_OK), 0); /* run `make firmware` first */
  char *dir = tt_tmpdir();
  char out_path[300], err_path[300];
  snprintf(out_path, sizeof out_path, "%s", tt_path(dir, "qemu.out"));
  snprintf(err_path, sizeof err_path, "%s", tt_path(dir, "qemu.err"));
  /* stdbuf: QEMU's standard output is a file here, which stdio would
   * hold back until exit; stdbuf execs QEMU in the same process. */
  const char *argv[] = { "/usr/bin/stdbuf",
                         "-o0",
                         "qemu-system-arm",
                         "-M",
                         "netduinoplus2",
                         "-nographic",
                         "-monitor",
                         "none",
                         "-serial",
                         "pty",
                         "-kernel",
                         IMAGE,
                         NULL };
  pid_t qemu = tt_spawn(argv, out_path, err_path);
  assert_true(qemu > 0);
  char source[300];
  if (pty_of(out_path, source, sizeof source) != 0) {
    kill(qemu, SIGKILL);
    tt_wait(qemu, 10);
    char *said = tt_read_file(err_path, NULL);
    fail_msg("QEMU named no pty; it said: %s", said ? said : "(nothing)");
  }
  char *show[] = {
    (char *)marionette, "run", PUPPET, "--glove", source, "--time", "3", "-q", NULL
  };
  tt_output o;
  assert_int_equal(tt_capture(show, &o), 0);
  kill(qemu, SIGTERM);
  tt_wait(qemu, 10);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  printf("%s", o.out);
  assert_non_null(strstr(o.out, "glove: live\n"));
  char v[64];
  assert_int_equal(tt_field(o.out, "glove samples", v, sizeof v), 0);
  assert_true(atol(v) >= 100);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  marionette = argc > 1 ? argv[1] : "marionette";
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_firmware_image_is_read_as_a_glove_by_the_theater),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

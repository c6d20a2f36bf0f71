/* `marionette` and the programs it becomes: `sim` maps no graphics
 * library, nor the MQTT client a broker's glove needs (the dynamic loader,
 * asked through LD_DEBUG=libs, names every library a process loads, at
 * start-up or later); `render`, `run`, `list-ports` and `calibrate` still
 * reach their programs, from the build tree, after an install under any
 * PREFIX and DESTDIR, and say so in one line when one is missing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "proc.h"

static char *cmake;
static char *marionette;
static char *binary_dir;

#define STICK MR_SOURCE_DIR "/host/scenes/stick.yaml"

/* The libraries that draw, or that only a drawing library pulls in: GL and
 * its dispatch, the software rasteriser, EGL, SDL2, X11 and Wayland, DRM,
 * Assimp, and ffmpeg's codecs. A name matches when a loaded library's
 * file name starts with it. */
static const char *const graphics[] = { "libGL",      "libOSMesa", "libEGL",    "libgbm",
                                        "libglapi",   "libLLVM",   "libSDL2",   "libX11",
                                        "libwayland", "libdrm",    "libassimp", "libavcodec" };
#define N_GRAPHICS (sizeof graphics / sizeof graphics[0])

/* The libraries a glove source may need and sim does not: the MQTT
 * client and the TLS it brings. */
static const char *const network[] = { "libmosquitto", "libssl", "libcrypto" };
#define N_NETWORK (sizeof network / sizeof network[0])

/* Marks in seen[] each of the n names that a library named in ld_debug
 * (LD_DEBUG=libs output: "find library=NAME", "trying file=PATH",
 * "calling init: PATH") starts with; every word is read, so a library
 * opened later with dlopen counts as much as one linked. Returns how many
 * libraries the loader initialised in all. */
static int names_loaded(const char *ld_debug, const char *const names[], size_t n_names,
                        bool *seen) {
  for (const char *p = ld_debug; *p != '\0';) {
    size_t n = strcspn(p, " \t\n=;:");
    const char *base = p;
    for (const char *q = p; q < p + n; q++)
      if (*q == '/') base = q + 1;
    for (size_t i = 0; i < n_names; i++) {
      size_t len = strlen(names[i]);
      if (base + len <= p + n && strncmp(base, names[i], len) == 0) seen[i] = true;
    }
    p += n;
    if (*p != '\0') p++;
  }
  int inits = 0;
  for (const char *p = ld_debug; (p = strstr(p, "calling init: ")) != NULL; p++) inits++;
  return inits;
}

/* Runs argv with LD_DEBUG=libs; the loader's lines are on its stderr. */
static void capture_ld_debug(char *const argv[], tt_output *o) {
  setenv("LD_DEBUG", "libs", 1);
  int rc = tt_capture(argv, o);
  unsetenv("LD_DEBUG");
  assert_int_equal(rc, 0);
}

/* A short sim under LD_DEBUG=libs; fails naming the first of names it
 * loaded. */
static void sim_loads_none_of(const char *const names[], size_t n) {
  char *argv[] = { marionette, "sim", "--time", "0.05", "-q", STICK, NULL };
  tt_output o;
  capture_ld_debug(argv, &o);
  if (o.status != 0) fail_msg("status %d: %s", o.status, o.err);
  bool seen[N_GRAPHICS > N_NETWORK ? N_GRAPHICS : N_NETWORK] = { false };
  /* The loader did report: at least the C library and libm. */
  assert_true(names_loaded(o.err, names, n, seen) >= 2);
  for (size_t i = 0; i < n; i++)
    if (seen[i]) fail_msg("marionette sim loaded %s*:\n%s", names[i], o.err);
  tt_output_free(&o);
}

static void sim_maps_no_graphics_library(void **state) {
  (void)state;
  sim_loads_none_of(graphics, N_GRAPHICS);
}

/* Nor the MQTT client and TLS that a broker's glove needs: the glove's
 * own commands, list-ports and calibrate, live in the glove program. */
static void sim_maps_no_network_library(void **state) {
  (void)state;
  sim_loads_none_of(network, N_NETWORK);
}

/* ...which that check would see: list-ports, through marionette, reaches
 * the glove program, which loads the MQTT client. */
static void list_ports_reaches_the_glove_program_and_its_mqtt_client(void **state) {
  (void)state;
  char *argv[] = { marionette, "list-ports", "--help", NULL };
  tt_output o;
  capture_ld_debug(argv, &o);
  assert_int_equal(o.status, 0);
  assert_non_null(strstr(o.out, "usage: marionette list-ports"));
  bool seen[N_NETWORK] = { false };
  names_loaded(o.err, network, N_NETWORK, seen);
  if (!seen[0]) fail_msg("list-ports did not load libmosquitto*:\n%s", o.err);
  tt_output_free(&o);
}

/* The check above can fail: the same reading of the loader's lines finds
 * the graphics libraries when `render` starts (its --help is enough, as
 * they load before main). */
static void render_maps_the_graphics_libraries(void **state) {
  (void)state;
  char *argv[] = { marionette, "render", "--help", NULL };
  tt_output o;
  capture_ld_debug(argv, &o);
  assert_int_equal(o.status, 0);
  assert_non_null(strstr(o.out, "usage: marionette render"));
  bool seen[N_GRAPHICS] = { false };
  names_loaded(o.err, graphics, N_GRAPHICS, seen);
  const char *linked[] = { "libSDL2", "libOSMesa", "libEGL", "libassimp" };
  for (size_t k = 0; k < sizeof linked / sizeof linked[0]; k++)
    for (size_t i = 0; i < N_GRAPHICS; i++)
      if (strcmp(graphics[i], linked[k]) == 0 && !seen[i])
        fail_msg("render did not load %s*:\n%s", linked[k], o.err);
  tt_output_free(&o);
}

/* `cmake --install` of the program's component into DESTDIR=dir under
 * PREFIX /opt/mr, the way `make install PREFIX=/opt/mr DESTDIR=dir` does. */
static void install_into(const char *dir) {
  char *argv[] = { cmake,     "--install",   binary_dir,   "--prefix",
                   "/opt/mr", "--component", "marionette", NULL };
  setenv("DESTDIR", dir, 1);
  tt_output o;
  int rc = tt_capture(argv, &o);
  unsetenv("DESTDIR");
  assert_int_equal(rc, 0);
  if (o.status != 0) fail_msg("cmake --install: status %d: %s%s", o.status, o.out, o.err);
  tt_output_free(&o);
}

static void an_installed_marionette_runs_render_and_run_from_libexec(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  install_into(dir);
  char bin[1024], stage[1024];
  snprintf(bin, sizeof bin, "%s/opt/mr/bin/marionette", dir);
  snprintf(stage, sizeof stage, "%s/opt/mr/bin/marionette-stage", dir);
  /* The stage program is not a command of its own on PATH. */
  assert_int_not_equal(access(stage, F_OK), 0);
  snprintf(stage, sizeof stage, "%s/opt/mr/libexec/marionette/marionette-stage", dir);
  assert_int_equal(access(stage, X_OK), 0);
  const char *cmds[] = { "render", "run", "list-ports", "calibrate" };
  for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; i++) {
    char *argv[] = { bin, (char *)cmds[i], "--help", NULL };
    tt_output o;
    assert_int_equal(tt_capture(argv, &o), 0);
    if (o.status != 0) fail_msg("%s: status %d: %s", cmds[i], o.status, o.err);
    char want[64];
    snprintf(want, sizeof want, "usage: marionette %s", cmds[i]);
    assert_non_null(strstr(o.out, want));
    tt_output_free(&o);
  }
  tt_rmdir(dir);
  free(dir);
}

/* marionette alone, copied where no stage program is: sim works, render
 * is one line that says where the stage program was looked for, and
 * list-ports where the glove program was. */
static void without_the_stage_program_render_says_so_and_sim_still_runs(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  char *copy[] = { cmake, "-E", "copy", marionette, dir, NULL };
  tt_output o;
  assert_int_equal(tt_capture(copy, &o), 0);
  assert_int_equal(o.status, 0);
  tt_output_free(&o);
  char *alone = (char *)tt_path(dir, "marionette");
  char *render[] = { alone, "render", "--help", NULL };
  assert_int_equal(tt_capture(render, &o), 0);
  assert_int_equal(o.status, 1);
  assert_non_null(strstr(o.err, "marionette render: the stage program marionette-stage is "
                                "neither in "));
  assert_int_equal(strchr(o.err, '\n') - o.err + 1, (long)strlen(o.err));
  tt_output_free(&o);
  /* The glove program's absence is named as the glove program's. */
  char *ports[] = { alone, "list-ports", "--help", NULL };
  assert_int_equal(tt_capture(ports, &o), 0);
  assert_int_equal(o.status, 1);
  assert_non_null(strstr(o.err, "marionette list-ports: the glove program marionette-glove is "
                                "neither in "));
  tt_output_free(&o);
  char *sim[] = { alone, "sim", "--time", "0.05", "-q", STICK, NULL };
  assert_int_equal(tt_capture(sim, &o), 0);
  if (o.status != 0) fail_msg("sim: status %d: %s", o.status, o.err);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  if (argc < 4) {
    fprintf(stderr, "usage: %s CMAKE MARIONETTE BINARY_DIR\n", argv[0]);
    return 2;
  }
  cmake = argv[1];
  marionette = argv[2];
  binary_dir = argv[3];
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(sim_maps_no_graphics_library),
    cmocka_unit_test(render_maps_the_graphics_libraries),
    cmocka_unit_test(sim_maps_no_network_library),
    cmocka_unit_test(list_ports_reaches_the_glove_program_and_its_mqtt_client),
    cmocka_unit_test(an_installed_marionette_runs_render_and_run_from_libexec),
    cmocka_unit_test(without_the_stage_program_render_says_so_and_sim_still_runs),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

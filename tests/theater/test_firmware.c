/* The firmware in the loop: the glove's own firmware image, booted in QEMU
 * (netduinoplus2) with its USART on a pty, drives `marionette run`: the
 * theater reads its INFO and takes its samples as from a glove on a serial
 * port, and the control frame moves with the emulated ADC. QEMU's ADC
 * model returns a ramp (firmware/README.md, "QEMU"), which the firmware's
 * filter turns into a wave of about 35 Hz over half the ADC's range.
 *
 * The show records its take; the test decodes the take itself and, frame
 * by frame, feeds the mapping the newest sample each frame had read, as
 * the theater does. The frame's recorded poses must be those poses, and
 * they must move. The image comes from `make firmware`; the test fails,
 * never skips, when it is missing. */
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

#include <math.h>

#include "gp.h"
#include "mr_control.h"
#include "mr_io.h"
#include "mr_scene.h"
#include "proc.h"

#define IMAGE  MR_FIRMWARE_OUT "/qemu_netduinoplus2/fw.elf"
#define PUPPET MR_SOURCE_DIR "/host/scenes/puppet.yaml"

static const char *marionette;

/* puppet.yaml, its control frame let follow the QEMU ADC's 35 Hz wave:
 * far past what a hand does, so the glove's acceleration limits
 * (control.max_accel, max_turn_accel) would hold the frame back from the
 * samples this test checks it takes. Written into dir; its path. */
static const char *unlimited_puppet(const char *dir) {
  static char path[300];
  snprintf(path, sizeof path, "%s", tt_path(dir, "puppet.yaml"));
  char *text = tt_read_file(PUPPET, NULL);
  assert_non_null(text);
  const char *at = strstr(text, "\n  control:\n");
  assert_non_null(at);
  at += strlen("\n  control:\n");
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fprintf(f, "%.*s    max_accel: 1e9\n    max_turn_accel: 1e10\n%s", (int)(at - text), text, at);
  assert_int_equal(fclose(f), 0);
  free(text);
  return path;
}

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

enum { MAX_SAMPLES = 4000 };

typedef struct take_samples {
  double t[MAX_SAMPLES]; /* the show time of the chunk that carried it */
  double v[MAX_SAMPLES][5];
  size_t n;
} take_samples;

/* Every SAMPLE in the take, with its chunk's time, calibrated as the host
 * calibrates a glove without a saved range: by the ADC's full scale. */
static void read_take(const char *path, take_samples *out) {
  mr_rec_reader r;
  mr_io_error err;
  assert_int_equal(mr_rec_reader_open(&r, path, &err), 0);
  gp_decoder dec;
  gp_decoder_init(&dec, GP_SPEC_HASH);
  out->n = 0;
  uint64_t t_ns;
  const uint8_t *data;
  size_t len;
  while (mr_rec_reader_next(&r, &t_ns, &data, &len, &err) == 1) {
    while (len > 0) {
      gp_msg m;
      gp_event ev;
      size_t used = gp_decoder_feed(&dec, data, len, &m, &ev);
      data += used;
      len -= used;
      if (ev != GP_EV_FRAME || m.type != GP_SAMPLE || out->n == MAX_SAMPLES) continue;
      out->t[out->n] = (double)t_ns * 1e-9;
      for (int c = 0; c < 5; c++) out->v[out->n][c] = m.u.sample.ch[c] / 4095.0;
      out->n++;
    }
  }
  mr_rec_reader_close(&r);
}

/* The frame's turn about z (the thumb's axis in the default mapping), deg. */
static double turn_z_deg(const mr_pose *p) {
  const double *q = p->orientation;
  return atan2(2 * (q[0] * q[3] + q[1] * q[2]), 1 - 2 * (q[2] * q[2] + q[3] * q[3])) * 180 /
         3.14159265358979323846;
}

/* Each frame of the poses file against the mapping fed, at that frame's
 * time, the newest sample read by then; the share of frames within 0.01
 * degree of it into *share, the largest difference in degrees into *worst,
 * the spread of the thumb's turn into *spread. */
static void compare(const char *scene, const char *poses_path, const take_samples *ts,
                    double *share, double *worst, double *spread) {
  mr_scene s;
  mr_scene_error serr;
  assert_int_equal(mr_scene_load(scene, &s, &serr), MR_SCENE_OK);
  mr_mapping_def def = mr_default_mapping_def();
  def.neutral = s.frames[0].pose;
  mr_control *c = NULL;
  assert_int_equal(mr_control_create(&def, 1, &c, NULL, 0), MR_CONTROL_OK);
  char *text = tt_read_file(poses_path, NULL);
  assert_non_null(text);
  mr_pose want = s.frames[0].pose;
  size_t next = 0, frames = 0, close = 0;
  double lo = INFINITY, hi = -INFINITY;
  *worst = 0;
  for (char *line = strtok(text, "\n"); line != NULL; line = strtok(NULL, "\n")) {
    double v[8];
    assert_int_equal(sscanf(line, "%lf %lf %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3],
                            &v[4], &v[5], &v[6], &v[7]),
                     8);
    bool fresh = false;
    /* The file has the frame time to the microsecond. */
    while (next < ts->n && ts->t[next] <= v[0] + 5e-6) next++, fresh = true;
    if (fresh) assert_int_equal(mr_control_update(c, ts->v[next - 1], v[0], &want, NULL), 0);
    mr_pose got;
    memcpy(got.position, v + 1, sizeof got.position);
    memcpy(got.orientation, v + 4, sizeof got.orientation);
    /* The angle from the chord, not acos of the dot product, which the
     * file's seven decimals would blur near zero. */
    double dot = 0, chord = 0;
    for (int i = 0; i < 4; i++) dot += got.orientation[i] * want.orientation[i];
    for (int i = 0; i < 4; i++) {
      double e = got.orientation[i] - (dot < 0 ? -1 : 1) * want.orientation[i];
      chord += e * e;
    }
    double deg = 4 * asin(fmin(1.0, sqrt(chord) / 2)) * 180 / 3.14159265358979323846;
    *worst = fmax(*worst, deg);
    close += deg < 0.01;
    lo = fmin(lo, turn_z_deg(&got));
    hi = fmax(hi, turn_z_deg(&got));
    frames++;
  }
  assert_true(frames >= 150);
  *spread = hi - lo;
  *share = (double)close / (double)frames;
  free(text);
  mr_control_destroy(c);
  mr_scene_free(&s);
}

static void the_firmware_image_drives_the_frame_with_its_adc(void **state) {
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
  char take[300], poses[300];
  snprintf(take, sizeof take, "%s", tt_path(dir, "take.mrec"));
  snprintf(poses, sizeof poses, "%s", tt_path(dir, "poses"));
  const char *scene = unlimited_puppet(dir);
  char *show[] = { (char *)marionette, "run", (char *)scene, "--glove", source, "--time", "3", "-q",
                   "--record",         take,  "--poses",     poses,     NULL };
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
  static take_samples ts;
  read_take(take, &ts);
  assert_int_equal((long)ts.n, atol(v));
  double share = 0, worst = 0, spread = 0;
  compare(scene, poses, &ts, &share, &worst, &spread);
  printf("the frame's thumb turn spans %.1f deg; %.1f %% of the frames are within 0.01 deg of the "
         "mapped samples (at most %.2g deg off)\n",
         spread, 100 * share, worst);
  assert_true(spread > 1.0); /* 5 to 11 degrees, as the wave and the frames fall */
  /* All of them on a quiet machine; under a loaded test run the odd frame
   * the limiter or a late read shifts. */
  assert_true(share >= 0.9);
  tt_output_free(&o);
  tt_rmdir(dir);
  free(dir);
}

int main(int argc, char **argv) {
  marionette = argc > 1 ? argv[1] : "marionette";
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(the_firmware_image_drives_the_frame_with_its_adc),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Pictures of the stage against committed goldens (issue 10, acceptance).
 * Each display-mode scene (host/scenes/modes, §3.3) and each example
 * scene, at one fixed frame, drawn at 320 x 180 by the real `marionette
 * render --frame T` through OSMesa and, where the machine has it, EGL,
 * agrees with its PNG in tests/golden/ at the tolerance of
 * tests/render/golden.h (each channel within 5/255 on 99.9 % of pixels).
 * The compare is not blind: copies of a scene with one material colour,
 * one model or the frame's time changed fail it, while an unchanged copy
 * passes; the same input gives the same frame, byte for byte. And the
 * input moves the picture: two control poses give frames that differ, and
 * only where the puppet and its shadow are.
 *
 * MR_UPDATE_GOLDEN=1 rewrites the goldens from the OSMesa frames (then
 * look at each before committing it). Argument: the marionette program. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <stb_image.h>

#include "golden.h"
#include "pictures.h"
#include "proc.h"

enum { W = 320, H = 180 };

static char *marionette;
static char *scratch; /* frames and scene copies, removed at the end */

static const char *scene_path(const char *rel) {
  static char path[1024];
  snprintf(path, sizeof path, "%s/host/scenes/%s", MR_SOURCE_DIR, rel);
  return path;
}

static const char *golden_path(const char *name) {
  static char path[1024];
  snprintf(path, sizeof path, "%s/tests/golden/%s.png", MR_SOURCE_DIR, name);
  return path;
}

/* A W x H PNG as RGB (free it). */
static uint8_t *load_png(const char *path) {
  int w = 0, h = 0, n = 0;
  uint8_t *rgb = stbi_load(path, &w, &h, &n, 3);
  if (rgb == NULL) fail_msg("%s: cannot read (%s)", path, stbi_failure_reason());
  if (w != W || h != H) {
    stbi_image_free(rgb);
    fail_msg("%s: %dx%d, expected %dx%d", path, w, h, W, H);
  }
  return rgb;
}

/* The frame of scene (a path) at time t drawn by `marionette render`
 * through backend, as RGB (free it); tag names its PNG in the scratch
 * folder. NULL only when backend is egl and the machine has no EGL. */
static uint8_t *draw(const char *scene, const char *t, const char *backend, const char *tag) {
  char name[128];
  snprintf(name, sizeof name, "%s-%s.png", tag, backend);
  char out[1024];
  snprintf(out, sizeof out, "%s", tt_path(scratch, name));
  char size[32];
  snprintf(size, sizeof size, "%dx%d", W, H);
  char *argv[] = { marionette, "render", (char *)scene, "--frame",       (char *)t,
                   "--size",   size,     "--backend",   (char *)backend, "-q",
                   "-o",       out,      NULL };
  tt_output run;
  assert_int_equal(tt_capture(argv, &run), 0);
  if (run.status != 0) {
    int no_egl = strcmp(backend, "egl") == 0 && strstr(run.err, "EGL: ") != NULL;
    fprintf(stderr, "%s (%s, t %s): exit %d: %s", scene, backend, t, run.status, run.err);
    tt_output_free(&run);
    if (no_egl) return NULL;
    fail_msg("marionette render failed on %s", scene);
  }
  tt_output_free(&run);
  return load_png(out);
}

/* FNV-1a of a frame: what "the same frame" means below. */
static uint64_t frame_hash(const uint8_t *rgb) {
  uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < (size_t)W * H * 3; i++) h = (h ^ rgb[i]) * 1099511628211ull;
  return h;
}

static double agreement(const uint8_t *a, const uint8_t *b) {
  return mr_frames_agreement(a, b, W, H, MR_GOLDEN_TOLERANCE, NULL);
}

static double agreement_with_golden(const char *name, const uint8_t *rgb) {
  uint8_t *g = load_png(golden_path(name));
  double a = agreement(rgb, g);
  stbi_image_free(g);
  return a;
}

/* Each picture through OSMesa against its golden (which MR_UPDATE_GOLDEN
 * rewrites), then through EGL against the same golden: one picture, two
 * backends. Every picture is tried before the test fails, each failure
 * named. */
static void check_pictures(const picture *list, size_t n) {
  int failed = 0;
  for (size_t i = 0; i < n; i++) {
    const picture *p = &list[i];
    char msg[1024] = "";
    uint8_t *rgb = draw(scene_path(p->scene), p->frame, "osmesa", p->name);
    if (mr_golden_compare(golden_path(p->name), rgb, W, H, msg, sizeof msg) != 0) {
      fprintf(stderr, "%s (osmesa, t %s): %s\n", p->name, p->frame, msg);
      failed++;
    }
    stbi_image_free(rgb);
    if ((rgb = draw(scene_path(p->scene), p->frame, "egl", p->name)) == NULL) {
      fprintf(stderr, "%s: no EGL on this machine, only OSMesa checked\n", p->name);
      continue;
    }
    double a = agreement_with_golden(p->name, rgb);
    if (a < MR_GOLDEN_FRACTION) {
      char actual[256];
      snprintf(actual, sizeof actual, "%s/tests/pictures/%s.egl.png", MR_BINARY_DIR, p->name);
      mr_png_write(actual, rgb, W, H);
      fprintf(stderr, "%s (egl, t %s): only %.4f %% of pixels agree with %s; the frame is in %s\n",
              p->name, p->frame, 100 * a, golden_path(p->name), actual);
      failed++;
    }
    stbi_image_free(rgb);
  }
  if (failed) fail_msg("%d of %zu pictures differ from their goldens", failed, 2 * n);
}

/* The mode scenes are checked like the examples: their scripted tracks
 * stay finite, never reset and keep within their expect: bounds. */
static void mode_scenes_run_their_tracks_within_their_bounds(void **state) {
  (void)state;
  for (size_t i = 0; i < N_OF(modes); i++) {
    char *argv[] = { marionette, "sim", "--check", (char *)scene_path(modes[i].scene), NULL };
    tt_output run;
    assert_int_equal(tt_capture(argv, &run), 0);
    if (run.status != 0) fprintf(stderr, "%s: %s%s", modes[i].scene, run.out, run.err);
    assert_int_equal(run.status, 0);
    assert_non_null(strstr(run.out, "check: passed"));
    assert_non_null(strstr(run.out, "\nresets: 0\n"));
    tt_output_free(&run);
  }
}

static void each_display_mode_matches_its_golden(void **state) {
  (void)state;
  check_pictures(modes, N_OF(modes));
}

static void each_example_scene_matches_its_golden(void **state) {
  (void)state;
  check_pictures(examples, N_OF(examples));
}

/* The same scene, time and size give the same frame: the same bytes, so
 * the same hash, run after run, through each backend. */
static void same_frame_twice(const char *backend) {
  const char *scene = scene_path(modes[3].scene);
  char tag[64];
  snprintf(tag, sizeof tag, "same_a");
  uint8_t *a = draw(scene, "3", backend, tag);
  if (a == NULL) return; /* no EGL here */
  snprintf(tag, sizeof tag, "same_b");
  uint8_t *b = draw(scene, "3", backend, tag);
  assert_non_null(b);
  printf("%s: frame hash %016llx and %016llx\n", backend, (unsigned long long)frame_hash(a),
         (unsigned long long)frame_hash(b));
  assert_true(frame_hash(a) == frame_hash(b));
  assert_memory_equal(a, b, (size_t)W * H * 3);
  stbi_image_free(a);
  stbi_image_free(b);
}

static void the_same_input_gives_the_same_frame(void **state) {
  (void)state;
  same_frame_twice("osmesa");
  same_frame_twice("egl");
}

/* text with the span [at, at + len) replaced by to, written to the
 * scratch folder as name; its path (static, until the next call). */
static const char *write_spliced(const char *text, const char *at, size_t len, const char *to,
                                 const char *name) {
  size_t head = (size_t)(at - text), n = strlen(text) - len + strlen(to);
  char *out = malloc(n + 1);
  assert_non_null(out);
  memcpy(out, text, head);
  memcpy(out + head, to, strlen(to));
  strcpy(out + head + strlen(to), at + len);
  static char path[1024];
  snprintf(path, sizeof path, "%s", tt_path(scratch, name));
  FILE *f = fopen(path, "wb");
  assert_non_null(f);
  assert_int_equal(fwrite(out, 1, n, f), n);
  assert_int_equal(fclose(f), 0);
  free(out);
  return path;
}

/* text with its one `from` replaced by to, written as name; its path. */
static const char *write_changed(const char *text, const char *from, const char *to,
                                 const char *name) {
  const char *at = strstr(text, from);
  if (at == NULL || strstr(at + 1, from) != NULL) fail_msg("'%s' is not in the scene once", from);
  return write_spliced(text, at, strlen(from), to, name);
}

/* How well a copy of the particle scene, with from replaced by to and
 * drawn at time t, agrees with the scene's golden. */
static double changed_agreement(const char *from, const char *to, const char *t, const char *tag) {
  char *text = tt_read_file(scene_path(modes[0].scene), NULL);
  assert_non_null(text);
  char name[64];
  snprintf(name, sizeof name, "%s.yaml", tag);
  const char *copy = write_changed(text, from, to, name);
  free(text);
  uint8_t *rgb = draw(copy, t, "osmesa", tag);
  double a = agreement_with_golden(modes[0].name, rgb);
  printf("%-10s %.4f %% of pixels agree with the golden\n", tag, 100 * a);
  stbi_image_free(rgb);
  return a;
}

/* The golden of the particle scene, against copies of the scene: the copy
 * as it is passes (so a copy elsewhere draws the same), while one bead's
 * colour, one bead's shape, or the pose at another time fails. */
static void a_changed_material_model_or_pose_fails_the_golden(void **state) {
  (void)state;
  const char *t = modes[0].frame;
  assert_true(changed_agreement("name: particle display mode", "name: particle display mode", t,
                                "unchanged") >= MR_GOLDEN_FRACTION);
  assert_true(changed_agreement("color: [0.30, 0.75, 0.30]", "color: [0.75, 0.20, 0.75]", t,
                                "material") < MR_GOLDEN_FRACTION);
  assert_true(changed_agreement("{name: bead4, shape: sphere,", "{name: bead4, shape: cone,", t,
                                "model") < MR_GOLDEN_FRACTION);
  assert_true(changed_agreement("name: particle display mode", "name: particle display mode", "3.5",
                                "pose") < MR_GOLDEN_FRACTION);
}

/* The particle scene's track, replaced by one that holds the bar still
 * (pose A) or one that carries it aside and tilts it (pose B). */
static const char *const track_from =
    "        - {t: 2.0, position: [ 0.10, 1.22, 0], rotation: [0, 0, 20]}\n"
    "        - {t: 3.0, position: [-0.10, 1.22, 0], rotation: [0, 20, -20]}\n"
    "        - {t: 4.5, position: [ 0.00, 1.20, 0], rotation: [0, 0, 0]}\n";
static const char *const track_a = "        - {t: 2.0, position: [ 0.00, 1.20, 0]}\n";
static const char *const track_b =
    "        - {t: 2.0, position: [ 0.15, 1.26, 0], rotation: [0, 0, 20]}\n";

/* Where a frame differs from the empty stage's: the puppet's region. */
static void mark(const uint8_t *f, const uint8_t *empty, uint8_t *region) {
  for (size_t i = 0; i < (size_t)W * H; i++)
    for (int c = 0; c < 3; c++)
      if (abs((int)f[3 * i + (size_t)c] - (int)empty[3 * i + (size_t)c]) > MR_GOLDEN_TOLERANCE)
        region[i] = 1;
}

/* The region grown by 2 pixels: in software the frame's edges are
 * smoothed by a pass that reads up to 2 pixels away along an edge, so a
 * string or a shadow's edge moves the pixels beside it a little (less
 * than the tolerance in each frame, yet the two frames can move them
 * opposite ways). */
static void grow(uint8_t *region) {
  uint8_t *was = malloc((size_t)W * H);
  assert_non_null(was);
  memcpy(was, region, (size_t)W * H);
  for (int y = 0; y < H; y++)
    for (int x = 0; x < W; x++)
      for (int dy = -2; dy <= 2; dy++)
        for (int dx = -2; dx <= 2; dx++) {
          int u = x + dx, v = y + dy;
          if (u >= 0 && v >= 0 && u < W && v < H && was[(size_t)v * W + (size_t)u])
            region[(size_t)y * W + (size_t)x] = 1;
        }
  free(was);
}

/* Two control poses (two tracks of the bar, drawn at the same time) give
 * frames that differ on many pixels, and every pixel where they differ is
 * in the puppet's region: where either frame differs from the same stage
 * with no puppet drawn (its models shrunk to a speck, its strings
 * hidden), shadows included, and 2 pixels about it (grow). */
static void two_control_poses_differ_in_the_puppets_region(void **state) {
  (void)state;
  char *text = tt_read_file(scene_path(modes[0].scene), NULL);
  assert_non_null(text);
  uint8_t *a = draw(write_changed(text, track_from, track_a, "pose_a.yaml"), "3", "osmesa", "a");
  uint8_t *b = draw(write_changed(text, track_from, track_b, "pose_b.yaml"), "3", "osmesa", "b");
  /* The empty stage: the models section down to one speck, the strings
   * hidden (stage: follows models: in the file). */
  const char *models = strstr(text, "\nmodels:\n"), *stage = strstr(text, "\nstage:\n");
  assert_true(models != NULL && stage != NULL && models < stage);
  const char *speck = "\nmodels:\n  - {name: speck, shape: sphere, scale: 0.0001, particle: b0}\n"
                      "\nstage:\n  strings: {show: false}\n";
  const char *empty_path = write_spliced(
      text, models, (size_t)(stage - models) + strlen("\nstage:\n"), speck, "empty.yaml");
  uint8_t *empty = draw(empty_path, "3", "osmesa", "empty");
  uint8_t *region = calloc((size_t)W * H, 1);
  assert_non_null(region);
  mark(a, empty, region);
  mark(b, empty, region);
  grow(region);
  size_t inside = 0, outside = 0, puppet = 0;
  for (size_t i = 0; i < (size_t)W * H; i++) {
    int far = 0;
    for (int c = 0; c < 3; c++)
      far |= abs((int)a[3 * i + (size_t)c] - (int)b[3 * i + (size_t)c]) > MR_GOLDEN_TOLERANCE;
    puppet += region[i];
    inside += far && region[i];
    outside += far && !region[i];
  }
  printf("puppet region %zu px; the poses differ on %zu px in it, %zu outside\n", puppet, inside,
         outside);
  assert_true(inside >= 300);
  assert_true(outside == 0);
  free(region);
  free(text);
  stbi_image_free(a);
  stbi_image_free(b);
  stbi_image_free(empty);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s MARIONETTE\n", argv[0]);
    return 2;
  }
  marionette = argv[1];
  scratch = tt_tmpdir();
  if (scratch == NULL) return 1;
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(mode_scenes_run_their_tracks_within_their_bounds),
    cmocka_unit_test(each_display_mode_matches_its_golden),
    cmocka_unit_test(each_example_scene_matches_its_golden),
    cmocka_unit_test(the_same_input_gives_the_same_frame),
    cmocka_unit_test(a_changed_material_model_or_pose_fails_the_golden),
    cmocka_unit_test(two_control_poses_differ_in_the_puppets_region),
  };
  int rc = cmocka_run_group_tests(tests, NULL, NULL);
  tt_rmdir(scratch);
  free(scratch);
  return rc;
}

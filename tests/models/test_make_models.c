/* The example puppets' meshes: tools/models/make_models.py makes the
 * committed files byte for byte, and each loads through the model loader
 * at the size the script documents. argv[1]: the Python interpreter. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "model.h"
#include "mr_pose.h"
#include "proc.h"

static const char *g_python;

#define MODELS_DIR MR_SOURCE_DIR "/host/scenes/models"

/* Each mesh with its bounds as the script's header gives them (metres). */
typedef struct mesh_case {
  const char *name;
  float lo[3], hi[3];
} mesh_case;

static const mesh_case meshes[] = {
  { "stick_head", { -0.1f, -0.11f, -0.1f }, { 0.1f, 0.11f, 0.1015f } },
  { "stick_torso", { -0.0295f, -0.2f, -0.0295f }, { 0.0295f, 0.2f, 0.0295f } },
  { "humanoid_head", { -0.0864f, -0.095f, -0.0955f }, { 0.0864f, 0.1006f, 0.101f } },
  { "humanoid_torso", { -0.17f, -0.26f, -0.1054f }, { 0.17f, 0.3f, 0.1054f } },
  { "dragon_head", { -0.1f, -0.09f, -0.12f }, { 0.1f, 0.1812f, 0.26f } },
  { "dragon_wing", { 0, -0.001f, -0.3194f }, { 0.45f, 0.06f, 0.12f } },
  { "bird_body", { -0.07f, -0.05f, -0.2002f }, { 0.07f, 0.085f, 0.2f } },
  { "bird_wing", { 0, -0.001f, -0.07f }, { 0.25f, 0.02f, 0.05f } },
  { "ghost", { -0.22f, -0.52f, -0.0009f }, { 0.22f, 0, 0.05f } },
};
enum { N_MESHES = sizeof meshes / sizeof meshes[0] };

static void assert_same_file(const char *a, const char *b) {
  size_t na, nb;
  char *ta = tt_read_file(a, &na), *tb = tt_read_file(b, &nb);
  assert_non_null(ta);
  assert_non_null(tb);
  if (na != nb || memcmp(ta, tb, na) != 0) fail_msg("%s differs from %s", a, b);
  assert_true(na < 200 * 1024); /* small enough to keep in the repository */
  free(ta);
  free(tb);
}

static void test_the_script_makes_the_committed_meshes_byte_for_byte(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  assert_non_null(dir);
  const char *argv[] = { g_python, MR_SOURCE_DIR "/tools/models/make_models.py", dir, NULL };
  assert_int_equal(tt_run(argv, NULL, NULL, 60), 0);
  for (size_t i = 0; i < N_MESHES; i++) {
    char name[128], committed[1024];
    for (int k = 0; k < 2; k++) {
      snprintf(name, sizeof name, "%s.%s", meshes[i].name, k ? "mtl" : "obj");
      snprintf(committed, sizeof committed, "%s/%s", MODELS_DIR, name);
      assert_same_file(tt_path(dir, name), committed);
    }
  }
  tt_rmdir(dir);
  free(dir);
}

static void test_each_mesh_loads_at_its_documented_size(void **state) {
  (void)state;
  for (size_t i = 0; i < N_MESHES; i++) {
    mr_model_def d;
    memset(&d, 0, sizeof d);
    d.shape = MR_SHAPE_FILE;
    snprintf(d.path, sizeof d.path, "%s/%s.obj", MODELS_DIR, meshes[i].name);
    d.scale[0] = d.scale[1] = d.scale[2] = 1;
    d.place = mr_pose_identity();
    mr_model m;
    char msg[256] = "";
    if (mr_model_load(&d, &m, msg, sizeof msg) != 0) fail_msg("%s: %s", d.path, msg);
    size_t triangles = 0;
    for (size_t k = 0; k < m.n_meshes; k++) {
      triangles += m.meshes[k].n_indices / 3;
      assert_true(m.meshes[k].material.base_color[3] == 1.0f);
    }
    assert_true(triangles >= 200);
    for (int a = 0; a < 3; a++) {
      assert_float_equal(m.bounds_min[a], meshes[i].lo[a], 2e-4);
      assert_float_equal(m.bounds_max[a], meshes[i].hi[a], 2e-4);
    }
    mr_model_free(&m);
  }
}

int main(int argc, char **argv) {
  g_python = argc > 1 ? argv[1] : "python3";
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_the_script_makes_the_committed_meshes_byte_for_byte),
    cmocka_unit_test(test_each_mesh_loads_at_its_documented_size),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* marionette export (issue 23, items 4 and 5): a take recorded on a scene
 * of every display mode is exported as glTF, re-imported through Assimp
 * and compared, pose by pose, with the draw lists the show itself gives;
 * the glTF's JSON is read with cJSON; the PC2 point cache and the CSV are
 * read back; and each bad input gives one clear line.
 *
 * argv[1]: marionette; argv[2]: glove-gen. */
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <setjmp.h>
#include <cmocka.h>

#include "mr_scene.h"
#include "mr_show.h"
#include "mr_stage.h"
#include "proc.h"

static const char *g_marionette, *g_glove_gen;
static char *g_dir;
static char g_scene[600], g_take[600], g_glb[600], g_pc2[600], g_csv[600];

/* The show as the test sees it: every frame's time and positions. */
static double *g_t, *g_xyz;
static size_t g_frames, g_cap, g_points, g_particles;
/* What the export of the take with every output printed. */
static char *g_summary;

/* Every display mode on one chain (host/scenes/modes/freeform.yaml's,
 * bound to a glove): a bead (particle), a cone on a constraint and a
 * thread on a string (link), the bar (rigid) and the sausage (freeform). */
static const char *const k_scene =
    "format: 1\n"
    "name: every mode\n"
    "sim: {duration: 2}\n"
    "physics:\n"
    "  effects: [gravity, drag, constraints, strings, control, floor]\n"
    "  drag: 0.3\n"
    "  ats: {dt_initial: 0.02, dt_min: 0.01, dt_max: 0.05, threshold_min: 0.0001, "
    "threshold_max: 0.01}\n"
    "  particles:\n"
    "    - {name: k0, position: [-0.30, %s, 0.00], mass: 0.04}\n"
    "    - {name: k1, position: [-0.20, 0.80, 0.00], mass: 0.05}\n"
    "    - {name: k2, position: [-0.10, 0.80, 0.00], mass: 0.05}\n"
    "    - {name: k3, position: [ 0.00, 0.80, 0.00], mass: 0.05}\n"
    "    - {name: k4, position: [ 0.10, 0.80, 0.00], mass: 0.05}\n"
    "  constraints:\n"
    "    - {between: [k0, k1]}\n"
    "    - {between: [k1, k2]}\n"
    "    - {between: [k2, k3]}\n"
    "    - {between: [k3, k4]}\n"
    "  control:\n"
    "    pose: {position: [0, 1.2, 0]}\n"
    "    points:\n"
    "      - {name: bar_l, offset: [-0.22, 0, 0]}\n"
    "      - {name: bar_r, offset: [ 0.22, 0, 0]}\n"
    "      - {name: bar_f, offset: [ 0.00, 0, 0.05]}\n"
    "  strings:\n"
    "    - {from: bar_l, to: k0, stiffness: 120, damping: 1.5}\n"
    "    - {from: bar_r, to: k4, stiffness: 120, damping: 1.5}\n"
    "  floor: {height: 0.0}\n"
    "models:\n"
    "  - {name: sausage, shape: sphere, scale: [0.12, 0.48, 0.12], rotation: [0, 0, 90],\n"
    "     position: [-0.1, 0.80, 0], display: freeform, bones: [k0, k1, k2, k3, k4],\n"
    "     influences: 3, material: {color: [0.35, 0.70, 0.35]}}\n"
    "  - {name: bead, shape: sphere, scale: [0.05, 0.05, 0.05], particle: k3}\n"
    "  - {name: cone, shape: cone, scale: [0.04, 1, 0.04], display: link, between: [k1, k2]}\n"
    "  - {name: thread, shape: cylinder, scale: [0.01, 1, 0.01], display: link,\n"
    "     between: [bar_l, k0]}\n"
    "  - {name: bar, shape: box, scale: [0.48, 0.025, 0.025], display: rigid,\n"
    "     particles: [bar_l, bar_r, bar_f], orientation: initial, position: [0, 1.2, 0]}\n"
    "%s"
    "stage: {frames: {show: false}}\n";

enum { N_MODELS = 5, N_BONES = 5, N_POSED = 4 };
static const char *const k_posed[N_POSED] = { "bead", "cone", "thread", "bar" };
static const char *const k_links[2] = { "cone", "thread" };

static void write_scene(const char *path, const char *k0_y, const char *extra) {
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fprintf(f, k_scene, k0_y, extra);
  fclose(f);
}

static void keep_frame(void *user, const mr_show_frame *f) {
  (void)user;
  g_points = (size_t)f->n_particles;
  if (g_frames == g_cap) {
    g_cap = g_cap ? 2 * g_cap : 256;
    g_t = realloc(g_t, g_cap * sizeof *g_t);
    g_xyz = realloc(g_xyz, g_cap * g_points * 3 * sizeof *g_xyz);
  }
  g_t[g_frames] = f->t;
  memcpy(&g_xyz[g_frames * g_points * 3], f->xyz, g_points * 3 * sizeof(double));
  g_frames++;
}

/* The show on the scene with glove source `source` at 30 fps, recording
 * into record (NULL: none) and keeping every frame when keep. */
static void play(const char *source, const char *record, int keep) {
  mr_scene scene;
  mr_scene_error se;
  if (mr_scene_load(g_scene, &scene, &se) != MR_SCENE_OK) fail_msg("%s", se.text);
  g_particles = scene.n_particles;
  mr_show_def d = mr_default_show_def();
  d.gloves[0] = source;
  d.n_gloves = 1;
  d.record[0] = record;
  d.fps = 30;
  mr_virtual_clock vc = { 0.0 };
  mr_clock clock = mr_clock_virtual(&vc);
  mr_show_hooks h = { NULL, NULL, keep ? keep_frame : NULL, NULL, NULL };
  mr_show_result r;
  mr_show_error err;
  mr_show_status st = mr_show_run(&scene, &d, &clock, &h, &r, &err);
  mr_show_result_free(&r);
  mr_scene_free(&scene);
  if (st != MR_SHOW_OK) fail_msg("%s", err.text);
}

static int run_export(const char *take, const char *scene, const char *out, tt_output *o) {
  char *argv[] = { (char *)g_marionette, "export", (char *)take, "--scene", (char *)scene, "-o",
                   (char *)out,          "--fps",  "30",         "-q",      NULL };
  if (tt_capture(argv, o) != 0) fail_msg("cannot start %s", g_marionette);
  return o->status;
}

static int setup(void **state) {
  (void)state;
  g_dir = tt_tmpdir();
  snprintf(g_scene, sizeof g_scene, "%s", tt_path(g_dir, "every.yaml"));
  snprintf(g_take, sizeof g_take, "%s", tt_path(g_dir, "take.mrec"));
  snprintf(g_glb, sizeof g_glb, "%s", tt_path(g_dir, "show.glb"));
  snprintf(g_pc2, sizeof g_pc2, "%s", tt_path(g_dir, "show.pc2"));
  snprintf(g_csv, sizeof g_csv, "%s", tt_path(g_dir, "show.csv"));
  write_scene(g_scene, "0.80", "");
  /* A glove's stream for 2 s, then the take a show records from it. */
  char raw[600], source[700];
  snprintf(raw, sizeof raw, "%s", tt_path(g_dir, "raw.mrec"));
  const char *gen[] = { g_glove_gen, "--fast",         "-q",       "-d", "2",
                        "-o",        "file:/dev/null", "--record", raw,  NULL };
  if (tt_run(gen, NULL, NULL, 60) != 0) fail_msg("glove-gen failed");
  snprintf(source, sizeof source, "file:%s", raw);
  play(source, g_take, 0);
  snprintf(source, sizeof source, "file:%s", g_take);
  play(source, NULL, 1);
  char *argv[] = { (char *)g_marionette,
                   "export",
                   g_take,
                   "--scene",
                   g_scene,
                   "-o",
                   g_glb,
                   "--points",
                   g_pc2,
                   "--csv",
                   g_csv,
                   "--fps",
                   "30",
                   "-q",
                   NULL };
  tt_output o;
  if (tt_capture(argv, &o) != 0 || o.status != 0) fail_msg("export failed: %s", o.err);
  g_summary = strdup(o.out);
  tt_output_free(&o);
  return 0;
}

static int teardown(void **state) {
  (void)state;
  tt_rmdir(g_dir);
  free(g_dir);
  free(g_t);
  free(g_xyz);
  free(g_summary);
  return 0;
}

static const struct aiNode *find_node(const struct aiNode *n, const char *name) {
  if (strcmp(n->mName.data, name) == 0) return n;
  for (unsigned i = 0; i < n->mNumChildren; i++) {
    const struct aiNode *f = find_node(n->mChildren[i], name);
    if (f != NULL) return f;
  }
  return NULL;
}

static const struct aiNodeAnim *find_channel(const struct aiAnimation *a, const char *name) {
  for (unsigned i = 0; i < a->mNumChannels; i++)
    if (strcmp(a->mChannels[i]->mNodeName.data, name) == 0) return a->mChannels[i];
  return NULL;
}

static const struct aiScene *import(void) {
  const struct aiScene *sc = aiImportFile(g_glb, aiProcess_ValidateDataStructure);
  if (sc == NULL) fail_msg("Assimp: %s", aiGetErrorString());
  return sc;
}

static void bone_name(char *out, size_t size, int b) {
  snprintf(out, size, "sausage/k%d", b);
}

/* Re-imported, the file has a node per model and per bone, a channel per
 * moving node, and a key per frame on each. */
static void
an_exported_take_reimports_with_a_node_per_model_and_bone_and_a_key_per_frame(void **state) {
  (void)state;
  const struct aiScene *sc = import();
  static const char *const models[N_MODELS] = { "sausage", "bead", "cone", "thread", "bar" };
  for (int i = 0; i < N_MODELS; i++)
    if (find_node(sc->mRootNode, models[i]) == NULL) fail_msg("no node '%s'", models[i]);
  for (int b = 0; b < N_BONES; b++) {
    char name[64];
    bone_name(name, sizeof name, b);
    if (find_node(sc->mRootNode, name) == NULL) fail_msg("no joint node '%s'", name);
  }
  assert_int_equal(sc->mNumAnimations, 1);
  const struct aiAnimation *a = sc->mAnimations[0];
  assert_int_equal(a->mNumChannels, N_POSED + N_BONES);
  for (unsigned i = 0; i < a->mNumChannels; i++) {
    assert_int_equal(a->mChannels[i]->mNumPositionKeys, g_frames);
    assert_int_equal(a->mChannels[i]->mNumRotationKeys, g_frames);
  }
  for (int i = 0; i < N_POSED; i++)
    if (find_channel(a, k_posed[i]) == NULL) fail_msg("no channel of '%s'", k_posed[i]);
  for (int i = 0; i < 2; i++)
    assert_int_equal(find_channel(a, k_links[i])->mNumScalingKeys, g_frames);
  unsigned skinned = 0;
  for (unsigned m = 0; m < sc->mNumMeshes; m++)
    if (sc->mMeshes[m]->mNumBones == N_BONES) skinned++;
  assert_int_equal(skinned, 1);
  aiReleaseImport(sc);
}

static double rotation_between(const double q[4], const struct aiQuaternion *k) {
  /* The angle of q⁻¹ k, from its vector part and scalar (robust near 0). */
  double a[4] = { k->w, k->x, k->y, k->z };
  double w = q[0] * a[0] + q[1] * a[1] + q[2] * a[2] + q[3] * a[3];
  double x = q[0] * a[1] - q[1] * a[0] - q[2] * a[3] + q[3] * a[2];
  double y = q[0] * a[2] + q[1] * a[3] - q[2] * a[0] - q[3] * a[1];
  double z = q[0] * a[3] - q[1] * a[2] + q[2] * a[1] - q[3] * a[0];
  return 2 * atan2(sqrt(x * x + y * y + z * z), fabs(w));
}

static void check_pose(const struct aiNodeAnim *c, size_t f, const mr_pose *p, const char *what) {
  for (int i = 0; i < 3; i++) {
    double v = i == 0   ? c->mPositionKeys[f].mValue.x
               : i == 1 ? c->mPositionKeys[f].mValue.y
                        : c->mPositionKeys[f].mValue.z;
    if (fabs(v - p->position[i]) > 1e-5)
      fail_msg("%s at frame %zu: position %d is %.9f, the show's %.9f", what, f, i, v,
               p->position[i]);
  }
  double angle = rotation_between(p->orientation, &c->mRotationKeys[f].mValue);
  if (angle > 1e-5) fail_msg("%s at frame %zu: turned %.3g rad from the show's", what, f, angle);
}

/* At ten times across the show, every node's keys are the show's draw
 * list (its own stage fed the frames the show gave) within 1e-5 m and
 * 1e-5 rad, and a link's scale is its stretch. */
static void the_poses_at_ten_times_match_the_shows_draw_list_within_1e5_m_and_rad(void **state) {
  (void)state;
  const struct aiScene *sc = import();
  const struct aiAnimation *a = sc->mAnimations[0];
  double tps = a->mTicksPerSecond > 0 ? a->mTicksPerSecond : 1.0;
  mr_scene scene;
  mr_scene_error se;
  assert_int_equal(mr_scene_load(g_scene, &scene, &se), MR_SCENE_OK);
  mr_stage *stage = NULL;
  char msg[400];
  assert_int_equal(mr_stage_create(&scene.stage, g_xyz, g_points, &stage, msg, sizeof msg),
                   MR_STAGE_OK);
  int checked = 0;
  for (int k = 0; k < 10; k++) {
    size_t f = (size_t)k * (g_frames - 1) / 9;
    const mr_draw_list *dl = NULL;
    assert_int_equal(mr_stage_update(stage, &g_xyz[f * g_points * 3], g_points, &dl), MR_STAGE_OK);
    for (size_t i = 0; i < dl->n_items; i++) {
      const char *name = scene.stage.models[dl->items[i].model].name;
      const struct aiNodeAnim *c = find_channel(a, name);
      assert_non_null(c);
      assert_true(fabs(c->mPositionKeys[f].mTime / tps - g_t[f]) < 1e-5);
      check_pose(c, f, &dl->items[i].pose, name);
      for (int j = 0; j < 2; j++)
        if (strcmp(name, k_links[j]) == 0)
          assert_true(fabs(c->mScalingKeys[f].mValue.y - dl->items[i].scale[1]) < 1e-5);
      checked++;
    }
    assert_int_equal(dl->n_skins, 1);
    for (int b = 0; b < dl->skins[0].n_bones; b++) {
      char name[64];
      bone_name(name, sizeof name, b);
      const struct aiNodeAnim *c = find_channel(a, name);
      assert_non_null(c);
      check_pose(c, f, &dl->skins[0].bones[b], name);
      checked++;
    }
  }
  assert_int_equal(checked, 10 * (N_POSED + N_BONES));
  mr_stage_destroy(stage);
  mr_scene_free(&scene);
  aiReleaseImport(sc);
}

/* The file as bytes: the JSON (parsed) and the binary chunk. */
typedef struct glb_file {
  char *bytes;
  size_t len;
  cJSON *json;
  const uint8_t *bin;
  uint32_t bin_len;
} glb_file;

static uint32_t u32(const char *p) {
  const uint8_t *b = (const uint8_t *)p;
  return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

static glb_file read_glb(void) {
  glb_file g;
  g.bytes = tt_read_file(g_glb, &g.len);
  assert_non_null(g.bytes);
  assert_true(g.len >= 28);
  assert_int_equal(u32(g.bytes), 0x46546C67u);
  assert_int_equal(u32(g.bytes + 4), 2);
  assert_int_equal(u32(g.bytes + 8), g.len);
  uint32_t jl = u32(g.bytes + 12);
  assert_int_equal(jl % 4, 0);
  assert_int_equal(u32(g.bytes + 16), 0x4E4F534Au);
  g.json = cJSON_ParseWithLength(g.bytes + 20, jl);
  assert_non_null(g.json);
  g.bin_len = u32(g.bytes + 20 + jl);
  assert_int_equal(g.bin_len % 4, 0);
  assert_int_equal(u32(g.bytes + 24 + jl), 0x004E4942u);
  assert_int_equal(28 + jl + g.bin_len, g.len);
  g.bin = (const uint8_t *)g.bytes + 28 + jl;
  return g;
}

static cJSON *item(const cJSON *o, const char *key) {
  cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
  if (v == NULL) fail_msg("required field '%s' missing", key);
  return v;
}

static int num(const cJSON *o, const char *key) {
  cJSON *v = item(o, key);
  assert_true(cJSON_IsNumber(v));
  return v->valueint;
}

/* Accessor a's floats (count x k) out of the binary chunk. */
static const float *floats_of(const glb_file *g, int a, int *count, int k) {
  const cJSON *acc = cJSON_GetArrayItem(item(g->json, "accessors"), a);
  const cJSON *view = cJSON_GetArrayItem(item(g->json, "bufferViews"), num(acc, "bufferView"));
  assert_int_equal(num(acc, "componentType"), 5126);
  *count = num(acc, "count");
  int off = num(view, "byteOffset");
  assert_int_equal(off % 4, 0);
  assert_true((size_t)off + (size_t)*count * (size_t)k * 4 <= g->bin_len);
  return (const float *)(const void *)(g->bin + off);
}

/* min and max given, and bounding the k-vectors exactly. */
static void check_min_max(const glb_file *g, int a, int k) {
  const cJSON *acc = cJSON_GetArrayItem(item(g->json, "accessors"), a);
  const cJSON *mn = item(acc, "min"), *mx = item(acc, "max");
  assert_int_equal(cJSON_GetArraySize(mn), k);
  int n;
  const float *x = floats_of(g, a, &n, k);
  for (int c = 0; c < k; c++) {
    float lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < n; i++) {
      lo = fminf(lo, x[i * k + c]);
      hi = fmaxf(hi, x[i * k + c]);
    }
    assert_float_equal(cJSON_GetArrayItem(mn, c)->valuedouble, lo, 1e-6);
    assert_float_equal(cJSON_GetArrayItem(mx, c)->valuedouble, hi, 1e-6);
  }
}

static void check_meshes(const glb_file *g) {
  const cJSON *mesh;
  cJSON_ArrayForEach(mesh, item(g->json, "meshes")) {
    const cJSON *p;
    cJSON_ArrayForEach(p, item(mesh, "primitives")) {
      check_min_max(g, num(item(p, "attributes"), "POSITION"), 3);
      num(p, "indices");
      const cJSON *mat = cJSON_GetArrayItem(item(g->json, "materials"), num(p, "material"));
      assert_int_equal(
          cJSON_GetArraySize(item(item(mat, "pbrMetallicRoughness"), "baseColorFactor")), 4);
    }
  }
}

static void check_animation(const glb_file *g) {
  const cJSON *anim = cJSON_GetArrayItem(item(g->json, "animations"), 0);
  const cJSON *s, *samplers = item(anim, "samplers"), *c;
  cJSON_ArrayForEach(s, samplers) {
    int in = num(s, "input"), n;
    check_min_max(g, in, 1);
    const float *t = floats_of(g, in, &n, 1);
    assert_int_equal(n, g_frames);
    for (int i = 1; i < n; i++)
      if (!(t[i] > t[i - 1])) fail_msg("time %d (%g) is not after %g", i, t[i], t[i - 1]);
  }
  int rotations = 0;
  cJSON_ArrayForEach(c, item(anim, "channels")) {
    const cJSON *target = item(c, "target");
    num(target, "node");
    if (strcmp(item(target, "path")->valuestring, "rotation") != 0) continue;
    int n;
    const float *q =
        floats_of(g, num(cJSON_GetArrayItem(samplers, num(c, "sampler")), "output"), &n, 4);
    for (int i = 0; i < n; i++) {
      double len = sqrt((double)q[4 * i] * q[4 * i] + (double)q[4 * i + 1] * q[4 * i + 1] +
                        (double)q[4 * i + 2] * q[4 * i + 2] + (double)q[4 * i + 3] * q[4 * i + 3]);
      if (fabs(len - 1) > 1e-6) fail_msg("rotation key %d has length %.9f", i, len);
    }
    rotations++;
  }
  assert_int_equal(rotations, N_POSED + N_BONES);
}

/* The JSON chunk, read with cJSON: the required fields, views on 4-byte
 * boundaries, min and max on every position and time accessor (and
 * right), times strictly increasing, unit quaternions. */
static void
the_gltf_has_its_required_fields_bounds_rising_times_and_unit_quaternions(void **state) {
  (void)state;
  glb_file g = read_glb();
  assert_string_equal(item(item(g.json, "asset"), "version")->valuestring, "2.0");
  const cJSON *v, *a;
  cJSON_ArrayForEach(v, item(g.json, "bufferViews")) {
    assert_int_equal(num(v, "byteOffset") % 4, 0);
    assert_true((uint32_t)(num(v, "byteOffset") + num(v, "byteLength")) <= g.bin_len);
    num(v, "buffer");
  }
  cJSON_ArrayForEach(a, item(g.json, "accessors")) {
    num(a, "bufferView");
    num(a, "componentType");
    num(a, "count");
    assert_true(cJSON_IsString(item(a, "type")));
  }
  assert_true((uint32_t)num(cJSON_GetArrayItem(item(g.json, "buffers"), 0), "byteLength") <=
              g.bin_len);
  assert_int_equal(cJSON_GetArraySize(item(g.json, "nodes")), N_MODELS + N_BONES);
  assert_int_equal(cJSON_GetArraySize(item(cJSON_GetArrayItem(item(g.json, "skins"), 0), "joints")),
                   N_BONES);
  check_meshes(&g);
  check_animation(&g);
  cJSON_Delete(g.json);
  free(g.bytes);
}

/* The point cache: its header, a sample per frame of every vertex of
 * the sausage, the first the rest mesh (the glTF's sausage positions). */
static void the_point_cache_has_its_header_a_sample_per_frame_and_starts_at_rest(void **state) {
  (void)state;
  size_t len;
  char *pc = tt_read_file(g_pc2, &len);
  assert_non_null(pc);
  assert_true(len >= 32);
  assert_memory_equal(pc, "POINTCACHE2\0", 12);
  assert_int_equal(u32(pc + 12), 1);
  uint32_t np = u32(pc + 16), ns = u32(pc + 28);
  float start, rate;
  memcpy(&start, pc + 20, 4);
  memcpy(&rate, pc + 24, 4);
  assert_float_equal(start, 0, 0);
  assert_float_equal(rate, 1, 0);
  assert_int_equal(ns, g_frames);
  assert_int_equal(len, 32 + (size_t)12 * np * ns);
  glb_file g = read_glb();
  const cJSON *mesh = cJSON_GetArrayItem(item(g.json, "meshes"), 0);
  assert_string_equal(item(mesh, "name")->valuestring, "sausage");
  const cJSON *p = cJSON_GetArrayItem(item(mesh, "primitives"), 0);
  int n;
  const float *rest = floats_of(&g, num(item(p, "attributes"), "POSITION"), &n, 3);
  assert_int_equal(np, n);
  for (int i = 0; i < 3 * n; i++) {
    float x;
    memcpy(&x, pc + 32 + 4 * i, 4);
    if (fabsf(x - rest[i]) > 1e-6f) fail_msg("point %d: %g, at rest %g", i / 3, x, rest[i]);
  }
  /* And it moves: the last sample is not the rest mesh. */
  float last;
  memcpy(&last, pc + 32 + (size_t)12 * np * (ns - 1) + 4, 4);
  assert_true(fabsf(last - rest[1]) > 1e-3f);
  cJSON_Delete(g.json);
  free(g.bytes);
  free(pc);
}

/* The CSV: a header, then a row per particle per frame, its time, id,
 * name and position the show's. */
static void the_csv_has_a_row_per_particle_per_frame_at_the_shows_positions(void **state) {
  (void)state;
  char *text = tt_read_file(g_csv, NULL);
  assert_non_null(text);
  char *line = strtok(text, "\n");
  assert_string_equal(line, "t,id,name,x,y,z");
  size_t rows = 0;
  while ((line = strtok(NULL, "\n")) != NULL) {
    double t, x, y, z;
    size_t id;
    char name[64];
    assert_int_equal(sscanf(line, "%lf,%zu,%63[^,],%lf,%lf,%lf", &t, &id, name, &x, &y, &z), 6);
    size_t f = rows / g_particles;
    assert_int_equal(id, rows % g_particles);
    char want[16];
    snprintf(want, sizeof want, "k%zu", id);
    assert_string_equal(name, want);
    assert_float_equal(t, g_t[f], 1e-6);
    const double *p = &g_xyz[(f * g_points + id) * 3];
    assert_float_equal(x, p[0], 1e-8);
    assert_float_equal(y, p[1], 1e-8);
    assert_float_equal(z, p[2], 1e-8);
    rows++;
  }
  assert_int_equal(rows, g_frames * g_particles);
  free(text);
}

/* The summary's field `key`, as it should read. */
static void expect_field(const char *key, const char *want) {
  char got[800];
  if (tt_field(g_summary, key, got, sizeof got) != 0) fail_msg("no '%s:' in '%s'", key, g_summary);
  if (strcmp(got, want) != 0) fail_msg("%s: '%s', not '%s'", key, got, want);
}

/* The summary counts what was written: the frames and the time of the
 * last, the glTF's nodes and channels, the cache's points and the CSV's
 * rows, each as the files themselves hold them. */
static void the_summary_counts_what_each_file_holds(void **state) {
  (void)state;
  char want[800];
  snprintf(want, sizeof want, "%zu at 30 fps (%.3f s)", g_frames, g_t[g_frames - 1]);
  expect_field("frames", want);
  glb_file g = read_glb();
  const cJSON *anim = cJSON_GetArrayItem(item(g.json, "animations"), 0);
  snprintf(want, sizeof want, "%s (%d nodes, %d channels of %zu keys)", g_glb,
           cJSON_GetArraySize(item(g.json, "nodes")), cJSON_GetArraySize(item(anim, "channels")),
           g_frames);
  expect_field("gltf", want);
  cJSON_Delete(g.json);
  free(g.bytes);
  size_t len;
  char *pc = tt_read_file(g_pc2, &len);
  assert_non_null(pc);
  assert_true(len >= 32);
  snprintf(want, sizeof want, "%s (%u points, %zu samples)", g_pc2, (unsigned)u32(pc + 16),
           g_frames);
  expect_field("points", want);
  free(pc);
  snprintf(want, sizeof want, "%s (%zu rows)", g_csv, g_frames * g_particles);
  expect_field("csv", want);
}

/* One line on stderr holding every one of the strings. */
static void expect_one_line(const tt_output *o, int status, ...) {
  if (o->status != status) fail_msg("exit %d, not %d; stderr: %s", o->status, status, o->err);
  const char *nl = strchr(o->err, '\n');
  if (nl == NULL || nl[1] != '\0') fail_msg("not one line: '%s'", o->err);
  va_list ap;
  va_start(ap, status);
  for (const char *s; (s = va_arg(ap, const char *)) != NULL;)
    if (strstr(o->err, s) == NULL) fail_msg("'%s' does not say '%s'", o->err, s);
  va_end(ap);
}

/* A take played on a scene whose world starts otherwise is refused. */
static void a_take_recorded_on_another_scene_is_refused_naming_both(void **state) {
  (void)state;
  char other[600];
  snprintf(other, sizeof other, "%s", tt_path(g_dir, "other.yaml"));
  write_scene(other, "0.85", "");
  tt_output o;
  run_export(g_take, other, tt_path(g_dir, "x.glb"), &o);
  expect_one_line(&o, 1, g_take, "recorded on another scene", other, NULL);
  assert_int_not_equal(access(tt_path(g_dir, "x.glb"), F_OK), 0);
  tt_output_free(&o);
}

/* A model file that is nowhere: the scene's line, the model, the file. */
static void a_scene_whose_model_file_is_missing_is_refused_naming_it(void **state) {
  (void)state;
  char lost[600];
  snprintf(lost, sizeof lost, "%s", tt_path(g_dir, "lost.yaml"));
  write_scene(lost, "0.80", "  - {name: ghost, file: nowhere.glb, particle: k2}\n");
  tt_output o;
  run_export(g_take, lost, tt_path(g_dir, "y.glb"), &o);
  expect_one_line(&o, 1, "model 'ghost'", "nowhere.glb", "lost.yaml:", NULL);
  tt_output_free(&o);
}

/* A take cut inside its last chunk: exported up to its last whole frame,
 * and a line says so; a take whose header is broken is refused. */
static void a_cut_take_exports_to_its_last_whole_frame_and_a_broken_one_is_refused(void **state) {
  (void)state;
  size_t len;
  char *bytes = tt_read_file(g_take, &len);
  assert_non_null(bytes);
  char cut[600];
  snprintf(cut, sizeof cut, "%s", tt_path(g_dir, "cut.mrec"));
  FILE *f = fopen(cut, "wb");
  fwrite(bytes, 1, len * 2 / 3, f);
  fclose(f);
  tt_output o;
  const char *out = tt_path(g_dir, "cut.glb");
  run_export(cut, g_scene, out, &o);
  expect_one_line(&o, 0, cut, "cut short", "last whole frame", NULL);
  char frames[64];
  assert_int_equal(tt_field(o.out, "frames", frames, sizeof frames), 0);
  long n = strtol(frames, NULL, 10);
  assert_true(n > (long)g_frames / 3 && n < (long)g_frames * 3 / 4);
  tt_output_free(&o);
  bytes[9] = 7; /* version 0x0701 */
  f = fopen(cut, "wb");
  fwrite(bytes, 1, len, f);
  fclose(f);
  run_export(cut, g_scene, out, &o);
  expect_one_line(&o, 1, cut, "version", NULL);
  tt_output_free(&o);
  free(bytes);
}

int main(int argc, char **argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: %s MARIONETTE GLOVE_GEN\n", argv[0]);
    return 2;
  }
  g_marionette = argv[1];
  g_glove_gen = argv[2];
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(an_exported_take_reimports_with_a_node_per_model_and_bone_and_a_key_per_frame),
    cmocka_unit_test(the_poses_at_ten_times_match_the_shows_draw_list_within_1e5_m_and_rad),
    cmocka_unit_test(the_gltf_has_its_required_fields_bounds_rising_times_and_unit_quaternions),
    cmocka_unit_test(the_point_cache_has_its_header_a_sample_per_frame_and_starts_at_rest),
    cmocka_unit_test(the_csv_has_a_row_per_particle_per_frame_at_the_shows_positions),
    cmocka_unit_test(the_summary_counts_what_each_file_holds),
    cmocka_unit_test(a_take_recorded_on_another_scene_is_refused_naming_both),
    cmocka_unit_test(a_scene_whose_model_file_is_missing_is_refused_naming_it),
    cmocka_unit_test(a_cut_take_exports_to_its_last_whole_frame_and_a_broken_one_is_refused),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}

/* Model files through the loader: one small scene written as OBJ with its
 * MTL, then exported by Assimp's own exporter as 3DS, FBX and glTF 2.0 into
 * this run's scratch folder, each loaded back; textures embedded in a GLB
 * (built here byte by byte) and beside an OBJ; placement; and every error
 * the loader reports. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include <assimp/cexport.h>
#include <assimp/cimport.h>
#include <stb_image_write.h>

#include "model.h"
#include "mr_pose.h"
#include "proc.h"

static mr_model_def file_def(const char *path) {
  mr_model_def d;
  memset(&d, 0, sizeof d);
  d.shape = MR_SHAPE_FILE;
  assert_true(snprintf(d.path, sizeof d.path, "%s", path) < (int)sizeof d.path);
  d.scale[0] = d.scale[1] = d.scale[2] = 1;
  d.place = mr_pose_identity();
  return d;
}

static const char *scratch(const char *name, const char *text) {
  const char *p = tt_tmp_file(name, text, strlen(text));
  assert_non_null(p);
  return p;
}

/* A block 2 m along x, 1 m tall and 0.5 m deep with a corner on the
 * origin: six quads, which the loader cuts into 12 triangles. */
static const double block_v[8][3] = { { 0, 0, 0 },   { 2, 0, 0 },   { 2, 1, 0 },   { 0, 1, 0 },
                                      { 0, 0, 0.5 }, { 2, 0, 0.5 }, { 2, 1, 0.5 }, { 0, 1, 0.5 } };
static const char block_faces[] =
    "usemtl clay\nf 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\nf 4 8 7 3\nf 1 2 6 5\n";
static const char block_mtl[] = "newmtl clay\nKd 0.2 0.4 0.6\nKa 0 0 0\nNs 98\nd 1\nillum 2\n";

/* The block as OBJ text; z_up writes it turned as a z-up program would
 * keep it (x, -z, y), which is how 3DS files hold their scenes and so
 * what Assimp's 3DS reader turns back to y up. */
static const char *write_block_as(const char *name, int z_up) {
  char text[1024];
  int n = snprintf(text, sizeof text, "mtllib block.mtl\no block\n");
  for (int i = 0; i < 8; i++) {
    const double *v = block_v[i];
    n += snprintf(text + n, sizeof text - (size_t)n, "v %g %g %g\n", v[0], z_up ? -v[2] : v[1],
                  z_up ? v[1] : v[2]);
  }
  snprintf(text + n, sizeof text - (size_t)n, "%s", block_faces);
  scratch("block.mtl", block_mtl);
  return scratch(name, text);
}

static size_t triangles(const mr_model *m) {
  size_t n = 0;
  for (size_t k = 0; k < m->n_meshes; k++) n += m->meshes[k].n_indices / 3;
  return n;
}

static void assert_bounds(const mr_model *m, const float lo[3], const float hi[3], double tol) {
  for (int i = 0; i < 3; i++) {
    assert_float_equal(m->bounds_min[i], lo[i], tol);
    assert_float_equal(m->bounds_max[i], hi[i], tol);
  }
}

/* The block, loaded from path, is the block: 12 triangles, its bounds,
 * its clay colour. */
static void check_block(const char *path) {
  static const float lo[3] = { 0, 0, 0 }, hi[3] = { 2, 1, 0.5f };
  mr_model_def d = file_def(path);
  mr_model m;
  char msg[512] = "";
  int rc = mr_model_load(&d, &m, msg, sizeof msg);
  if (rc != 0) print_error("%s: %s\n", path, msg);
  assert_int_equal(rc, 0);
  assert_int_equal(triangles(&m), 12);
  assert_bounds(&m, lo, hi, 1e-4);
  const mr_material_def *mat = &m.meshes[0].material;
  assert_float_equal(mat->base_color[0], 0.2, 1e-3);
  assert_float_equal(mat->base_color[1], 0.4, 1e-3);
  assert_float_equal(mat->base_color[2], 0.6, 1e-3);
  assert_float_equal(mat->base_color[3], 1.0, 1e-3);
  for (size_t v = 0; v < m.meshes[0].n_vertices; v++) {
    const float *n = &m.meshes[0].normals[3 * v];
    assert_float_equal(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-4);
  }
  mr_model_free(&m);
}

static const char *write_block(void) {
  return write_block_as("block.obj", 0);
}

static void test_an_obj_with_its_mtl_loads_with_its_triangles_bounds_and_colour(void **state) {
  (void)state;
  const char *obj = write_block();
  check_block(obj);
  /* Phong shininess 98 is kept as roughness sqrt(2 / 100). */
  mr_model_def d = file_def(obj);
  mr_model m;
  char msg[256];
  assert_int_equal(mr_model_load(&d, &m, msg, sizeof msg), 0);
  assert_float_equal(m.meshes[0].material.roughness, sqrt(0.02), 1e-4);
  mr_model_free(&m);
}

/* The block exported by Assimp as `format` to `name`, then loaded back. */
static void export_and_check(const char *format, const char *name, int z_up) {
  char obj[1024], out[1024];
  snprintf(obj, sizeof obj, "%s", write_block_as(z_up ? "block-z-up.obj" : "block.obj", z_up));
  snprintf(out, sizeof out, "%s", scratch(name, "")); /* the scratch folder's path */
  const struct aiScene *sc = aiImportFile(obj, 0);
  assert_non_null(sc);
  aiReturn r = aiExportScene(sc, format, out, 0);
  aiReleaseImport(sc);
  if (r != aiReturn_SUCCESS) print_error("export %s: %s\n", format, aiGetErrorString());
  assert_int_equal(r, aiReturn_SUCCESS);
  check_block(out);
}

static void test_a_3ds_file_loads_with_its_triangles_bounds_and_colour(void **state) {
  (void)state;
  export_and_check("3ds", "block.3ds", 1);
}

static void test_an_fbx_file_loads_with_its_triangles_bounds_and_colour(void **state) {
  (void)state;
  /* ASCII FBX: this Assimp (5.2) writes binary FBX that it cannot read
   * back itself, while it reads other programs' binary FBX. */
  export_and_check("fbxa", "block.fbx", 0);
}

static void test_a_gltf2_file_loads_with_its_triangles_bounds_and_colour(void **state) {
  (void)state;
  export_and_check("glb2", "block.glb", 0);
  export_and_check("gltf2", "block.gltf", 0);
}

/* ------------------------------------------------------------ textures */

typedef struct bytes {
  unsigned char data[4096];
  size_t n;
} bytes;

static void append(void *ctx, void *data, int size) {
  bytes *b = ctx;
  assert_true(b->n + (size_t)size <= sizeof b->data);
  memcpy(b->data + b->n, data, (size_t)size);
  b->n += (size_t)size;
}

/* 2 x 2 texels, top row first: red, green; blue, white. */
static const unsigned char texels[16] = { 255, 0, 0,   255, 0,   255, 0,   255,
                                          0,   0, 255, 255, 255, 255, 255, 255 };

static void png(bytes *b) {
  b->n = 0;
  assert_true(stbi_write_png_to_func(append, b, 2, 2, 4, texels, 8) != 0);
}

static void put_u32(bytes *b, uint32_t x) {
  unsigned char le[4] = { x & 0xff, (x >> 8) & 0xff, (x >> 16) & 0xff, x >> 24 };
  append(b, le, 4);
}

static void put_floats(bytes *b, const float *f, size_t n) {
  for (size_t i = 0; i < n; i++) {
    uint32_t u;
    memcpy(&u, &f[i], 4);
    put_u32(b, u);
  }
}

/* A one-quad GLB (glTF 2.0, binary): the unit square in the z = 0 plane
 * facing +z, wearing a metal-rough material whose base colour texture is
 * a PNG inside the file's own buffer. corner0_x puts its first corner's x
 * (a NaN there makes absurd input). */
static const char *write_glb(const char *name, float corner0_x) {
  bytes bin = { .n = 0 }, img, glb = { .n = 0 };
  const float pos[12] = { corner0_x, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 };
  const float uv[8] = { 0, 1, 1, 1, 1, 0, 0, 0 }; /* glTF's v = 0 is the image's top */
  const uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
  png(&img);
  put_floats(&bin, pos, 12);
  put_floats(&bin, uv, 8);
  for (int i = 0; i < 6; i++) put_u32(&bin, idx[i]);
  append(&bin, img.data, (int)img.n);
  while (bin.n % 4) append(&bin, "\0", 1);
  char json[2048];
  int n = snprintf(
      json, sizeof json,
      "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
      "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,"
      "\"TEXCOORD_0\":1},\"indices\":2,\"material\":0}]}],\"materials\":[{"
      "\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0.5,0.25,1],\"metallicFactor\":0.3,"
      "\"roughnessFactor\":0.7,\"baseColorTexture\":{\"index\":0}}}],"
      "\"textures\":[{\"source\":0}],\"images\":[{\"bufferView\":3,\"mimeType\":\"image/png\"}],"
      "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
      "\"min\":[0,0,0],\"max\":[1,1,0]},{\"bufferView\":1,\"componentType\":5126,\"count\":4,"
      "\"type\":\"VEC2\"},{\"bufferView\":2,\"componentType\":5125,\"count\":6,"
      "\"type\":\"SCALAR\"}],\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
      "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":32},{\"buffer\":0,\"byteOffset\":80,"
      "\"byteLength\":24},{\"buffer\":0,\"byteOffset\":104,\"byteLength\":%zu}],"
      "\"buffers\":[{\"byteLength\":%zu}]}",
      img.n, bin.n);
  while (n % 4) json[n++] = ' ';
  put_u32(&glb, 0x46546c67u); /* "glTF" */
  put_u32(&glb, 2);
  put_u32(&glb, (uint32_t)(12 + 8 + n + 8 + bin.n));
  put_u32(&glb, (uint32_t)n);
  put_u32(&glb, 0x4e4f534au); /* "JSON" */
  append(&glb, json, n);
  put_u32(&glb, (uint32_t)bin.n);
  put_u32(&glb, 0x004e4942u); /* "BIN" */
  append(&glb, bin.data, (int)bin.n);
  const char *p = tt_tmp_file(name, (const char *)glb.data, glb.n);
  assert_non_null(p);
  return p;
}

static void assert_texels(const mr_mesh *mesh) {
  assert_non_null(mesh->texture);
  assert_int_equal(mesh->texture_width, 2);
  assert_int_equal(mesh->texture_height, 2);
  assert_memory_equal(mesh->texture, texels, sizeof texels);
}

/* The uv of the mesh's vertex at (x, y, 0). */
static const float *uv_at(const mr_mesh *mesh, float x, float y) {
  for (size_t v = 0; v < mesh->n_vertices; v++)
    if (fabsf(mesh->positions[3 * v] - x) < 1e-5f && fabsf(mesh->positions[3 * v + 1] - y) < 1e-5f)
      return &mesh->uvs[2 * v];
  fail_msg("no vertex at (%g, %g)", x, y);
  return NULL;
}

static void test_a_glb_with_an_embedded_texture_loads_its_texels_and_metal_rough(void **state) {
  (void)state;
  mr_model_def d = file_def(write_glb("quad.glb", 0));
  mr_model m;
  char msg[256] = "";
  assert_int_equal(mr_model_load(&d, &m, msg, sizeof msg), 0);
  assert_int_equal(m.n_meshes, 1);
  assert_int_equal(triangles(&m), 2);
  const mr_mesh *mesh = &m.meshes[0];
  assert_texels(mesh);
  /* v = 0 is the texture's top row, the one stored first. */
  assert_float_equal(uv_at(mesh, 0, 1)[0], 0, 1e-6);
  assert_float_equal(uv_at(mesh, 0, 1)[1], 0, 1e-6);
  assert_float_equal(uv_at(mesh, 1, 0)[0], 1, 1e-6);
  assert_float_equal(uv_at(mesh, 1, 0)[1], 1, 1e-6);
  const mr_material_def *mat = &mesh->material;
  assert_float_equal(mat->base_color[0], 1, 1e-6);
  assert_float_equal(mat->base_color[1], 0.5, 1e-6);
  assert_float_equal(mat->base_color[2], 0.25, 1e-6);
  assert_float_equal(mat->metallic, 0.3, 1e-6);
  assert_float_equal(mat->roughness, 0.7, 1e-6);
  assert_float_equal(mesh->normals[2], 1, 1e-6); /* faces +z */
  mr_model_free(&m);
}

static const char quad_obj[] = "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                               "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl paper\n"
                               "f 1/1 2/2 3/3 4/4\n";

static const char *write_quad_obj(const char *texture) {
  char mtl[256];
  snprintf(mtl, sizeof mtl, "newmtl paper\nKd 1 1 1\nmap_Kd %s\n", texture);
  scratch("quad.mtl", mtl);
  return scratch("quad.obj", quad_obj);
}

static void test_a_texture_file_beside_an_obj_is_read_top_row_first(void **state) {
  (void)state;
  bytes b;
  png(&b);
  assert_non_null(tt_tmp_file("checker.png", (const char *)b.data, b.n));
  mr_model_def d = file_def(write_quad_obj("checker.png"));
  mr_model m;
  char msg[256] = "";
  assert_int_equal(mr_model_load(&d, &m, msg, sizeof msg), 0);
  assert_texels(&m.meshes[0]);
  /* OBJ's vt 0 1 is the image's top left corner: v = 0 here. */
  assert_float_equal(uv_at(&m.meshes[0], 0, 1)[1], 0, 1e-6);
  assert_float_equal(uv_at(&m.meshes[0], 1, 0)[1], 1, 1e-6);
  mr_model_free(&m);
}

/* ----------------------------------------------------------- placement */

static void test_placement_scales_then_turns_then_moves_the_bounds(void **state) {
  (void)state;
  mr_model_def d = file_def(write_block());
  const double at[3] = { 1, 2, 3 }, turn[3] = { 0, 90, 0 };
  d.scale[0] = 2;
  d.place = mr_pose_from_euler_deg(at, turn);
  mr_model m;
  char msg[256] = "";
  assert_int_equal(mr_model_load(&d, &m, msg, sizeof msg), 0);
  /* By hand: x 0..2 scaled to 0..4; a quarter turn about y takes (x, y, z)
   * to (z, y, -x): x 0..0.5, z -4..0; then moved by (1, 2, 3). */
  static const float lo[3] = { 1, 2, -1 }, hi[3] = { 1.5f, 3, 3 };
  assert_bounds(&m, lo, hi, 1e-5);
  mr_model_free(&m);
}

/* -------------------------------------------------------------- errors */

/* Loading def fails with a message that starts with want, the model left
 * empty. */
static void expect_error(const mr_model_def *d, const char *want) {
  mr_model m;
  char msg[512] = "";
  assert_int_equal(mr_model_load(d, &m, msg, sizeof msg), -1);
  if (strncmp(msg, want, strlen(want)) != 0) fail_msg("got \"%s\", want \"%s...\"", msg, want);
  assert_null(m.meshes);
  assert_int_equal(m.n_meshes, 0);
  mr_model_free(&m); /* harmless on an empty model */
}

static void test_a_missing_file_says_it_cannot_be_opened(void **state) {
  (void)state;
  char path[1024];
  snprintf(path, sizeof path, "%s", write_block());
  strcpy(strrchr(path, '/') + 1, "no-such-model.obj"); /* beside a real one */
  mr_model_def d = file_def(path);
  expect_error(&d, "cannot open: No such file or directory");
}

static void test_a_file_assimp_cannot_read_says_so_with_assimps_reason(void **state) {
  (void)state;
  unsigned char junk[300];
  for (size_t i = 0; i < sizeof junk; i++) junk[i] = (unsigned char)(i * 7919u >> 3);
  mr_model_def d = file_def(tt_tmp_file("junk.bin", (const char *)junk, sizeof junk));
  expect_error(&d, "not a model Assimp reads: No suitable reader");
}

static void test_a_model_of_lines_only_has_no_triangles(void **state) {
  (void)state;
  mr_model_def d = file_def(scratch("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n"));
  expect_error(&d, "no triangles");
}

static void test_a_texture_that_cannot_be_read_names_it_and_why(void **state) {
  (void)state;
  mr_model_def d = file_def(write_quad_obj("missing.png"));
  expect_error(&d, "texture 'missing.png': No such file or directory");
  scratch("bad.png", "this is not a picture");
  d = file_def(write_quad_obj("bad.png"));
  expect_error(&d, "texture 'bad.png': ");
}

static void test_vertices_that_are_not_numbers_are_refused(void **state) {
  (void)state;
  mr_model_def d = file_def(write_glb("nan.glb", NAN));
  expect_error(&d, "vertex 0 of mesh 0 is not a finite number");
  d = file_def(scratch("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 nan 0\nf 1 2 3\nf 2 4 3\n"));
  expect_error(&d, "vertex ");
}

/* A normal that is not a number costs only its shading: it becomes +y,
 * and the model loads. */
static void test_normals_that_are_not_numbers_become_up(void **state) {
  (void)state;
  mr_model_def d = file_def(scratch("nan-normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                       "vn nan nan nan\nf 1//1 2//1 3//1\n"));
  mr_model m;
  char msg[256] = "";
  assert_int_equal(mr_model_load(&d, &m, msg, sizeof msg), 0);
  for (size_t v = 0; v < m.meshes[0].n_vertices; v++) {
    assert_float_equal(m.meshes[0].normals[3 * v], 0, 0);
    assert_float_equal(m.meshes[0].normals[3 * v + 1], 1, 0);
    assert_float_equal(m.meshes[0].normals[3 * v + 2], 0, 0);
  }
  mr_model_free(&m);
}

static void test_a_path_that_fills_its_field_unended_is_refused(void **state) {
  (void)state;
  mr_model_def d = file_def("");
  memset(d.path, 'a', sizeof d.path);
  expect_error(&d, "path longer than 511 bytes");
}

static void test_a_placement_that_is_not_finite_or_flat_is_refused(void **state) {
  (void)state;
  mr_model_def d = file_def(write_block());
  d.scale[1] = 0;
  expect_error(&d, "scale must be finite and not 0");
  d.scale[1] = 1;
  d.place.orientation[0] = NAN;
  expect_error(&d, "placement is not a finite pose");
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_an_obj_with_its_mtl_loads_with_its_triangles_bounds_and_colour),
    cmocka_unit_test(test_a_3ds_file_loads_with_its_triangles_bounds_and_colour),
    cmocka_unit_test(test_an_fbx_file_loads_with_its_triangles_bounds_and_colour),
    cmocka_unit_test(test_a_gltf2_file_loads_with_its_triangles_bounds_and_colour),
    cmocka_unit_test(test_a_glb_with_an_embedded_texture_loads_its_texels_and_metal_rough),
    cmocka_unit_test(test_a_texture_file_beside_an_obj_is_read_top_row_first),
    cmocka_unit_test(test_placement_scales_then_turns_then_moves_the_bounds),
    cmocka_unit_test(test_a_missing_file_says_it_cannot_be_opened),
    cmocka_unit_test(test_a_file_assimp_cannot_read_says_so_with_assimps_reason),
    cmocka_unit_test(test_a_model_of_lines_only_has_no_triangles),
    cmocka_unit_test(test_a_texture_that_cannot_be_read_names_it_and_why),
    cmocka_unit_test(test_vertices_that_are_not_numbers_are_refused),
    cmocka_unit_test(test_normals_that_are_not_numbers_become_up),
    cmocka_unit_test(test_a_path_that_fills_its_field_unended_is_refused),
    cmocka_unit_test(test_a_placement_that_is_not_finite_or_flat_is_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The built-in shapes: their sizes, counts, normals and winding, and
 * placement applied to them (scale, then turn, then move). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "model.h"
#include "shapes.h"
#include "mr_pose.h"

static mr_model_def shape_def(mr_shape s) {
  mr_model_def d;
  memset(&d, 0, sizeof d);
  d.shape = s;
  d.scale[0] = d.scale[1] = d.scale[2] = 1;
  d.place = mr_pose_identity();
  return d;
}

typedef struct shape_case {
  mr_shape shape;
  size_t vertices, triangles;
  float lo[3], hi[3];
} shape_case;

/* 32 segments; the sphere has 16 rings, the capsule 8 per cap, the cone
 * 4 bands; poles make fans; seams repeat a column (33 per ring). */
static const shape_case cases[] = {
  { MR_SHAPE_SPHERE, 17 * 33, 2 * 32 * 15, { -0.5f, -0.5f, -0.5f }, { 0.5f, 0.5f, 0.5f } },
  { MR_SHAPE_BOX, 24, 12, { -0.5f, -0.5f, -0.5f }, { 0.5f, 0.5f, 0.5f } },
  { MR_SHAPE_CYLINDER, 2 * 33 + 2 * 33, 64 + 2 * 32, { -0.5f, 0, -0.5f }, { 0.5f, 1, 0.5f } },
  { MR_SHAPE_CAPSULE, 18 * 33, 17 * 64 - 64, { -0.5f, 0, -0.5f }, { 0.5f, 1, 0.5f } },
  { MR_SHAPE_CONE, 5 * 33 + 33, 4 * 64 - 32 + 32, { -0.5f, 0, -0.5f }, { 0.5f, 1, 0.5f } },
};

/* Counter-clockwise seen from outside: every triangle's own normal
 * (b - a) × (c - a) leans the way its corners' normals point. */
static void assert_faces_outward(const mr_mesh *mesh) {
  for (size_t t = 0; t < mesh->n_indices; t += 3) {
    const float *a = &mesh->positions[3 * mesh->indices[t]];
    const float *b = &mesh->positions[3 * mesh->indices[t + 1]];
    const float *cc = &mesh->positions[3 * mesh->indices[t + 2]];
    double e1[3], e2[3], f[3], nsum[3] = { 0, 0, 0 };
    for (int i = 0; i < 3; i++) e1[i] = b[i] - a[i], e2[i] = cc[i] - a[i];
    f[0] = e1[1] * e2[2] - e1[2] * e2[1];
    f[1] = e1[2] * e2[0] - e1[0] * e2[2];
    f[2] = e1[0] * e2[1] - e1[1] * e2[0];
    assert_true(f[0] * f[0] + f[1] * f[1] + f[2] * f[2] > 1e-12); /* no degenerate ones */
    for (int k = 0; k < 3; k++)
      for (int i = 0; i < 3; i++) nsum[i] += mesh->normals[3 * mesh->indices[t + k] + i];
    assert_true(f[0] * nsum[0] + f[1] * nsum[1] + f[2] * nsum[2] > 0);
  }
}

static void check_shape(const shape_case *c) {
  mr_model_def d = shape_def(c->shape);
  mr_model m;
  char msg[256] = "";
  assert_int_equal(mr_model_load(&d, &m, msg, sizeof msg), 0);
  assert_int_equal(m.n_meshes, 1);
  const mr_mesh *mesh = &m.meshes[0];
  assert_int_equal(mesh->n_vertices, c->vertices);
  assert_int_equal(mesh->n_indices, 3 * c->triangles);
  assert_non_null(mesh->uvs);
  assert_null(mesh->texture);
  for (int i = 0; i < 3; i++) {
    assert_float_equal(m.bounds_min[i], c->lo[i], 1e-6);
    assert_float_equal(m.bounds_max[i], c->hi[i], 1e-6);
  }
  /* The default surface until a scene gives one. */
  assert_float_equal(mesh->material.base_color[0], 0.8, 1e-6);
  assert_float_equal(mesh->material.roughness, 0.6, 1e-6);
  for (size_t v = 0; v < mesh->n_vertices; v++) {
    const float *n = &mesh->normals[3 * v];
    assert_float_equal(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-5);
    assert_true(mesh->uvs[2 * v] >= 0 && mesh->uvs[2 * v] <= 1);
    assert_true(mesh->uvs[2 * v + 1] >= 0 && mesh->uvs[2 * v + 1] <= 1);
  }
  assert_faces_outward(mesh);
  mr_model_free(&m);
  assert_null(m.meshes);
}

static void test_each_shape_has_its_counts_bounds_unit_normals_and_outward_faces(void **state) {
  (void)state;
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) check_shape(&cases[i]);
}

static void test_the_sphere_is_smooth_with_normals_along_its_radius(void **state) {
  (void)state;
  mr_model_def d = shape_def(MR_SHAPE_SPHERE);
  mr_model m;
  char msg[256];
  assert_int_equal(mr_model_load(&d, &m, msg, sizeof msg), 0);
  const mr_mesh *mesh = &m.meshes[0];
  for (size_t v = 0; v < mesh->n_vertices; v++)
    for (int i = 0; i < 3; i++) {
      assert_float_equal(mesh->normals[3 * v + i], 2 * mesh->positions[3 * v + i], 1e-5);
    }
  mr_model_free(&m);
}

/* A sphere of radius 0.5 scaled by (2, 1, 1) is the ellipsoid
 * x² + 4 y² + 4 z² = 1: its normals are the gradient (x, 4 y, 4 z) made
 * unit, which only the inverse transpose gives. Turned a quarter about y
 * ((x, y, z) -> (z, y, -x)) and moved, the gradient turns with it. */
static void test_a_stretched_turned_sphere_has_the_ellipsoids_normals(void **state) {
  (void)state;
  mr_model_def d = shape_def(MR_SHAPE_SPHERE);
  const double at[3] = { 1, 2, 3 }, turn[3] = { 0, 90, 0 };
  d.scale[0] = 2;
  d.place = mr_pose_from_euler_deg(at, turn);
  mr_model m;
  char msg[256] = "";
  assert_int_equal(mr_model_load(&d, &m, msg, sizeof msg), 0);
  static const float lo[3] = { 0.5f, 1.5f, 2 }, hi[3] = { 1.5f, 2.5f, 4 };
  for (int i = 0; i < 3; i++) {
    assert_float_equal(m.bounds_min[i], lo[i], 1e-5);
    assert_float_equal(m.bounds_max[i], hi[i], 1e-5);
  }
  const mr_mesh *mesh = &m.meshes[0];
  for (size_t v = 0; v < mesh->n_vertices; v++) {
    const float *p = &mesh->positions[3 * v], *n = &mesh->normals[3 * v];
    /* Back in the ellipsoid's own axes: x = -(pz - 3), y = py - 2, z = px - 1. */
    double x = -(p[2] - 3), y = p[1] - 2, z = p[0] - 1;
    double g[3] = { 4 * z, 4 * y, -x }; /* (x, 4y, 4z) turned: (4z, 4y, -x) */
    double len = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    for (int i = 0; i < 3; i++) assert_float_equal(n[i], g[i] / len, 1e-4);
  }
  assert_faces_outward(mesh);
  mr_model_free(&m);
}

/* A mirroring scale would turn the faces inside out; the loader turns
 * their winding round so they still face out. */
static void test_a_mirroring_scale_keeps_faces_outward(void **state) {
  (void)state;
  for (mr_shape s = MR_SHAPE_SPHERE; s <= MR_SHAPE_CONE; s++) {
    mr_model_def d = shape_def(s);
    d.scale[0] = -1;
    d.scale[2] = 0.5;
    mr_model m;
    char msg[256] = "";
    assert_int_equal(mr_model_load(&d, &m, msg, sizeof msg), 0);
    assert_faces_outward(&m.meshes[0]);
    mr_model_free(&m);
  }
}

/* The coarser levels (shapes drawn small): the sphere at 16 segments and
 * 8 rings, then 8 and 4; placed as the finest one is (stretched, turned,
 * moved, mirrored), their faces still outward, their corners inside its
 * box; a model file has none. */
static void test_each_coarser_level_halves_the_segments_and_is_placed_alike(void **state) {
  (void)state;
  static const size_t verts[2] = { 9 * 17, 5 * 9 }, tris[2] = { 2 * 16 * 7, 2 * 8 * 3 };
  mr_model_def d = shape_def(MR_SHAPE_SPHERE);
  const double at[3] = { 1, 2, 3 }, turn[3] = { 0, 90, 0 };
  d.scale[0] = -2;
  d.place = mr_pose_from_euler_deg(at, turn);
  mr_model m;
  char msg[256] = "";
  assert_int_equal(mr_model_load(&d, &m, msg, sizeof msg), 0);
  assert_int_equal(m.n_lods, 2);
  for (size_t k = 0; k < m.n_lods; k++) {
    const mr_mesh *lod = &m.lods[k];
    assert_int_equal(lod->n_vertices, verts[k]);
    assert_int_equal(lod->n_indices, 3 * tris[k]);
    for (size_t v = 0; v < lod->n_vertices; v++) {
      const float *p = &lod->positions[3 * v];
      /* On the ellipsoid (x / 2)² + y² + z² = 1/4, in its own axes. */
      double x = -(p[2] - 3), y = p[1] - 2, z = p[0] - 1;
      assert_float_equal(x * x / 4 + y * y + z * z, 0.25, 1e-5);
      for (int i = 0; i < 3; i++) {
        assert_true(p[i] >= m.bounds_min[i] - 1e-5f && p[i] <= m.bounds_max[i] + 1e-5f);
      }
    }
    assert_faces_outward(lod);
  }
  mr_model_free(&m);
  assert_int_equal(m.n_lods, 0);
  assert_int_equal(mr_shape_segments(0), 32);
  assert_int_equal(mr_shape_segments(1), 16);
  assert_int_equal(mr_shape_segments(2), 8);
  assert_int_equal(mr_shape_segments(3), 0);
}

/* Every built-in shape, at every level, is closed and wound outward (its
 * box's faces apart at the corners, welded by position); turned inside
 * out, with a triangle gone, or with a second copy of a part inside out,
 * it is not, and its back faces must then be drawn. */
static void test_a_closed_outward_mesh_is_told_from_an_open_or_inside_out_one(void **state) {
  (void)state;
  for (mr_shape s = MR_SHAPE_SPHERE; s <= MR_SHAPE_CONE; s++) {
    for (int level = 0; level < MR_SHAPE_LEVELS; level++) {
      mr_mesh m;
      assert_int_equal(mr_shape_mesh_lod(s, level, &m), 0);
      assert_true(mr_mesh_is_closed_outward(&m));
      for (size_t t = 0; t < m.n_indices; t += 3) { /* inside out */
        uint32_t k = m.indices[t + 1];
        m.indices[t + 1] = m.indices[t + 2], m.indices[t + 2] = k;
      }
      assert_false(mr_mesh_is_closed_outward(&m));
      m.n_indices -= 3; /* a hole, and inside out */
      assert_false(mr_mesh_is_closed_outward(&m));
      mr_mesh_release(&m);
    }
  }
  mr_mesh m;
  assert_int_equal(mr_shape_mesh(MR_SHAPE_SPHERE, &m), 0);
  m.n_indices -= 3; /* a hole */
  assert_false(mr_mesh_is_closed_outward(&m));
  mr_mesh_release(&m);
  /* Two boxes, one inside out: the volumes would add up positive. */
  mr_mesh one, two;
  assert_int_equal(mr_shape_mesh(MR_SHAPE_BOX, &one), 0);
  assert_int_equal(mr_mesh_alloc(&two, 2 * one.n_vertices, 2 * one.n_indices / 3, 1), 0);
  for (size_t v = 0; v < one.n_vertices; v++)
    for (int i = 0; i < 3; i++) {
      two.positions[3 * v + i] = 2 * one.positions[3 * v + i];
      two.positions[3 * (one.n_vertices + v) + i] = one.positions[3 * v + i] + (i == 0 ? 5 : 0);
      two.normals[3 * v + i] = two.normals[3 * (one.n_vertices + v) + i] = one.normals[3 * v + i];
    }
  for (size_t t = 0; t < one.n_indices; t++) {
    two.indices[t] = one.indices[t];
    two.indices[one.n_indices + t] = (uint32_t)one.n_vertices + one.indices[t];
  }
  assert_true(mr_mesh_is_closed_outward(&two));
  for (size_t t = one.n_indices; t < two.n_indices; t += 3) {
    uint32_t k = two.indices[t + 1];
    two.indices[t + 1] = two.indices[t + 2], two.indices[t + 2] = k;
  }
  assert_false(mr_mesh_is_closed_outward(&two));
  mr_mesh_release(&one);
  mr_mesh_release(&two);
}

static void test_a_shape_that_is_not_built_in_is_refused(void **state) {
  (void)state;
  mr_model_def d = shape_def((mr_shape)99);
  mr_model m;
  char msg[256] = "";
  assert_int_equal(mr_model_load(&d, &m, msg, sizeof msg), -1);
  assert_string_equal(msg, "not a built-in shape, or out of memory");
  assert_null(m.meshes);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(test_each_shape_has_its_counts_bounds_unit_normals_and_outward_faces),
    cmocka_unit_test(test_the_sphere_is_smooth_with_normals_along_its_radius),
    cmocka_unit_test(test_a_stretched_turned_sphere_has_the_ellipsoids_normals),
    cmocka_unit_test(test_a_mirroring_scale_keeps_faces_outward),
    cmocka_unit_test(test_each_coarser_level_halves_the_segments_and_is_placed_alike),
    cmocka_unit_test(test_a_closed_outward_mesh_is_told_from_an_open_or_inside_out_one),
    cmocka_unit_test(test_a_shape_that_is_not_built_in_is_refused),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

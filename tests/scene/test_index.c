/* The loader's index of particles by name and by place (scene_index.c):
 * every name found in a large scene, the first repeated name and the
 * first coincident pair in file order, coincidences found across every
 * face of the index's cells, and the stage's own models for a large
 * scene. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "mr_scene.h"

/* A chain of n particles 1 cm apart on a 100-wide grid, one distance
 * constraint per link, as tools/scene-bench writes it. Particle i is on
 * line 4 + i. rename_at/rename_to: particle rename_at[k] is named
 * rename_to[k] instead of p<i>. */
static char *chain(long n, const long *rename_at, const char *const *rename_to, int renames,
                   size_t *len) {
  size_t cap = (size_t)n * 100 + 256, used = 0;
  char *t = malloc(cap);
  assert_non_null(t);
  used += (size_t)snprintf(t + used, cap - used,
                           "physics:\n  effects: [gravity, constraints]\n  particles:\n");
  for (long i = 0; i < n; i++) {
    char name[32];
    snprintf(name, sizeof name, "p%ld", i);
    for (int k = 0; k < renames; k++)
      if (rename_at[k] == i) snprintf(name, sizeof name, "%s", rename_to[k]);
    used += (size_t)snprintf(t + used, cap - used,
                             "    - {name: %s, position: [%.2f, %.2f, 0], mass: 1}\n", name,
                             (double)(i % 100) * 0.01, (double)(i / 100) * 0.01);
  }
  used += (size_t)snprintf(t + used, cap - used, "  constraints:\n");
  for (long i = 1; i < n; i++)
    used += (size_t)snprintf(t + used, cap - used, "    - {between: [p%ld, p%ld]}\n", i - 1, i);
  *len = used;
  return t;
}

static void every_name_of_a_large_scene_is_found(void **state) {
  (void)state;
  const long n = 20000;
  size_t len;
  char *text = chain(n, NULL, NULL, 0, &len);
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load_text("t.yaml", text, len, &s, &e), MR_SCENE_OK);
  free(text);
  assert_int_equal(s.n_particles, n);
  assert_int_equal(s.n_distances, n - 1);
  for (long i = 0; i + 1 < n; i++) {
    assert_int_equal(s.distances[i].def.a, i);
    assert_int_equal(s.distances[i].def.b, i + 1);
  }
  /* No models: section: one link per constraint, then one joint per
   * particle, in that order. */
  assert_int_equal(s.stage.n_models, (size_t)(2 * n - 1));
  assert_string_equal(s.stage.models[0].name, "link:p0-p1");
  assert_string_equal(s.stage.models[n - 2].name, "link:p19998-p19999");
  assert_string_equal(s.stage.models[n - 1].name, "joint:p0");
  assert_string_equal(s.stage.models[2 * n - 2].name, "joint:p19999");
  assert_int_equal(s.stage.models[2 * n - 2].particles[0], n - 1);
  mr_scene_free(&s);
}

static void the_first_repeated_name_in_file_order_is_named(void **state) {
  (void)state;
  /* p3 repeated at 15 000, p2 at 17 000: the repeat that comes first is
   * the one reported, though its name sorts after the other's. */
  const long at[] = { 17000, 15000 };
  const char *const to[] = { "p2", "p3" };
  size_t len;
  char *text = chain(20000, at, to, 2, &len);
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load_text("t.yaml", text, len, &s, &e), MR_SCENE_ERR_VALUE);
  free(text);
  assert_string_equal(e.text,
                      "t.yaml:15004:7: expected a unique particle name, 'p3' is already declared");
}

/* Room for any error text. */
enum { TEXT_MAX = sizeof(((mr_scene_error *)0)->text) };

/* Three particles a, b, c at the given places; the load's error text, or
 * "" when it loads. */
static const char *three(const double a[3], const double b[3], const double c[3], char *out,
                         size_t size) {
  char text[512];
  snprintf(text, sizeof text,
           "physics:\n  effects: [gravity]\n  particles:\n"
           "    - {name: a, position: [%.9g, %.9g, %.9g], mass: 1}\n"
           "    - {name: b, position: [%.9g, %.9g, %.9g], mass: 1}\n"
           "    - {name: c, position: [%.9g, %.9g, %.9g], mass: 1}\n",
           a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]);
  mr_scene s;
  mr_scene_error e;
  if (mr_scene_load_text("t.yaml", text, strlen(text), &s, &e) == MR_SCENE_OK) {
    mr_scene_free(&s);
    snprintf(out, size, "%s", "");
  } else {
    snprintf(out, size, "%s", e.text);
  }
  return out;
}

static void coincident_particles_are_found_across_every_cell_face(void **state) {
  (void)state;
  static const char c_and_a[] = "t.yaml:6:7: particle 'c' coincides with particle 'a' (line 4); "
                                "expected distinct positions";
  const double far[3] = { 1, 1, 1 };
  /* Pairs 0.5 µm apart or less across the faces, edges and corners of
   * cells of 1 µm and of 4 µm, on both sides of zero. */
  const double pairs[][2][3] = {
    { { 3.9999996e-6, 0, 0 }, { 4.0000003e-6, 0, 0 } },
    { { 0.9999998e-6, 0, 0 }, { 1.0000002e-6, 0, 0 } },
    { { -3e-7, 0, 0 }, { 2e-7, 0, 0 } },
    { { 0, -0.0, 0 }, { 0, 0, 4e-7 } },
    { { 3.9999997e-6, -3e-7, 7.9999997e-6 }, { 4.0000001e-6, 1e-7, 8.0000001e-6 } },
    { { -4.0000002e-6, 12.0000002e-6, -3e-7 }, { -3.9999998e-6, 11.9999998e-6, 1e-7 } },
  };
  char got[TEXT_MAX];
  for (size_t k = 0; k < sizeof pairs / sizeof pairs[0]; k++) {
    assert_string_equal(three(pairs[k][0], far, pairs[k][1], got, sizeof got), c_and_a);
    /* The same pair in the other order is found from the other side. */
    assert_string_equal(three(pairs[k][1], far, pairs[k][0], got, sizeof got), c_and_a);
  }
  /* 1.2 µm apart across a face: distinct. */
  const double a[3] = { 3.4e-6, 0, 0 }, c[3] = { 4.6e-6, 0, 0 };
  assert_string_equal(three(a, far, c, got, sizeof got), "");
}

static void a_particle_near_two_names_the_earlier(void **state) {
  (void)state;
  /* a and b 1.6 µm apart; c 0.8 µm from each. */
  const double a[3] = { 0, 0, 0 }, b[3] = { 1.6e-6, 0, 0 }, c[3] = { 0.8e-6, 0, 0 };
  char got[TEXT_MAX];
  assert_string_equal(three(a, b, c, got, sizeof got),
                      "t.yaml:6:7: particle 'c' coincides with particle 'a' (line 4); "
                      "expected distinct positions");
  assert_string_equal(three(b, a, c, got, sizeof got),
                      "t.yaml:6:7: particle 'c' coincides with particle 'a' (line 4); "
                      "expected distinct positions");
}

static void the_stage_names_its_own_models_cut_to_fit(void **state) {
  (void)state;
  const char *text = "physics:\n  effects: [gravity, constraints]\n  particles:\n"
                     "    - {name: abcdefghijklmnopqrstuvwxyz0123456789ABCD, position: [0, 1, 0], "
                     "mass: 1}\n"
                     "    - {name: EFGHIJKLMNOPQRSTUVWXYZ, position: [1, 1, 0], mass: 1}\n"
                     "  constraints:\n"
                     "    - {between: [abcdefghijklmnopqrstuvwxyz0123456789ABCD, "
                     "EFGHIJKLMNOPQRSTUVWXYZ]}\n";
  mr_scene s;
  mr_scene_error e;
  assert_int_equal(mr_scene_load_text("t.yaml", text, strlen(text), &s, &e), MR_SCENE_OK);
  assert_int_equal(s.stage.n_models, 3);
  /* "link:" + 40 + "-" + 22 characters, cut to the 47 a model name holds. */
  assert_string_equal(s.stage.models[0].name, "link:abcdefghijklmnopqrstuvwxyz0123456789ABCD-E");
  assert_string_equal(s.stage.models[1].name, "joint:abcdefghijklmnopqrstuvwxyz0123456789ABCD");
  assert_string_equal(s.stage.models[2].name, "joint:EFGHIJKLMNOPQRSTUVWXYZ");
  mr_scene_free(&s);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(every_name_of_a_large_scene_is_found),
    cmocka_unit_test(the_first_repeated_name_in_file_order_is_named),
    cmocka_unit_test(coincident_particles_are_found_across_every_cell_face),
    cmocka_unit_test(a_particle_near_two_names_the_earlier),
    cmocka_unit_test(the_stage_names_its_own_models_cut_to_fit),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

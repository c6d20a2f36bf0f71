/* The public vocabulary of mr_physics: definitions must come from their
 * default makers (a zeroed struct is refused by every create and add call),
 * and each enum has one name table that reads both ways. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "mr_physics.h"

/* A world declaring every effect, with two free particles (0, 1) and one on
 * a control frame (2), so each add call gets as far as its cookie check. */
static mr_world *full_world(void) {
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_ALL;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  mr_frame_def fd = mr_default_frame_def();
  assert_int_equal(mr_world_add_frame(w, &fd, NULL), MR_OK);
  for (int i = 0; i < 3; i++) {
    mr_particle_def p = mr_default_particle_def();
    p.position[0] = i;
    p.frame = i == 2 ? 0 : -1;
    assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_OK);
  }
  return w;
}

/* The refusal names the call and tells how to make the struct. */
static void assert_refused(mr_world *w, mr_status s, const char *call) {
  assert_int_equal(s, MR_ERR_ARG);
  const char *msg = mr_world_last_error(w);
  assert_non_null(strstr(msg, call));
  assert_non_null(strstr(msg, "mr_default_"));
}

/* One test per add call: a zeroed definition is refused with MR_ERR_ARG,
 * and the one from the maker (same particles) is accepted. */
#define ZEROED_IS_REFUSED(kind, setup)                                                   \
  static void zeroed_##kind##_def_is_refused_and_the_maker_s_is_accepted(void **state) { \
    (void)state;                                                                         \
    mr_world *w = full_world();                                                          \
    mr_##kind##_def d;                                                                   \
    memset(&d, 0, sizeof d);                                                             \
    setup;                                                                               \
    int before = mr_world_particle_count(w);                                             \
    assert_refused(w, mr_world_add_##kind(w, &d, NULL), "mr_world_add_" #kind);          \
    assert_int_equal(mr_world_particle_count(w), before);                                \
    mr_##kind##_def good = mr_default_##kind##_def();                                    \
    d = good;                                                                            \
    setup;                                                                               \
    assert_int_equal(mr_world_add_##kind(w, &d, NULL), MR_OK);                           \
    mr_world_destroy(w);                                                                 \
  }

static const int group_ids[] = { 0, 1 };
static const double key_time[] = { 0.0 };
static const double key_point[] = { 0.0, 0.0, 0.0 };

ZEROED_IS_REFUSED(particle, d.mass = 1.0)
ZEROED_IS_REFUSED(frame, d.pose = mr_pose_identity())
ZEROED_IS_REFUSED(spring, (d.a = 0, d.b = 1, d.rest_length = -1, d.stiffness = 1))
ZEROED_IS_REFUSED(string, (d.frame_particle = 2, d.puppet_particle = 0, d.rest_length = -1))
ZEROED_IS_REFUSED(antigravity, (d.acted = 0, d.trigger = 1))
ZEROED_IS_REFUSED(triggered, (d.acted = 0, d.control = 2, d.trigger = 1))
ZEROED_IS_REFUSED(sine_spring, (d.a = 0, d.b = 1, d.rest_length = -1, d.reach = 0.1))
ZEROED_IS_REFUSED(distance, (d.a = 0, d.b = 1, d.length = -1))
ZEROED_IS_REFUSED(pin, (d.particle = 0, d.at_current = 1))
ZEROED_IS_REFUSED(curve,
                  (d.particle = 1, d.key_count = 1, d.times = key_time, d.points = key_point))
ZEROED_IS_REFUSED(rigid_group, (d.particles = group_ids, d.count = 2))
ZEROED_IS_REFUSED(plane, d.normal[1] = 1)
ZEROED_IS_REFUSED(part, (d.particles = group_ids, d.count = 2))

static void zeroed_world_def_is_refused_with_a_message(void **state) {
  (void)state;
  mr_world_def d;
  memset(&d, 0, sizeof d);
  mr_world *w = (mr_world *)&d; /* must be overwritten with NULL */
  char msg[200] = "";
  assert_int_equal(mr_world_create(&d, &w, msg, sizeof msg), MR_ERR_ARG);
  assert_null(w);
  assert_non_null(strstr(msg, "mr_default_world_def"));
  d = mr_default_world_def();
  assert_int_equal(mr_world_create(&d, &w, msg, sizeof msg), MR_OK);
  mr_world_destroy(w);
}

static void every_effect_name_parses_back_to_its_bit(void **state) {
  (void)state;
  uint32_t seen = 0;
  for (int i = 0; i < MR_EFFECT_COUNT; i++) {
    uint32_t bit = 1u << i, back = 0;
    const char *name = mr_effect_name(bit);
    assert_string_not_equal(name, "unknown");
    assert_int_equal(mr_effect_parse(name, &back), 0);
    assert_int_equal(back, bit);
    seen |= back;
  }
  assert_int_equal(seen, MR_EFFECT_ALL);
  uint32_t out = 0;
  assert_int_equal(mr_effect_parse("sine_springs", &out), 0);
  assert_int_equal(out, MR_EFFECT_SINE_SPRINGS);
  assert_int_equal(mr_effect_parse("sine", &out), -1);
  assert_int_equal(mr_effect_parse("sine-springsx", &out), -1);
  assert_int_equal(mr_effect_parse(NULL, &out), -1);
  assert_string_equal(mr_effect_name(MR_EFFECT_GRAVITY | MR_EFFECT_DRAG), "unknown");
  assert_string_equal(mr_effect_name(0), "unknown");
}

static void every_pass_and_integrator_name_parses_back(void **state) {
  (void)state;
  for (int p = 0; p < MR_PASS_COUNT; p++) {
    mr_pass back = MR_PASS_COUNT;
    assert_int_equal(mr_pass_parse(mr_pass_name((mr_pass)p), &back), 0);
    assert_int_equal(back, p);
  }
  assert_string_equal(mr_pass_name(MR_PASS_COUNT), "unknown");
  for (int i = 0; i < MR_INTEGRATOR_COUNT; i++) {
    mr_integrator back = MR_INTEGRATOR_COUNT;
    assert_int_equal(mr_integrator_parse(mr_integrator_name((mr_integrator)i), &back), 0);
    assert_int_equal(back, i);
  }
  mr_integrator out;
  assert_int_equal(mr_integrator_parse("semi_implicit_euler", &out), 0);
  assert_int_equal(out, MR_INTEGRATOR_SEMI_IMPLICIT_EULER);
  assert_int_equal(mr_integrator_parse("rk5", &out), -1);
  assert_string_equal(mr_integrator_name(MR_INTEGRATOR_COUNT), "unknown");
}

/* The force-kind table makes an effect and a pass of the same name for
 * each kind, and the passes run in the table's order. */
static void each_force_kind_has_an_effect_and_a_pass_of_one_name(void **state) {
  (void)state;
  int next = MR_PASS_FRAMES + 1, bit = 0;
#define CHECK_KIND(id, stem, name)                           \
  assert_string_equal(mr_effect_name(MR_EFFECT_##id), name); \
  assert_string_equal(mr_pass_name(MR_PASS_##id), name);     \
  assert_int_equal(MR_PASS_##id, next++);                    \
  assert_int_equal(MR_EFFECT_##id, 1u << bit++);
  MR_FORCE_KINDS(CHECK_KIND)
#undef CHECK_KIND
  assert_int_equal(MR_PASS_CONSTRAINTS, next);
}

static void unknown_effect_bits_are_refused(void **state) {
  (void)state;
  mr_world_def d = mr_default_world_def();
  d.effects = MR_EFFECT_ALL + 1u;
  mr_world *w = NULL;
  char msg[200] = "";
  assert_int_equal(mr_world_create(&d, &w, msg, sizeof msg), MR_ERR_ARG);
  assert_non_null(strstr(msg, "effect"));
  d.effects = MR_EFFECT_ALL;
  assert_int_equal(mr_world_create(&d, &w, msg, sizeof msg), MR_OK);
  mr_world_destroy(w);
}

/* A curve's keys out of order are refused with the key and the two times
 * named, whichever key it is (the last one too); in order, they are
 * taken. */
static void curve_keys_out_of_order_are_named(void **state) {
  (void)state;
  const double points[9] = { 0, 0, 0, 1, 0, 0, 2, 0, 0 };
  const double orders[2][3] = { { 0.0, 2.0, 1.5 }, { 0.5, 0.25, 1.0 } };
  const char *names[2] = { "key 2: times must increase (1.5 after 2)",
                           "key 1: times must increase (0.25 after 0.5)" };
  for (int o = 0; o < 2; o++) {
    mr_world *w = full_world();
    mr_curve_def c = mr_default_curve_def();
    c.particle = 0;
    c.key_count = 3;
    c.times = orders[o];
    c.points = points;
    assert_int_equal(mr_world_add_curve(w, &c, NULL), MR_ERR_ARG);
    assert_non_null(strstr(mr_world_last_error(w), names[o]));
    const double in_order[3] = { 0.0, 1.0, 2.0 };
    c.times = in_order;
    assert_int_equal(mr_world_add_curve(w, &c, NULL), MR_OK);
    mr_world_destroy(w);
  }
}

#define T(kind) cmocka_unit_test(zeroed_##kind##_def_is_refused_and_the_maker_s_is_accepted)

int main(void) {
  const struct CMUnitTest tests[] = {
    T(particle),
    T(frame),
    T(spring),
    T(string),
    T(antigravity),
    T(triggered),
    T(sine_spring),
    T(distance),
    T(pin),
    T(curve),
    T(rigid_group),
    T(plane),
    T(part),
    cmocka_unit_test(zeroed_world_def_is_refused_with_a_message),
    cmocka_unit_test(every_effect_name_parses_back_to_its_bit),
    cmocka_unit_test(every_pass_and_integrator_name_parses_back),
    cmocka_unit_test(each_force_kind_has_an_effect_and_a_pass_of_one_name),
    cmocka_unit_test(unknown_effect_bits_are_refused),
    cmocka_unit_test(curve_keys_out_of_order_are_named),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Contacts along the whole step (§4.4, §4.5, §5.4): a body thrown at up to
 * 40 m/s never passes through a thin sphere or the floor within a step,
 * the contact time found is the analytic one to within the slop, and the
 * search costs a fast body far from anything no step. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>

#include "mr_physics.h"

#define SLOP 2e-4 /* twice the default, so the tests see a non-default one */

static mr_world *world(uint32_t effects) {
  mr_world_def def = mr_default_world_def();
  def.effects = effects;
  def.drag = 0.0;
  def.contact_slop = SLOP;
  def.dt_initial = def.dt_max; /* the first step spans the contact */
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  return w;
}

static int ball(mr_world *w, const double x[3], const double v[3], double r, int puppet) {
  mr_particle_def p = mr_default_particle_def();
  for (int k = 0; k < 3; k++) {
    p.position[k] = x[k];
    p.velocity[k] = v[k];
  }
  p.radius = r;
  p.puppet = puppet;
  int id = -1;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  mr_part_def d = mr_default_part_def();
  d.particles = &id;
  d.count = 1;
  d.radius = r;
  assert_int_equal(mr_world_add_part(w, &d, NULL), MR_OK);
  return id;
}

static double speed_x(const mr_world *w, int id) {
  double v[3];
  mr_world_particle_state(w, id, NULL, v);
  return v[0];
}

/* Steps to t_end; the smallest end-of-step gap between a and b, and the
 * impacts. */
static double run(mr_world *w, double t_end, int a, int b, double ra, double rb, int *impacts) {
  double worst = INFINITY;
  *impacts = 0;
  while (mr_world_time(w) < t_end) {
    mr_step_report rep;
    mr_status s = mr_world_step(w, &rep);
    assert_true(s == MR_OK || s == MR_DEPENDENT);
    assert_int_equal(rep.divergences, 0);
    *impacts += rep.collisions;
    double xa[3], xb[3];
    mr_world_particle_state(w, a, xa, NULL);
    mr_world_particle_state(w, b, xb, NULL);
    double d = sqrt((xa[0] - xb[0]) * (xa[0] - xb[0]) + (xa[1] - xb[1]) * (xa[1] - xb[1]) +
                    (xa[2] - xb[2]) * (xa[2] - xb[2]));
    worst = fmin(worst, d - ra - rb);
  }
  return worst;
}

/* A ball of radius ra thrown at v into a resting ball of radius rb, head-on
 * or glancing (offset across): the thrown ball must bounce back or be
 * turned aside, never come out the other side. */
static void thrown_at_sphere(double v, double ra, double rb, double across) {
  mr_world *w = world(MR_EFFECT_PUPPET_COLLISION);
  const double xa[3] = { -0.6, 0, 0 }, va[3] = { v, 0, 0 };
  const double xb[3] = { 0, across, 0 }, vb[3] = { 0, 0, 0 };
  int a = ball(w, xa, va, ra, 0), b = ball(w, xb, vb, rb, 1);
  int hits;
  double g = run(w, 0.1, a, b, ra, rb, &hits);
  mr_stats st;
  mr_world_stats(w, &st);
  double vy[3];
  mr_world_particle_state(w, a, NULL, vy);
  printf("%4.0f m/s, r %.3f on %.3f, across %.4f: %d impacts, gap >= %.3g, depth %.3g, "
         "v after (%.3g, %.3g)\n",
         v, ra, rb, across, hits, g, st.max_penetration, vy[0], vy[1]);
  assert_true(hits >= 1);
  assert_true(g >= -SLOP);
  assert_true(st.max_penetration <= SLOP + 1e-3);
  /* The thrown ball (equal mass, restitution 0.5) lost most of its speed
   * along x to the one it struck. */
  assert_true(speed_x(w, a) < 0.8 * v);
  mr_world_destroy(w);
}

static void a_ball_thrown_at_up_to_40_m_s_never_passes_through_a_thin_sphere(void **state) {
  (void)state;
  const double speeds[] = { 10, 25, 40 }, radii[] = { 0.004, 0.01, 0.025 };
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      thrown_at_sphere(speeds[i], radii[j], radii[2 - j], 0.0);
      thrown_at_sphere(speeds[i], radii[j], radii[2 - j], 0.7 * (radii[j] + radii[2 - j]));
    }
}

/* A ball thrown at the floor at v, straight down or at a slant: it stops at
 * the floor's surface, within the slop, and bounces. */
static void a_ball_thrown_at_the_floor_at_up_to_40_m_s_stops_at_its_surface(void **state) {
  (void)state;
  const double speeds[] = { 10, 25, 40 }, radii[] = { 0.003, 0.02 };
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 2; j++)
      for (int slant = 0; slant < 2; slant++) {
        mr_world *w = world(MR_EFFECT_PLANES);
        mr_plane_def pl = mr_default_plane_def();
        assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
        mr_particle_def p = mr_default_particle_def();
        p.position[1] = 1.0;
        p.velocity[0] = slant ? 0.6 * speeds[i] : 0.0;
        p.velocity[1] = -(slant ? 0.8 : 1.0) * speeds[i];
        p.radius = radii[j];
        int id;
        assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
        double lowest = INFINITY;
        while (mr_world_time(w) < 0.2) {
          assert_int_equal(mr_world_step(w, NULL), MR_OK);
          double x[3];
          mr_world_particle_state(w, id, x, NULL);
          lowest = fmin(lowest, x[1] - radii[j]);
        }
        double v[3];
        mr_world_particle_state(w, id, NULL, v);
        printf("floor at %.0f m/s, r %.3f, %s: lowest gap %.3g, v_y after %.3g\n", speeds[i],
               radii[j], slant ? "slant" : "straight", lowest, v[1]);
        assert_true(lowest >= -SLOP);
        assert_true(v[1] > 0 || lowest < 1e-3); /* bounced, or still at the floor */
        mr_world_destroy(w);
      }
}

/* Two balls closing at 2v with no force between: they touch at the
 * analytic time t* = (d − ra − rb) / 2v. The first step, planned longer,
 * is cut there: it ends with the gap within [−slop, 0], so at a time within
 * slop / 2v after t*. The floor likewise, at t* = (y − r) / v. */
static void the_contact_time_found_is_the_analytic_one(void **state) {
  (void)state;
  const double speeds[] = { 3, 17, 40 };
  for (int i = 0; i < 3; i++) {
    const double v = speeds[i], ra = 0.012, rb = 0.007, d = 0.5;
    mr_world *w = world(MR_EFFECT_PUPPET_COLLISION);
    const double xa[3] = { -0.5 * d, 0, 0 }, va[3] = { v, 0, 0 };
    const double xb[3] = { 0.5 * d, 0, 0 }, vb[3] = { -v, 0, 0 };
    ball(w, xa, va, ra, 0);
    ball(w, xb, vb, rb, 1);
    double exact = (d - ra - rb) / (2 * v), found = -1;
    while (found < 0) {
      mr_step_report rep;
      assert_int_equal(mr_world_step(w, &rep), MR_OK);
      if (mr_world_time(w) > exact - 1e-12 || rep.collisions > 0) found = mr_world_time(w);
    }
    printf("spheres at %.0f m/s: contact at %.9f s, exact %.9f s, late by %.3g s (<= %.3g)\n", v,
           found, exact, found - exact, SLOP / (2 * v));
    assert_true(found >= exact - 1e-12 && found - exact <= SLOP / (2 * v) + 1e-12);
    mr_world_destroy(w);

    w = world(MR_EFFECT_PLANES);
    mr_plane_def pl = mr_default_plane_def();
    assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
    mr_particle_def p = mr_default_particle_def();
    p.position[1] = 0.8;
    p.velocity[1] = -v;
    p.radius = ra;
    assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_OK);
    exact = (0.8 - ra) / v;
    found = -1;
    while (found < 0) {
      assert_int_equal(mr_world_step(w, NULL), MR_OK);
      if (mr_world_time(w) > exact - 1e-12) found = mr_world_time(w);
    }
    printf("floor at %.0f m/s: contact at %.9f s, exact %.9f s\n", v, found, exact);
    assert_true(found >= exact - 1e-12 && found - exact <= SLOP / v + 1e-12);
    mr_world_destroy(w);
  }
}

/* Two puppets of 5 mm spheres 10 m apart, one flying away at 40 m/s: no
 * contact is possible, so it takes the steps it would take with no
 * collisions at all (the upper bound, 0.05 s), not the 0.1 ms a limit on
 * travel per step would give it. */
static void a_fast_puppet_far_from_anything_is_not_slowed(void **state) {
  (void)state;
  mr_world *w = world(MR_EFFECT_PUPPET_COLLISION | MR_EFFECT_SELF_COLLISION);
  const double xa[3] = { 0, 0, 0 }, va[3] = { 40, 0, 0 }, xa2[3] = { 0, 0.05, 0 };
  const double xb[3] = { -10, 0, 0 }, vb[3] = { 0, 0, 0 };
  ball(w, xa, va, 0.005, 0);
  ball(w, xa2, va, 0.005, 0);
  ball(w, xb, vb, 0.005, 1);
  mr_step_report rep;
  assert_int_equal(mr_world_step_to(w, 1.0, &rep), MR_OK);
  printf("far from anything at 40 m/s: %d steps for 1 s\n", rep.steps);
  assert_true(rep.steps <= 21);
  mr_world_destroy(w);
}

/* Bodies swinging into the floor on curved paths, which the model of the
 * step (the cubic through its ends) follows only approximately: a
 * pendulum's bob, at three lengths, and a spinning rod, each dropped so
 * that it strikes the floor many times. Each contact is located in time
 * with one or two integrations (the model's trial, and rarely a second),
 * not the several of a search by true integrations alone, and none is
 * passed through. */
static void a_contact_is_located_with_few_integrations(void **state) {
  (void)state;
  const double lengths[] = { 0.3, 0.6, 1.0 };
  uint64_t located = 0, trials = 0;
  for (int k = 0; k < 4; k++) {
    mr_world *w = world(MR_EFFECT_PLANES | MR_EFFECT_CONSTRAINTS | MR_EFFECT_GRAVITY);
    mr_plane_def pl = mr_default_plane_def();
    assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
    mr_particle_def p = mr_default_particle_def();
    p.radius = 0.01;
    int a, b;
    mr_distance_def d = mr_default_distance_def();
    if (k < 3) { /* a bob swinging from rest at the height of its pin */
      p.position[1] = lengths[k] - 0.05;
      assert_int_equal(mr_world_add_particle(w, &p, &a), MR_OK);
      mr_pin_def pin = mr_default_pin_def();
      pin.particle = a;
      assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
      p.position[0] = lengths[k];
    } else { /* a rod spinning at 30 rad/s, dropped from 0.5 m */
      p.position[0] = -0.1;
      p.position[1] = 0.5;
      p.velocity[1] = 3.0;
      assert_int_equal(mr_world_add_particle(w, &p, &a), MR_OK);
      p.position[0] = 0.1;
      p.velocity[1] = -3.0;
    }
    assert_int_equal(mr_world_add_particle(w, &p, &b), MR_OK);
    d.a = a;
    d.b = b;
    assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
    double lowest = INFINITY;
    while (mr_world_time(w) < 1.5) {
      mr_status s = mr_world_step(w, NULL);
      assert_true(s == MR_OK || s == MR_DEPENDENT);
      double x[3];
      mr_world_particle_state(w, b, x, NULL);
      lowest = fmin(lowest, x[1] - p.radius);
    }
    mr_stats st;
    mr_world_stats(w, &st);
    printf("%s: %llu contacts located with %llu integrations, lowest gap %.3g\n",
           k < 3 ? "pendulum" : "spinning rod", (unsigned long long)st.located,
           (unsigned long long)st.location_integrations, lowest);
    assert_true(lowest >= -SLOP);
    assert_true(st.divergences == 0);
    located += st.located;
    trials += st.location_integrations;
    mr_world_destroy(w);
  }
  printf("in all: %.2f integrations per location\n", (double)trials / (double)located);
  assert_true(located >= 8);
  assert_true(trials <= 1.3 * (double)located);
}

/* After a contact cuts a step short, Δt doubles each step while the rule
 * would at least hold it (§4.5). A ball thrown at the floor has its first
 * step cut to 2 ms; beside it a pendulum's deviation lies inside a dead
 * band made wide, where the rule alone keeps any Δt: it must not keep the
 * sliver the cut left. */
static void after_a_contact_the_step_doubles_while_the_rule_holds_it(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_PLANES | MR_EFFECT_CONSTRAINTS | MR_EFFECT_GRAVITY;
  def.drag = 0.0;
  def.contact_slop = SLOP;
  def.dt_initial = def.dt_max;
  def.error_length = def.error_speed = 0.0; /* the deviation alone steers Δt */
  def.deviation_low = 1e-300;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  mr_plane_def pl = mr_default_plane_def();
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  p.radius = 0.01;
  p.position[1] = 0.03;
  p.velocity[1] = -10.0; /* at the floor after 2 ms */
  assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_OK);
  p.velocity[1] = 0.0;
  p.position[0] = 5.0;
  p.position[1] = 2.0;
  int a, b;
  assert_int_equal(mr_world_add_particle(w, &p, &a), MR_OK);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = a;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  p.position[0] = 5.5;
  assert_int_equal(mr_world_add_particle(w, &p, &b), MR_OK);
  mr_distance_def d = mr_default_distance_def();
  d.a = a;
  d.b = b;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  mr_step_report rep;
  mr_status s = mr_world_step_to(w, 0.5, &rep);
  mr_stats st;
  mr_world_stats(w, &st);
  printf(
      "ball at the floor beside a pendulum: %d steps in 0.5 s, %llu located, dt %.3g to %.3g s\n",
      rep.steps, (unsigned long long)st.located, st.min_dt, st.max_dt);
  assert_true(s == MR_OK || s == MR_DEPENDENT);
  assert_true(st.located >= 1);
  assert_true(st.min_dt < 0.003); /* the cut */
  /* 2, 4, 8, 16 then 32 ms, held there: about 20 steps, not 125 of 4 ms. */
  assert_true(st.max_dt > 0.6 * def.dt_max);
  assert_true(rep.steps <= 30);
  /* The doubling is over once the step reached the bound: a step then cut
   * short to land keeps the plan, as it does with no contact before. */
  const double plan = mr_world_next_dt(w);
  assert_int_equal(mr_world_step_to(w, mr_world_time(w) + 0.1 * plan, &rep), MR_OK);
  assert_int_equal(rep.rejected, 0);
  assert_true(mr_world_next_dt(w) == plan);
  mr_world_destroy(w);
}

/* Only a taut string is a contact: a spring string stretched past its rest
 * length pulls, and is nothing to locate, even beside a taut one (whose
 * presence has strings swept at all). A weight dropped 10 cm onto a spring
 * string, and bouncing on it, steps as it would alone. */
static void a_stretched_spring_string_is_no_contact(void **state) {
  (void)state;
  uint64_t steps[2] = { 0, 0 };
  for (int with_taut = 0; with_taut < 2; with_taut++) {
    mr_world_def def = mr_default_world_def();
    def.effects = MR_EFFECT_GRAVITY | MR_EFFECT_FRAMES | MR_EFFECT_STRINGS;
    def.contact_slop = SLOP;
    mr_world *w = NULL;
    assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
    mr_frame_def f = mr_default_frame_def();
    f.pose.position[1] = 2.0;
    int frame;
    assert_int_equal(mr_world_add_frame(w, &f, &frame), MR_OK);
    mr_particle_def p = mr_default_particle_def();
    p.frame = frame;
    p.position[1] = 2.0;
    int bar, bob, slack_bar, slack_bob;
    assert_int_equal(mr_world_add_particle(w, &p, &bar), MR_OK);
    p.position[0] = 1.0;
    assert_int_equal(mr_world_add_particle(w, &p, &slack_bar), MR_OK);
    p = mr_default_particle_def();
    p.position[1] = 1.6; /* 0.4 m below the bar on a 0.5 m string */
    assert_int_equal(mr_world_add_particle(w, &p, &bob), MR_OK);
    p.position[0] = 1.0;
    p.position[1] = 1.9; /* 0.1 m below its bar on a 1 m string: slack */
    assert_int_equal(mr_world_add_particle(w, &p, &slack_bob), MR_OK);
    mr_string_def sd = mr_default_string_def();
    sd.frame_particle = bar;
    sd.puppet_particle = bob;
    sd.rest_length = 0.5;
    sd.mode = MR_STRING_SPRING;
    sd.stiffness = 200.0;
    sd.damping = 1.0;
    assert_int_equal(mr_world_add_string(w, &sd, NULL), MR_OK);
    if (with_taut) {
      sd = mr_default_string_def();
      sd.frame_particle = slack_bar;
      sd.puppet_particle = slack_bob;
      sd.rest_length = 1.0;
      assert_int_equal(mr_world_add_string(w, &sd, NULL), MR_OK);
    }
    mr_step_report rep;
    assert_int_equal(mr_world_step_to(w, 0.3, &rep), MR_OK); /* before the slack one is taut */
    mr_stats st;
    mr_world_stats(w, &st);
    printf("spring string %s a slack taut one: %d steps, %llu located\n",
           with_taut ? "beside" : "without", rep.steps, (unsigned long long)st.located);
    assert_int_equal((int)st.located, 0);
    steps[with_taut] = (uint64_t)rep.steps;
    mr_world_destroy(w);
  }
  assert_true(steps[1] == steps[0]);
}

/* A step that lands on the requested time but crosses a contact first is
 * cut there like any other (§4.5), and the call goes on to its target
 * after the impact: a ball reaching the floor at 46.5 ms, stepped to
 * 48 ms at once, is there bouncing up; the cut step is the rule's, not a
 * landing. */
static void a_landing_step_cut_at_a_contact_goes_on_to_the_target(void **state) {
  (void)state;
  mr_world *w = world(MR_EFFECT_PLANES);
  mr_plane_def pl = mr_default_plane_def();
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  const double r = 0.01, v = 17.0;
  p.position[1] = 0.8;
  p.velocity[1] = -v;
  p.radius = r;
  int id;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  const double exact = (0.8 - r) / v, target = 0.048;
  mr_step_report rep;
  assert_int_equal(mr_world_step_to(w, target, &rep), MR_OK);
  double x[3], u[3];
  mr_world_particle_state(w, id, x, u);
  mr_stats st;
  mr_world_stats(w, &st);
  printf(
      "contact at %.4f s inside a landing on %.3f s: %d steps, %d impacts, y %.4g m, v_y %.3g m/s, "
      "dt min %.4g s (rule), %.4g s (landing)\n",
      exact, target, rep.steps, rep.collisions, x[1], u[1], st.min_dt, st.min_dt_landing);
  assert_true(mr_world_time(w) == target);
  assert_int_equal(rep.steps, 2);
  assert_int_equal(rep.collisions, 1);
  assert_true(u[1] > 0.4 * v); /* restitution 0.5, bounced */
  assert_true(fabs(x[1] - (r + u[1] * (target - exact))) < 1e-3);
  assert_true(st.min_dt >= exact - 1e-12 && st.min_dt - exact <= SLOP / v + 1e-12);
  assert_true(st.min_dt_landing < target - exact + 1e-9);
  mr_world_destroy(w);
}

/* A step whose end is far off a taut string's length only because the
 * string's force was not in it is cut to the snap and kept (§7 and §4.5):
 * a bob thrown at 20 m/s from 4 cm to the end of a 5 cm string goes 20 cm
 * past its length in a step of dt_min, four times the rest length and
 * past the divergence bound, yet at the snap it is within it. The string
 * is an over-length, not a depth: nothing reads as penetration. */
static void a_string_snapping_taut_within_a_step_is_no_divergence(void **state) {
  (void)state;
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_FRAMES | MR_EFFECT_STRINGS;
  def.contact_slop = SLOP;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  mr_frame_def f = mr_default_frame_def();
  int frame;
  assert_int_equal(mr_world_add_frame(w, &f, &frame), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  p.frame = frame;
  int bar, bob;
  assert_int_equal(mr_world_add_particle(w, &p, &bar), MR_OK);
  p = mr_default_particle_def();
  p.position[0] = 0.04;
  p.velocity[0] = 20.0;
  assert_int_equal(mr_world_add_particle(w, &p, &bob), MR_OK);
  mr_string_def sd = mr_default_string_def();
  sd.frame_particle = bar;
  sd.puppet_particle = bob;
  sd.rest_length = 0.05;
  assert_int_equal(mr_world_add_string(w, &sd, NULL), MR_OK);
  mr_step_report rep;
  mr_status s = mr_world_step_to(w, 0.05, &rep);
  mr_stats st;
  mr_world_stats(w, &st);
  double x[3];
  mr_world_particle_state(w, bob, x, NULL);
  printf("bob snapping its string: %s, %d steps, %d resets, %llu located, at %.4g m, depth %.3g\n",
         s == MR_OK ? "ok" : mr_world_last_error(w), rep.steps, rep.divergences,
         (unsigned long long)st.located, sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]),
         st.max_penetration);
  assert_int_equal(s, MR_OK);
  assert_int_equal(rep.divergences, 0);
  assert_true(st.located >= 1);
  assert_true(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) <= 0.05 * (1.0 + def.deviation_high));
  assert_true(st.max_penetration == 0.0);
  mr_world_destroy(w);
}

/* What an accepted step leaves deeper than the slop goes into the stats
 * (mr_stats.max_penetration, which `marionette sim` reports and the hard
 * cases bound): a ball put 2 mm into the floor at rest starts its first
 * step that deep, and the stats say so. */
static void a_step_that_starts_deep_counts_its_depth(void **state) {
  (void)state;
  mr_world *w = world(MR_EFFECT_PLANES);
  mr_plane_def pl = mr_default_plane_def();
  assert_int_equal(mr_world_add_plane(w, &pl, NULL), MR_OK);
  mr_particle_def p = mr_default_particle_def();
  p.radius = 0.02;
  p.position[1] = p.radius - 2e-3;
  assert_int_equal(mr_world_add_particle(w, &p, NULL), MR_OK);
  mr_stats st;
  mr_world_stats(w, &st);
  assert_true(st.max_penetration == 0.0);
  assert_int_equal(mr_world_step(w, NULL), MR_OK);
  mr_world_stats(w, &st);
  printf("2 mm into the floor: %.4g m recorded after one step\n", st.max_penetration);
  assert_true(st.max_penetration >= 2e-3 - 1e-12 && st.max_penetration < 3e-3);
  mr_world_destroy(w);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_ball_thrown_at_up_to_40_m_s_never_passes_through_a_thin_sphere),
    cmocka_unit_test(a_ball_thrown_at_the_floor_at_up_to_40_m_s_stops_at_its_surface),
    cmocka_unit_test(the_contact_time_found_is_the_analytic_one),
    cmocka_unit_test(a_fast_puppet_far_from_anything_is_not_slowed),
    cmocka_unit_test(a_contact_is_located_with_few_integrations),
    cmocka_unit_test(after_a_contact_the_step_doubles_while_the_rule_holds_it),
    cmocka_unit_test(a_stretched_spring_string_is_no_contact),
    cmocka_unit_test(a_landing_step_cut_at_a_contact_goes_on_to_the_target),
    cmocka_unit_test(a_string_snapping_taut_within_a_step_is_no_divergence),
    cmocka_unit_test(a_step_that_starts_deep_counts_its_depth),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

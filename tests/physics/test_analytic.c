/* Analytic checks of the solver against closed-form motion: free fall,
 * the small-angle pendulum, the spring–mass oscillator, and bounds on energy
 * and constraint drift over long runs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>

#include "mr_physics.h"

static const double pi = 3.14159265358979323846;

static mr_world *make_world(uint32_t effects) {
  mr_world_def def = mr_default_world_def();
  def.effects = effects;
  mr_world *w = NULL;
  char msg[200];
  assert_int_equal(mr_world_create(&def, &w, msg, sizeof msg), MR_OK);
  return w;
}

static int add(mr_world *w, double x, double y, double z, double mass) {
  mr_particle_def p = mr_default_particle_def();
  p.position[0] = x;
  p.position[1] = y;
  p.position[2] = z;
  p.mass = mass;
  int id = -1;
  assert_int_equal(mr_world_add_particle(w, &p, &id), MR_OK);
  return id;
}

/* RK4 integrates a constant acceleration exactly: x(t) = x0 + v0 t + ½ g t².
 * Only rounding separates the two, whatever steps the ATS takes. */
static void free_fall_is_exact_under_rk4(void **state) {
  (void)state;
  mr_world *w = make_world(MR_EFFECT_GRAVITY);
  int p = add(w, 0.0, 100.0, 0.0, 2.0);
  double v0[3] = { 1.5, 4.0, -0.5 }, x0[3] = { 0.0, 100.0, 0.0 };
  assert_int_equal(mr_world_set_particle_state(w, p, x0, v0), MR_OK);
  double worst = 0.0;
  for (int f = 1; f <= 120; f++) {
    double t = f / 60.0;
    assert_int_equal(mr_world_step_to(w, t, NULL), MR_OK);
    assert_true(mr_world_time(w) == t);
    double x[3], v[3];
    mr_world_particle_state(w, p, x, v);
    double ex[3] = { x0[0] + v0[0] * t, x0[1] + v0[1] * t - 0.5 * 9.81 * t * t, x0[2] + v0[2] * t };
    for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(x[k] - ex[k]));
    assert_true(fabs(v[1] - (v0[1] - 9.81 * t)) < 1e-12);
  }
  printf("free fall: worst position error over 2 s = %.3g m\n", worst);
  assert_true(worst < 1e-12);
  mr_world_destroy(w);
}

/* Period from upward zero crossings of coordinate k of particle p, sampled
 * every `dt` and interpolated linearly between samples. */
static double measure_period(mr_world *w, int p, int k, double dt, double t_end) {
  double prev = 0, t_prev = 0, first = -1, last = -1;
  int crossings = 0;
  mr_world_particle_state(w, p, (double[3]){ 0 }, NULL);
  for (double t = dt; t <= t_end + 1e-12; t += dt) {
    assert_true(mr_world_step_to(w, t, NULL) >= MR_OK);
    double x[3];
    mr_world_particle_state(w, p, x, NULL);
    if (t > dt && prev < 0 && x[k] >= 0) {
      double tc = t_prev + (t - t_prev) * (-prev) / (x[k] - prev);
      if (first < 0) first = tc;
      last = tc;
      crossings++;
    }
    prev = x[k];
    t_prev = t;
  }
  assert_true(crossings >= 2);
  return (last - first) / (crossings - 1);
}

/* A bob on a distance constraint to a pinned particle: T = 2π√(L/g), with
 * the finite-amplitude factor (1 + θ₀²/16) for θ₀ = 0.05 rad (1.6e-4). */
static void small_angle_pendulum_period_within_half_percent(void **state) {
  (void)state;
  mr_world *w = make_world(MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS);
  const double L = 1.0, th = 0.05;
  int pivot = add(w, 0, 0, 0, 1.0);
  int bob = add(w, L * sin(-th), -L * cos(th), 0, 1.0);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = pivot;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  mr_distance_def d = mr_default_distance_def();
  d.a = pivot;
  d.b = bob;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  double T = measure_period(w, bob, 0, 0.05, 20.0); /* 20 Hz: full 0.05 s steps */
  double expect = 2 * pi * sqrt(L / 9.81) * (1 + th * th / 16);
  printf("pendulum: T = %.6f s, expected %.6f s, error %.5f %%\n", T, expect,
         100 * fabs(T - expect) / expect);
  assert_true(fabs(T - expect) / expect < 0.005);
  mr_world_destroy(w);
}

/* A mass on a spring to a pinned particle: T = 2π√(m/k). */
static void spring_mass_period_within_half_percent(void **state) {
  (void)state;
  mr_world *w = make_world(MR_EFFECT_SPRINGS | MR_EFFECT_CONSTRAINTS);
  int anchor = add(w, 0, 0, 0, 1.0);
  int m = add(w, 1.1, 0, 0, 0.5);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = anchor;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  mr_spring_def s = mr_default_spring_def();
  s.a = anchor;
  s.b = m;
  s.rest_length = 1.0;
  s.stiffness = 80.0;
  s.damping = 0.0;
  assert_int_equal(mr_world_add_spring(w, &s, NULL), MR_OK);
  /* Crossings of x − rest: shift by measuring x of the mass minus 1 m. */
  double prev = 0, t_prev = 0, first = -1, last = -1;
  int crossings = 0;
  /* Sampled at 100 Hz, so the steps are 0.01 s (ω·Δt = 0.13). */
  for (double t = 0.01; t <= 10.0; t += 0.01) {
    assert_int_equal(mr_world_step_to(w, t, NULL), MR_OK);
    double x[3];
    mr_world_particle_state(w, m, x, NULL);
    double u = x[0] - 1.0;
    if (t > 0.01 && prev < 0 && u >= 0) {
      double tc = t_prev + (t - t_prev) * (-prev) / (u - prev);
      if (first < 0) first = tc;
      last = tc;
      crossings++;
    }
    prev = u;
    t_prev = t;
  }
  double T = (last - first) / (crossings - 1), expect = 2 * pi * sqrt(0.5 / 80.0);
  printf("spring-mass: T = %.6f s, expected %.6f s, error %.5f %% (%d periods)\n", T, expect,
         100 * fabs(T - expect) / expect, crossings - 1);
  assert_true(crossings > 10);
  assert_true(fabs(T - expect) / expect < 0.005);
  mr_world_destroy(w);
}

static double pendulum_energy(mr_world *w, int bob) {
  double x[3], v[3];
  mr_world_particle_state(w, bob, x, v);
  return 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 9.81 * x[1];
}

/* Without friction the pendulum's energy may only drift by the integrator's
 * and the constraint correction's error: over 10⁴ steps at θ₀ = 0.5 rad
 * we allow 1 % of m g L. */
static void energy_drift_bounded_over_ten_thousand_steps(void **state) {
  (void)state;
  mr_world *w = make_world(MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS);
  int pivot = add(w, 0, 0, 0, 1.0);
  int bob = add(w, sin(0.5), -cos(0.5), 0, 1.0);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = pivot;
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  mr_distance_def d = mr_default_distance_def();
  d.a = pivot;
  d.b = bob;
  assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  double e0 = pendulum_energy(w, bob), worst = 0;
  mr_stats st;
  int frames = 0;
  do {
    frames++;
    assert_int_equal(mr_world_step_to(w, frames / 30.0, NULL), MR_OK);
    worst = fmax(worst, fabs(pendulum_energy(w, bob) - e0));
    mr_world_stats(w, &st);
  } while (st.steps < 10000);
  printf("energy drift: max |E - E0| = %.3g J/kg (m g L = 9.81) over %llu steps, %.1f s\n", worst,
         (unsigned long long)st.steps, mr_world_time(w));
  assert_true(worst < 0.01 * 9.81);
  mr_world_destroy(w);
}

/* A three-link chain hanging from a pin, released from horizontal (a
 * chaotic whip, no friction), for 10⁵ steps. Bounds:
 *  - every step longer than the 0.01 s lower bound ends with its deviation
 *    under the 1 % upper threshold: a step above it is rejected and retried
 *    shorter (that is the ATS's job, so it holds exactly);
 *  - at the lower bound nothing shorter is allowed and a whip can leave a
 *    few percent, which the K_s/K_d correction pulls back within a few
 *    steps: we allow 5 %, a tenth of the 50 % divergence bound;
 *  - the deviation does not accumulate: under 0.1 % at the end;
 *  - the world never diverges. */
static void constraint_drift_bounded_over_hundred_thousand_steps(void **state) {
  (void)state;
  mr_world *w = make_world(MR_EFFECT_GRAVITY | MR_EFFECT_CONSTRAINTS);
  int p[4];
  for (int i = 0; i < 4; i++) p[i] = add(w, 0.5 * i, 0, 0.1 * i, 1.0);
  mr_pin_def pin = mr_default_pin_def();
  pin.particle = p[0];
  assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
  for (int i = 0; i < 3; i++) {
    mr_distance_def d = mr_default_distance_def();
    d.a = p[i];
    d.b = p[i + 1];
    assert_int_equal(mr_world_add_distance(w, &d, NULL), MR_OK);
  }
  mr_stats st;
  double worst_long = 0;
  int at_floor = 0;
  for (int i = 0; i < 100000; i++) {
    assert_int_equal(mr_world_step(w, NULL), MR_OK);
    mr_world_stats(w, &st);
    if (st.last_dt > 0.01)
      worst_long = fmax(worst_long, st.last_error);
    else if (st.last_error > 1e-2)
      at_floor++;
  }
  printf("constraint drift: %llu steps, %.0f s, max deviation %.3g (%.3g on steps above 0.01 s; %d "
         "floor steps over 1 %%), final %.3g, rejected %llu, mean dt %.4f s\n",
         (unsigned long long)st.steps, mr_world_time(w), st.max_error, worst_long, at_floor,
         mr_world_deviation(w), (unsigned long long)st.rejected,
         mr_world_time(w) / (double)st.steps);
  assert_true(worst_long <= 1e-2);
  assert_true(st.max_error < 5e-2);
  assert_true(mr_world_deviation(w) < 1e-3);
  assert_int_equal((int)st.divergences, 0);
  mr_world_destroy(w);
}

/* The accuracy–cost comparison: a frictionless spring–mass (ω = 10/s) for
 * 5 s at a fixed 0.01 s step under each integrator. The relative energy
 * error ranks them as their orders say (explicit Euler grows geometrically,
 * by at least 1 + ω²Δt² per step; semi-implicit Euler stays bounded at O(ωΔt); midpoint
 * grows by O((ωΔt)⁴); RK4 loses O((ωΔt)⁶)), and the cost is their number of
 * force evaluations per step: 1, 1, 2, 4. */
static void integrators_rank_by_accuracy_and_cost(void **state) {
  (void)state;
  const mr_integrator kinds[4] = { MR_INTEGRATOR_EULER, MR_INTEGRATOR_SEMI_IMPLICIT_EULER,
                                   MR_INTEGRATOR_MIDPOINT, MR_INTEGRATOR_RK4 };
  /* Each method's own evaluations. The local error estimate's evaluation
   * at the step's end is the next step's first (integrate.c), so only the
   * last step pays for one more. */
  const int evals[4] = { 1, 1, 2, 4 };
  double err[4];
  for (int i = 0; i < 4; i++) {
    mr_world_def def = mr_default_world_def();
    def.effects = MR_EFFECT_SPRINGS | MR_EFFECT_CONSTRAINTS;
    def.integrator = kinds[i];
    def.dt_floor = def.dt_min = def.dt_max = def.dt_initial = 0.01;
    mr_world *w = NULL;
    assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
    int anchor = add(w, 0, 0, 0, 1.0), m = add(w, 1.1, 0, 0, 1.0);
    mr_pin_def pin = mr_default_pin_def();
    pin.particle = anchor;
    assert_int_equal(mr_world_add_pin(w, &pin, NULL), MR_OK);
    mr_spring_def s = mr_default_spring_def();
    s.a = anchor;
    s.b = m;
    s.rest_length = 1.0;
    s.damping = 0.0;
    assert_int_equal(mr_world_add_spring(w, &s, NULL), MR_OK);
    const double e0 = 0.5 * 100.0 * 0.01;
    assert_int_equal(mr_world_step_to(w, 5.0, NULL), MR_OK);
    double x[3], v[3];
    mr_world_particle_state(w, m, x, v);
    double e =
        0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 0.5 * 100.0 * (x[0] - 1) * (x[0] - 1);
    err[i] = fabs(e - e0) / e0;
    mr_stats st;
    mr_world_stats(w, &st);
    const uint64_t calls = mr_world_pass_calls(w, MR_PASS_SPRINGS);
    printf("%-20s energy error %.3e, %.3f force evaluations per step, %llu steps\n",
           mr_integrator_name(kinds[i]), err[i], (double)calls / (double)st.steps,
           (unsigned long long)st.steps);
    assert_true(calls == (uint64_t)evals[i] * st.steps + 1);
    mr_world_destroy(w);
  }
  assert_true(err[3] < 1e-5);
  assert_true(err[3] < err[2] && err[2] < err[1] && err[1] < err[0]);
  assert_true(err[0] > 10.0);
}

/* Each integrator converges at its order on a time-dependent problem: a
 * 1 kg particle on a spring (k = 100 N/m, rest 1 m) whose other end is a
 * control-frame particle moving at u = 0.5 m/s along x. With z = x − u t − 1,
 * z̈ = −ω² z, z(0) = 0, ż(0) = −u, so x(t) = 1 + u t − (u/ω) sin ωt. The
 * frame is placed at each stage's own time, so a stage evaluated at the
 * wrong time breaks the order. Halving Δt (0.01 → 0.005 → 0.0025 s, fixed)
 * divides the state error at t = 1 s, √(e_x² + (e_v/ω)²), by 2^p: p = 1, 1,
 * 2, 4. */
static double driven_error(mr_integrator kind, double dt) {
  mr_world_def def = mr_default_world_def();
  def.effects = MR_EFFECT_SPRINGS | MR_EFFECT_FRAMES;
  def.integrator = kind;
  def.dt_min = def.dt_max = def.dt_initial = dt;
  mr_world *w = NULL;
  assert_int_equal(mr_world_create(&def, &w, NULL, 0), MR_OK);
  mr_frame_def fd = mr_default_frame_def();
  fd.path = MR_FRAME_LINEAR; /* the drive starts at u at once */
  int frame;
  assert_int_equal(mr_world_add_frame(w, &fd, &frame), MR_OK);
  mr_particle_def pd = mr_default_particle_def();
  pd.frame = frame;
  int end, m;
  assert_int_equal(mr_world_add_particle(w, &pd, &end), MR_OK);
  pd.frame = -1;
  pd.position[0] = 1.0;
  assert_int_equal(mr_world_add_particle(w, &pd, &m), MR_OK);
  mr_spring_def s = mr_default_spring_def();
  s.a = end;
  s.b = m;
  s.stiffness = 100.0;
  s.damping = 0.0;
  assert_int_equal(mr_world_add_spring(w, &s, NULL), MR_OK);
  const double u = 0.5, omega = 10.0, T = 1.0;
  mr_pose pose = mr_pose_identity();
  pose.position[0] = u * 2.0;
  assert_int_equal(mr_world_set_frame_target(w, frame, &pose, 2.0), MR_OK);
  assert_int_equal(mr_world_step_to(w, T, NULL), MR_OK);
  double x[3], v[3];
  mr_world_particle_state(w, m, x, v);
  mr_world_destroy(w);
  double ex = x[0] - (1.0 + u * T - u / omega * sin(omega * T));
  double ev = v[0] - (u - u * cos(omega * T));
  return sqrt(ex * ex + ev * ev / (omega * omega));
}

static void integrators_converge_at_their_order(void **state) {
  (void)state;
  const mr_integrator kinds[4] = { MR_INTEGRATOR_EULER, MR_INTEGRATOR_SEMI_IMPLICIT_EULER,
                                   MR_INTEGRATOR_MIDPOINT, MR_INTEGRATOR_RK4 };
  const double order[4] = { 1, 1, 2, 4 };
  for (int i = 0; i < 4; i++) {
    double e1 = driven_error(kinds[i], 0.01), e2 = driven_error(kinds[i], 0.005),
           e3 = driven_error(kinds[i], 0.0025);
    double p1 = log2(e1 / e2), p2 = log2(e2 / e3);
    printf("%-20s error at 1 s: %.3e, %.3e, %.3e; observed order %.3f, %.3f\n",
           mr_integrator_name(kinds[i]), e1, e2, e3, p1, p2);
    assert_true(fabs(p2 - order[i]) < 0.15);
    assert_true(fabs(p1 - order[i]) < 0.3);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(free_fall_is_exact_under_rk4),
    cmocka_unit_test(small_angle_pendulum_period_within_half_percent),
    cmocka_unit_test(spring_mass_period_within_half_percent),
    cmocka_unit_test(energy_drift_bounded_over_ten_thousand_steps),
    cmocka_unit_test(constraint_drift_bounded_over_hundred_thousand_steps),
    cmocka_unit_test(integrators_rank_by_accuracy_and_cost),
    cmocka_unit_test(integrators_converge_at_their_order),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

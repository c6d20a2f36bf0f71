/* Item 2: the stick marionette in our engine and in MuJoCo, side by side
 * in one process. Each engine runs at the cheapest of its settings that
 * meets one bar on every track: stable, its strings at most 1 % over
 * length, and the end effector within 1 % of a limb's length of its own
 * converged reference (or twice what halving that reference's step moves
 * it, where that is more) over the horizon: the whole 10 s gentle sway,
 * the first 0.5 s of the rapid Fig. 10 track, which is chaotic later (over
 * 2 s, halving either reference's step moved its hand 0.5-0.8 m, and the
 * bar asked for nothing but stability). The
 * chosen pair is then timed again, interleaved, and the ratio of CPU per
 * simulated second printed.
 * Built only where MuJoCo is (MR_BENCH_MUJOCO). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "peer.h"

#ifdef MR_BENCH_MUJOCO
#include <mujoco/mujoco.h>

typedef struct mj_run {
  double cpu, sim, over, *ee;
  int ee_n, stable;
} mj_run;

/* The bar's pose from our scene's own track, so both follow one track. */
static void bar_pose(const mr_scene *sc, double t, mjData *d) {
  mr_pose p;
  mr_scene_frame_pose_at(sc, 0, t, &p);
  for (int k = 0; k < 3; k++) d->mocap_pos[k] = p.position[k];
  for (int k = 0; k < 4; k++) d->mocap_quat[k] = p.orientation[k];
}

static mjModel *mj_model(const bench *b, const peer_mj_setting *s) {
  char path[1024], err[512] = "";
  snprintf(path, sizeof path, "%s/peer.xml", b->out);
  char *xml = peer_mjcf(s);
  FILE *f = xml ? fopen(path, "w") : NULL;
  if (f != NULL) {
    fputs(xml, f);
    fclose(f);
  }
  free(xml);
  mjModel *m = f ? mj_loadXML(path, NULL, err, sizeof err) : NULL;
  if (m == NULL) fprintf(stderr, "marionette-bench: MuJoCo: %s\n", err);
  return m;
}

/* The hand's position at each 60 Hz frame up to the horizon,
 * interpolated between the steps around it. */
static void record(mj_run *r, double t0, const double *p0, double t1, const double *p1,
                   double horizon) {
  for (;;) {
    double tf = (r->ee_n + 1) / 60.0;
    if (tf > t1 + 1e-12 || tf > horizon + 1e-9) return;
    double *q = realloc(r->ee, (size_t)(r->ee_n + 1) * 3 * sizeof *q);
    if (q == NULL) return;
    r->ee = q;
    double s = t1 > t0 ? (tf - t0) / (t1 - t0) : 1.0;
    for (int k = 0; k < 3; k++) q[3 * r->ee_n + k] = p0[k] + s * (p1[k] - p0[k]);
    r->ee_n++;
  }
}

/* Drag −c v at every point mass, as a force and a torque about its
 * body's centre of mass (MuJoCo has no drag of its own that matches). */
static void mj_drag(const mjModel *m, mjData *d, const int *sites, int n) {
  mju_zero(d->xfrc_applied, 6 * m->nbody);
  for (int i = 0; i < n; i++) {
    double vel[6], f[3], r[3];
    int body = m->site_bodyid[sites[i]];
    mj_objectVelocity(m, d, mjOBJ_SITE, sites[i], vel, 0);
    for (int k = 0; k < 3; k++) {
      f[k] = -PEER_DRAG * vel[3 + k];
      r[k] = d->site_xpos[3 * sites[i] + k] - d->xipos[3 * body + k];
    }
    double *x = &d->xfrc_applied[6 * body];
    for (int k = 0; k < 3; k++) x[k] += f[k];
    x[3] += r[1] * f[2] - r[2] * f[1];
    x[4] += r[2] * f[0] - r[0] * f[2];
    x[5] += r[0] * f[1] - r[1] * f[0];
  }
}

static int mj_simulate(const bench *b, const peer_mj_setting *s, const mr_scene *sc,
                       double duration, double horizon, mj_run *r) {
  memset(r, 0, sizeof *r);
  mjModel *m = mj_model(b, s);
  if (m == NULL) return -1;
  mjData *d = mj_makeData(m);
  int hand = mj_name2id(m, mjOBJ_SITE, "p_hand_l"), sites[64], ns = peer_point_count();
  for (int i = 0; i < ns; i++) {
    char name[64];
    snprintf(name, sizeof name, "p_%s", peer_point_name(i));
    sites[i] = mj_name2id(m, mjOBJ_SITE, name);
  }
  long steps = lround(duration / s->dt);
  double t0 = bench_cpu_seconds(), prev[3];
  mj_forward(m, d);
  memcpy(prev, &d->site_xpos[3 * hand], sizeof prev);
  r->stable = 1;
  for (long i = 0; i < steps && r->stable; i++) {
    double before = d->time;
    bar_pose(sc, d->time + s->dt, d);
    mj_drag(m, d, sites, ns);
    mj_step(m, d);
    record(r, before, prev, d->time, &d->site_xpos[3 * hand], horizon);
    memcpy(prev, &d->site_xpos[3 * hand], sizeof prev);
    for (int k = 0; k < m->ntendon; k++) {
      double lim = m->tendon_range[2 * k + 1];
      r->over = fmax(r->over, (d->ten_length[k] - lim) / lim);
    }
    for (int k = 0; k < m->nq; k++) r->stable &= isfinite(d->qpos[k]);
    r->stable &= d->warning[mjWARN_BADQACC].number == 0;
  }
  r->cpu = bench_cpu_seconds() - t0;
  r->sim = d->time;
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}

static void ee_error(const double *a, int na, const double *b, int nb, double *max) {
  int n = na < nb ? na : nb;
  *max = n > 0 ? 0.0 : NAN;
  for (int i = 0; i < n; i++) {
    double d2 = 0;
    for (int k = 0; k < 3; k++) d2 += (a[3 * i + k] - b[3 * i + k]) * (a[3 * i + k] - b[3 * i + k]);
    if (!(sqrt(d2) <= *max)) *max = sqrt(d2);
  }
}
#endif

#ifdef MR_BENCH_MUJOCO
/* Our settings, each one a scene could set (physics.time_step and
 * physics.solver): the ATS thresholds (the lower is 1/100 of the upper),
 * the local error estimate on or off, the bounds, the integrator, or a
 * fixed step. As broad as MuJoCo's list below (steps, limit softness):
 * an engine offered fewer settings cannot show its cheapest. */
typedef struct ours_setting {
  double high;           /* upper threshold */
  int estimate;          /* the local error estimate (error_length, error_speed) */
  double dt_min, dt_max; /* s; 0: the scene's (0.01–0.05 s, §7) */
  double fixed;          /* s; > 0: fixed steps of this length */
  mr_integrator integrator;
} ours_setting;
#define RK4 MR_INTEGRATOR_RK4
#define SIE MR_INTEGRATOR_SEMI_IMPLICIT_EULER
#define MID MR_INTEGRATOR_MIDPOINT
static const ours_setting ours[] = {
  /* the scene's bounds */
  { 1e-1, 0, 0, 0, 0, RK4 },
  { 1e-1, 1, 0, 0, 0, RK4 },
  { 1e-2, 0, 0, 0, 0, RK4 }, /* the paper's */
  { 1e-2, 1, 0, 0, 0, RK4 }, /* the default */
  { 1e-3, 1, 0, 0, 0, RK4 },
  { 1e-4, 1, 0, 0, 0, RK4 },
  /* shorter bounds */
  { 1e-1, 0, 0.005, 0.02, 0, RK4 },
  { 1e-1, 1, 0.005, 0.02, 0, RK4 },
  { 1e-2, 0, 0.005, 0.02, 0, RK4 },
  { 1e-2, 1, 0.005, 0.02, 0, RK4 },
  { 1e-3, 1, 0.005, 0.02, 0, RK4 },
  { 1e-1, 0, 0.002, 0.01, 0, RK4 },
  { 1e-1, 1, 0.002, 0.01, 0, RK4 },
  { 1e-2, 0, 0.002, 0.01, 0, RK4 },
  { 1e-2, 1, 0.002, 0.01, 0, RK4 },
  { 1e-3, 1, 0.002, 0.01, 0, RK4 },
  { 1e-1, 0, 0.001, 0.005, 0, RK4 },
  { 1e-2, 0, 0.001, 0.005, 0, RK4 },
  { 1e-2, 1, 0.001, 0.005, 0, RK4 },
  /* fixed steps */
  { 1e-2, 0, 0, 0, 0.02, RK4 },
  { 1e-2, 0, 0, 0, 0.01, RK4 },
  { 1e-2, 0, 0, 0, 0.005, RK4 },
  { 1e-2, 0, 0, 0, 0.0025, RK4 },
  { 1e-2, 0, 0, 0, 0.00125, RK4 },
  /* the cheaper integrators */
  { 1e-1, 0, 0.005, 0.02, 0, SIE },
  { 1e-1, 0, 0.002, 0.01, 0, SIE },
  { 1e-1, 0, 0.005, 0.02, 0, MID },
  { 1e-1, 0, 0.002, 0.01, 0, MID },
};
#undef RK4
#undef SIE
#undef MID
enum { N_OURS = sizeof ours / sizeof ours[0] };

static void ours_label(const ours_setting *o, char *out, size_t n) {
  const char *integ = mr_integrator_name(o->integrator);
  if (o->fixed > 0) {
    snprintf(out, n, "%s, fixed %g ms", integ, 1e3 * o->fixed);
    return;
  }
  char bounds[48] = "";
  if (o->dt_max > 0)
    snprintf(bounds, sizeof bounds, ", %g-%g ms", 1e3 * o->dt_min, 1e3 * o->dt_max);
  snprintf(out, n, "%s, thresholds %g..%g%s%s", integ, o->high / 100, o->high,
           o->estimate ? "" : ", no estimate", bounds);
}

typedef struct pick {
  char label[96];
  double cost_ms, hand, over, violation; /* hand: end-effector error; over: string over-length */
  int ok, index;
} pick;

static int peer_scene_load(const peer_track *tr, mr_scene *sc) {
  size_t len;
  char *text = peer_scene(tr, &len);
  mr_scene_error err;
  int rc = text && mr_scene_load_text("peer", text, len, sc, &err) == MR_SCENE_OK ? 0 : -1;
  if (rc != 0) fprintf(stderr, "marionette-bench: peer scene: %s\n", text ? err.text : "no memory");
  free(text);
  return rc;
}

static int ours_run(const mr_scene *base, const ours_setting *o, double duration, double horizon,
                    bench_run *run) {
  mr_scene sc = *base;
  mr_world_def *w = &sc.world;
  w->deviation_high = o->high;
  w->deviation_low = o->high / 100.0;
  if (!o->estimate) w->error_length = w->error_speed = 0.0;
  w->integrator = o->integrator;
  if (o->dt_max > 0) {
    w->dt_min = o->dt_min;
    w->dt_max = o->dt_max;
    w->dt_initial = fmin(fmax(w->dt_initial, o->dt_min), o->dt_max);
  }
  if (o->fixed > 0) w->dt_initial = w->dt_min = w->dt_max = w->dt_floor = o->fixed;
  return bench_run_scene(&sc, duration, (size_t)peer_effector(), horizon, run);
}

/* MuJoCo's own integrator (Euler; its RK4 measured 2-4x the cost for no
 * less over-length), the step, and the tendon limit's softness: the
 * default time constant or twice the step, the default impedance or 0.99. */
static peer_mj_setting mj_setting(int i) {
  static const double dts[] = { 0.01, 0.005, 0.002, 0.001, 0.0005, 0.00025, 0.000125 };
  peer_mj_setting s = { dts[i / 4], i % 2 ? 2 * dts[i / 4] : 0.02, 0, (i / 2) % 2 };
  return s;
}
enum { N_MJ = 28 };

static void mj_label(const peer_mj_setting *s, char *out, size_t n) {
  snprintf(out, n, "dt %g ms, limit %g ms%s", 1e3 * s->dt, 1e3 * s->timeconst,
           s->hard ? ", impedance 0.99" : "");
}
#endif

#ifdef MR_BENCH_MUJOCO
static void keep_cheapest(pick *p, const char *label, int index, double cost, double hand,
                          double over, double violation, int ok) {
  if (!ok || (p->ok && p->cost_ms <= cost)) return;
  snprintf(p->label, sizeof p->label, "%s", label);
  p->index = index, p->cost_ms = cost, p->hand = hand, p->over = over;
  p->violation = violation, p->ok = 1;
}

static int ours_fixed(const mr_scene *base, double h, double T, bench_run *run) {
  mr_scene sc = *base;
  sc.world.integrator = MR_INTEGRATOR_RK4;
  sc.world.dt_initial = sc.world.dt_min = sc.world.dt_max = sc.world.dt_floor = h;
  return bench_run_scene(&sc, T, (size_t)peer_effector(), T, run);
}

/* Each engine's cheapest setting meeting the track's bar: strings at most
 * 1 % over length, and the end effector within tol of the engine's own
 * reference over the horizon H (the whole gentle track; the first 0.5 s of
 * the rapid one, which is chaotic further on, so no reference resolves it). */
static void search(bench *b, const mr_scene *sc, double T, double H, int gentle, pick *po,
                   pick *pm) {
  const double tol = 0.01 * peer_limb_length();
  bench_run ref = { 0 }, half = { 0 };
  mj_run mref = { 0 }, mhalf = { 0 };
  peer_mj_setting r1 = { 2.5e-4, 5e-4, 1, 1 }, r2 = { 1.25e-4, 2.5e-4, 1, 1 };
  double bar_o = tol, bar_m = tol;
  bench_progress("peer", "%s: references", gentle ? "gentle" : "rapid");
  ours_fixed(sc, 1e-3, H, &half);
  ours_fixed(sc, 5e-4, H, &ref);
  mj_simulate(b, &r1, sc, H, H, &mhalf);
  mj_simulate(b, &r2, sc, H, H, &mref);
  double e1, e2;
  bench_ee_error(&half, &ref, &e1, &(double){ 0 });
  ee_error(mhalf.ee, mhalf.ee_n, mref.ee, mref.ee_n, &e2);
  /* A bar below what halving the reference's step moves it by cannot
   * be told from noise: it is raised to twice that, and said. */
  bar_o = fmax(tol, 2 * e1), bar_m = fmax(tol, 2 * e2);
  bench_say(b,
            "references over %g s: halving the step moves the hand %.2e m (ours, RK4 0.5 ms), "
            "%.2e m (MuJoCo, RK4 0.125 ms); 1 %% of a limb is %.2e m; bars: ours %.2e m, "
            "MuJoCo %.2e m\n",
            H, e1, e2, tol, bar_o, bar_m);
  for (int i = 0; i < N_OURS; i++) {
    bench_run run;
    char label[96];
    ours_label(&ours[i], label, sizeof label);
    bench_progress("peer", "%s: ours, %s", gentle ? "gentle" : "rapid", label);
    if (ours_run(sc, &ours[i], T, H, &run) != 0) continue;
    double e = NAN, over = run.r.string_stretch - 1.0;
    bench_ee_error(&run, &ref, &e, &(double){ 0 });
    int ok = run.r.finite && run.r.resets == 0 && e <= bar_o && over <= 0.01 &&
             run.r.max_deviation <= 0.01;
    bench_progress("peer",
                   "  %.3f ms/sim-s, %d steps, %d rejected, hand error %.2e, over-length %.2e%s",
                   1e3 * run.cpu / run.r.sim_time, (int)run.r.steps, (int)run.r.rejected, e, over,
                   run.r.resets ? ", RESETS" : "");
    keep_cheapest(po, label, i, 1e3 * run.cpu / run.r.sim_time, e, over,
                  fmax(run.r.max_deviation, over), ok);
    bench_run_free(&run);
  }
  for (int i = 0; i < N_MJ; i++) {
    peer_mj_setting s = mj_setting(i);
    char label[96];
    mj_label(&s, label, sizeof label);
    bench_progress("peer", "%s: MuJoCo, %s", gentle ? "gentle" : "rapid", label);
    mj_run r;
    if (mj_simulate(b, &s, sc, T, H, &r) != 0) continue;
    double e = NAN;
    ee_error(r.ee, r.ee_n, mref.ee, mref.ee_n, &e);
    int ok = r.stable && e <= bar_m && r.over <= 0.01;
    bench_progress("peer", "  %.3f ms/sim-s, hand error %.2e, over-length %.2e, %s",
                   1e3 * r.cpu / r.sim, e, r.over, r.stable ? "stable" : "UNSTABLE");
    keep_cheapest(pm, label, i, 1e3 * r.cpu / r.sim, e, r.over, r.over, ok);
    free(r.ee);
  }
  bench_run_free(&ref);
  bench_run_free(&half);
  free(mref.ee);
  free(mhalf.ee);
}
#endif

#ifdef MR_BENCH_MUJOCO
/* The two picks timed again in turns, three rounds, the fastest of each:
 * the ratio is measured in one process, on the same load. */
static double interleaved(bench *b, const mr_scene *sc, double T, const pick *po, const pick *pm) {
  double best_o = INFINITY, best_m = INFINITY;
  peer_mj_setting s = mj_setting(pm->index);
  for (int round = 0; round < 3; round++) {
    bench_run run;
    if (ours_run(sc, &ours[po->index], T, 0, &run) == 0)
      best_o = fmin(best_o, run.cpu / run.r.sim_time);
    bench_run_free(&run);
    mj_run r;
    if (mj_simulate(b, &s, sc, T, 0, &r) == 0) best_m = fmin(best_m, r.cpu / r.sim);
    free(r.ee);
  }
  return best_o / best_m;
}

static int track(bench *b, const char *name, const peer_track *tr, double T, double H, int gentle) {
  mr_scene sc;
  if (peer_scene_load(tr, &sc) != 0) return -1;
  pick po = { .ok = 0 }, pm = { .ok = 0 };
  bench_say(b,
            "\n%s track, %g s: cheapest setting that stays stable with its strings at most 1 %% "
            "over length (ours: and its links within 1 %%, as MuJoCo's joints are exact) and the "
            "hand within the bar of its own reference over %g s\n",
            name, T, H);
  search(b, &sc, T, H, gentle, &po, &pm);
  const pick *p[2] = { &po, &pm };
  const char *who[2] = { "ours", "MuJoCo 2.2.2" };
  for (int k = 0; k < 2; k++) {
    if (!p[k]->ok) {
      bench_say(b, "  %-13s no setting met the bar\n", who[k]);
      continue;
    }
    bench_say(b,
              "  %-13s %-46s %8.3f ms/sim-s  hand error %.2e  over-length %.2e  worst violation "
              "%.2e  stable\n",
              who[k], p[k]->label, p[k]->cost_ms, p[k]->hand, p[k]->over, p[k]->violation);
  }
  if (po.ok && pm.ok)
    bench_say(b, "  CPU per simulated second, ours / MuJoCo, interleaved in one process: %.2f\n",
              interleaved(b, &sc, T, &po, &pm));
  mr_scene_free(&sc);
  return 0;
}
#endif

#ifdef MR_BENCH_MUJOCO
/* MuJoCo prints its warnings; the runs count them (mjWARN_BADQACC). */
static void mj_quiet(const char *msg) {
  (void)msg;
}
#endif

int bench_peer(bench *b) {
#ifdef MR_BENCH_MUJOCO
  mju_user_warning = mj_quiet;
  bench_say(b,
            "\n== our engine against MuJoCo %s (item 2), the stick marionette of Fig. 10 "
            "from one description (tools/marionette-bench/peer_model.c) ==\n",
            mj_versionString());
  const peer_track gentle = { { 0.1, 0, 0 }, 10, 0.5, 1 };
  const peer_track rapid = { { 0, 0.3, 0 }, 0, 3, 1 };
  double T = b->quick ? 2 : 10;
  int rc = track(b, "gentle (0.5 Hz sway)", &gentle, T, T, 1);
  if (track(b, "rapid (Fig. 10: 3 Hz, 0.3 m vertical)", &rapid, b->quick ? 2 : 60, 0.5, 0) != 0)
    rc = -1;
  return rc;
#else
  bench_say(b, "\n== MuJoCo peer (item 2): not built (libmujoco-dev was not found) ==\n");
  return 0;
#endif
}

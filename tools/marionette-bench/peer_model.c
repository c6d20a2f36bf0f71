/* Item 2: one description of the stick marionette, from which both our
 * scene and MuJoCo's model are generated, so the two cannot drift apart.
 * The puppet is Fig. 10's (hard case 01) made of rigid bodies joined at
 * shared points: a torso and a head (rigid groups sharing the neck), and
 * two-link arms and legs. Its seven strings hold their length (our taut
 * mode; MuJoCo's spatial tendons limited to [0, L]). Drag, −c v on every
 * point mass, is ours as it is and MuJoCo's as applied forces (peer.c):
 * without it the two-link limbs swing on undamped and chaotically, and no
 * two runs agree for long. No antigravity: MuJoCo has none. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "peer.h"

typedef struct pt {
  const char *name;
  double p[3], m;
} pt;
static const pt points[] = {
  { "neck", { 0.00, 0.62, 0.00 }, 0.08 },       { "shoulder_l", { -0.12, 0.56, 0.00 }, 0.15 },
  { "shoulder_r", { 0.12, 0.56, 0.00 }, 0.15 }, { "chest", { 0.00, 0.46, 0.06 }, 0.15 },
  { "hip_l", { -0.08, 0.32, 0.00 }, 0.12 },     { "hip_r", { 0.08, 0.32, 0.00 }, 0.12 },
  { "head_top", { 0.00, 0.80, 0.00 }, 0.10 },   { "nose", { 0.00, 0.71, 0.07 }, 0.06 },
  { "ear_l", { -0.06, 0.71, 0.00 }, 0.06 },     { "elbow_l", { -0.15, 0.42, 0.00 }, 0.06 },
  { "hand_l", { -0.16, 0.28, 0.02 }, 0.08 },    { "elbow_r", { 0.15, 0.42, 0.00 }, 0.06 },
  { "hand_r", { 0.16, 0.28, 0.02 }, 0.08 },     { "knee_l", { -0.08, 0.18, 0.01 }, 0.08 },
  { "foot_l", { -0.08, 0.04, 0.00 }, 0.08 },    { "knee_r", { 0.08, 0.18, 0.01 }, 0.08 },
  { "foot_r", { 0.08, 0.04, 0.00 }, 0.08 },
};
enum { N_POINTS = sizeof points / sizeof points[0] };

/* Bodies: the joint point (shared with the parent; the torso has none),
 * then the points whose mass the body carries. */
typedef struct body {
  const char *name;
  int parent, joint, first, count;
} body;
static const body bodies[] = {
  { "torso", -1, -1, 0, 6 },    { "head", 0, 0, 6, 3 },         { "upper_arm_l", 0, 1, 9, 1 },
  { "forearm_l", 2, 9, 10, 1 }, { "upper_arm_r", 0, 2, 11, 1 }, { "forearm_r", 4, 11, 12, 1 },
  { "thigh_l", 0, 4, 13, 1 },   { "shin_l", 6, 13, 14, 1 },     { "thigh_r", 0, 5, 15, 1 },
  { "shin_r", 8, 15, 16, 1 },
};
enum { N_BODIES = sizeof bodies / sizeof bodies[0] };

typedef struct str {
  const char *bar;
  double offset[3];
  int to;
} str;
static const str strings[] = {
  { "bar_head", { 0.00, 0, 0.00 }, 6 },       { "bar_shoulder_l", { -0.12, 0, 0.00 }, 1 },
  { "bar_shoulder_r", { 0.12, 0, 0.00 }, 2 }, { "bar_hand_l", { -0.25, 0, 0.06 }, 10 },
  { "bar_hand_r", { 0.25, 0, 0.06 }, 12 },    { "bar_knee_l", { -0.08, 0, 0.15 }, 13 },
  { "bar_knee_r", { 0.08, 0, 0.15 }, 15 },
};
enum { N_STRINGS = sizeof strings / sizeof strings[0] };
static const double bar_at[3] = { 0, 1.25, 0 };

int peer_effector(void) {
  return 10; /* hand_l */
}

double peer_limb_length(void) {
  const double *a = points[1].p, *b = points[9].p; /* shoulder_l to elbow_l */
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}

int peer_string_count(void) {
  return N_STRINGS;
}

int peer_point_count(void) {
  return N_POINTS;
}

const char *peer_point_name(int i) {
  return points[i].name;
}

/* A growing text buffer. */
typedef struct text {
  char *s;
  size_t n, cap;
} text;
static void put(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(text *t, const char *fmt, ...) {
  for (;;) {
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(t->s ? t->s + t->n : NULL, t->s ? t->cap - t->n : 0, fmt, ap);
    va_end(ap);
    if (k < 0) return;
    if (t->s && t->n + (size_t)k < t->cap) {
      t->n += (size_t)k;
      return;
    }
    size_t cap = (t->cap + (size_t)k + 1) * 2;
    char *p = realloc(t->s, cap);
    if (p == NULL) return;
    t->s = p;
    t->cap = cap;
  }
}

char *peer_scene(const peer_track *tr, size_t *len) {
  text t = { 0 };
  put(&t,
      "format: 1\nname: peer stick marionette\nphysics:\n"
      "  effects: [gravity, drag, constraints, strings, control]\n  drag: %g\n  particles:\n",
      PEER_DRAG);
  for (int i = 0; i < N_POINTS; i++)
    put(&t, "    - {name: %s, position: [%g, %g, %g], mass: %g}\n", points[i].name, points[i].p[0],
        points[i].p[1], points[i].p[2], points[i].m);
  put(&t, "  groups:\n    - {name: torso, particles: [neck, shoulder_l, shoulder_r, chest, hip_l, "
          "hip_r]}\n    - {name: head, particles: [neck, head_top, nose, ear_l]}\n"
          "  constraints:\n");
  for (int b = 2; b < N_BODIES; b++)
    put(&t, "    - {between: [%s, %s]}\n", points[bodies[b].joint].name,
        points[bodies[b].first].name);
  put(&t, "  control:\n    pose: {position: [%g, %g, %g]}\n    points:\n", bar_at[0], bar_at[1],
      bar_at[2]);
  for (int s = 0; s < N_STRINGS; s++)
    put(&t, "      - {name: %s, offset: [%g, %g, %g]}\n", strings[s].bar, strings[s].offset[0],
        strings[s].offset[1], strings[s].offset[2]);
  put(&t,
      "    track: {oscillate: {amplitude: [%g, %g, %g], rotation: [0, 0, %g], frequency: %g, "
      "ramp: %g}}\n  strings:\n",
      tr->amplitude[0], tr->amplitude[1], tr->amplitude[2], tr->roll_deg, tr->frequency, tr->ramp);
  for (int s = 0; s < N_STRINGS; s++)
    put(&t, "    - {from: %s, to: %s, mode: taut}\n", strings[s].bar, points[strings[s].to].name);
  *len = t.n;
  return t.s;
}

/* Absolute origin of body b's frame: its joint point (the world's origin
 * for the torso, which floats). */
static void origin(int b, double o[3]) {
  for (int k = 0; k < 3; k++) o[k] = bodies[b].joint < 0 ? 0.0 : points[bodies[b].joint].p[k];
}

/* Mass, centre and inertia about the centre (xx yy zz xy xz yz) of the
 * point masses a body carries, in its frame; a floor of 1e-6 kg·m² keeps
 * a one-point body's inertia positive. */
static void inertial(int b, double *m, double c[3], double in[6]) {
  double o[3];
  origin(b, o);
  *m = 0;
  memset(c, 0, 3 * sizeof *c);
  memset(in, 0, 6 * sizeof *in);
  for (int i = bodies[b].first; i < bodies[b].first + bodies[b].count; i++) {
    *m += points[i].m;
    for (int k = 0; k < 3; k++) c[k] += points[i].m * (points[i].p[k] - o[k]);
  }
  for (int k = 0; k < 3; k++) c[k] /= *m;
  for (int i = bodies[b].first; i < bodies[b].first + bodies[b].count; i++) {
    double r[3], m_i = points[i].m;
    for (int k = 0; k < 3; k++) r[k] = points[i].p[k] - o[k] - c[k];
    in[0] += m_i * (r[1] * r[1] + r[2] * r[2]);
    in[1] += m_i * (r[0] * r[0] + r[2] * r[2]);
    in[2] += m_i * (r[0] * r[0] + r[1] * r[1]);
    in[3] -= m_i * r[0] * r[1];
    in[4] -= m_i * r[0] * r[2];
    in[5] -= m_i * r[1] * r[2];
  }
  for (int k = 0; k < 3; k++) in[k] += 1e-6;
}

static void mjcf_body(text *t, int b, int depth) {
  double o[3], po[3], m, c[3], in[6];
  origin(b, o);
  if (bodies[b].parent >= 0)
    origin(bodies[b].parent, po);
  else
    po[0] = po[1] = po[2] = 0;
  inertial(b, &m, c, in);
  put(t, "%*s<body name=\"%s\" pos=\"%g %g %g\">\n", depth, "", bodies[b].name, o[0] - po[0],
      o[1] - po[1], o[2] - po[2]);
  put(t, "%*s<%s/>\n", depth + 1, "", bodies[b].parent < 0 ? "freejoint" : "joint type=\"ball\"");
  put(t,
      "%*s<inertial pos=\"%.9g %.9g %.9g\" mass=\"%g\" fullinertia=\"%.9g %.9g %.9g %.9g %.9g "
      "%.9g\"/>\n",
      depth + 1, "", c[0], c[1], c[2], m, in[0], in[1], in[2], in[3], in[4], in[5]);
  for (int i = bodies[b].first; i < bodies[b].first + bodies[b].count; i++) {
    const double *p = points[i].p;
    put(t, "%*s<geom type=\"capsule\" fromto=\"0 0 0 %g %g %g\"/>\n", depth + 1, "", p[0] - o[0],
        p[1] - o[1], p[2] - o[2]);
    put(t, "%*s<site name=\"p_%s\" pos=\"%g %g %g\"/>\n", depth + 1, "", points[i].name,
        p[0] - o[0], p[1] - o[1], p[2] - o[2]);
  }
  for (int k = 0; k < N_BODIES; k++)
    if (bodies[k].parent == b) mjcf_body(t, k, depth + 1);
  put(t, "%*s</body>\n", depth, "");
}

char *peer_mjcf(const peer_mj_setting *s) {
  text t = { 0 };
  put(&t,
      "<mujoco model=\"peer stick marionette\">\n <compiler inertiafromgeom=\"false\"/>\n"
      " <option timestep=\"%g\" gravity=\"0 -9.81 0\" integrator=\"%s\"/>\n"
      " <default><geom contype=\"0\" conaffinity=\"0\" size=\"0.01\"/></default>\n"
      " <worldbody>\n  <body name=\"bar\" mocap=\"true\" pos=\"%g %g %g\">\n",
      s->dt, s->rk4 ? "RK4" : "Euler", bar_at[0], bar_at[1], bar_at[2]);
  for (int k = 0; k < N_STRINGS; k++)
    put(&t, "   <site name=\"%s\" pos=\"%g %g %g\"/>\n", strings[k].bar, strings[k].offset[0],
        strings[k].offset[1], strings[k].offset[2]);
  put(&t, "  </body>\n");
  mjcf_body(&t, 0, 2);
  put(&t, " </worldbody>\n <tendon>\n");
  for (int k = 0; k < N_STRINGS; k++) {
    const double *p = points[strings[k].to].p;
    double d[3];
    for (int j = 0; j < 3; j++) d[j] = p[j] - bar_at[j] - strings[k].offset[j];
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    put(&t,
        "  <spatial name=\"t%d\" limited=\"true\" range=\"0 %.9g\" solreflimit=\"%g 1\"%s>"
        "<site site=\"%s\"/><site site=\"p_%s\"/></spatial>\n",
        k, len, s->timeconst, s->hard ? " solimplimit=\"0.99 0.999 0.001\"" : "", strings[k].bar,
        points[strings[k].to].name);
  }
  put(&t, " </tendon>\n</mujoco>\n");
  return t.s;
}

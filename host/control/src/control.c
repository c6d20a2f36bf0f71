/* Five values to the control frame's pose (§3.2: "the five degrees of
 * freedom ... the rotation axes, the vertical axis and forward/backward";
 * §6.2, method 1: the frame is moved to the input pose and the strings do
 * the rest). Each channel: clamp to 0..1, check, smooth (One Euro), dead
 * zone about neutral, then the axis's linear range. The turns compose in
 * the frame's own axes, x first, then y, then z, as a scene's Euler angles
 * do, on top of the neutral pose. */
#include "mr_control.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct mr_control {
  mr_mapping_def maps[MR_CONTROL_MAX_MAPPINGS];
  int n, selected;
  mr_one_euro filter[MR_CONTROL_CHANNELS];
  double smoothed[MR_CONTROL_CHANNELS];
  double at_end_since[MR_CONTROL_CHANNELS]; /* when a channel reached 0 or 1; NAN if not there */
  double last_t;
  bool started;
};

static const char *const dof_names[MR_DOF_COUNT] = { "turn_x", "turn_y", "turn_z",
                                                     "move_x", "move_y", "move_z" };

const char *mr_dof_name(mr_dof d) {
  return (int)d >= 0 && d < MR_DOF_COUNT ? dof_names[d] : "unknown";
}

int mr_dof_parse(const char *name, mr_dof *out) {
  for (int d = 0; name != NULL && d < MR_DOF_COUNT; d++)
    if (strcmp(name, dof_names[d]) == 0) {
      *out = (mr_dof)d;
      return 0;
    }
  return -1;
}

const char *mr_channel_state_name(mr_channel_state s) {
  switch (s) {
  case MR_CHANNEL_OK:
    return "ok";
  case MR_CHANNEL_NOT_FINITE:
    return "not a number";
  case MR_CHANNEL_STUCK:
    return "stuck at an end";
  }
  return "unknown";
}

static mr_axis_def axis(int channel, double low, double high) {
  mr_axis_def a = { channel, low, high, false, 0.5, 0.02 };
  return a;
}

mr_mapping_def mr_default_mapping_def(void) {
  mr_mapping_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  snprintf(d.name, sizeof d.name, "default");
  d.neutral = mr_pose_identity();
  d.axes[MR_DOF_TURN_Z] = axis(0, -30, 30);
  d.axes[MR_DOF_TURN_X] = axis(1, -30, 30);
  d.axes[MR_DOF_TURN_Y] = axis(2, -45, 45);
  d.axes[MR_DOF_MOVE_Y] = axis(3, -0.15, 0.15);
  d.axes[MR_DOF_MOVE_Z] = axis(4, -0.2, 0.2);
  d.axes[MR_DOF_MOVE_X] = axis(-1, -0.15, 0.15); /* not driven; its range if it is */
  d.min_cutoff = 1.0;
  d.beta = 0.7;
  d.d_cutoff = 1.0;
  d.stuck_after = 2.0;
  return d;
}

/* Names the first bad field of def, or returns 0. */
static int check_def(const mr_mapping_def *d, int i, char *msg, size_t size) {
  char dummy[8];
  if (msg == NULL) {
    msg = dummy;
    size = sizeof dummy;
  }
  if (d->cookie != MR_DEF_COOKIE)
    return snprintf(msg, size, "mapping %d was not made by mr_default_mapping_def", i), -1;
  if (!mr_pose_is_finite(&d->neutral))
    return snprintf(msg, size, "mapping '%s': the neutral pose is not finite", d->name), -1;
  if (!(d->min_cutoff > 0) || !(d->d_cutoff > 0) || !(d->beta >= 0) || !isfinite(d->beta) ||
      !isfinite(d->min_cutoff) || !isfinite(d->d_cutoff))
    return snprintf(msg, size,
                    "mapping '%s': expected min_cutoff and d_cutoff > 0 and beta >= 0, got %g, "
                    "%g, %g",
                    d->name, d->min_cutoff, d->d_cutoff, d->beta),
           -1;
  if (!(d->stuck_after > 0))
    return snprintf(msg, size, "mapping '%s': expected stuck_after > 0 s, got %g", d->name,
                    d->stuck_after),
           -1;
  for (int a = 0; a < MR_DOF_COUNT; a++) {
    const mr_axis_def *x = &d->axes[a];
    if (x->channel < -1 || x->channel >= MR_CONTROL_CHANNELS)
      return snprintf(msg, size, "mapping '%s', %s: expected channel 0..%d or -1, got %d", d->name,
                      dof_names[a], MR_CONTROL_CHANNELS - 1, x->channel),
             -1;
    if (!isfinite(x->low) || !isfinite(x->high) || !(x->neutral >= 0 && x->neutral <= 1) ||
        !(x->dead_zone >= 0 && x->dead_zone <= 0.5))
      return snprintf(msg, size,
                      "mapping '%s', %s: expected a finite range, neutral in 0..1 and dead zone "
                      "in 0..0.5",
                      d->name, dof_names[a]),
             -1;
  }
  return 0;
}

mr_control_status mr_control_create(const mr_mapping_def *defs, int n, mr_control **out, char *msg,
                                    size_t msg_size) {
  if (out != NULL) *out = NULL;
  if (defs == NULL || out == NULL || n < 1 || n > MR_CONTROL_MAX_MAPPINGS) {
    if (msg != NULL && msg_size > 0)
      snprintf(msg, msg_size, "expected 1 to %d mappings and somewhere to put the controller",
               MR_CONTROL_MAX_MAPPINGS);
    return MR_CONTROL_ERR_ARG;
  }
  for (int i = 0; i < n; i++)
    if (check_def(&defs[i], i, msg, msg_size) != 0) return MR_CONTROL_ERR_ARG;
  mr_control *c = calloc(1, sizeof *c);
  if (c == NULL) {
    if (msg != NULL && msg_size > 0) snprintf(msg, msg_size, "out of memory");
    return MR_CONTROL_ERR_ARG;
  }
  memcpy(c->maps, defs, (size_t)n * sizeof *defs);
  c->n = n;
  for (int k = 0; k < MR_CONTROL_CHANNELS; k++) {
    mr_one_euro_init(&c->filter[k], defs[0].min_cutoff, defs[0].beta, defs[0].d_cutoff);
    c->at_end_since[k] = NAN;
    c->smoothed[k] = 0.5;
  }
  *out = c;
  return MR_CONTROL_OK;
}

void mr_control_destroy(mr_control *c) {
  free(c);
}

mr_control_status mr_control_select(mr_control *c, int i) {
  if (c == NULL || i < 0 || i >= c->n) return MR_CONTROL_ERR_ARG;
  c->selected = i;
  for (int k = 0; k < MR_CONTROL_CHANNELS; k++) {
    c->filter[k].min_cutoff = c->maps[i].min_cutoff;
    c->filter[k].beta = c->maps[i].beta;
    c->filter[k].d_cutoff = c->maps[i].d_cutoff;
  }
  return MR_CONTROL_OK;
}

int mr_control_find(const mr_control *c, const char *name) {
  for (int i = 0; c != NULL && name != NULL && i < c->n; i++)
    if (strcmp(c->maps[i].name, name) == 0) return i;
  return -1;
}

int mr_control_selected(const mr_control *c) {
  return c != NULL ? c->selected : -1;
}

void mr_control_values(const mr_control *c, double out[MR_CONTROL_CHANNELS]) {
  for (int k = 0; k < MR_CONTROL_CHANNELS; k++) out[k] = c != NULL ? c->smoothed[k] : 0.0;
}

/* The neutral input of channel k under mapping m: that of the first axis
 * it drives, else the middle. */
static double channel_neutral(const mr_mapping_def *m, int k) {
  for (int a = 0; a < MR_DOF_COUNT; a++)
    if (m->axes[a].channel == k) return m->axes[a].neutral;
  return 0.5;
}

/* One channel's reading: checked, clamped, held at neutral when broken,
 * then smoothed. */
static double read_channel(mr_control *c, int k, double v, double t, mr_channel_state *state) {
  const mr_mapping_def *m = &c->maps[c->selected];
  *state = MR_CHANNEL_OK;
  if (!isfinite(v)) {
    *state = MR_CHANNEL_NOT_FINITE;
    c->at_end_since[k] = NAN;
    v = channel_neutral(m, k);
  } else {
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    if (v <= 0.0 || v >= 1.0) {
      if (isnan(c->at_end_since[k])) c->at_end_since[k] = t;
      if (t - c->at_end_since[k] > m->stuck_after) {
        *state = MR_CHANNEL_STUCK;
        v = channel_neutral(m, k);
      }
    } else {
      c->at_end_since[k] = NAN;
    }
  }
  c->smoothed[k] = mr_one_euro_filter(&c->filter[k], v, t);
  return c->smoothed[k];
}

/* The axis's value for smoothed input u: dead zone about neutral, then
 * the linear range. */
static double axis_value(const mr_axis_def *a, double u) {
  if (fabs(u - a->neutral) <= a->dead_zone) u = a->neutral;
  if (a->invert) u = 1.0 - u;
  return a->low + (a->high - a->low) * u;
}

mr_control_status mr_control_update(mr_control *c, const double values[MR_CONTROL_CHANNELS],
                                    double t, mr_pose *out,
                                    mr_channel_state states[MR_CONTROL_CHANNELS]) {
  if (c == NULL || values == NULL || out == NULL) return MR_CONTROL_ERR_ARG;
  if (!isfinite(t) || (c->started && t < c->last_t)) return MR_CONTROL_ERR_TIME;
  c->started = true;
  c->last_t = t;
  mr_channel_state st[MR_CONTROL_CHANNELS];
  double u[MR_CONTROL_CHANNELS];
  for (int k = 0; k < MR_CONTROL_CHANNELS; k++) u[k] = read_channel(c, k, values[k], t, &st[k]);
  if (states != NULL) memcpy(states, st, sizeof st);

  const mr_mapping_def *m = &c->maps[c->selected];
  double deg[3] = { 0, 0, 0 }, move[3] = { 0, 0, 0 };
  for (int a = 0; a < MR_DOF_COUNT; a++) {
    const mr_axis_def *ax = &m->axes[a];
    if (ax->channel < 0) continue;
    double v = axis_value(ax, u[ax->channel]);
    if (a <= MR_DOF_TURN_Z)
      deg[a - MR_DOF_TURN_X] = v;
    else
      move[a - MR_DOF_MOVE_X] = v;
  }
  /* The offset in the frame's own axes, composed onto the neutral pose. */
  mr_pose offset = mr_pose_from_euler_deg(move, deg);
  *out = mr_pose_compose(&m->neutral, &offset);
  return MR_CONTROL_OK;
}

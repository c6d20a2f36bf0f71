/* Applied forces (§5.1, §6.2): springs, strings, sine springs, antigravity
 * and triggered action forces. Numbers a file leaves out stay NaN and take
 * the physics library's defaults; a rest length left out is the distance
 * at the start. */
#include "scene_read.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* *out is the section's sequence, or NULL when the file has none. */
static int section(mr_reader *r, const mr_ynode *physics, const char *key, unsigned fx,
                   const char *what, const mr_ynode **out) {
  const mr_ynode *n = *out = mr_scene_yaml_get(physics, key);
  if (n == NULL)
    return 0;
  if (mr_scene_read_seq(r, n, key) != 0 || (n->count > 0 && mr_scene_read_need_effect(r, n, fx, what) != 0))
    return -1;
  return 0;
}

static void *alloc_items(mr_reader *r, const mr_ynode *n, size_t size) {
  void *p = calloc(n->count ? n->count : 1, size);
  if (p == NULL)
    mr_scene_read_fail(r, n, MR_SCENE_ERR_NOMEM, "out of memory");
  return p;
}

static int pair(mr_reader *r, const mr_ynode *it, const char *what, mr_scene_ref *a,
                mr_scene_ref *b) {
  const mr_ynode *v = mr_scene_read_need(r, it, "between", what);
  if (v == NULL)
    return -1;
  if (v->kind != MR_YNODE_SEQ || v->count != 2)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA, "expected [point, point] for between in %s",
                   what);
  if (mr_scene_read_point_ref(r, v->items[0], a) != 0 || mr_scene_read_point_ref(r, v->items[1], b) != 0)
    return -1;
  if (a->control == b->control && a->index == b->index)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                   "zero-length %s: both ends are the same point; expected two points", what);
  if (a->control && b->control)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                   "%s between two control points moves nothing; expected a particle", what);
  return 0;
}

static int read_springs(mr_reader *r, const mr_ynode *physics) {
  static const char *const keys[] = {"between", "rest", "stiffness", "damping", NULL};
  mr_scene *s = r->scene;
  const mr_ynode *n;
  if (section(r, physics, "springs", MR_SCENE_FX_SPRINGS, "springs are", &n) != 0)
    return -1;
  if (n == NULL)
    return 0;
  if ((s->springs = alloc_items(r, n, sizeof *s->springs)) == NULL)
    return -1;
  for (size_t i = 0; i < n->count; i++) {
    const mr_ynode *it = n->items[i];
    mr_scene_spring *sp = &s->springs[i];
    mr_scene_ref a, b;
    if (mr_scene_read_map(r, it, "a spring", keys) != 0 || pair(r, it, "a spring", &a, &b) != 0)
      return -1;
    if (a.control || b.control)
      return mr_scene_read_fail(r, mr_scene_yaml_get(it, "between"), MR_SCENE_ERR_VALUE,
                     "expected two particles for a spring (use strings for control points)");
    sp->a = a.index;
    sp->b = b.index;
    sp->rest = sp->stiffness = sp->damping = NAN;
    if (mr_scene_read_nonneg_key(r, it, "rest", &sp->rest) != 0 ||
        mr_scene_read_nonneg_key(r, it, "stiffness", &sp->stiffness) != 0 ||
        mr_scene_read_nonneg_key(r, it, "damping", &sp->damping) != 0)
      return -1;
    sp->pos = mr_scene_read_pos(it);
    s->n_springs = i + 1;
  }
  return 0;
}

static int read_strings(mr_reader *r, const mr_ynode *physics) {
  static const char *const keys[] = {"from", "to", "rest", "stiffness", "damping", NULL};
  mr_scene *s = r->scene;
  const mr_ynode *n;
  if (section(r, physics, "strings", MR_SCENE_FX_STRINGS, "strings are", &n) != 0)
    return -1;
  if (n == NULL)
    return 0;
  if ((s->strings = alloc_items(r, n, sizeof *s->strings)) == NULL)
    return -1;
  for (size_t i = 0; i < n->count; i++) {
    const mr_ynode *it = n->items[i];
    mr_scene_string *st = &s->strings[i];
    const mr_ynode *v;
    if (mr_scene_read_map(r, it, "a string", keys) != 0)
      return -1;
    if ((v = mr_scene_read_need(r, it, "from", "a string")) == NULL ||
        mr_scene_read_control_ref(r, v, &st->control) != 0)
      return -1;
    if ((v = mr_scene_read_need(r, it, "to", "a string")) == NULL ||
        mr_scene_read_particle_ref(r, v, &st->particle) != 0)
      return -1;
    st->rest = st->stiffness = st->damping = NAN;
    if (mr_scene_read_nonneg_key(r, it, "rest", &st->rest) != 0 ||
        mr_scene_read_positive_key(r, it, "stiffness", &st->stiffness) != 0 ||
        mr_scene_read_nonneg_key(r, it, "damping", &st->damping) != 0)
      return -1;
    st->pos = mr_scene_read_pos(it);
    s->n_strings = i + 1;
  }
  return 0;
}

static int read_sine_springs(mr_reader *r, const mr_ynode *physics) {
  static const char *const keys[] = {"between", "rest", "max_force", "reach", "damping", NULL};
  mr_scene *s = r->scene;
  const mr_ynode *n;
  if (section(r, physics, "sine_springs", MR_SCENE_FX_SINE_SPRINGS, "sine springs are", &n) != 0)
    return -1;
  if (n == NULL)
    return 0;
  if ((s->sine_springs = alloc_items(r, n, sizeof *s->sine_springs)) == NULL)
    return -1;
  for (size_t i = 0; i < n->count; i++) {
    const mr_ynode *it = n->items[i];
    mr_scene_sine_spring *sp = &s->sine_springs[i];
    if (mr_scene_read_map(r, it, "a sine spring", keys) != 0 ||
        pair(r, it, "a sine spring", &sp->a, &sp->b) != 0)
      return -1;
    sp->rest = sp->max_force = sp->reach = sp->damping = NAN;
    if (mr_scene_read_nonneg_key(r, it, "rest", &sp->rest) != 0 ||
        mr_scene_read_positive_key(r, it, "max_force", &sp->max_force) != 0 ||
        mr_scene_read_positive_key(r, it, "reach", &sp->reach) != 0 ||
        mr_scene_read_nonneg_key(r, it, "damping", &sp->damping) != 0)
      return -1;
    sp->pos = mr_scene_read_pos(it);
    s->n_sine_springs = i + 1;
  }
  return 0;
}

static int distinct(mr_reader *r, const mr_ynode *at, mr_scene_ref a, mr_scene_ref b,
                    const char *what) {
  if (a.control == b.control && a.index == b.index)
    return mr_scene_read_fail(r, at, MR_SCENE_ERR_VALUE, "expected %s to be a different point", what);
  return 0;
}

static int read_antigravity(mr_reader *r, const mr_ynode *physics) {
  static const char *const keys[] = {"acted", "trigger", "fraction", "max_scale", NULL};
  mr_scene *s = r->scene;
  const mr_ynode *n;
  if (section(r, physics, "antigravity", MR_SCENE_FX_ANTIGRAVITY, "antigravity is", &n) != 0)
    return -1;
  if (n == NULL)
    return 0;
  if ((s->antigravities = alloc_items(r, n, sizeof *s->antigravities)) == NULL)
    return -1;
  for (size_t i = 0; i < n->count; i++) {
    const mr_ynode *it = n->items[i];
    mr_scene_antigravity *ag = &s->antigravities[i];
    const mr_ynode *v;
    if (mr_scene_read_map(r, it, "an antigravity force", keys) != 0)
      return -1;
    if ((v = mr_scene_read_need(r, it, "acted", "an antigravity force")) == NULL ||
        mr_scene_read_point_ref(r, v, &ag->acted) != 0)
      return -1;
    if (ag->acted.control)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                     "expected a particle to act on, not a control point");
    if ((v = mr_scene_read_need(r, it, "trigger", "an antigravity force")) == NULL ||
        mr_scene_read_point_ref(r, v, &ag->trigger) != 0 ||
        distinct(r, v, ag->acted, ag->trigger, "the trigger") != 0)
      return -1;
    ag->fraction = ag->max_scale = NAN;
    if (mr_scene_read_nonneg_key(r, it, "fraction", &ag->fraction) != 0 ||
        mr_scene_read_positive_key(r, it, "max_scale", &ag->max_scale) != 0)
      return -1;
    ag->pos = mr_scene_read_pos(it);
    s->n_antigravities = i + 1;
  }
  return 0;
}

static int read_triggered(mr_reader *r, const mr_ynode *physics) {
  static const char *const keys[] = {"acted", "control", "trigger", "gain", "max_force", NULL};
  mr_scene *s = r->scene;
  const mr_ynode *n;
  if (section(r, physics, "triggered", MR_SCENE_FX_TRIGGERED, "triggered action forces are", &n) != 0)
    return -1;
  if (n == NULL)
    return 0;
  if ((s->triggered = alloc_items(r, n, sizeof *s->triggered)) == NULL)
    return -1;
  for (size_t i = 0; i < n->count; i++) {
    const mr_ynode *it = n->items[i];
    mr_scene_triggered *tg = &s->triggered[i];
    const mr_ynode *v;
    if (mr_scene_read_map(r, it, "a triggered force", keys) != 0)
      return -1;
    if ((v = mr_scene_read_need(r, it, "acted", "a triggered force")) == NULL ||
        mr_scene_read_point_ref(r, v, &tg->acted) != 0)
      return -1;
    if (tg->acted.control)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                     "expected a particle to act on, not a control point");
    if ((v = mr_scene_read_need(r, it, "control", "a triggered force")) == NULL ||
        mr_scene_read_point_ref(r, v, &tg->control) != 0 ||
        distinct(r, v, tg->acted, tg->control, "control") != 0)
      return -1;
    if ((v = mr_scene_read_need(r, it, "trigger", "a triggered force")) == NULL ||
        mr_scene_read_point_ref(r, v, &tg->trigger) != 0 ||
        distinct(r, v, tg->control, tg->trigger, "the trigger") != 0)
      return -1;
    tg->gain = tg->max_force = NAN;
    if (mr_scene_read_nonneg_key(r, it, "gain", &tg->gain) != 0 ||
        mr_scene_read_positive_key(r, it, "max_force", &tg->max_force) != 0)
      return -1;
    tg->pos = mr_scene_read_pos(it);
    s->n_triggered = i + 1;
  }
  return 0;
}

int mr_scene_read_forces(mr_reader *r, const mr_ynode *physics) {
  if (read_springs(r, physics) != 0 || read_strings(r, physics) != 0 ||
      read_sine_springs(r, physics) != 0 || read_antigravity(r, physics) != 0 ||
      read_triggered(r, physics) != 0)
    return -1;
  return 0;
}

#include "scene_read.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static void set_text(mr_scene_error *e, const char *file) {
  if (e->line > 0)
    snprintf(e->text, sizeof e->text, "%s:%d:%d: %s", file, e->line, e->column,
             e->message);
  else
    snprintf(e->text, sizeof e->text, "%s: %s", file, e->message);
}

static int vfail(mr_reader *r, int line, int column, mr_scene_status status,
                 const char *fmt, va_list ap) {
  mr_scene_error *e = r->err;
  e->status = status;
  e->line = line;
  e->column = column;
  vsnprintf(e->message, sizeof e->message, fmt, ap);
  set_text(e, r->file);
  return -1;
}

int mr_scene_read_fail_at(mr_reader *r, int line, int column, mr_scene_status status,
               const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vfail(r, line, column, status, fmt, ap);
  va_end(ap);
  return -1;
}

int mr_scene_read_fail(mr_reader *r, const mr_ynode *at, mr_scene_status status,
            const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vfail(r, at ? at->line : 0, at ? at->column : 0, status, fmt, ap);
  va_end(ap);
  return -1;
}

mr_scene_pos mr_scene_read_pos(const mr_ynode *node) {
  mr_scene_pos p = {node ? node->line : 0, node ? node->column : 0};
  return p;
}

/* Quotes a scalar for a message, shortened so one line stays one line. */
static const char *shown(const mr_ynode *n, char *buf, size_t size) {
  if (n->kind != MR_YNODE_SCALAR) {
    snprintf(buf, size, "a %s", mr_scene_yaml_kind_name(n->kind));
    return buf;
  }
  char tmp[40];
  size_t k = 0;
  for (const char *s = n->text; *s && k + 1 < sizeof tmp; s++)
    tmp[k++] = (*s == '\n' || *s == '\t') ? ' ' : *s;
  tmp[k] = '\0';
  snprintf(buf, size, "'%s%s'", tmp, strlen(n->text) >= sizeof tmp - 1 ? "..." : "");
  return buf;
}

int mr_scene_read_map(mr_reader *r, const mr_ynode *node, const char *what,
           const char *const *allowed) {
  char b[64];
  if (node->kind != MR_YNODE_MAP)
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_SCHEMA, "expected a mapping for %s, got %s",
                   what, shown(node, b, sizeof b));
  for (size_t i = 0; i < node->count; i++) {
    const mr_ynode *key = node->items[2 * i];
    bool ok = false;
    for (const char *const *a = allowed; *a != NULL; a++)
      if (strcmp(key->text, *a) == 0)
        ok = true;
    if (!ok) {
      char list[256] = "";
      size_t used = 0;
      for (const char *const *a = allowed; *a != NULL && used < sizeof list; a++)
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s",
                                 a == allowed ? "" : ", ", *a);
      return mr_scene_read_fail(r, key, MR_SCENE_ERR_SCHEMA,
                     "unknown key '%s' in %s; expected one of: %s", key->text,
                     what, list);
    }
  }
  return 0;
}

int mr_scene_read_seq(mr_reader *r, const mr_ynode *node, const char *what) {
  char b[64];
  if (node->kind != MR_YNODE_SEQ)
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_SCHEMA,
                   "expected a sequence (- item or [a, b]) for %s, got %s", what,
                   shown(node, b, sizeof b));
  return 0;
}

static bool is_nan_or_inf(const char *s) {
  const char *t = s;
  if (*t == '+' || *t == '-')
    t++;
  if (*t == '.')
    t++;
  return strcasecmp(t, "nan") == 0 || strcasecmp(t, "inf") == 0 ||
         strcasecmp(t, "infinity") == 0;
}

int mr_scene_read_number(mr_reader *r, const mr_ynode *node, const char *what, double *out) {
  char b[64];
  if (node->kind != MR_YNODE_SCALAR || node->quoted || node->text[0] == '\0')
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_SCHEMA, "expected a number for %s, got %s",
                   what, shown(node, b, sizeof b));
  if (is_nan_or_inf(node->text))
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_VALUE,
                   "expected a finite number for %s, got %s", what,
                   shown(node, b, sizeof b));
  const char *s = node->text;
  /* Decimal only: strtod would also take hex floats and "nan(...)". */
  for (const char *p = s; *p; p++)
    if (!(isdigit((unsigned char)*p) || strchr("+-.eE", *p)))
      return mr_scene_read_fail(r, node, MR_SCENE_ERR_SCHEMA, "expected a number for %s, got %s",
                     what, shown(node, b, sizeof b));
  char *end = NULL;
  errno = 0;
  double v = strtod(s, &end);
  if (end == s || *end != '\0')
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_SCHEMA, "expected a number for %s, got %s",
                   what, shown(node, b, sizeof b));
  if (!isfinite(v) || errno == ERANGE)
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_VALUE,
                   "expected a finite number for %s, got %s", what,
                   shown(node, b, sizeof b));
  *out = v;
  return 0;
}

int mr_scene_read_number_key(mr_reader *r, const mr_ynode *map, const char *key, double *out) {
  const mr_ynode *v = mr_scene_yaml_get(map, key);
  return v ? mr_scene_read_number(r, v, key, out) : 0;
}

int mr_scene_read_positive_key(mr_reader *r, const mr_ynode *map, const char *key,
                    double *out) {
  const mr_ynode *v = mr_scene_yaml_get(map, key);
  if (v == NULL)
    return 0;
  double x;
  if (mr_scene_read_number(r, v, key, &x) != 0)
    return -1;
  if (!(x > 0))
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected a positive number for %s, got %g",
                   key, x);
  *out = x;
  return 0;
}

int mr_scene_read_nonneg_key(mr_reader *r, const mr_ynode *map, const char *key, double *out) {
  const mr_ynode *v = mr_scene_yaml_get(map, key);
  if (v == NULL)
    return 0;
  double x;
  if (mr_scene_read_number(r, v, key, &x) != 0)
    return -1;
  if (x < 0)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                   "expected a number >= 0 for %s, got %g", key, x);
  *out = x;
  return 0;
}

int mr_scene_read_vec3(mr_reader *r, const mr_ynode *node, const char *what, double out[3]) {
  char b[64];
  if (node->kind != MR_YNODE_SEQ || node->count != 3)
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_SCHEMA,
                   "expected [x, y, z] (three numbers) for %s, got %s%s", what,
                   node->kind == MR_YNODE_SEQ ? "a sequence of " : "",
                   node->kind == MR_YNODE_SEQ
                       ? (snprintf(b, sizeof b, "%zu items", node->count), b)
                       : shown(node, b, sizeof b));
  double v[3];
  for (int i = 0; i < 3; i++)
    if (mr_scene_read_number(r, node->items[i], what, &v[i]) != 0)
      return -1;
  memcpy(out, v, sizeof v);
  return 0;
}

int mr_scene_read_vec3_key(mr_reader *r, const mr_ynode *map, const char *key, double out[3]) {
  const mr_ynode *v = mr_scene_yaml_get(map, key);
  return v ? mr_scene_read_vec3(r, v, key, out) : 0;
}

int mr_scene_read_bool(mr_reader *r, const mr_ynode *node, const char *what, bool *out) {
  char b[64];
  if (node->kind == MR_YNODE_SCALAR && !node->quoted) {
    if (strcmp(node->text, "true") == 0) {
      *out = true;
      return 0;
    }
    if (strcmp(node->text, "false") == 0) {
      *out = false;
      return 0;
    }
  }
  return mr_scene_read_fail(r, node, MR_SCENE_ERR_SCHEMA, "expected true or false for %s, got %s",
                 what, shown(node, b, sizeof b));
}

int mr_scene_read_long(mr_reader *r, const mr_ynode *node, const char *what, long *out) {
  char b[64];
  if (node->kind == MR_YNODE_SCALAR && !node->quoted && node->text[0] != '\0') {
    char *end = NULL;
    errno = 0;
    long v = strtol(node->text, &end, 10);
    if (*end == '\0' && errno == 0) {
      *out = v;
      return 0;
    }
  }
  return mr_scene_read_fail(r, node, MR_SCENE_ERR_SCHEMA, "expected an integer for %s, got %s",
                 what, shown(node, b, sizeof b));
}

int mr_scene_read_name(mr_reader *r, const mr_ynode *node, const char *what,
            char out[MR_SCENE_NAME_MAX]) {
  char b[64];
  if (node->kind != MR_YNODE_SCALAR || node->text[0] == '\0')
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_SCHEMA, "expected a name for %s, got %s", what,
                   shown(node, b, sizeof b));
  size_t n = strlen(node->text);
  if (n >= MR_SCENE_NAME_MAX)
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_VALUE,
                   "expected a name of at most %d characters for %s",
                   MR_SCENE_NAME_MAX - 1, what);
  for (const char *p = node->text; *p; p++)
    if (!(isalnum((unsigned char)*p) || *p == '_' || *p == '-' || *p == '.'))
      return mr_scene_read_fail(r, node, MR_SCENE_ERR_VALUE,
                     "expected a name of letters, digits, '_', '-' or '.' for %s, got %s",
                     what, shown(node, b, sizeof b));
  memcpy(out, node->text, n + 1);
  return 0;
}

const mr_ynode *mr_scene_read_need(mr_reader *r, const mr_ynode *map, const char *key,
                        const char *what) {
  const mr_ynode *v = mr_scene_yaml_get(map, key);
  if (v == NULL)
    mr_scene_read_fail(r, map, MR_SCENE_ERR_SCHEMA, "expected key '%s' in %s", key, what);
  return v;
}

int mr_scene_read_particle_ref(mr_reader *r, const mr_ynode *node, size_t *out) {
  char name[MR_SCENE_NAME_MAX];
  if (mr_scene_read_name(r, node, "a particle", name) != 0)
    return -1;
  size_t i = mr_scene_find_particle(r->scene, name);
  if (i == (size_t)-1)
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_VALUE,
                   "expected the name of a particle declared under particles, got '%s'",
                   name);
  *out = i;
  return 0;
}

int mr_scene_read_control_ref(mr_reader *r, const mr_ynode *node, size_t *out) {
  char name[MR_SCENE_NAME_MAX];
  if (mr_scene_read_name(r, node, "a control point", name) != 0)
    return -1;
  size_t i = mr_scene_find_control_point(r->scene, name);
  if (i == (size_t)-1)
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_VALUE,
                   "expected the name of a control point declared under control.points, got '%s'",
                   name);
  *out = i;
  return 0;
}

int mr_scene_read_point_ref(mr_reader *r, const mr_ynode *node, mr_scene_ref *out) {
  char name[MR_SCENE_NAME_MAX];
  if (mr_scene_read_name(r, node, "a point", name) != 0)
    return -1;
  size_t i = mr_scene_find_particle(r->scene, name);
  if (i != (size_t)-1) {
    out->control = false;
    out->index = i;
    return 0;
  }
  i = mr_scene_find_control_point(r->scene, name);
  if (i != (size_t)-1) {
    out->control = true;
    out->index = i;
    return 0;
  }
  return mr_scene_read_fail(r, node, MR_SCENE_ERR_VALUE,
                 "expected the name of a particle or control point, got '%s'", name);
}

int mr_scene_read_particle_list(mr_reader *r, const mr_ynode *node, const char *what, size_t **out,
                     size_t *count) {
  if (mr_scene_read_seq(r, node, what) != 0)
    return -1;
  size_t *m = calloc(node->count ? node->count : 1, sizeof *m);
  if (m == NULL)
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_NOMEM, "out of memory");
  *out = m;
  *count = 0;
  for (size_t k = 0; k < node->count; k++) {
    if (mr_scene_read_particle_ref(r, node->items[k], &m[k]) != 0)
      return -1;
    for (size_t j = 0; j < k; j++)
      if (m[j] == m[k])
        return mr_scene_read_fail(r, node->items[k], MR_SCENE_ERR_VALUE,
                       "particle '%s' is listed twice in %s",
                       r->scene->particles[m[k]].name, what);
    *count = k + 1;
  }
  return 0;
}

int mr_scene_read_need_effect(mr_reader *r, const mr_ynode *at, unsigned fx, const char *what) {
  if (r->scene->effects & fx)
    return 0;
  unsigned bit = 0;
  while (!(fx & (1u << bit)))
    bit++;
  return mr_scene_read_fail(r, at, MR_SCENE_ERR_SCHEMA,
                 "%s declared but effect '%s' is not listed in physics.effects", what,
                 mr_scene_effect_name(bit));
}

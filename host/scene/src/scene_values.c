#include "scene_read.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <stddef.h>

static void set_text(mr_scene_error *e, const char *file) {
  if (e->line > 0)
    snprintf(e->text, sizeof e->text, "%s:%d:%d: %s", file, e->line, e->column, e->message);
  else
    snprintf(e->text, sizeof e->text, "%s: %s", file, e->message);
}

/* A key or value from the file can hold a newline or a terminal's escape
 * codes; an error stays one line of plain text: control bytes are written
 * as \n, \t or \xNN. */
static void escape_controls(char *s, size_t size) {
  char out[sizeof((mr_scene_error *)0)->message];
  size_t k = 0;
  for (const unsigned char *p = (const unsigned char *)s; *p && k + 5 < sizeof out; p++) {
    if (*p >= 0x20 && *p != 0x7f) {
      out[k++] = (char)*p;
    } else if (*p == '\n' || *p == '\t') {
      out[k++] = '\\';
      out[k++] = *p == '\n' ? 'n' : 't';
    } else {
      k += (size_t)snprintf(out + k, sizeof out - k, "\\x%02x", *p);
    }
  }
  out[k] = '\0';
  snprintf(s, size, "%s", out);
}

static int vfail(mr_reader *r, int line, int column, mr_scene_status status, const char *fmt,
                 va_list ap) {
  mr_scene_error *e = r->err;
  e->status = status;
  e->line = line;
  e->column = column;
  vsnprintf(e->message, sizeof e->message, fmt, ap);
  escape_controls(e->message, sizeof e->message);
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

int mr_scene_read_fail(mr_reader *r, const mr_ynode *at, mr_scene_status status, const char *fmt,
                       ...) {
  va_list ap;
  va_start(ap, fmt);
  vfail(r, at ? at->line : 0, at ? at->column : 0, status, fmt, ap);
  va_end(ap);
  return -1;
}

mr_scene_pos mr_scene_read_pos(const mr_ynode *node) {
  mr_scene_pos p = { node ? node->line : 0, node ? node->column : 0 };
  return p;
}

/* Quotes a scalar for a message, shortened so one line stays one line. */
static const char *shown(const mr_ynode *n, char *buf, size_t size) {
  if (n->kind != MR_YNODE_SCALAR) {
    snprintf(buf, size, "a %s", mr_scene_yaml_kind_name(n->kind));
    return buf;
  }
  if (n->text[0] == '\0' && !n->quoted) {
    snprintf(buf, size, "nothing");
    return buf;
  }
  char tmp[40];
  size_t k = 0;
  for (const char *s = n->text; *s && k + 1 < sizeof tmp; s++)
    tmp[k++] = (*s == '\n' || *s == '\t') ? ' ' : *s;
  tmp[k] = '\0';
  snprintf(buf, size, "'%s%s'", tmp, n->text[k] != '\0' ? "..." : "");
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
    for (const char *const *a = allowed; *a != NULL && !ok; a++)
      ok = key->text[0] == (*a)[0] && strcmp(key->text, *a) == 0;
    if (!ok) {
      char list[256] = "";
      size_t used = 0;
      for (const char *const *a = allowed; *a != NULL && used < sizeof list; a++)
        used +=
            (size_t)snprintf(list + used, sizeof list - used, "%s%s", a == allowed ? "" : ", ", *a);
      return mr_scene_read_fail(r, key, MR_SCENE_ERR_SCHEMA,
                                "unknown key '%s' in %s; expected one of: %s", key->text, what,
                                list);
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
  if (*t == '+' || *t == '-') t++;
  if (*t == '.') t++;
  if (*t >= '0' && *t <= '9') return false; /* every number a scene holds */
  return strcasecmp(t, "nan") == 0 || strcasecmp(t, "inf") == 0 || strcasecmp(t, "infinity") == 0;
}

/* A finite decimal number, not yet held to its range. */
static int read_number_unranged(mr_reader *r, const mr_ynode *node, const char *what, double *out) {
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
    if (!((*p >= '0' && *p <= '9') || *p == '+' || *p == '-' || *p == '.' || *p == 'e' ||
          *p == 'E'))
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

int mr_scene_read_number(mr_reader *r, const mr_ynode *node, const char *what, double *out) {
  double v;
  if (read_number_unranged(r, node, what, &v) != 0 || mr_scene_range_check(r, node, what, v) != 0)
    return -1;
  *out = v;
  return 0;
}

int mr_scene_read_quantity(mr_reader *r, const mr_ynode *node, const char *what, double *out) {
  return read_number_unranged(r, node, what, out);
}

int mr_scene_read_vec3(mr_reader *r, const mr_ynode *node, const char *what, double out[3]) {
  char b[64];
  if (node->kind != MR_YNODE_SEQ || node->count != 3)
    return mr_scene_read_fail(
        r, node, MR_SCENE_ERR_SCHEMA, "expected [x, y, z] (three numbers) for %s, got %s%s", what,
        node->kind == MR_YNODE_SEQ ? "a sequence of " : "",
        node->kind == MR_YNODE_SEQ ? (snprintf(b, sizeof b, "%zu items", node->count), b)
                                   : shown(node, b, sizeof b));
  double v[3];
  for (int i = 0; i < 3; i++)
    if (mr_scene_read_number(r, node->items[i], what, &v[i]) != 0) return -1;
  memcpy(out, v, sizeof v);
  return 0;
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
      return mr_scene_read_fail(
          r, node, MR_SCENE_ERR_VALUE,
          "expected a name of letters, digits, '_', '-' or '.' for %s, got %s", what,
          shown(node, b, sizeof b));
  memcpy(out, node->text, n + 1);
  return 0;
}

const mr_ynode *mr_scene_read_named(mr_reader *r, const mr_ynode *item, const char *what,
                                    const char *const *keys, const char *label,
                                    char name[MR_SCENE_NAME_MAX]) {
  const mr_ynode *v;
  if (mr_scene_read_map(r, item, what, keys) != 0 ||
      (v = mr_scene_read_need(r, item, "name", what)) == NULL ||
      mr_scene_read_name(r, v, label, name) != 0)
    return NULL;
  return v;
}

const mr_ynode *mr_scene_read_need(mr_reader *r, const mr_ynode *map, const char *key,
                                   const char *what) {
  const mr_ynode *v = mr_scene_yaml_get(map, key);
  if (v == NULL)
    mr_scene_read_fail(r, map, MR_SCENE_ERR_SCHEMA, "expected key '%s' in %s", key, what);
  return v;
}

static double *field_double(void *def, const mr_scene_field *f) {
  return (double *)((char *)def + f->offset);
}

/* The range checks of the non-negative kinds, after the number is read. */
static int check_range(mr_reader *r, const mr_ynode *v, const mr_scene_field *f, double x) {
  if (f->kind == MR_SCENE_FIELD_POSITIVE && !(x > 0))
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected a positive number for %s, got %g",
                              f->key, x);
  if ((f->kind == MR_SCENE_FIELD_NONNEG || f->kind == MR_SCENE_FIELD_UNIT) && x < 0)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected a number >= 0 for %s, got %g",
                              f->key, x);
  if (f->kind == MR_SCENE_FIELD_UNIT && x > 1)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected %s between 0 and 1, got %g",
                              f->key, x);
  return 0;
}

int mr_scene_read_field(mr_reader *r, const mr_ynode *map, const mr_scene_field *f, void *def) {
  const mr_ynode *v = mr_scene_yaml_get(map, f->key);
  if (v == NULL) return 0;
  if (f->kind == MR_SCENE_FIELD_VEC3) return mr_scene_read_vec3(r, v, f->key, field_double(def, f));
  if (f->kind == MR_SCENE_FIELD_INT) {
    long x;
    if (mr_scene_read_long(r, v, f->key, &x) != 0) return -1;
    if (x < f->lo || x > f->hi)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                                "expected %s between %ld and %ld, got %ld", f->key, f->lo, f->hi,
                                x);
    *(int *)((char *)def + f->offset) = (int)x;
    return 0;
  }
  double x;
  /* The kind's own words first ("expected a positive ..."), then the range. */
  if (read_number_unranged(r, v, f->key, &x) != 0 || check_range(r, v, f, x) != 0 ||
      mr_scene_range_check(r, v, f->key, x) != 0)
    return -1;
  *field_double(def, f) = x;
  return 0;
}

int mr_scene_read_fields(mr_reader *r, const mr_ynode *map, const mr_scene_field *fields, size_t n,
                         void *def) {
  for (size_t i = 0; i < n; i++)
    if (mr_scene_read_field(r, map, &fields[i], def) != 0) return -1;
  return 0;
}

void mr_scene_list_names(char *out, size_t size, mr_scene_name_fn name) {
  size_t used = 0;
  out[0] = '\0';
  for (int i = 0; used < size && strcmp(name(i), "unknown") != 0; i++)
    used += (size_t)snprintf(out + used, size - used, "%s%s", i ? ", " : "", name(i));
}

int mr_scene_read_choice(mr_reader *r, const mr_ynode *map, const char *key,
                         mr_scene_parse_fn parse, mr_scene_name_fn name, int *out) {
  const mr_ynode *v = mr_scene_yaml_get(map, key);
  if (v == NULL || (v->kind == MR_YNODE_SCALAR && parse(v->text, out) == 0)) return 0;
  char list[256];
  mr_scene_list_names(list, sizeof list, name);
  return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected %s to be one of: %s, got '%s'", key,
                            list, v->kind == MR_YNODE_SCALAR ? v->text : "?");
}

int mr_scene_read_need_effect(mr_reader *r, const mr_ynode *at, uint32_t effect, const char *what) {
  if (r->scene->world.effects & effect) return 0;
  uint32_t bit = effect & (~effect + 1u); /* the lowest: the one a message names */
  return mr_scene_read_fail(r, at, MR_SCENE_ERR_SCHEMA,
                            "%s declared but effect '%s' is not listed in physics.effects", what,
                            mr_scene_effect_name(bit));
}

int mr_scene_read_items(mr_reader *r, const mr_ynode *seq, const char *what, uint32_t effect,
                        const char *declared, size_t size, void **items, size_t *count,
                        mr_scene_item_fn read) {
  if (mr_scene_read_seq(r, seq, what) != 0) return -1;
  if (seq->count > 0 && effect != 0 && mr_scene_read_need_effect(r, seq, effect, declared) != 0)
    return -1;
  /* Appends: each puppet adds its items after the scene's own. */
  size_t have = *count, total = have + seq->count;
  unsigned char *a = realloc(*items, (total ? total : 1) * size);
  if (a == NULL) return mr_scene_read_fail(r, seq, MR_SCENE_ERR_NOMEM, "out of memory");
  memset(a + have * size, 0, (total - have) * size);
  *items = a;
  for (size_t i = 0; i < seq->count; i++) {
    *count = have + i + 1;
    if (read(r, seq->items[i], a + (have + i) * size) != 0) return -1;
  }
  return 0;
}

bool mr_scene_is_control_id(const mr_scene *s, int id) {
  return id >= 0 && (size_t)id >= s->n_particles;
}

const char *mr_scene_point_name(const mr_scene *s, int id) {
  if (id < 0) return "?";
  if (!mr_scene_is_control_id(s, id)) return s->particles[id].name;
  size_t j = (size_t)id - s->n_particles;
  return j < s->n_control_points ? s->control_points[j].name : "?";
}

/* A name resolved to a world id among the particles, the control points,
 * or both; `expected` completes "expected the name of ...". Inside a
 * puppet its own particles and points come first: "hand" is "alice.hand"
 * there. */
static int resolve(mr_reader *r, const mr_ynode *node, const char *what, bool particles,
                   bool controls, const char *expected, int *id) {
  char name[MR_SCENE_NAME_MAX], own[MR_SCENE_NAME_MAX];
  const mr_scene *s = r->scene;
  if (mr_scene_read_name(r, node, what, name) != 0) return -1;
  size_t i = (size_t)-1;
  if (particles && r->puppet != NULL && mr_scene_qualify(r, name, own) == 0)
    i = mr_scene_lookup_particle(r, own);
  if (particles && i == (size_t)-1) i = mr_scene_lookup_particle(r, name);
  if (i == (size_t)-1 && controls) {
    size_t j = (size_t)-1;
    if (r->puppet != NULL && mr_scene_qualify(r, name, own) == 0)
      j = mr_scene_find_control_point(s, own);
    if (j == (size_t)-1) j = mr_scene_find_control_point(s, name);
    if (j != (size_t)-1) i = j + s->n_particles;
  }
  if (i == (size_t)-1)
    return mr_scene_read_fail(r, node, MR_SCENE_ERR_VALUE, "expected the name of %s, got '%s'",
                              expected, name);
  *id = (int)i;
  return 0;
}

int mr_scene_read_particle(mr_reader *r, const mr_ynode *node, int *id) {
  return resolve(r, node, "a particle", true, false, "a particle declared under particles", id);
}

int mr_scene_read_control_point(mr_reader *r, const mr_ynode *node, int *id) {
  return resolve(r, node, "a control point", false, true,
                 "a control point declared under control.points", id);
}

int mr_scene_read_point(mr_reader *r, const mr_ynode *node, int *id) {
  return resolve(r, node, "a point", true, true, "a particle or control point", id);
}

int mr_scene_read_particle_list(mr_reader *r, const mr_ynode *node, const char *what, int **out,
                                int *count) {
  if (mr_scene_read_seq(r, node, what) != 0) return -1;
  int *m = calloc(node->count ? node->count : 1, sizeof *m);
  if (m == NULL) return mr_scene_read_fail(r, node, MR_SCENE_ERR_NOMEM, "out of memory");
  *out = m;
  *count = 0;
  for (size_t k = 0; k < node->count; k++) {
    if (mr_scene_read_particle(r, node->items[k], &m[k]) != 0) return -1;
    for (size_t j = 0; j < k; j++)
      if (m[j] == m[k])
        return mr_scene_read_fail(r, node->items[k], MR_SCENE_ERR_VALUE,
                                  "particle '%s' is listed twice in %s",
                                  r->scene->particles[m[k]].name, what);
    *count = (int)k + 1;
  }
  return 0;
}

int mr_scene_read_between(mr_reader *r, const mr_ynode *it, const char *what, int *a, int *b) {
  const mr_ynode *v = mr_scene_read_need(r, it, "between", what);
  if (v == NULL) return -1;
  if (v->kind != MR_YNODE_SEQ || v->count != 2)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA,
                              "expected [point, point] for between in %s", what);
  if (mr_scene_read_point(r, v->items[0], a) != 0 || mr_scene_read_point(r, v->items[1], b) != 0)
    return -1;
  if (*a == *b)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "zero-length %s: both ends are the same point; expected two points",
                              what);
  if (mr_scene_is_control_id(r->scene, *a) && mr_scene_is_control_id(r->scene, *b))
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE,
                              "%s between two control points moves nothing; expected a particle",
                              what);
  return 0;
}

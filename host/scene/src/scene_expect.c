/* The `expect:` section: what a run of this scene must show. Hard cases
 * carry their own pass criteria, so the suite is one folder of files. */
#include "scene_read.h"

#include <ctype.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int read_resets(mr_reader *r, const mr_ynode *v) {
  static const char *const keys[] = { "min", "max", NULL };
  mr_scene_expect *e = &r->scene->expect;
  if (v->kind == MR_YNODE_SCALAR) {
    long n;
    if (mr_scene_read_long(r, v, "resets", &n) != 0) return -1;
    if (n < 0)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_VALUE, "expected resets >= 0, got %ld", n);
    e->resets_min = e->resets_max = n;
    return 0;
  }
  if (mr_scene_read_map(r, v, "expect.resets", keys) != 0) return -1;
  const mr_ynode *m;
  if ((m = mr_scene_yaml_get(v, "min")) != NULL &&
      (mr_scene_read_long(r, m, "resets.min", &e->resets_min) != 0 || e->resets_min < 0))
    return e->resets_min < 0 ? mr_scene_read_fail(r, m, MR_SCENE_ERR_VALUE, "expected min >= 0")
                             : -1;
  if ((m = mr_scene_yaml_get(v, "max")) != NULL &&
      (mr_scene_read_long(r, m, "resets.max", &e->resets_max) != 0 || e->resets_max < 0))
    return e->resets_max < 0 ? mr_scene_read_fail(r, m, MR_SCENE_ERR_VALUE, "expected max >= 0")
                             : -1;
  return 0;
}

#define EXPECT(field) offsetof(mr_scene_expect, field)

static int read_rest(mr_reader *r, const mr_ynode *v) {
  static const char *const keys[] = { "particles", "settle", "creep", "jitter", NULL };
  static const mr_scene_field fields[] = {
    { "settle", MR_SCENE_FIELD_NONNEG, EXPECT(settle), 0, 0 },
    { "creep", MR_SCENE_FIELD_POSITIVE, EXPECT(creep), 0, 0 },
    { "jitter", MR_SCENE_FIELD_POSITIVE, EXPECT(jitter), 0, 0 }
  };
  mr_scene_expect *e = &r->scene->expect;
  if (mr_scene_read_map(r, v, "expect.rest", keys) != 0) return -1;
  const mr_ynode *p = mr_scene_read_need(r, v, "particles", "expect.rest");
  if (p == NULL || mr_scene_read_seq(r, p, "expect.rest.particles") != 0) return -1;
  e->watch = calloc(p->count ? p->count : 1, sizeof *e->watch);
  if (e->watch == NULL) return mr_scene_read_fail(r, p, MR_SCENE_ERR_NOMEM, "out of memory");
  for (size_t i = 0; i < p->count; i++) {
    if (mr_scene_read_particle(r, p->items[i], &e->watch[i]) != 0) return -1;
    e->n_watch = i + 1;
  }
  if (mr_scene_read_need(r, v, "settle", "expect.rest") == NULL ||
      mr_scene_read_fields(r, v, fields, 3, e) != 0)
    return -1;
  if (isnan(e->creep) && isnan(e->jitter))
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA, "expected creep or jitter in expect.rest");
  return 0;
}

/* 0x and one to sixteen hex digits: the hash as `marionette sim` prints it. */
static int read_state_hash(mr_reader *r, const mr_ynode *v, uint64_t *out) {
  const char *s = v->text;
  size_t n = v->kind == MR_YNODE_SCALAR ? strlen(s) : 0;
  bool ok = !v->quoted && n > 2 && n <= 18 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
  uint64_t h = 0;
  for (size_t i = 2; ok && i < n; i++) {
    int d = isdigit((unsigned char)s[i])    ? s[i] - '0'
            : isxdigit((unsigned char)s[i]) ? tolower((unsigned char)s[i]) - 'a' + 10
                                            : -1;
    ok = d >= 0;
    h = h << 4 | (uint64_t)(d & 15);
  }
  if (!ok)
    return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA,
                              "expected state_hash as 0x and up to 16 hex digits");
  *out = h;
  return 0;
}

int mr_scene_read_expect(mr_reader *r, const mr_ynode *n) {
  static const char *const keys[] = { "finite",      "max_deviation",      "resets",
                                      "min_mean_dt", "min_string_stretch", "max_string_stretch",
                                      "max_speed",   "max_penetration",    "rest",
                                      "load_error",  "state_hash",         NULL };
  static const mr_scene_field fields[] = {
    { "max_deviation", MR_SCENE_FIELD_POSITIVE, EXPECT(max_deviation), 0, 0 },
    { "min_mean_dt", MR_SCENE_FIELD_POSITIVE, EXPECT(min_mean_dt), 0, 0 },
    { "min_string_stretch", MR_SCENE_FIELD_POSITIVE, EXPECT(min_string_stretch), 0, 0 },
    { "max_string_stretch", MR_SCENE_FIELD_POSITIVE, EXPECT(max_string_stretch), 0, 0 },
    { "max_speed", MR_SCENE_FIELD_POSITIVE, EXPECT(max_speed), 0, 0 },
    { "max_penetration", MR_SCENE_FIELD_POSITIVE, EXPECT(max_penetration), 0, 0 }
  };
  mr_scene_expect *e = &r->scene->expect;
  if (mr_scene_read_map(r, n, "expect", keys) != 0) return -1;
  e->present = true;
  e->pos = mr_scene_read_pos(n);
  const mr_ynode *v;
  if ((v = mr_scene_yaml_get(n, "load_error")) != NULL)
    /* The scene loaded, so the expected error did not happen; --check
     * reports that. Keep the text for its message. */
    e->has_load_error = true;
  if (v != NULL) {
    if (v->kind != MR_YNODE_SCALAR)
      return mr_scene_read_fail(r, v, MR_SCENE_ERR_SCHEMA, "expected a text for load_error");
    snprintf(e->load_error, sizeof e->load_error, "%s", v->text);
  }
  if ((v = mr_scene_yaml_get(n, "finite")) != NULL &&
      mr_scene_read_bool(r, v, "finite", &e->finite) != 0)
    return -1;
  if (mr_scene_read_fields(r, n, fields, sizeof fields / sizeof fields[0], e) != 0) return -1;
  if ((v = mr_scene_yaml_get(n, "resets")) != NULL && read_resets(r, v) != 0) return -1;
  if ((v = mr_scene_yaml_get(n, "rest")) != NULL && read_rest(r, v) != 0) return -1;
  if ((v = mr_scene_yaml_get(n, "state_hash")) != NULL) {
    if (read_state_hash(r, v, &e->state_hash) != 0) return -1;
    e->has_state_hash = true;
  }
  return 0;
}

/* Reads only expect.load_error from a file that may not load as a scene:
 * the point of such a file is that the rest of it is wrong. */
int mr_scene_expected_load_error(const char *path, char *out, size_t size) {
  FILE *f = fopen(path, "rb");
  if (f == NULL) return -1;
  char *buf = malloc(1 << 20);
  size_t len = buf ? fread(buf, 1, 1 << 20, f) : 0;
  fclose(f);
  if (buf == NULL) return -1;
  mr_ydoc doc;
  mr_yerror err;
  int rc = -1;
  if (mr_scene_yaml_parse(buf, len, &doc, &err) == 0) {
    const mr_ynode *v = mr_scene_yaml_get(mr_scene_yaml_get(doc.root, "expect"), "load_error");
    if (v != NULL && v->kind == MR_YNODE_SCALAR) {
      snprintf(out, size, "%s", v->text);
      rc = 0;
    }
    mr_scene_yaml_free(&doc);
  }
  free(buf);
  return rc;
}

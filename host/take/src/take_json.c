/* takes.json, through cJSON: read into the book's entries, written from
 * them to a temporary file and renamed over the old one. */
#include "take_internal.h"
#include "take_book.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static const char *const HOW[] = {
  "recorded", "punch", "split", "trim", "smooth", "offset", "scale"
};

const char *mr_take_how_name(mr_take_how how) {
  return (unsigned)how < sizeof HOW / sizeof HOW[0] ? HOW[how] : "?";
}

/* --- reading ---------------------------------------------------------------- */

typedef struct reader {
  const char *path;
  size_t index;
  mr_take_error *err;
} reader;

/* -1 in plain sight (mr_take_fail is in another file): an optimised build
 * then sees that a getter that failed set nothing its caller goes on to
 * read. */
static int bad(const reader *rd, const char *field, const char *what) {
  (void)mr_take_fail(rd->err, MR_TAKE_ERR_FORMAT, "%s: takes[%zu].%s: %s", rd->path, rd->index,
                     field, what);
  return -1;
}

static int get_num(const reader *rd, const cJSON *o, const char *key, double *v) {
  const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, key);
  if (!cJSON_IsNumber(x) || !isfinite(x->valuedouble)) return bad(rd, key, "expected a number");
  *v = x->valuedouble;
  return 0;
}

static int get_int(const reader *rd, const cJSON *o, const char *key, int lo, int hi, int *v) {
  double d;
  if (get_num(rd, o, key, &d) != 0) return -1;
  if (d != floor(d) || d < lo || d > hi) return bad(rd, key, "expected a whole number in range");
  *v = (int)d;
  return 0;
}

static int get_str(const reader *rd, const cJSON *o, const char *key, char *out, size_t cap) {
  const cJSON *x = cJSON_GetObjectItemCaseSensitive(o, key);
  if (!cJSON_IsString(x) || strlen(x->valuestring) >= cap) return bad(rd, key, "expected a string");
  snprintf(out, cap, "%s", x->valuestring);
  return 0;
}

/* [[glove, finger], ...] or, for offsets, [[glove, finger, s], ...]. */
static int get_arms(const reader *rd, const cJSON *o, const char *key, mr_take_entry *e,
                    bool offsets) {
  const cJSON *a = cJSON_GetObjectItemCaseSensitive(o, key);
  if (!cJSON_IsArray(a)) return bad(rd, key, "expected a list");
  const cJSON *x;
  cJSON_ArrayForEach(x, a) {
    int n = cJSON_GetArraySize(x);
    const cJSON *g = cJSON_GetArrayItem(x, 0), *f = cJSON_GetArrayItem(x, 1);
    if (!cJSON_IsArray(x) || n != (offsets ? 3 : 2) || !cJSON_IsNumber(g) || !cJSON_IsNumber(f) ||
        g->valueint < 0 || g->valueint >= MR_TAKE_MAX_GLOVES || f->valueint < 0 ||
        f->valueint >= MR_TAKE_CHANNELS || e->n_arms == MR_TAKE_MAX_ARMS)
      return bad(rd, key,
                 offsets ? "expected [glove, finger, seconds] items"
                         : "expected [glove 0..7, finger 0..4] items");
    if (offsets) {
      const cJSON *s = cJSON_GetArrayItem(x, 2);
      if (!cJSON_IsNumber(s) || !isfinite(s->valuedouble)) return bad(rd, key, "expected seconds");
      e->offset[g->valueint][f->valueint] = s->valuedouble;
    }
    e->arms[e->n_arms++] = (mr_take_arm){ g->valueint, f->valueint };
  }
  return 0;
}

static int read_made(const reader *rd, const cJSON *m, mr_take_entry *e) {
  char how[32];
  if (!cJSON_IsObject(m)) return bad(rd, "made", "expected an object");
  if (get_str(rd, m, "how", how, sizeof how) != 0) return -1;
  size_t k = 0;
  while (k < sizeof HOW / sizeof HOW[0] && strcmp(HOW[k], how) != 0) k++;
  if (k == sizeof HOW / sizeof HOW[0]) return bad(rd, "made.how", "unknown way a take was made");
  e->how = (mr_take_how)k;
  const int max = 1 << 30;
  if (e->how == MR_TAKE_RECORDED) return 0;
  if (get_int(rd, m, e->how == MR_TAKE_PUNCHED ? "base" : "source", 1, max, &e->source_id) != 0)
    return -1;
  switch (e->how) {
  case MR_TAKE_PUNCHED:
    return get_int(rd, m, "over", 1, max, &e->over_id) || get_num(rd, m, "in", &e->t0) ||
                   get_num(rd, m, "out", &e->t1) || get_arms(rd, m, "arms", e, false)
               ? -1
               : 0;
  case MR_TAKE_SPLIT:
    return get_num(rd, m, "at", &e->t0) || get_int(rd, m, "part", 1, 2, &e->part) ? -1 : 0;
  case MR_TAKE_TRIMMED:
    return get_num(rd, m, "from", &e->t0) || get_num(rd, m, "to", &e->t1) ? -1 : 0;
  case MR_TAKE_SMOOTHED:
    return get_num(rd, m, "min_cutoff", &e->min_cutoff) || get_num(rd, m, "beta", &e->beta) ||
                   get_num(rd, m, "d_cutoff", &e->d_cutoff) || get_arms(rd, m, "channels", e, false)
               ? -1
               : 0;
  case MR_TAKE_OFFSET:
    return get_arms(rd, m, "offsets", e, true);
  case MR_TAKE_SCALED:
    return get_num(rd, m, "factor", &e->factor);
  default:
    return 0;
  }
}

static int read_entry(const reader *rd, const cJSON *t, mr_take_entry *e) {
  memset(e, 0, sizeof *e);
  char hash[32];
  if (!cJSON_IsObject(t)) return bad(rd, "", "expected an object");
  if (get_str(rd, t, "name", e->name, sizeof e->name) != 0 ||
      get_int(rd, t, "id", 1, 1 << 30, &e->id) != 0 ||
      get_num(rd, t, "duration", &e->duration) != 0 ||
      get_str(rd, t, "scene_hash", hash, sizeof hash) != 0)
    return -1;
  char *end;
  e->scene_hash = strtoull(hash, &end, 16);
  if (hash[0] == '\0' || *end != '\0') return bad(rd, "scene_hash", "expected 16 hex digits");
  double created;
  if (get_num(rd, t, "created_unix", &created) != 0) return -1;
  e->created_unix = (int64_t)created;
  const cJSON *del = cJSON_GetObjectItemCaseSensitive(t, "deleted");
  if (!cJSON_IsBool(del)) return bad(rd, "deleted", "expected true or false");
  e->deleted = cJSON_IsTrue(del);
  const cJSON *files = cJSON_GetObjectItemCaseSensitive(t, "files"), *f;
  if (!cJSON_IsArray(files) || cJSON_GetArraySize(files) < 1 ||
      cJSON_GetArraySize(files) > MR_TAKE_MAX_GLOVES)
    return bad(rd, "files", "expected a list of 1..8 file names");
  cJSON_ArrayForEach(f, files) {
    if (!cJSON_IsString(f) || f->valuestring[0] == '\0' || strchr(f->valuestring, '/') ||
        strlen(f->valuestring) >= MR_TAKE_NAME_MAX)
      return bad(rd, "files", "expected file names inside the book's directory");
    snprintf(e->files[e->n_files++], MR_TAKE_NAME_MAX, "%s", f->valuestring);
  }
  return read_made(rd, cJSON_GetObjectItemCaseSensitive(t, "made"), e);
}

int mr_take_json_read(mr_take_book *b, const char *path, const char *text, mr_take_error *err) {
  cJSON *root = cJSON_Parse(text);
  if (root == NULL)
    return mr_take_fail(err, MR_TAKE_ERR_FORMAT, "%s: not JSON (near byte %ld)", path,
                        cJSON_GetErrorPtr() ? (long)(cJSON_GetErrorPtr() - text) : 0L);
  reader rd = { path, 0, err };
  const cJSON *fmt = cJSON_GetObjectItemCaseSensitive(root, "format");
  const cJSON *next = cJSON_GetObjectItemCaseSensitive(root, "next_id");
  const cJSON *takes = cJSON_GetObjectItemCaseSensitive(root, "takes"), *t;
  int rc = 0;
  if (!cJSON_IsNumber(fmt) || fmt->valueint != 1 || !cJSON_IsNumber(next) || next->valueint < 1 ||
      !cJSON_IsArray(takes)) {
    rc = mr_take_fail(err, MR_TAKE_ERR_FORMAT,
                      "%s: expected an object with format 1, next_id "
                      "and a list of takes",
                      path);
  } else {
    b->next_id = next->valueint;
    size_t n = (size_t)cJSON_GetArraySize(takes);
    b->takes = calloc(n + 1, sizeof *b->takes);
    if (b->takes == NULL) rc = mr_take_fail(err, MR_TAKE_ERR_IO, "%s: out of memory", path);
    cJSON_ArrayForEach(t, takes) {
      if (rc != 0) break;
      rd.index = b->n;
      mr_take_entry *e = &b->takes[b->n];
      rc = read_entry(&rd, t, e);
      if (rc == 0 && (mr_take_book_find(b, e->name) != NULL || mr_take_book_find_id(b, e->id)))
        rc = bad(&rd, "name", "a name or id given twice");
      if (rc == 0 && e->id >= b->next_id) rc = bad(&rd, "id", "not below next_id");
      if (rc == 0) b->n++;
    }
  }
  cJSON_Delete(root);
  return rc;
}

/* --- writing ---------------------------------------------------------------- */

static cJSON *arms_json(const mr_take_entry *e, bool offsets) {
  cJSON *a = cJSON_CreateArray();
  for (size_t i = 0; a != NULL && i < e->n_arms; i++) {
    const mr_take_arm *m = &e->arms[i];
    double v[3] = { m->glove, m->finger, offsets ? e->offset[m->glove][m->finger] : 0 };
    cJSON_AddItemToArray(a, cJSON_CreateDoubleArray(v, offsets ? 3 : 2));
  }
  return a;
}

static cJSON *made_json(const mr_take_entry *e) {
  cJSON *m = cJSON_CreateObject();
  cJSON_AddStringToObject(m, "how", mr_take_how_name(e->how));
  if (e->how == MR_TAKE_RECORDED) return m;
  cJSON_AddNumberToObject(m, e->how == MR_TAKE_PUNCHED ? "base" : "source", e->source_id);
  switch (e->how) {
  case MR_TAKE_PUNCHED:
    cJSON_AddNumberToObject(m, "over", e->over_id);
    cJSON_AddItemToObject(m, "arms", arms_json(e, false));
    cJSON_AddNumberToObject(m, "in", e->t0);
    cJSON_AddNumberToObject(m, "out", e->t1);
    break;
  case MR_TAKE_SPLIT:
    cJSON_AddNumberToObject(m, "at", e->t0);
    cJSON_AddNumberToObject(m, "part", e->part);
    break;
  case MR_TAKE_TRIMMED:
    cJSON_AddNumberToObject(m, "from", e->t0);
    cJSON_AddNumberToObject(m, "to", e->t1);
    break;
  case MR_TAKE_SMOOTHED:
    cJSON_AddNumberToObject(m, "min_cutoff", e->min_cutoff);
    cJSON_AddNumberToObject(m, "beta", e->beta);
    cJSON_AddNumberToObject(m, "d_cutoff", e->d_cutoff);
    cJSON_AddItemToObject(m, "channels", arms_json(e, false));
    break;
  case MR_TAKE_OFFSET:
    cJSON_AddItemToObject(m, "offsets", arms_json(e, true));
    break;
  case MR_TAKE_SCALED:
    cJSON_AddNumberToObject(m, "factor", e->factor);
    break;
  default:
    break;
  }
  return m;
}

static cJSON *entry_json(const mr_take_entry *e) {
  cJSON *t = cJSON_CreateObject();
  cJSON_AddStringToObject(t, "name", e->name);
  cJSON_AddNumberToObject(t, "id", e->id);
  cJSON *files = cJSON_AddArrayToObject(t, "files");
  for (size_t k = 0; k < e->n_files; k++)
    cJSON_AddItemToArray(files, cJSON_CreateString(e->files[k]));
  cJSON_AddItemToObject(t, "made", made_json(e));
  cJSON_AddNumberToObject(t, "duration", e->duration);
  char hash[24], when[32];
  snprintf(hash, sizeof hash, "%016llx", (unsigned long long)e->scene_hash);
  cJSON_AddStringToObject(t, "scene_hash", hash);
  cJSON_AddNumberToObject(t, "created_unix", (double)e->created_unix);
  time_t s = (time_t)e->created_unix;
  struct tm tm;
  if (gmtime_r(&s, &tm) != NULL && strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &tm) > 0)
    cJSON_AddStringToObject(t, "created", when);
  cJSON_AddBoolToObject(t, "deleted", e->deleted);
  return t;
}

int mr_take_json_write(const mr_take_book *b, mr_take_error *err) {
  cJSON *root = cJSON_CreateObject();
  cJSON_AddNumberToObject(root, "format", 1);
  cJSON_AddNumberToObject(root, "next_id", b->next_id);
  cJSON *takes = cJSON_AddArrayToObject(root, "takes");
  for (size_t i = 0; takes != NULL && i < b->n; i++)
    cJSON_AddItemToArray(takes, entry_json(&b->takes[i]));
  char *text = cJSON_Print(root);
  cJSON_Delete(root);
  char path[MR_TAKE_PATH_MAX + 16], tmp[MR_TAKE_PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/takes.json", b->dir);
  snprintf(tmp, sizeof tmp, "%s/.takes.json.%ld", b->dir, (long)getpid());
  if (text == NULL) return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: out of memory", path);
  FILE *f = fopen(tmp, "wb");
  int ok = f != NULL && fputs(text, f) >= 0 && fputc('\n', f) != EOF && fflush(f) == 0 &&
           fsync(fileno(f)) == 0;
  int e = errno;
  if (f != NULL && fclose(f) != 0 && ok) ok = 0, e = errno;
  free(text);
  if (!ok || rename(tmp, path) != 0) {
    if (ok) e = errno;
    unlink(tmp);
    return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: cannot write: %s", path, strerror(e));
  }
  return 0;
}

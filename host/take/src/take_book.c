/* The take list: a directory with takes.json and the takes' files. Files
 * are written once, under names from the take's stable id, and never
 * rewritten; the list is rewritten atomically after each change. */
#include "take_internal.h"
#include "take_book.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "mr_def.h"

static char *read_all(const char *path, mr_take_error *err) {
  FILE *f = fopen(path, "rb");
  if (f == NULL) {
    mr_take_fail(err, MR_TAKE_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
    return NULL;
  }
  size_t cap = 4096, n = 0;
  char *text = malloc(cap);
  for (size_t got; text != NULL && (got = fread(text + n, 1, cap - n - 1, f)) > 0;) {
    n += got;
    if (n + 1 == cap) {
      char *more = realloc(text, cap *= 2);
      if (more == NULL) free(text);
      text = more;
    }
  }
  fclose(f);
  if (text == NULL)
    mr_take_fail(err, MR_TAKE_ERR_IO, "%s: out of memory", path);
  else
    text[n] = '\0';
  return text;
}

int mr_take_book_open(const char *dir, bool create, mr_take_book *b, mr_take_error *err) {
  memset(b, 0, sizeof *b);
  if (dir == NULL || dir[0] == '\0' || strlen(dir) >= MR_TAKE_PATH_MAX - 64)
    return mr_take_fail(err, MR_TAKE_ERR_ARG, "expected a book's directory, got '%s'",
                        dir ? dir : "");
  snprintf(b->dir, sizeof b->dir, "%s", dir);
  b->next_id = 1;
  char path[MR_TAKE_PATH_MAX + 16];
  snprintf(path, sizeof path, "%s/takes.json", dir);
  struct stat st;
  if (stat(path, &st) != 0) {
    if (!create)
      return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: no take list here (%s)", path, strerror(errno));
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
      return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: cannot make the directory: %s", dir,
                          strerror(errno));
    b->takes = calloc(1, sizeof *b->takes);
    if (b->takes == NULL) return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: out of memory", dir);
    return mr_take_json_write(b, err);
  }
  char *text = read_all(path, err);
  if (text == NULL) return -1;
  int rc = mr_take_json_read(b, path, text, err);
  free(text);
  if (rc != 0) mr_take_book_close(b);
  return rc;
}

void mr_take_book_close(mr_take_book *b) {
  free(b->takes);
  b->takes = NULL;
  b->n = 0;
}

const mr_take_entry *mr_take_book_find(const mr_take_book *b, const char *name) {
  for (size_t i = 0; name != NULL && i < b->n; i++)
    if (strcmp(b->takes[i].name, name) == 0) return &b->takes[i];
  return NULL;
}

const mr_take_entry *mr_take_book_find_id(const mr_take_book *b, int id) {
  for (size_t i = 0; i < b->n; i++)
    if (b->takes[i].id == id) return &b->takes[i];
  return NULL;
}

int mr_take_book_check_name(const mr_take_book *b, const char *name, mr_take_error *err) {
  if (name == NULL || name[0] == '\0')
    return mr_take_fail(err, MR_TAKE_ERR_NAME, "a take's name must not be empty");
  if (strchr(name, '/') != NULL || strlen(name) >= MR_TAKE_NAME_MAX)
    return mr_take_fail(err, MR_TAKE_ERR_NAME,
                        "a take's name holds no '/' and at most %d "
                        "bytes: '%s'",
                        MR_TAKE_NAME_MAX - 1, name);
  const mr_take_entry *e = mr_take_book_find(b, name);
  if (e != NULL)
    return mr_take_fail(err, MR_TAKE_ERR_NAME, "%s: a take named '%s' is already there%s", b->dir,
                        name, e->deleted ? " (deleted; restore it or pick another)" : "");
  return 0;
}

/* The take's entry, visible or not; NULL and an error naming it if none. */
const mr_take_entry *mr_take_book_get(const mr_take_book *b, const char *name, mr_take_error *err) {
  const mr_take_entry *e = mr_take_book_find(b, name);
  if (e == NULL)
    mr_take_fail(err, MR_TAKE_ERR_NAME, "%s: no take named '%s'", b->dir, name ? name : "");
  return e;
}

int mr_take_book_paths(const mr_take_book *b, const char *name, char paths[][MR_TAKE_PATH_MAX],
                       size_t cap, size_t *n, mr_take_error *err) {
  const mr_take_entry *e = mr_take_book_get(b, name, err);
  if (e == NULL) return -1;
  if (e->n_files > cap)
    return mr_take_fail(err, MR_TAKE_ERR_ARG, "take '%s' has %zu files, room for %zu", name,
                        e->n_files, cap);
  for (size_t k = 0; k < e->n_files; k++) {
    snprintf(paths[k], MR_TAKE_PATH_MAX, "%.440s/%.63s", b->dir, e->files[k]);
    struct stat st;
    if (stat(paths[k], &st) != 0)
      return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: take '%s' names this file: %s", paths[k], name,
                          strerror(errno));
  }
  *n = e->n_files;
  return 0;
}

/* The first free take-N. */
static void default_name(const mr_take_book *b, char *out) {
  for (int k = 1;; k++) {
    snprintf(out, MR_TAKE_NAME_MAX, "take-%d", k);
    if (mr_take_book_find(b, out) == NULL) return;
  }
}

/* A new entry at the end of the list, named name (or take-N), with a fresh
 * id and its file names; NULL on error. */
mr_take_entry *mr_take_book_append(mr_take_book *b, const char *name, size_t n_files,
                                   mr_take_how how, mr_take_error *err) {
  char chosen[MR_TAKE_NAME_MAX];
  if (name == NULL || name[0] == '\0')
    default_name(b, chosen);
  else if (mr_take_book_check_name(b, name, err) != 0)
    return NULL;
  else
    snprintf(chosen, sizeof chosen, "%s", name);
  if (n_files == 0 || n_files > MR_TAKE_MAX_GLOVES) {
    mr_take_fail(err, MR_TAKE_ERR_ARG, "a take has 1..%d files (one per glove), got %zu",
                 MR_TAKE_MAX_GLOVES, n_files);
    return NULL;
  }
  mr_take_entry *more = realloc(b->takes, (b->n + 1) * sizeof *b->takes);
  if (more == NULL) {
    mr_take_fail(err, MR_TAKE_ERR_IO, "out of memory");
    return NULL;
  }
  b->takes = more;
  mr_take_entry *e = &b->takes[b->n++];
  memset(e, 0, sizeof *e);
  snprintf(e->name, sizeof e->name, "%s", chosen);
  e->id = b->next_id++;
  e->how = how;
  e->n_files = n_files;
  for (size_t k = 0; k < n_files; k++)
    snprintf(e->files[k], sizeof e->files[k], "t%04d-g%zu.mrec", e->id, k);
  e->created_unix = (int64_t)time(NULL);
  return e;
}

/* Removes the newest entry's files (those already written) and the entry. */
void mr_take_book_drop_last(mr_take_book *b) {
  if (b->n == 0) return;
  mr_take_entry *e = &b->takes[--b->n];
  for (size_t k = 0; k < e->n_files; k++) {
    char path[MR_TAKE_PATH_MAX + MR_TAKE_NAME_MAX];
    snprintf(path, sizeof path, "%s/%s", b->dir, e->files[k]);
    unlink(path);
  }
}

/* Copies src to dst, which must not exist yet. */
static int copy_file(const char *src, const char *dst, mr_take_error *err) {
  int in = open(src, O_RDONLY | O_CLOEXEC);
  if (in < 0) return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: %s", src, strerror(errno));
  int out = open(dst, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0444);
  if (out < 0) {
    close(in);
    return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: %s", dst, strerror(errno));
  }
  char buf[65536];
  ssize_t got;
  int rc = 0;
  while ((got = read(in, buf, sizeof buf)) > 0)
    if (write(out, buf, (size_t)got) != got) rc = -1;
  if (got < 0 || rc != 0 || fsync(out) != 0) rc = -1;
  int e = errno;
  close(in);
  if (close(out) != 0) rc = -1;
  if (rc != 0) return mr_take_fail(err, MR_TAKE_ERR_IO, "%s: cannot copy: %s", dst, strerror(e));
  return 0;
}

/* Brings one recorded file in as dst (move: renamed when it can be). */
static int bring_in(const char *src, const char *dst, bool move, mr_take_error *err) {
  if (move && access(dst, F_OK) != 0 && errno == ENOENT && link(src, dst) == 0) {
    unlink(src);
    return 0;
  }
  if (copy_file(src, dst, err) != 0) return -1;
  if (move) unlink(src);
  return 0;
}

/* Checks each file and reads its duration and scene: all inputs are
 * whole recordings, and their scenes agree. */
int mr_take_survey(const char *const *paths, size_t n, double *duration, uint64_t *scene,
                   char *note, size_t note_size, mr_take_error *err) {
  *duration = 0;
  *scene = 0;
  for (size_t k = 0; k < n; k++) {
    mr_take_rec r;
    if (mr_take_rec_load(paths[k], &r, err) != 0) return -1;
    double d = mr_take_rec_duration(&r);
    uint64_t h = r.header.scene_hash;
    if (r.truncated && note != NULL && note[0] == '\0') snprintf(note, note_size, "%s", r.note);
    mr_take_rec_free(&r);
    if (d > *duration) *duration = d;
    if (h != 0 && *scene != 0 && h != *scene)
      return mr_take_fail(err, MR_TAKE_ERR_SCENE,
                          "%s: recorded against scene %016llx, the "
                          "take's other gloves against %016llx",
                          paths[k], (unsigned long long)h, (unsigned long long)*scene);
    if (h != 0) *scene = h;
  }
  return 0;
}

int mr_take_book_add(mr_take_book *b, const char *name, const char *const *paths, size_t n,
                     bool move, mr_take_made *made, mr_take_error *err) {
  mr_take_made m;
  memset(&m, 0, sizeof m);
  double duration;
  uint64_t scene;
  if (mr_take_survey(paths, n, &duration, &scene, m.note, sizeof m.note, err) != 0) return -1;
  mr_take_entry *e = mr_take_book_append(b, name, n, MR_TAKE_RECORDED, err);
  if (e == NULL) return -1;
  e->duration = duration;
  e->scene_hash = scene;
  for (size_t k = 0; k < n; k++) {
    char dst[MR_TAKE_PATH_MAX + MR_TAKE_NAME_MAX];
    snprintf(dst, sizeof dst, "%s/%s", b->dir, e->files[k]);
    if (bring_in(paths[k], dst, move, err) != 0) {
      mr_take_book_drop_last(b);
      return -1;
    }
  }
  snprintf(m.name, sizeof m.name, "%s", e->name);
  if (mr_take_json_write(b, err) != 0) {
    /* A moved file stays in the book's folder: it is the raw input. */
    if (!move) mr_take_book_drop_last(b);
    return -1;
  }
  if (made != NULL) *made = m;
  return 0;
}

static int set_deleted(mr_take_book *b, const char *name, bool deleted, mr_take_error *err) {
  mr_take_entry *e = (mr_take_entry *)mr_take_book_get(b, name, err);
  if (e == NULL) return -1;
  if (e->deleted == deleted)
    return mr_take_fail(err, MR_TAKE_ERR_NAME, "%s: take '%s' is %s", b->dir, name,
                        deleted ? "already deleted" : "not deleted");
  e->deleted = deleted;
  if (mr_take_json_write(b, err) == 0) return 0;
  e->deleted = !deleted;
  return -1;
}

int mr_take_book_delete(mr_take_book *b, const char *name, mr_take_error *err) {
  return set_deleted(b, name, true, err);
}

int mr_take_book_restore(mr_take_book *b, const char *name, mr_take_error *err) {
  return set_deleted(b, name, false, err);
}

int mr_take_book_rename(mr_take_book *b, const char *name, const char *new_name,
                        mr_take_error *err) {
  mr_take_entry *e = (mr_take_entry *)mr_take_book_get(b, name, err);
  if (e == NULL || mr_take_book_check_name(b, new_name, err) != 0) return -1;
  char old[MR_TAKE_NAME_MAX];
  snprintf(old, sizeof old, "%s", e->name);
  snprintf(e->name, sizeof e->name, "%s", new_name);
  if (mr_take_json_write(b, err) == 0) return 0;
  snprintf(e->name, sizeof e->name, "%s", old);
  return -1;
}

int mr_take_resolve(const char *ref, char paths[][MR_TAKE_PATH_MAX], size_t cap, size_t *n,
                    mr_take_error *err) {
  const char *colon = ref != NULL ? strrchr(ref, ':') : NULL;
  if (colon == NULL || colon == ref || colon[1] == '\0') return 0;
  char dir[MR_TAKE_PATH_MAX], json[MR_TAKE_PATH_MAX + 16];
  if ((size_t)(colon - ref) >= sizeof dir) return 0;
  memcpy(dir, ref, (size_t)(colon - ref));
  dir[colon - ref] = '\0';
  snprintf(json, sizeof json, "%s/takes.json", dir);
  struct stat st;
  if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode) || stat(json, &st) != 0) return 0;
  mr_take_book b;
  if (mr_take_book_open(dir, false, &b, err) != 0) return -1;
  int rc = mr_take_book_paths(&b, colon + 1, paths, cap, n, err);
  mr_take_book_close(&b);
  return rc == 0 ? 1 : -1;
}

static const char *const FINGER[] = { "thumb", "index", "middle", "ring", "little" };

int mr_take_arms_parse(const char *text, mr_take_arm *arms, size_t cap, size_t *n,
                       mr_take_error *err) {
  *n = 0;
  const char *p = text;
  while (p != NULL && *p != '\0') {
    char *end;
    long g = strtol(p, &end, 10);
    if (end == p || *end != ':' || g < 0 || g >= MR_TAKE_MAX_GLOVES)
      return mr_take_fail(err, MR_TAKE_ERR_ARG, "expected GLOVE:FINGER (glove 0..7), got '%s'", p);
    p = end + 1;
    size_t len = strcspn(p, ",");
    long f = -1;
    for (int k = 0; k < MR_TAKE_CHANNELS; k++)
      if (strlen(FINGER[k]) == len && strncmp(p, FINGER[k], len) == 0) f = k;
    if (f < 0 && len == 1 && p[0] >= '0' && p[0] <= '4') f = p[0] - '0';
    if (f < 0)
      return mr_take_fail(err, MR_TAKE_ERR_ARG,
                          "expected a finger 0..4 or thumb, index, "
                          "middle, ring, little, got '%.*s'",
                          (int)len, p);
    if (*n == cap) return mr_take_fail(err, MR_TAKE_ERR_ARG, "more than %zu channels", cap);
    arms[(*n)++] = (mr_take_arm){ (int)g, (int)f };
    p += len;
    if (*p == ',') p++;
  }
  if (*n == 0) return mr_take_fail(err, MR_TAKE_ERR_ARG, "expected at least one GLOVE:FINGER");
  return 0;
}

mr_take_punch_def mr_default_take_punch_def(void) {
  mr_take_punch_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.t_in = d.t_out = NAN;
  return d;
}

mr_take_smooth_def mr_default_take_smooth_def(void) {
  mr_take_smooth_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.min_cutoff = 1.0;
  d.beta = 0.0;
  d.d_cutoff = 1.0;
  return d;
}

/* The show's state out (state_pub.h): the scene's files gathered once,
 * then each frame handed to mr_state_out on the thread that simulates. */
#define _POSIX_C_SOURCE 200809L

#include "state_pub.h"

#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "mr_scene_world.h"

struct mr_app_state_pub {
  mr_state_out *out;
  FILE *particles;
  bool write_failed, refused;
  char refusal[400];
  double *poses; /* 7 n_frames */
  size_t n_frames, n_points;
};

/* A whole file into memory; NULL when it cannot be read. */
static char *slurp(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (f == NULL) return NULL;
  char *data = NULL;
  size_t cap = 0, n = 0, got;
  do {
    if (n + 65536 > cap) {
      char *p = realloc(data, cap = 2 * cap + 65536);
      if (p == NULL) break;
      data = p;
    }
    got = fread(data + n, 1, cap - n, f);
    n += got;
  } while (got > 0);
  bool bad = ferror(f) != 0;
  fclose(f);
  if (bad) {
    free(data);
    return NULL;
  }
  *len = n;
  return data;
}

/* name (relative to the scene's folder dir), read and added, and the
 * files it names in turn (an OBJ's mtllib, an MTL's map_*); a file added
 * already is not added again. */
static int add_file(mr_state_bundle *b, const char *dir, const char *name, char *msg, size_t size) {
  size_t off = 0;
  mr_state_file seen;
  while (mr_state_bundle_next(b->data, b->size, &off, &seen) == 1)
    if (strcmp(seen.name, name) == 0) return 0;
  char path[1200];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  size_t len = 0;
  char *data = slurp(path, &len);
  if (data == NULL) return snprintf(msg, size, "cannot read %s", path), -1;
  if (mr_state_bundle_add(b, name, data, len) != 0) {
    free(data);
    return snprintf(msg, size, "%s: a name a watcher could not write beside the scene", name), -1;
  }
  /* The names an OBJ or MTL gives are beside it. */
  const char *slash = strrchr(name, '/');
  int here = slash != NULL ? (int)(slash - name + 1) : 0;
  int rc = 0;
  for (char *line = data; rc == 0 && line < data + len;) {
    char *end = memchr(line, '\n', (size_t)(data + len - line));
    if (end == NULL) end = data + len;
    *end = '\0';
    char word[32], other[600];
    if (sscanf(line, "%31s %599s", word, other) == 2 &&
        (strcmp(word, "mtllib") == 0 || strncmp(word, "map_", 4) == 0)) {
      char sub[700];
      snprintf(sub, sizeof sub, "%.*s%s", here, name, other);
      rc = add_file(b, dir, sub, msg, size);
    }
    line = end + 1;
  }
  free(data);
  return rc;
}

int mr_app_scene_files(const mr_scene *scene, mr_state_bundle *b, char *msg, size_t msg_size) {
  char dir[1024];
  snprintf(dir, sizeof dir, "%s", scene->path);
  char *slash = strrchr(dir, '/');
  const char *base = slash != NULL ? slash + 1 : scene->path;
  if (slash != NULL)
    *slash = '\0';
  else
    snprintf(dir, sizeof dir, ".");
  if (add_file(b, dir, base, msg, msg_size) != 0) return -1;
  size_t dl = strlen(dir);
  for (size_t i = 0; i < scene->stage.n_models; i++) {
    const mr_model_def *m = &scene->stage.models[i];
    if (m->shape != MR_SHAPE_FILE) continue;
    const char *p = m->path;
    if (strncmp(p, "./", 2) == 0 && strcmp(dir, ".") == 0)
      p += 2;
    else if (strncmp(p, dir, dl) == 0 && p[dl] == '/')
      p += dl + 1;
    else if (strcmp(dir, ".") != 0 || p[0] == '/')
      return snprintf(msg, msg_size,
                      "model %s: %s is not beside the scene, and a watcher builds the "
                      "scene from the files beside it (host/net/STATE.md)",
                      m->name, m->path),
             -1;
    if (add_file(b, dir, p, msg, msg_size) != 0) return -1;
  }
  return 0;
}

static int open_link(mr_app_state_pub *p, const char *url, const mr_scene *scene, double fps,
                     char *msg, size_t msg_size) {
  mr_state_bundle b;
  memset(&b, 0, sizeof b);
  if (mr_app_scene_files(scene, &b, msg, msg_size) != 0) {
    mr_state_bundle_free(&b);
    return -1;
  }
  mr_state_out_def d = mr_default_state_out_def();
  d.url = url;
  d.scene = &b;
  d.fps = fps;
  d.n_frames = (int)p->n_frames;
  d.n_points = (int)p->n_points;
  mr_io_error err;
  int rc = mr_state_out_open(&d, &p->out, &err);
  if (rc != 0) snprintf(msg, msg_size, "--publish: %s", err.msg);
  mr_state_bundle_free(&b);
  return rc;
}

int mr_app_state_pub_open(const char *url, const char *particles, const mr_scene *scene, double fps,
                          mr_app_state_pub **out, char *msg, size_t msg_size) {
  *out = NULL;
  mr_app_state_pub *p = calloc(1, sizeof *p);
  if (p == NULL) return snprintf(msg, msg_size, "out of memory"), -1;
  mr_scene_error err;
  double *start = mr_scene_start_positions(scene, &p->n_points, &err);
  free(start);
  p->n_frames = scene->n_frames;
  p->poses = calloc(7 * p->n_frames + 1, sizeof *p->poses);
  int rc = 0;
  if (start == NULL || p->poses == NULL) {
    snprintf(msg, msg_size, "%s", start == NULL ? err.text : "out of memory");
    rc = -1;
  } else if (p->n_frames > MR_STATE_MAX_FRAMES || p->n_points > MR_STATE_MAX_POINTS) {
    snprintf(msg, msg_size,
             "--publish: the scene has more than 255 control frames or 65535 "
             "particles, more than a state message holds");
    rc = -1;
  }
  if (rc == 0 && url != NULL) rc = open_link(p, url, scene, fps, msg, msg_size);
  if (rc == 0 && particles != NULL && (p->particles = fopen(particles, "w")) == NULL) {
    snprintf(msg, msg_size, "cannot write %s", particles);
    rc = -1;
  }
  if (rc != 0) {
    mr_app_state_pub_close(p, NULL);
    return -1;
  }
  *out = p;
  return 0;
}

/* One line: the frame's time, then x y z of each particle. */
static void write_particles(mr_app_state_pub *p, const mr_show_frame *f) {
  int bad = fprintf(p->particles, "%.6f", f->t) < 0;
  for (int i = 0; i < 3 * f->n_particles; i++) bad |= fprintf(p->particles, " %.9g", f->xyz[i]) < 0;
  if (bad || fputc('\n', p->particles) == EOF) p->write_failed = true;
}

void mr_app_state_pub_frame(mr_app_state_pub *p, const mr_show_frame *f) {
  if (p == NULL) return;
  if (p->particles != NULL) write_particles(p, f);
  if (p->out == NULL || p->refused || (size_t)f->n_particles != p->n_points ||
      f->n_frames != p->n_frames)
    return;
  for (size_t k = 0; k < f->n_frames; k++) {
    memcpy(p->poses + 7 * k, f->pose[k].position, 3 * sizeof(double));
    memcpy(p->poses + 7 * k + 3, f->pose[k].orientation, 4 * sizeof(double));
  }
  mr_io_error err;
  if (mr_state_out_frame(p->out, f->t, p->poses, f->xyz, &err) < 0) {
    p->refused = true;
    snprintf(p->refusal, sizeof p->refusal, "%s", err.msg);
  }
}

int mr_app_state_pub_close(mr_app_state_pub *p, FILE *out) {
  if (p == NULL) return 0;
  int rc = p->write_failed ? -1 : 0;
  if (p->particles != NULL && fclose(p->particles) != 0) rc = -1;
  if (p->out != NULL && out != NULL) {
    mr_state_out_counters c;
    mr_state_out_get_counters(p->out, &c);
    fprintf(out, "published frames: %" PRIu64 " (%" PRIu64 " bytes, %.0f a frame)\n", c.sent,
            c.bytes, c.sent > 0 ? (double)c.bytes / (double)c.sent : 0.0);
    fprintf(out, "published scene: %zu bytes, sent %" PRIu64 " times\n", c.scene_bytes, c.scenes);
    fprintf(out, "publish dropped: %" PRIu64 " (network behind), %" PRIu64 " (broker away)\n",
            c.dropped_behind, c.dropped_away);
  }
  if (p->refused) {
    fprintf(stderr, "marionette run: --publish: %s\n", p->refusal);
    rc = -1;
  }
  mr_state_out_close(p->out);
  free(p->poses);
  free(p);
  return rc;
}

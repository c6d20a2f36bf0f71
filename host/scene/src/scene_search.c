/* Where a scene's model file is found (host/scenes/FORMAT.md, "Where
 * models are found"): the scene file's folder first, then each folder of
 * the environment's MARIONETTE_PATH (':'-separated), then the installed
 * scenes' folder (MR_SCENE_DATADIR, PREFIX/share/marionette/scenes). */
#define _POSIX_C_SOURCE 200809L
#include "scene_read.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef MR_SCENE_DATADIR
#error "MR_SCENE_DATADIR names the installed scenes' folder (host/scene/CMakeLists.txt)"
#endif

/* Appends ", place" (or "place" first) to the list; a list that no longer
 * fits ends in "...". */
static void note_place(char *looked, size_t size, const char *place) {
  size_t used = strlen(looked);
  if (used + 4 >= size) return;
  int n = snprintf(looked + used, size - used, "%s%s", used ? ", " : "", place);
  if (n < 0 || (size_t)n >= size - used) strcpy(looked + size - 4, "...");
}

/* dir/name into out when it fits; 0 if it does. */
static int join(char *out, size_t size, const char *dir, size_t dir_len, const char *name) {
  const char *sep = dir_len > 0 && dir[dir_len - 1] != '/' ? "/" : "";
  int n = snprintf(out, size, "%.*s%s%s", (int)dir_len, dir, sep, name);
  return n >= 0 && (size_t)n < size ? 0 : -1;
}

/* Tries one place: found (1), not there (0, and named in looked). */
static int try_place(const char *place, char *path, size_t size, char *looked, size_t looked_size) {
  if (access(place, R_OK) == 0) {
    snprintf(path, size, "%s", place);
    return 1;
  }
  note_place(looked, looked_size, place);
  return 0;
}

int mr_scene_model_find(const char *scene_path, const char *name, char *path, size_t size,
                        char *looked, size_t looked_size) {
  looked[0] = '\0';
  const char *slash = strrchr(scene_path, '/');
  size_t dir = name[0] == '/' || slash == NULL ? 0 : (size_t)(slash - scene_path) + 1;
  /* The scene's own folder: the path kept when the file is nowhere, so
   * that the error names it first. */
  int n = snprintf(path, size, "%.*s%s", (int)dir, scene_path, name);
  if (n < 0 || (size_t)n >= size) return -1;
  if (name[0] == '/' || access(path, R_OK) == 0) return 0;
  char first[MR_STAGE_PATH_MAX], place[MR_STAGE_PATH_MAX];
  snprintf(first, sizeof first, "%s", path);
  const char *env = getenv("MARIONETTE_PATH");
  for (const char *p = env; p && *p;) {
    size_t len = strcspn(p, ":");
    if (len > 0 && join(place, sizeof place, p, len, name) == 0 &&
        try_place(place, path, size, looked, looked_size))
      return looked[0] = '\0', 0;
    p += len + (p[len] == ':');
  }
  if (join(place, sizeof place, MR_SCENE_DATADIR, strlen(MR_SCENE_DATADIR), name) == 0 &&
      try_place(place, path, size, looked, looked_size))
    return looked[0] = '\0', 0;
  snprintf(path, size, "%s", first);
  return 0;
}

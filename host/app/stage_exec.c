/* `marionette run` and `marionette render` draw; `sim`, `calibrate` and
 * `list-ports` do not. The drawing commands live in a program of their own,
 * the stage program, linked against the renderer, so that `marionette`
 * itself maps no graphics library: starting the dynamic loader on GL, SDL,
 * Assimp and their dependencies costs about 57 M instructions, more than
 * a 10 s walk simulates in. For a drawing command this program replaces
 * itself with the stage program: same process, same arguments, same
 * descriptors and signals, so a caller sees one program. `marionette
 * export`, which loads models through Assimp but draws nothing, lives in
 * the export program beside it, reached the same way, and `list-ports`
 * and `calibrate`, which open gloves (a broker's too: the MQTT client and
 * TLS), in the glove program. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "app.h"

/* Both come from host/app/CMakeLists.txt: the stage program's file name,
 * and where it is installed relative to this program's folder. */
#ifndef MR_STAGE_PROGRAM
#error "MR_STAGE_PROGRAM (the stage program's file name) is not defined"
#endif
#ifndef MR_EXPORT_PROGRAM
#error "MR_EXPORT_PROGRAM (the export program's file name) is not defined"
#endif
#ifndef MR_GLOVE_PROGRAM
#error "MR_GLOVE_PROGRAM (the glove program's file name) is not defined"
#endif
#ifndef MR_STAGE_FROM_BINDIR
#error "MR_STAGE_FROM_BINDIR (the stage program's folder relative to bin) is not defined"
#endif

/* This program's own folder into dir; 0 or -1. /proc/self/exe rather than
 * argv[0]: the program may have been found along PATH or through a link. */
static int own_folder(char *dir, size_t size) {
  ssize_t n = readlink("/proc/self/exe", dir, size - 1);
  if (n <= 0 || (size_t)n >= size - 1) return -1;
  dir[n] = '\0';
  char *slash = strrchr(dir, '/');
  if (slash == NULL) return -1;
  *slash = '\0';
  return 0;
}

/* What the program is called in a message. */
static const char *kind(const char *program) {
  if (strcmp(program, MR_STAGE_PROGRAM) == 0) return "stage";
  return strcmp(program, MR_GLOVE_PROGRAM) == 0 ? "glove" : "export";
}

int mr_stage_exec(const char *program, char **argv) {
  char dir[PATH_MAX];
  if (own_folder(dir, sizeof dir) != 0) {
    fprintf(stderr, "marionette %s: cannot find this program's own folder: %s\n", argv[1],
            strerror(errno));
    return MR_EXIT_FAIL;
  }
  /* Beside this program in the build tree; under libexec once installed
   * (PREFIX and DESTDIR move both folders alike). */
  const char *places[] = { "", "/" MR_STAGE_FROM_BINDIR };
  char path[PATH_MAX];
  for (size_t i = 0; i < sizeof places / sizeof places[0]; i++) {
    int n = snprintf(path, sizeof path, "%s%s/%s", dir, places[i], program);
    if (n < 0 || (size_t)n >= sizeof path || access(path, X_OK) != 0) continue;
    fflush(NULL);
    execv(path, argv);
    fprintf(stderr, "marionette %s: cannot start %s: %s\n", argv[1], path, strerror(errno));
    return MR_EXIT_FAIL;
  }
  fprintf(stderr,
          "marionette %s: the %s program %s is neither in %s nor in %s/%s; build or "
          "install it (make, make install)\n",
          argv[1], kind(program), program, dir, dir, MR_STAGE_FROM_BINDIR);
  return MR_EXIT_FAIL;
}

/* Runs a program as a real child process and captures what it prints. */
#ifndef SCENE_PROC_H
#define SCENE_PROC_H

#include <stddef.h>

typedef struct scene_proc {
  int status; /* exit status, or 128 + signal */
  char *out;  /* stdout, NUL-terminated */
  char *err;  /* stderr, NUL-terminated */
} scene_proc;

/* argv[0] is the program path; argv ends with NULL. Returns 0 when the
 * child ran (whatever its status), -1 when it could not be started. */
int scene_proc_run(char *const argv[], scene_proc *p);
void scene_proc_free(scene_proc *p);

/* The value after "key: " on a line of text, copied into out; 0 or -1. */
int scene_proc_field(const char *text, const char *key, char *out, size_t size);

/* Writes text to a fresh file under the build tree and returns its path
 * (static storage, valid until the next call with the same slot). */
const char *scene_tmp_file(const char *name, const char *text, size_t len);

#endif

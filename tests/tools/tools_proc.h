/* Helpers for the tools tests: real processes, files and bounded waits. */
#ifndef TOOLS_PROC_H
#define TOOLS_PROC_H

#include <stddef.h>
#include <sys/types.h>

/* Starts argv[0] with stdout and stderr sent to files (NULL: /dev/null). */
pid_t tt_spawn(const char *const argv[], const char *out_path, const char *err_path);

/* Waits at most timeout_s for pid: its exit status, 128+signal if killed by a
 * signal, or -1 if it did not end in time (it is then killed). */
int tt_wait(pid_t pid, int timeout_s);

/* spawn + wait. */
int tt_run(const char *const argv[], const char *out_path, const char *err_path,
           int timeout_s);

/* The whole file, NUL-terminated (free it); NULL if it cannot be read. */
char *tt_read_file(const char *path, size_t *len);

/* Waits at most timeout_s for path to exist with content. 0 or -1. */
int tt_wait_for_file(const char *path, int timeout_s);

/* The value of a "key=value" line in text, or -1 if absent. */
long long tt_kv(const char *text, const char *key);

/* A fresh directory under /tmp (free the string); tt_rmdir removes it and
 * the files in it. */
char *tt_tmpdir(void);
void tt_rmdir(const char *dir);

/* dir/name in a static buffer ring (valid for a few calls). */
const char *tt_path(const char *dir, const char *name);

/* The paths of the tools, from the test's command line. */
extern const char *tt_glove_gen;
extern const char *tt_glove_dump;
void tt_take_args(int argc, char **argv);

#endif

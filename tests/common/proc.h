/* Test helpers shared by every area: real child processes with bounded
 * waits, their output captured to files or to memory, and scratch files.
 * A failure says why: what the child printed, how it ended. */
#ifndef TEST_PROC_H
#define TEST_PROC_H

#include <stddef.h>
#include <sys/types.h>

/* --- time ----------------------------------------------------------------- */

/* The monotonic clock in seconds, for bounding a test's waits. */
double tt_now_s(void);
/* Sleeps s seconds (s >= 0). */
void tt_sleep_s(double s);

/* --- child processes ------------------------------------------------------ */

/* Starts argv[0] with stdin from /dev/null and stdout and stderr sent to
 * files (NULL: /dev/null). The pid, or -1. */
pid_t tt_spawn(const char *const argv[], const char *out_path, const char *err_path);

/* Waits at most timeout_s for pid: its exit status, 128+signal if killed by
 * a signal, or -1 if it did not end in time (it is then killed). */
int tt_wait(pid_t pid, int timeout_s);

/* spawn + wait. */
int tt_run(const char *const argv[], const char *out_path, const char *err_path, int timeout_s);

/* A finished child's status and everything it printed. */
typedef struct tt_output {
  int status; /* exit status, or 128 + signal */
  char *out;  /* stdout, NUL-terminated */
  char *err;  /* stderr, NUL-terminated */
} tt_output;

/* Runs argv (argv[0] a path, NULL-terminated) to its end, capturing stdout
 * and stderr in memory. 0 when the child ran (whatever its status), -1 when
 * it could not be started. */
int tt_capture(char *const argv[], tt_output *o);
void tt_output_free(tt_output *o);

/* Waits at most timeout_s for path to exist with content, while the child
 * pid runs: it stops at once if the child exits first. 0, or -1 after
 * printing to stderr how the child ended and, from err_path (may be NULL),
 * what it said. */
int tt_await_file(pid_t pid, const char *path, const char *err_path, int timeout_s);

/* glove-gen (its path) streaming on a pty of its own, reached as a glove:
 * the arguments every test gives it (-o pty, a path file in dir, --wait 30,
 * --linger 0, -q), then extra (NULL-terminated; may be NULL). On success
 * its pid, with "pty:PATH" in source; -1 after printing why. */
pid_t tt_glove_on_pty(const char *glove_gen, const char *dir, const char *const extra[],
                      char *source, size_t size);

/* --- files and text ------------------------------------------------------- */

/* The whole file, NUL-terminated (free it); NULL if it cannot be read. */
char *tt_read_file(const char *path, size_t *len);

/* Waits at most timeout_s for path to exist with content. 0 or -1. */
int tt_wait_for_file(const char *path, int timeout_s);

/* The value of a "key=value" line in text, or -1 if absent. */
long long tt_kv(const char *text, const char *key);

/* The value after "key: " on a line of text, copied into out; 0 or -1. */
int tt_field(const char *text, const char *key, char *out, size_t size);

/* A fresh directory under /tmp (free the string); tt_rmdir removes it and
 * the files in it. */
char *tt_tmpdir(void);
void tt_rmdir(const char *dir);

/* dir/name in a static buffer ring (valid for a few calls). */
const char *tt_path(const char *dir, const char *name);

/* Writes len bytes of text to name in this process's own scratch folder
 * and returns its path (static storage, valid until the next call). */
const char *tt_tmp_file(const char *name, const char *text, size_t len);

#endif

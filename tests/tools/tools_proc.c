#include "tools_proc.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

const char *tt_glove_gen = "glove-gen";
const char *tt_glove_dump = "glove-dump";

void tt_take_args(int argc, char **argv) {
  if (argc > 1) tt_glove_gen = argv[1];
  if (argc > 2) tt_glove_dump = argv[2];
}

static void sleep_ms(int ms) {
  struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
  nanosleep(&ts, NULL);
}

pid_t tt_spawn(const char *const argv[], const char *out_path, const char *err_path) {
  pid_t pid = fork();
  if (pid == 0) {
    int out = open(out_path ? out_path : "/dev/null", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    int err = open(err_path ? err_path : "/dev/null", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    int in = open("/dev/null", O_RDONLY);
    if (out < 0 || err < 0 || in < 0) _exit(126);
    dup2(in, 0);
    dup2(out, 1);
    dup2(err, 2);
    execv(argv[0], (char *const *)argv);
    _exit(127);
  }
  return pid;
}

int tt_wait(pid_t pid, int timeout_s) {
  int status;
  for (int waited = 0; waited <= timeout_s * 100; waited++) {
    pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) {
      if (WIFEXITED(status)) return WEXITSTATUS(status);
      if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
      return -1;
    }
    sleep_ms(10);
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

int tt_run(const char *const argv[], const char *out_path, const char *err_path,
           int timeout_s) {
  pid_t pid = tt_spawn(argv, out_path, err_path);
  return pid < 0 ? -1 : tt_wait(pid, timeout_s);
}

char *tt_read_file(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  char *buf = NULL;
  size_t cap = 0, n = 0;
  if (!f) return NULL;
  for (;;) {
    size_t got;
    if (cap - n < 65536) {
      char *nb = realloc(buf, cap + 65536 + 1);
      if (!nb) {
        free(buf);
        fclose(f);
        return NULL;
      }
      buf = nb;
      cap += 65536;
    }
    got = fread(buf + n, 1, cap - n, f);
    n += got;
    if (got == 0) break;
  }
  fclose(f);
  buf[n] = 0;
  if (len) *len = n;
  return buf;
}

int tt_wait_for_file(const char *path, int timeout_s) {
  for (int waited = 0; waited <= timeout_s * 100; waited++) {
    struct stat st;
    if (stat(path, &st) == 0 && st.st_size > 0) return 0;
    sleep_ms(10);
  }
  return -1;
}

long long tt_kv(const char *text, const char *key) {
  size_t kl = strlen(key);
  for (const char *p = text; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL) {
    if (strncmp(p, key, kl) == 0 && p[kl] == '=') return atoll(p + kl + 1);
  }
  return -1;
}

char *tt_tmpdir(void) {
  char *d = strdup("/tmp/mr-tools-test-XXXXXX");
  if (!d || !mkdtemp(d)) {
    free(d);
    return NULL;
  }
  return d;
}

void tt_rmdir(const char *dir) {
  DIR *d = opendir(dir);
  struct dirent *e;
  if (!d) return;
  while ((e = readdir(d))) {
    if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
    unlink(tt_path(dir, e->d_name));
  }
  closedir(d);
  rmdir(dir);
}

const char *tt_path(const char *dir, const char *name) {
  static char ring[8][1024];
  static int next;
  char *p = ring[next++ % 8];
  snprintf(p, sizeof ring[0], "%s/%s", dir, name);
  return p;
}

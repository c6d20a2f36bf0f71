#include "proc.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

double tt_now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

void tt_sleep_s(double s) {
  struct timespec ts = { (time_t)s, (long)((s - (double)(time_t)s) * 1e9) };
  nanosleep(&ts, NULL);
}

static void sleep_ms(int ms) {
  struct timespec ts = { ms / 1000, (long)(ms % 1000) * 1000000L };
  nanosleep(&ts, NULL);
}

static int status_of(int wstatus) {
  if (WIFEXITED(wstatus)) return WEXITSTATUS(wstatus);
  if (WIFSIGNALED(wstatus)) return 128 + WTERMSIG(wstatus);
  return -1;
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
    if (r == pid) return status_of(status);
    sleep_ms(10);
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

int tt_run(const char *const argv[], const char *out_path, const char *err_path, int timeout_s) {
  pid_t pid = tt_spawn(argv, out_path, err_path);
  return pid < 0 ? -1 : tt_wait(pid, timeout_s);
}

typedef struct buf {
  char *data;
  size_t len, cap;
} buf;

static int append(buf *b, const char *src, size_t n) {
  if (b->len + n + 1 > b->cap) {
    size_t cap = b->cap ? b->cap : 4096;
    char *d;
    while (cap < b->len + n + 1) cap *= 2;
    d = realloc(b->data, cap);
    if (!d) return -1;
    b->data = d;
    b->cap = cap;
  }
  memcpy(b->data + b->len, src, n);
  b->len += n;
  b->data[b->len] = '\0';
  return 0;
}

/* Reads both pipes until both close, so a chatty child never blocks on a
 * full pipe while we wait on the other. */
static void drain_pipes(int out_fd, int err_fd, buf *bo, buf *be) {
  struct pollfd fds[2] = { { out_fd, POLLIN, 0 }, { err_fd, POLLIN, 0 } };
  int open_fds = 2;
  while (open_fds > 0) {
    if (poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < 2; i++) {
      char chunk[4096];
      ssize_t n;
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      n = read(fds[i].fd, chunk, sizeof chunk);
      if (n > 0) {
        append(i == 0 ? bo : be, chunk, (size_t)n);
      } else {
        close(fds[i].fd);
        fds[i].fd = -1;
        open_fds--;
      }
    }
  }
}

int tt_capture(char *const argv[], tt_output *o) {
  int out[2], err[2], status = 0;
  buf bo = { 0 }, be = { 0 };
  pid_t pid;
  memset(o, 0, sizeof *o);
  if (pipe(out) != 0) return -1;
  if (pipe(err) != 0) {
    close(out[0]);
    close(out[1]);
    return -1;
  }
  pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    dup2(out[1], 1);
    dup2(err[1], 2);
    close(out[0]);
    close(err[0]);
    close(out[1]);
    close(err[1]);
    execv(argv[0], argv);
    _exit(127);
  }
  close(out[1]);
  close(err[1]);
  append(&bo, "", 0);
  append(&be, "", 0);
  drain_pipes(out[0], err[0], &bo, &be);
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  o->status = status_of(status);
  o->out = bo.data;
  o->err = be.data;
  return 0;
}

void tt_output_free(tt_output *o) {
  free(o->out);
  free(o->err);
  o->out = o->err = NULL;
}

static int file_has_content(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 && st.st_size > 0;
}

static void print_child_stderr(const char *err_path) {
  char *text = err_path ? tt_read_file(err_path, NULL) : NULL;
  fprintf(stderr, "  its stderr: %s\n", text && *text ? text : "(empty)");
  free(text);
}

pid_t tt_glove_on_pty(const char *glove_gen, const char *dir, const char *const extra[],
                      char *source, size_t size) {
  char pf[600], err[600];
  snprintf(pf, sizeof pf, "%s", tt_path(dir, "pty.path"));
  snprintf(err, sizeof err, "%s", tt_path(dir, "gen.err"));
  unlink(pf); /* a glove started before in the same folder left its path */
  const char *argv[32] = { glove_gen, "-o", "pty",      "--path-file", pf,
                           "--wait",  "30", "--linger", "0",           "-q" };
  size_t n = 10;
  for (size_t i = 0; extra != NULL && extra[i] != NULL && n < 31; i++) argv[n++] = extra[i];
  argv[n] = NULL;
  pid_t gen = tt_spawn(argv, NULL, err);
  if (gen <= 0 || tt_await_file(gen, pf, err, 30) != 0) return -1;
  char *path = tt_read_file(pf, NULL);
  if (path == NULL) return -1;
  path[strcspn(path, "\n")] = '\0';
  snprintf(source, size, "pty:%s", path);
  free(path);
  return gen;
}

int tt_await_file(pid_t pid, const char *path, const char *err_path, int timeout_s) {
  for (int waited = 0; waited <= timeout_s * 100; waited++) {
    siginfo_t info;
    if (file_has_content(path)) return 0;
    /* WNOWAIT: look without reaping, so the caller's tt_wait still gets the
     * status. */
    memset(&info, 0, sizeof info);
    if (waitid(P_PID, (id_t)pid, &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid) {
      /* The child may have written the file just before it ended. */
      if (file_has_content(path)) return 0;
      fprintf(stderr, "child %ld %s %d without writing %s\n", (long)pid,
              info.si_code == CLD_EXITED ? "exited with status" : "was killed by signal",
              info.si_status, path);
      print_child_stderr(err_path);
      return -1;
    }
    sleep_ms(10);
  }
  fprintf(stderr, "child %ld did not write %s within %d s\n", (long)pid, path, timeout_s);
  print_child_stderr(err_path);
  return -1;
}

char *tt_read_file(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  char *data = NULL;
  size_t cap = 0, n = 0;
  if (!f) return NULL;
  for (;;) {
    size_t got;
    if (cap - n < 65536) {
      char *nb = realloc(data, cap + 65536 + 1);
      if (!nb) {
        free(data);
        fclose(f);
        return NULL;
      }
      data = nb;
      cap += 65536;
    }
    got = fread(data + n, 1, cap - n, f);
    n += got;
    if (got == 0) break;
  }
  fclose(f);
  data[n] = 0;
  if (len) *len = n;
  return data;
}

int tt_wait_for_file(const char *path, int timeout_s) {
  for (int waited = 0; waited <= timeout_s * 100; waited++) {
    if (file_has_content(path)) return 0;
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

int tt_field(const char *text, const char *key, char *out, size_t size) {
  size_t klen = strlen(key);
  for (const char *line = text; line && *line;) {
    const char *end = strchr(line, '\n');
    size_t n = end ? (size_t)(end - line) : strlen(line);
    if (n > klen + 1 && strncmp(line, key, klen) == 0 && line[klen] == ':' &&
        line[klen + 1] == ' ') {
      size_t v = n - klen - 2;
      if (v >= size) v = size - 1;
      memcpy(out, line + klen + 2, v);
      out[v] = '\0';
      return 0;
    }
    line = end ? end + 1 : NULL;
  }
  return -1;
}

char *tt_tmpdir(void) {
  char *d = strdup("/tmp/mr-test-XXXXXX");
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

/* One scratch folder per process, removed at exit: tests that run at the
 * same time (ctest -j, or two build trees) never share a name. */
static char g_scratch[64];

static void remove_scratch(void) {
  if (g_scratch[0]) tt_rmdir(g_scratch);
}

const char *tt_tmp_file(const char *name, const char *text, size_t len) {
  static char path[1024];
  FILE *f;
  if (!g_scratch[0]) {
    char *d = tt_tmpdir();
    if (!d) return NULL;
    snprintf(g_scratch, sizeof g_scratch, "%s", d);
    free(d);
    atexit(remove_scratch);
  }
  snprintf(path, sizeof path, "%s/%s", g_scratch, name);
  f = fopen(path, "wb");
  if (!f) return NULL;
  if (fwrite(text, 1, len, f) != len) {
    fclose(f);
    return NULL;
  }
  if (fclose(f) != 0) return NULL;
  return path;
}

#define _POSIX_C_SOURCE 200809L

#include "scene_proc.h"

#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

typedef struct buf {
  char *data;
  size_t len, cap;
} buf;

static int append(buf *b, const char *src, size_t n) {
  if (b->len + n + 1 > b->cap) {
    size_t cap = (b->cap ? b->cap : 4096);
    while (cap < b->len + n + 1)
      cap *= 2;
    char *d = realloc(b->data, cap);
    if (d == NULL)
      return -1;
    b->data = d;
    b->cap = cap;
  }
  memcpy(b->data + b->len, src, n);
  b->len += n;
  b->data[b->len] = '\0';
  return 0;
}

int scene_proc_run(char *const argv[], scene_proc *p) {
  memset(p, 0, sizeof *p);
  int out[2], err[2];
  if (pipe(out) != 0)
    return -1;
  if (pipe(err) != 0) {
    close(out[0]);
    close(out[1]);
    return -1;
  }
  pid_t pid = fork();
  if (pid < 0)
    return -1;
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
  buf bo = {0}, be = {0};
  append(&bo, "", 0);
  append(&be, "", 0);
  struct pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  int open_fds = 2;
  while (open_fds > 0) {
    if (poll(fds, 2, -1) < 0) {
      if (errno == EINTR)
        continue;
      break;
    }
    for (int i = 0; i < 2; i++) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR)))
        continue;
      char chunk[4096];
      ssize_t n = read(fds[i].fd, chunk, sizeof chunk);
      if (n > 0) {
        append(i == 0 ? &bo : &be, chunk, (size_t)n);
      } else {
        close(fds[i].fd);
        fds[i].fd = -1;
        open_fds--;
      }
    }
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
    ;
  p->status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  p->out = bo.data;
  p->err = be.data;
  return 0;
}

void scene_proc_free(scene_proc *p) {
  free(p->out);
  free(p->err);
  p->out = p->err = NULL;
}

int scene_proc_field(const char *text, const char *key, char *out, size_t size) {
  size_t klen = strlen(key);
  for (const char *line = text; line && *line;) {
    const char *end = strchr(line, '\n');
    size_t n = end ? (size_t)(end - line) : strlen(line);
    if (n > klen + 1 && strncmp(line, key, klen) == 0 && line[klen] == ':' &&
        line[klen + 1] == ' ') {
      size_t v = n - klen - 2;
      if (v >= size)
        v = size - 1;
      memcpy(out, line + klen + 2, v);
      out[v] = '\0';
      return 0;
    }
    line = end ? end + 1 : NULL;
  }
  return -1;
}

const char *scene_tmp_file(const char *name, const char *text, size_t len) {
  static char path[4096];
  char dir[3500];
  snprintf(dir, sizeof dir, "%s/tests/scene/tmp", MR_BINARY_DIR);
  mkdir(dir, 0777);
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "wb");
  if (f == NULL)
    return NULL;
  fwrite(text, 1, len, f);
  fclose(f);
  return path;
}

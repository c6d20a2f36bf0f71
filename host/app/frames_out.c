/* PNG frames, an MP4 through ffmpeg, and a contact sheet (issue 10, item
 * 6). Images are written by stb_image_write, whose PNG bytes depend only
 * on the pixels: the same frame gives the same file. */
#define _GNU_SOURCE /* pipe2 */

#include "frames_out.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <stb_image_write.h>

#include "sheet.h"

struct mr_frames_out {
  mr_frames_out_def def;
  char dir[512], mp4[512], sheet[512];
  uint64_t frames, pngs, encoded;
  pid_t ffmpeg;
  int pipe_fd; /* ffmpeg's stdin, -1 without */
  bool pipe_broken;
  mr_sheet *sh;
  uint8_t *last;       /* keep_time: the frame piped last, to repeat */
  uint64_t next_index; /* keep_time: the video frame to write next */
};

mr_frames_out_def mr_default_frames_out_def(void) {
  mr_frames_out_def d;
  memset(&d, 0, sizeof d);
  d.cookie = MR_DEF_COOKIE;
  d.every = 1;
  d.fps = 30;
  d.sheet_cells = 24;
  return d;
}

int mr_png_write(const char *path, const uint8_t *rgb, int width, int height) {
  return stbi_write_png(path, width, height, 3, rgb, width * 3) ? 0 : -1;
}

bool mr_on_path(const char *program) {
  const char *path = getenv("PATH");
  if (path == NULL) return false;
  while (*path != '\0') {
    size_t n = strcspn(path, ":");
    char full[1024];
    snprintf(full, sizeof full, "%.*s/%s", (int)(n > 0 ? n : 1), n > 0 ? path : ".", program);
    if (access(full, X_OK) == 0) return true;
    path += n;
    if (*path == ':') path++;
  }
  return false;
}

/* A folder and its parents, as mkdir -p. */
int mr_make_dir(const char *dir) {
  char buf[512];
  if (strlen(dir) >= sizeof buf) return errno = ENAMETOOLONG, -1;
  snprintf(buf, sizeof buf, "%s", dir);
  for (char *p = buf + 1; *p != '\0'; p++) {
    if (*p != '/') continue;
    *p = '\0';
    if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
    *p = '/';
  }
  if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
  struct stat st;
  return stat(buf, &st) == 0 && S_ISDIR(st.st_mode) ? 0 : -1;
}

/* ffmpeg reading raw RGB on its stdin: H.264 in yuv420p, which every
 * player takes; odd sizes padded to even, as yuv420p needs. */
static int start_ffmpeg(mr_frames_out *fo, char *msg, size_t msg_size) {
  int fds[2];
  /* Close-on-exec: ffmpeg inherits only its stdin, not the pipe's write
   * end (it would never see the end of its input). */
  if (pipe2(fds, O_CLOEXEC) != 0) {
    snprintf(msg, msg_size, "cannot start ffmpeg: %s", strerror(errno));
    return -1;
  }
  char size[32], rate[32];
  snprintf(size, sizeof size, "%dx%d", fo->def.width, fo->def.height);
  snprintf(rate, sizeof rate, "%g", fo->def.fps);
  pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[0], 0);
    close(fds[0]);
    close(fds[1]);
    const char *argv[] = { "ffmpeg",
                           "-hide_banner",
                           "-loglevel",
                           "error",
                           "-nostdin",
                           "-y",
                           "-f",
                           "rawvideo",
                           "-pix_fmt",
                           "rgb24",
                           "-s",
                           size,
                           "-r",
                           rate,
                           "-i",
                           "pipe:0",
                           "-an",
                           "-vf",
                           "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                           "-c:v",
                           "libx264",
                           "-pix_fmt",
                           "yuv420p",
                           "-movflags",
                           "+faststart",
                           fo->mp4,
                           NULL };
    /* -nostdin keeps ffmpeg off the terminal; the video comes from -i. */
    execvp("ffmpeg", (char *const *)argv);
    _exit(127);
  }
  close(fds[0]);
  if (pid < 0) {
    close(fds[1]);
    snprintf(msg, msg_size, "cannot start ffmpeg: %s", strerror(errno));
    return -1;
  }
  fo->ffmpeg = pid;
  fo->pipe_fd = fds[1];
  return 0;
}

int mr_frames_out_open(const mr_frames_out_def *def, mr_frames_out **out, char *msg,
                       size_t msg_size) {
  *out = NULL;
  if (def->cookie != MR_DEF_COOKIE) {
    snprintf(msg, msg_size, "the frames' def was not made by mr_default_frames_out_def");
    return -1;
  }
  if (def->width <= 0 || def->height <= 0 || def->every < 1) {
    snprintf(msg, msg_size, "expected a frame size and --every of at least 1");
    return -1;
  }
  mr_frames_out *fo = calloc(1, sizeof *fo);
  if (fo == NULL) return snprintf(msg, msg_size, "out of memory"), -1;
  fo->def = *def;
  fo->pipe_fd = -1;
  if (def->dir != NULL) snprintf(fo->dir, sizeof fo->dir, "%s", def->dir);
  if (def->mp4 != NULL) snprintf(fo->mp4, sizeof fo->mp4, "%s", def->mp4);
  if (def->sheet != NULL) snprintf(fo->sheet, sizeof fo->sheet, "%s", def->sheet);
  if (fo->dir[0] != '\0' && mr_make_dir(fo->dir) != 0) {
    snprintf(msg, msg_size, "cannot make the folder %s: %s", fo->dir, strerror(errno));
    free(fo);
    return -1;
  }
  if (fo->sheet[0] != '\0' &&
      (fo->sh = mr_sheet_create(def->width, def->height, def->sheet_cells)) == NULL) {
    snprintf(msg, msg_size, "out of memory");
    free(fo);
    return -1;
  }
  if (def->keep_time && (fo->last = malloc((size_t)def->width * (size_t)def->height * 3)) == NULL) {
    snprintf(msg, msg_size, "out of memory");
    mr_sheet_destroy(fo->sh);
    free(fo);
    return -1;
  }
  /* A reader that went away must not kill the show: writes then fail. */
  signal(SIGPIPE, SIG_IGN);
  if (fo->mp4[0] != '\0' && start_ffmpeg(fo, msg, msg_size) != 0) {
    free(fo->last);
    mr_sheet_destroy(fo->sh);
    free(fo);
    return -1;
  }
  *out = fo;
  return 0;
}

static int write_all(int fd, const uint8_t *p, size_t n) {
  while (n > 0) {
    ssize_t k = write(fd, p, n);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return -1;
    p += k;
    n -= (size_t)k;
  }
  return 0;
}

static void pipe_frame(mr_frames_out *fo, const uint8_t *rgb) {
  if (fo->pipe_fd < 0 || fo->pipe_broken) return;
  size_t n = (size_t)fo->def.width * (size_t)fo->def.height * 3;
  if (write_all(fo->pipe_fd, rgb, n) != 0)
    fo->pipe_broken = true; /* ffmpeg's own message is on stderr; close says it */
  else
    fo->encoded++;
}

/* The video frame that show time t falls on. */
static uint64_t video_index(const mr_frames_out *fo, double t) {
  double k = floor(t * fo->def.fps + 0.5);
  return k > 0 ? (uint64_t)k : 0;
}

/* keep_time: the last frame again up to (not including) video frame k. */
static void repeat_until(mr_frames_out *fo, uint64_t k) {
  for (; fo->next_index < k && fo->last != NULL && !fo->pipe_broken; fo->next_index++)
    pipe_frame(fo, fo->last);
}

int mr_frames_out_hold(mr_frames_out *fo, double t, char *msg, size_t msg_size) {
  if (fo == NULL || !fo->def.keep_time || fo->pipe_fd < 0) return 0;
  repeat_until(fo, video_index(fo, t) + 1);
  if (!fo->pipe_broken) return 0;
  snprintf(msg, msg_size, "ffmpeg stopped reading %s", fo->mp4);
  return -1;
}

int mr_frames_out_add(mr_frames_out *fo, const uint8_t *rgb, double t, char *msg, size_t msg_size) {
  uint64_t i = fo->frames++;
  if (fo->dir[0] != '\0' && i % (uint64_t)fo->def.every == 0) {
    char path[600];
    snprintf(path, sizeof path, "%s/frame_%06llu.png", fo->dir,
             (unsigned long long)(i / (uint64_t)fo->def.every));
    if (mr_png_write(path, rgb, fo->def.width, fo->def.height) != 0) {
      snprintf(msg, msg_size, "cannot write %s", path);
      return -1;
    }
    fo->pngs++;
  }
  if (!fo->def.keep_time) {
    pipe_frame(fo, rgb);
  } else if (fo->pipe_fd >= 0) {
    uint64_t k = video_index(fo, t);
    repeat_until(fo, k);
    /* A frame whose video slot is taken already (two shows in one
     * frame period) replaces nothing: the video's clock rules. */
    if (k >= fo->next_index) {
      pipe_frame(fo, rgb);
      fo->next_index = k + 1;
      memcpy(fo->last, rgb, (size_t)fo->def.width * (size_t)fo->def.height * 3);
    }
  }
  if (fo->sh != NULL) mr_sheet_offer(fo->sh, rgb, t);
  return 0;
}

static bool finish_ffmpeg(mr_frames_out *fo) {
  if (fo->ffmpeg <= 0) return false;
  close(fo->pipe_fd);
  int status = 0;
  while (waitpid(fo->ffmpeg, &status, 0) < 0 && errno == EINTR) {
  }
  return !fo->pipe_broken && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

int mr_frames_out_close(mr_frames_out *fo, mr_frames_out_summary *sum, char *msg, size_t msg_size) {
  memset(sum, 0, sizeof *sum);
  if (fo == NULL) return 0;
  int rc = 0;
  sum->frames = fo->frames;
  sum->pngs = fo->pngs;
  sum->encoded = fo->encoded;
  if (fo->sh != NULL) {
    sum->sheet_cells = mr_sheet_cells(fo->sh);
    if (mr_sheet_write(fo->sh, fo->sheet) != 0) {
      snprintf(msg, msg_size, "cannot write the contact sheet %s", fo->sheet);
      rc = -1;
    }
  }
  if (fo->ffmpeg > 0) {
    sum->mp4_ok = finish_ffmpeg(fo);
    if (!sum->mp4_ok && rc == 0) {
      snprintf(msg, msg_size, "ffmpeg did not write %s (its message is above)", fo->mp4);
      rc = -1;
    }
  }
  mr_sheet_destroy(fo->sh);
  free(fo->last);
  free(fo);
  return rc;
}

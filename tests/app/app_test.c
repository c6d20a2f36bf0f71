#include "app_test.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <stb_image.h>

#include "proc.h"

int at_png_size(const char *path, int *width, int *height) {
  unsigned char h[24];
  FILE *f = fopen(path, "rb");
  if (f == NULL) return -1;
  size_t n = fread(h, 1, sizeof h, f);
  fclose(f);
  static const unsigned char sig[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
  if (n != sizeof h || memcmp(h, sig, 8) != 0 || memcmp(h + 12, "IHDR", 4) != 0) return -1;
  *width = (int)((unsigned)h[16] << 24 | (unsigned)h[17] << 16 | (unsigned)h[18] << 8 | h[19]);
  *height = (int)((unsigned)h[20] << 24 | (unsigned)h[21] << 16 | (unsigned)h[22] << 8 | h[23]);
  return 0;
}

uint8_t *at_png_rgb(const char *path, int *width, int *height) {
  int comp = 0;
  return stbi_load(path, width, height, &comp, 3);
}

int at_which(const char *program, char *out, size_t size) {
  const char *path = getenv("PATH");
  while (path != NULL && *path != '\0') {
    size_t n = strcspn(path, ":");
    snprintf(out, size, "%.*s/%s", (int)n, path, program);
    if (n > 0 && access(out, X_OK) == 0) return 0;
    path += n;
    if (*path == ':') path++;
  }
  return -1;
}

int at_video_stream(const char *ffprobe, const char *path, const char *entries, char *out,
                    size_t size) {
  char show[200];
  snprintf(show, sizeof show, "stream=%s", entries);
  char *argv[] = { (char *)ffprobe, "-v", "error", "-count_frames", "-select_streams", "v:0",
                   "-show_entries", show, "-of",   "csv=p=0",       (char *)path,      NULL };
  tt_output o;
  if (tt_capture(argv, &o) != 0) return -1;
  int rc = o.status == 0 ? 0 : -1;
  snprintf(out, size, "%s", o.out);
  tt_output_free(&o);
  return rc;
}

int at_count_files(const char *dir, const char *prefix) {
  DIR *d = opendir(dir);
  if (d == NULL) return -1;
  int n = 0;
  for (struct dirent *e = readdir(d); e != NULL; e = readdir(d))
    if (strncmp(e->d_name, prefix, strlen(prefix)) == 0) n++;
  closedir(d);
  return n;
}

int at_lines(const char *text) {
  int n = 0;
  for (const char *p = text; *p != '\0'; p++)
    if (*p == '\n' || p[1] == '\0') n++;
  return n;
}

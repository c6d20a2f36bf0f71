/* Helpers of the stage's program tests: PNG headers and pixels, programs
 * on PATH, and small scene files. */
#ifndef APP_TEST_H
#define APP_TEST_H

#include <stddef.h>
#include <stdint.h>

/* A PNG's width and height from its IHDR; 0 or -1 (not a PNG). */
int at_png_size(const char *path, int *width, int *height);

/* The RGB pixels of a PNG (stb_image), free() them; NULL on failure. */
uint8_t *at_png_rgb(const char *path, int *width, int *height);

/* The full path of program on PATH in out; 0 or -1. */
int at_which(const char *program, char *out, size_t size);

/* The files in dir whose names start with prefix. */
int at_count_files(const char *dir, const char *prefix);

/* What ffprobe (its path) says of the first video stream of the file at
 * path, its frames counted: the entries asked (e.g.
 * "nb_read_frames,width,height"), comma-separated on one line, in out.
 * 0, or -1 when ffprobe failed. */
int at_video_stream(const char *ffprobe, const char *path, const char *entries, char *out,
                    size_t size);

/* The lines of text (a trailing line without a newline counts). */
int at_lines(const char *text);

#endif

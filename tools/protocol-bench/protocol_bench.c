/* protocol-bench: how fast the host decodes glove streams, and what a SAMPLE
 * costs on the wire. A benchmark, not a test: it prints figures. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gg_stream.h"
#include "gp.h"

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static void usage(FILE *f) {
  fprintf(f, "usage: protocol-bench [--frames N] [--repeat R] [--chunk BYTES]\n"
             "Decodes a synthetic stream of N SAMPLE frames (default 1000000) R times\n"
             "(default 5) and prints the best decoder throughput in MB/s and frames/s,\n"
             "fed CHUNK bytes per call (default 4096; 1 = byte at a time), plus the wire\n"
             "bytes per SAMPLE frame and the share of a 115200 and a 921600 8N1 link.\n");
}

static long arg_long(const char *flag, const char *v, long lo, long hi) {
  char *end;
  long x = v ? strtol(v, &end, 10) : 0;
  if (!v || *end || x < lo || x > hi) {
    fprintf(stderr, "protocol-bench: %s expects an integer in %ld..%ld\n", flag, lo, hi);
    exit(2);
  }
  return x;
}

int main(int argc, char **argv) {
  long frames = 1000000, repeat = 5, chunk = 4096;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(argv[i], "--frames"))
      frames = arg_long("--frames", i + 1 < argc ? argv[++i] : NULL, 1, 100000000);
    else if (!strcmp(argv[i], "--repeat"))
      repeat = arg_long("--repeat", i + 1 < argc ? argv[++i] : NULL, 1, 1000);
    else if (!strcmp(argv[i], "--chunk"))
      chunk = arg_long("--chunk", i + 1 < argc ? argv[++i] : NULL, 1, 1 << 20);
    else {
      fprintf(stderr, "protocol-bench: unknown option '%s' (see --help)\n", argv[i]);
      return 2;
    }
  }
  size_t len = 0;
  uint8_t *stream = gg_sample_burst(frames, &len);
  if (!stream) {
    fprintf(stderr, "protocol-bench: cannot allocate the stream of %ld frames\n", frames);
    return 1;
  }
  double best = 1e30;
  uint32_t decoded = 0;
  for (long k = 0; k < repeat; k++) {
    gp_decoder d;
    gp_decoder_init(&d, GP_SPEC_HASH);
    double t0 = now_s();
    for (size_t off = 0; off < len;) {
      size_t n = len - off < (size_t)chunk ? len - off : (size_t)chunk;
      while (n) {
        gp_msg out;
        gp_event ev;
        size_t used = gp_decoder_feed(&d, stream + off, n, &out, &ev);
        off += used;
        n -= used;
      }
    }
    double t = now_s() - t0;
    if (t < best) best = t;
    decoded = d.c.frames;
  }
  free(stream);
  if (decoded != (uint32_t)frames) {
    fprintf(stderr, "protocol-bench: decoded %u of %ld frames\n", decoded, frames);
    return 1;
  }
  double per = (double)len / (double)frames;
  printf("wire bytes per SAMPLE frame: %.0f\n", per);
  printf("link share at 250 Hz on 115200 8N1: %.1f %%\n", per * 10 * 250 / 115200 * 100);
  printf("link share at 1000 Hz on 921600 8N1: %.1f %%\n", per * 10 * 1000 / 921600 * 100);
  printf("decoder, %ld-byte chunks, best of %ld: %.1f MB/s, %.2f M frames/s (%.0f ns/frame)\n",
         chunk, repeat, (double)len / best / 1e6, (double)frames / best / 1e6,
         best / (double)frames * 1e9);
  return 0;
}

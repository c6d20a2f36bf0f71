/* marionette-bench: what accuracy costs in time. A thin client of the host
 * libraries (mr_scene, mr_theater, mr_physics): it loads the shipped scenes,
 * changes their settings the way a scene file could, runs them with
 * mr_sim_run and prints figures. Nothing here is needed by a program. */
#ifndef MARIONETTE_BENCH_H
#define MARIONETTE_BENCH_H

#include <stdbool.h>
#include <stdio.h>
#include <sys/types.h>

#include "mr_render.h"
#include "mr_scene.h"
#include "mr_sim.h"

typedef struct bench {
  bool quick;        /* about a minute in all */
  const char *out;   /* folder for the CSV files and plots */
  const char *root;  /* the source tree, for host/scenes */
  char machine[256]; /* "Linux 6.1.0 x86_64, AMD EPYC 7B13, 2 cores" */
  FILE *summary;     /* summary.txt in out: every figure printed */
} bench;

/* machine.c */
void bench_machine(char *out, size_t size);
double bench_cpu_seconds(void);
/* The monotonic wall clock, s. */
double bench_wall_seconds(void);
/* printf to stdout and to the summary file. */
void bench_say(bench *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Progress on stderr: "[section] what" (a line per run, so a long run
 * shows it is alive). */
void bench_progress(const char *section, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* Opens out/name for writing (NULL with a message on stderr). */
FILE *bench_open(const bench *b, const char *name);
/* Loads root/rel into scene; 0, or −1 with a message on stderr. */
int bench_load(const bench *b, const char *rel, mr_scene *scene);

/* One run of a scene as it stands, its track at 60 frames a second
 * presented by interpolation (so frames do not cut the ATS's steps), the
 * end effector's position recorded at every frame up to `horizon`. */
typedef struct bench_run {
  mr_sim_result r;
  double cpu;   /* CPU seconds of the run */
  double *ee;   /* 3 per frame, up to the horizon */
  int ee_count; /* frames recorded */
  int ee_cap;
  size_t ee_index; /* the end effector's particle */
  double horizon;
} bench_run;
int bench_run_scene(const mr_scene *scene, double duration, size_t ee_index, double horizon,
                    bench_run *out);
/* The same from a given state (mr_sim_def.start_state, NULL: the scene's),
 * leaving the end state in end (NULL: nowhere). */
int bench_run_scene_from(const mr_scene *scene, double duration, size_t ee_index, double horizon,
                         const double *start, double *end, bench_run *out);
void bench_run_free(bench_run *r);
/* Sorts v[0..n) ascending. */
void bench_sort(double *v, int n);
/* Largest and RMS distance between two runs' end-effector tracks, m. */
void bench_ee_error(const bench_run *a, const bench_run *ref, double *max, double *rms);

/* windows.c: a chaotic track judged in windows along its whole length,
 * each from the reference's own state at a turning point of the bar. */
typedef struct bench_windows {
  int n;
  double *start;     /* each window's track time */
  double **states;   /* the reference's state there, 6 per scene particle */
  bench_run *ref;    /* the reference from each, RK4 at 0.5 ms */
  double resolution; /* the median over the windows of what halving its step moves the hand */
} bench_windows;
/* The windows every `gap` s of frame 0's oscillating track; their count
 * (0 for another track), or −1. */
int bench_windows_open(const mr_scene *base, size_t ee, double duration, double horizon, double gap,
                       bench_windows *w);
/* sc (a setting's scene) through the windows: the median of its RMS in
 * each into *ee_med, the largest distance in any into *ee_max; 0 or −1. */
int bench_windows_error(mr_scene *sc, size_t ee, double horizon, const bench_windows *w,
                        double *ee_max, double *ee_med);
void bench_windows_free(bench_windows *w);

/* A scene's stage drawn headless at w x h and read back (render_cost.c),
 * for the sections that time drawing. */
typedef struct bench_drawing {
  mr_stage *stage;
  mr_render *render;
  mr_render_view view;
  uint8_t *rgb;
  size_t rgb_size, n; /* n: the scene's particles */
} bench_drawing;
/* 0, or −1 with the reason in msg. Close it either way. */
int bench_drawing_open(const mr_scene *sc, int w, int h, bench_drawing *d, char *msg, size_t size);
/* Draws the positions xyz of n particles and reads the frame back; 0 or −1. */
int bench_drawing_draw(bench_drawing *d, const double *xyz, int n);
void bench_drawing_close(bench_drawing *d);

/* The sections, each printing its figures and writing its CSV. 0 or −1. */
int bench_sweep(bench *b);
int bench_paper_run(bench *b);
int bench_capacity(bench *b);
/* n stick puppets of Fig. 10 on a grid 1 m apart, each on its own control
 * frame swaying at 0.5 Hz (capacity.c); 0, or -1 with a message on stderr. */
int bench_crowd_load(int n, mr_scene *sc);
int bench_load_time(bench *b);
int bench_latency(bench *b);
/* glove-gen at 250 Hz on a new pty for `seconds`, waiting up to 10 s for
 * its reader; the slave's path into path once it is open (latency_live.c,
 * its path file named after `name` in out). Its pid, or -1. */
pid_t bench_glove_gen_start(const bench *b, const char *name, double seconds, char *path,
                            size_t size);
/* The show as a puppeteer runs it, in a window (window_live.c). */
int bench_window(bench *b);
/* Item 4, live: glove-gen through a pty, on the wall clock (latency_live.c). */
int bench_latency_live(bench *b);
/* Item 2: ours against MuJoCo (peer.c), or a line saying it is not built. */
int bench_peer(bench *b);
/* Item 5: milliseconds a frame for each example scene (render_cost.c). */
int bench_render(bench *b);
/* Section net (net_scale.c): a show's state through a broker to watchers. */
int bench_net(bench *b);
/* The fixed runs `make bench-count` counts under callgrind: "puppet"
 * (host/scenes/puppet.yaml for 10 s) or "decode" (10 000 SAMPLE frames). */
int bench_count_run(bench *b, const char *which);
/* --count render: one humanoid frame at 640x360 and one at 1280x720, one
 * llvmpipe thread, each its own callgrind dump (render_cost.c). */
int bench_count_render(bench *b);
/* `make bench-count`'s sweep: the quick settings on every puppet, each run
 * its own callgrind dump, a CSV line per run on stdout (sweep.c). */
int bench_sweep_count(bench *b);

#endif

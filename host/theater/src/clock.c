/* The two clocks: the wall (CLOCK_MONOTONIC, which no time adjustment
 * moves backwards) and a virtual one that moves only when told. */
#define _POSIX_C_SOURCE 200809L
#include "mr_theater.h"

#include <errno.h>
#include <math.h>
#include <time.h>

static double wall_now(void *self) {
  (void)self;
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void wall_wait_until(void *self, double t) {
  (void)self;
  if (!isfinite(t)) return;
  struct timespec ts;
  ts.tv_sec = (time_t)floor(t);
  ts.tv_nsec = (long)((t - floor(t)) * 1e9);
  if (ts.tv_nsec > 999999999L) ts.tv_nsec = 999999999L;
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR) {
  }
}

mr_clock mr_clock_wall(void) {
  mr_clock c = { wall_now, wall_wait_until, NULL };
  return c;
}

static double virtual_now(void *self) {
  return ((mr_virtual_clock *)self)->t;
}

static void virtual_wait_until(void *self, double t) {
  mr_virtual_clock *vc = self;
  if (t > vc->t) vc->t = t;
}

mr_clock mr_clock_virtual(mr_virtual_clock *vc) {
  mr_clock c = { virtual_now, virtual_wait_until, vc };
  return c;
}

void mr_virtual_clock_spend(mr_virtual_clock *vc, double seconds) {
  if (vc != NULL && seconds > 0) vc->t += seconds;
}

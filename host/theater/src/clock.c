/* The two clocks: the wall (CLOCK_MONOTONIC, which no time adjustment
 * moves backwards) and a virtual one that moves only when told. */
#define _POSIX_C_SOURCE 200809L
#include "mr_theater.h"

#include <errno.h>
#include <math.h>
#include <string.h>
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

bool mr_clock_is_wall(const mr_clock *c) {
  return c != NULL && c->now == wall_now && c->wait_until == wall_wait_until;
}

/* The scaled clock: show time = show_base + rate (base - base_base) while
 * running, show_base while paused; the two bases are tied anew whenever
 * the rate or the pause changes, so show time never jumps. */

static double base_now(const mr_scaled_clock *sc) {
  return sc->base.now(sc->base.self);
}

double mr_scaled_clock_now(const mr_scaled_clock *sc) {
  if (sc->paused) return sc->show_base;
  return sc->show_base + sc->rate * (base_now(sc) - sc->base_base);
}

/* Held back: (1 - rate) base seconds per base second, exactly 0 at rate 1. */
static double held_now(const mr_scaled_clock *sc) {
  if (sc->paused) return sc->held_base;
  return sc->held_base + (1.0 - sc->rate) * (base_now(sc) - sc->base_base);
}

double mr_scaled_clock_pace_now(const mr_scaled_clock *sc) {
  return mr_scaled_clock_now(sc) + held_now(sc);
}

static void rebase(mr_scaled_clock *sc) {
  sc->held_base = held_now(sc);
  sc->show_base = mr_scaled_clock_now(sc);
  sc->base_base = base_now(sc);
}

void mr_scaled_clock_init(mr_scaled_clock *sc, const mr_clock *base) {
  memset(sc, 0, sizeof *sc);
  sc->base = *base;
  sc->rate = 1.0;
  sc->base_base = base_now(sc);
}

void mr_scaled_clock_pause(mr_scaled_clock *sc, bool paused) {
  if (sc->paused == paused) return;
  rebase(sc);
  sc->paused = paused;
}

void mr_scaled_clock_set_rate(mr_scaled_clock *sc, double rate) {
  if (!(rate > 0) || !isfinite(rate)) return;
  rebase(sc);
  sc->rate = rate;
}

void mr_scaled_clock_step(mr_scaled_clock *sc) {
  mr_scaled_clock_pause(sc, true);
  sc->steps++;
}

static double scaled_now(void *self) {
  return mr_scaled_clock_now(self);
}

static void scaled_wait_until(void *self, double t) {
  mr_scaled_clock *sc = self;
  for (;;) {
    if (sc->paused && sc->steps > 0 && sc->show_base < t) {
      sc->steps--;
      sc->held_base = held_now(sc);
      sc->show_base = t;
      sc->base_base = base_now(sc);
      return;
    }
    if (mr_scaled_clock_now(sc) >= t) return;
    double deadline = sc->paused ? INFINITY : sc->base_base + (t - sc->show_base) / sc->rate;
    /* Rounding may leave show time a hair short of t: its time has come. */
    if (base_now(sc) >= deadline) return;
    if (sc->idle != NULL) {
      if (sc->idle(sc->user, deadline) != 0) return;
    } else {
      if (sc->paused) return;
      sc->base.wait_until(sc->base.self, deadline);
    }
  }
}

mr_clock mr_clock_scaled(mr_scaled_clock *sc) {
  mr_clock c = { scaled_now, scaled_wait_until, sc };
  return c;
}

static double paced_now(void *self) {
  return mr_scaled_clock_pace_now(self);
}

mr_clock mr_clock_paced(mr_scaled_clock *sc) {
  mr_clock c = { paced_now, scaled_wait_until, sc };
  return c;
}

#include "take_gen.h"

#include <setjmp.h>
#include <stdarg.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "mr_io.h"

void gen_init(gen_take *g, uint16_t lo, uint16_t hi, uint64_t scene) {
  memset(g, 0, sizeof *g);
  g->info = gp_default_glove_info();
  gp_glove_info_set_rate(&g->info, 100);
  g->info.cal_state = GP_CAL_VALID;
  for (int k = 0; k < 5; k++) {
    g->info.cal_min[k] = lo;
    g->info.cal_max[k] = hi;
  }
  g->info2 = g->info;
  g->scene = scene;
  g->t0 = 0.01;
  g->dt = 0.01;
}

static void add(mr_rec_writer *w, uint64_t t, const uint8_t *b, size_t n) {
  mr_io_error err;
  if (mr_rec_writer_add(w, t, b, n, &err) != 0) fail_msg("%s", err.msg);
}

void gen_write(gen_take *g, const char *path) {
  mr_rec_writer w;
  mr_io_error err;
  if (mr_rec_writer_open_scene(&w, path, GP_SPEC_HASH, 0, g->scene, &err) != 0)
    fail_msg("%s", err.msg);
  uint8_t wire[GP_MAX_WIRE];
  size_t n = gp_glove_info_encode(&g->info, wire, sizeof wire);
  add(&w, 0, wire, n);
  int info2 = g->info2_at > 0;
  for (size_t i = 0; i < g->n; i++) {
    double t = g->t0 + (double)i * g->dt;
    uint64_t ns = (uint64_t)llround(t * 1e9);
    if (info2 && t >= g->info2_at) {
      add(&w, ns, wire, gp_glove_info_encode(&g->info2, wire, sizeof wire));
      info2 = 0;
    }
    gp_sample s = gp_glove_sample((uint16_t)i, gp_glove_time_us(t), g->ch[i]);
    n = gp_glove_sample_encode(&s, GP_SPEC_HASH, wire, sizeof wire);
    assert_true(n > 10);
    if (i % 50 == 7) {
      add(&w, ns, wire, 10);
      ns += 4000000u;
      add(&w, ns, wire + 10, n - 10);
    } else {
      add(&w, ns, wire, n);
    }
    g->read_ns[i] = ns;
  }
  if (mr_rec_writer_close(&w, &err) != 0) fail_msg("%s", err.msg);
}

double gen_value(const gen_take *g, int k, uint16_t r) {
  return ((double)r - g->info.cal_min[k]) / (double)(g->info.cal_max[k] - g->info.cal_min[k]);
}

uint16_t gen_raw(const gen_take *g, int k, double v) {
  double r = round(g->info.cal_min[k] + v * (double)(g->info.cal_max[k] - g->info.cal_min[k]));
  return (uint16_t)(r < 0 ? 0 : r > 4095 ? 4095 : r);
}

long gen_at(const gen_take *g, uint64_t t_ns) {
  long j = -1;
  for (size_t i = 0; i < g->n && g->read_ns[i] <= t_ns; i++) j = (long)i;
  return j;
}

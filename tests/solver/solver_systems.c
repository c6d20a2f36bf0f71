#include "solver_systems.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static uint64_t next(test_rng *r) {
  uint64_t z = (r->s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

double test_rng_uniform(test_rng *r) {
  return (double)(next(r) >> 11) * 0x1.0p-53;
}

double test_rng_range(test_rng *r, double lo, double hi) {
  return lo + (hi - lo) * test_rng_uniform(r);
}

void test_system_init(test_system *s, int np) {
  memset(s, 0, sizeof *s);
  s->pos = calloc((size_t)np * 3, sizeof *s->pos);
  s->inv_mass = calloc((size_t)np, sizeof *s->inv_mass);
  mr_jac_reset(&s->J, np);
}

void test_system_free(test_system *s) {
  free(s->pos);
  free(s->inv_mass);
  free(s->dense_j);
  mr_jac_free(&s->J);
  memset(s, 0, sizeof *s);
}

int test_system_add_particle(test_system *s, const double x[3], double inv_mass) {
  int p = s->np++;
  memcpy(s->pos + 3 * p, x, 3 * sizeof *x);
  s->inv_mass[p] = inv_mass;
  return p;
}

/* Appends a row to both the library's J and the dense copy. The particle
 * count is fixed at init (the dense copy's width). */
static double *new_row(test_system *s) {
  int width = 3 * s->J.n_particles;
  s->dense_j = realloc(s->dense_j, (size_t)(s->k + 1) * (size_t)width * sizeof *s->dense_j);
  double *row = s->dense_j + (size_t)s->k * (size_t)width;
  memset(row, 0, (size_t)width * sizeof *row);
  s->k++;
  mr_jac_begin_row(&s->J);
  return row;
}

void test_system_distance(test_system *s, int a, int b) {
  double u[3], len = 0.0;
  for (int c = 0; c < 3; c++) {
    u[c] = s->pos[3 * a + c] - s->pos[3 * b + c];
    len += u[c] * u[c];
  }
  len = sqrt(len);
  double mu[3];
  for (int c = 0; c < 3; c++) {
    u[c] /= len;
    mu[c] = -u[c];
  }
  double *row = new_row(s);
  for (int c = 0; c < 3; c++) {
    row[3 * a + c] += u[c];
    row[3 * b + c] += mu[c];
  }
  mr_jac_add(&s->J, a, u);
  mr_jac_add(&s->J, b, mu);
}

void test_system_pin(test_system *s, int p, const double e[3]) {
  double *row = new_row(s);
  for (int c = 0; c < 3; c++) row[3 * p + c] += e[c];
  mr_jac_add(&s->J, p, e);
}

void test_system_copy_row(test_system *s, int i) {
  int width = 3 * s->J.n_particles;
  double *row = new_row(s);
  memcpy(row, s->dense_j + (size_t)i * (size_t)width, (size_t)width * sizeof *row);
  for (int e = s->J.row_ptr[i]; e < s->J.row_ptr[i + 1]; e++) {
    double d[3] = { s->J.d[e][0], s->J.d[e][1], s->J.d[e][2] };
    mr_jac_add(&s->J, s->J.particle[e], d);
  }
}

static void unit_to(const test_system *s, int a, int b, double u[3]) {
  double len = 0.0;
  for (int c = 0; c < 3; c++) {
    u[c] = s->pos[3 * a + c] - s->pos[3 * b + c];
    len += u[c] * u[c];
  }
  len = sqrt(len);
  for (int c = 0; c < 3; c++) u[c] /= len;
}

static double det3(const double a[3], const double b[3], const double c[3]) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

void test_system_random(test_system *s, int k, uint64_t seed) {
  test_rng rng = { seed };
  /* At most k + 1 particles are needed (each adds at least one row). */
  test_system_init(s, k + 1);
  double x[3] = { 0.0, 0.0, 2.0 };
  test_system_add_particle(s, x, 0.0);
  while (s->k < k) {
    for (int c = 0; c < 3; c++) x[c] = test_rng_range(&rng, -1.0, 1.0);
    double mass = exp(test_rng_range(&rng, log(0.1), log(10.0)));
    int p = test_system_add_particle(s, x, 1.0 / mass);
    int want = 1 + (int)(test_rng_uniform(&rng) * 3.0);
    if (want > k - s->k) want = k - s->k;
    if (test_rng_uniform(&rng) < 0.15) {
      static const double axes[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
      int first = (int)(test_rng_uniform(&rng) * 3.0);
      for (int a = 0; a < want; a++) test_system_pin(s, p, axes[(first + a) % 3]);
      continue;
    }
    if (want > p) want = p;
    /* Pick neighbours among the recent particles (a chain of rigid
         * clusters, like a puppet's limbs) whose directions from p are far
         * from coplanar or collinear. */
    int nb[3];
    double u[3][3];
    for (int tries = 0;; tries++) {
      int window = p < 8 ? p : 8;
      int ok = 1;
      for (int a = 0; a < want && ok; a++) {
        nb[a] = p - 1 - (int)(test_rng_uniform(&rng) * window);
        for (int c = 0; c < a; c++) ok &= nb[c] != nb[a];
        unit_to(s, p, nb[a], u[a]);
      }
      if (ok && want == 2) {
        double d = u[0][0] * u[1][0] + u[0][1] * u[1][1] + u[0][2] * u[1][2];
        ok = fabs(d) < 0.9;
      }
      if (ok && want == 3) ok = fabs(det3(u[0], u[1], u[2])) > 0.3;
      if (ok) break;
      if (tries > 50) {
        want = 1;
        nb[0] = p - 1;
        break;
      }
    }
    for (int a = 0; a < want; a++) test_system_distance(s, p, nb[a]);
  }
}

void test_system_consistent_rhs(const test_system *s, test_rng *rng, double *b) {
  int width = 3 * s->J.n_particles;
  double *v = malloc((size_t)width * sizeof *v);
  for (int p = 0; p < s->J.n_particles; p++)
    for (int c = 0; c < 3; c++)
      v[3 * p + c] = (p < s->np ? s->inv_mass[p] : 0.0) * test_rng_range(rng, -10.0, 10.0);
  for (int i = 0; i < s->k; i++) {
    double sum = 0.0;
    for (int c = 0; c < width; c++) sum += s->dense_j[(size_t)i * (size_t)width + (size_t)c] * v[c];
    b[i] = sum;
  }
  free(v);
}

void test_dense_jmjt(const test_system *s, double *a) {
  int width = 3 * s->J.n_particles;
  for (int i = 0; i < s->k; i++) {
    for (int j = 0; j < s->k; j++) {
      double sum = 0.0;
      for (int c = 0; c < width; c++) {
        int p = c / 3;
        double w = p < s->np ? s->inv_mass[p] : 0.0;
        sum += s->dense_j[(size_t)i * (size_t)width + (size_t)c] * w *
               s->dense_j[(size_t)j * (size_t)width + (size_t)c];
      }
      a[(size_t)i * (size_t)s->k + (size_t)j] = sum;
    }
  }
}

void test_dense_jt(const test_system *s, const double *lam, double *f) {
  int width = 3 * s->J.n_particles;
  for (int c = 0; c < width; c++) {
    double sum = 0.0;
    for (int i = 0; i < s->k; i++)
      sum += s->dense_j[(size_t)i * (size_t)width + (size_t)c] * lam[i];
    f[c] = sum;
  }
}

double test_norm(int n, const double *v) {
  double sum = 0.0;
  for (int i = 0; i < n; i++) sum += v[i] * v[i];
  return sqrt(sum);
}

double test_rel_diff(int n, const double *x, const double *ref) {
  double d = 0.0;
  for (int i = 0; i < n; i++) d += (x[i] - ref[i]) * (x[i] - ref[i]);
  double r = test_norm(n, ref);
  return sqrt(d) / (r > 0.0 ? r : 1.0);
}

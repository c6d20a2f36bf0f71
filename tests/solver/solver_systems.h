/* Constraint systems for the solver tests, built the way the physics builds
 * them: particles with masses, distance and pin constraints, J and b from
 * their definitions. Each system also keeps its own dense copy of J, so the
 * tests can check the library against arithmetic it did not do. */
#ifndef SOLVER_SYSTEMS_H
#define SOLVER_SYSTEMS_H

#include "mr_solver.h"

#include <stdint.h>

typedef struct test_system {
  int np, k;
  double *pos;      /* 3 np */
  double *inv_mass; /* np; 0 = fixed */
  double *dense_j;  /* k × 3np, row-major */
  mr_jac J;
} test_system;

/* A deterministic generator (splitmix64). */
typedef struct test_rng {
  uint64_t s;
} test_rng;
double test_rng_uniform(test_rng *r); /* [0, 1) */
double test_rng_range(test_rng *r, double lo, double hi);

void test_system_init(test_system *s, int np);
void test_system_free(test_system *s);
int test_system_add_particle(test_system *s, const double x[3], double inv_mass);
/* C = |x_a − x_b| − L: row ∂C/∂x_a = u, ∂C/∂x_b = −u, u the unit a−b. */
void test_system_distance(test_system *s, int a, int b);
/* C = e·x_p − c: the pin of particle p along the unit vector e. */
void test_system_pin(test_system *s, int p, const double e[3]);

/* Appends a copy of row i (a constraint written twice). */
void test_system_copy_row(test_system *s, int i);

/* k independent constraints on random particles with random masses: each
 * new particle is tied by up to three distance constraints to earlier
 * particles in non-planar directions, or pinned along up to three axes
 * (§5.1's rule against dependent constraints). Particle 0 is fixed. */
void test_system_random(test_system *s, int k, uint64_t seed);

/* b = J M⁻¹ f for a random force f: consistent by construction, as the
 * −J M⁻¹ F_a term of §5.2 eq. 8 is. */
void test_system_consistent_rhs(const test_system *s, test_rng *rng, double *b);

/* Dense helpers on the system's own J. */
void test_dense_jmjt(const test_system *s, double *a_kk); /* k × k */
void test_dense_jt(const test_system *s, const double *lam, double *f3n);

double test_norm(int n, const double *v);
double test_rel_diff(int n, const double *x, const double *ref);

#endif

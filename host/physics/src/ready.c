/* A world made ready to step: the data derived from its elements (scratch
 * sized to the particles, each puppet's mass, the sphere trees, room for
 * contacts and solves), rebuilt when elements were added, so that a step
 * itself allocates nothing once the first has run. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* 3n scratch, and the integrator's 8 × 3n, for the particles there are. */
static int size_scratch(mr_world *w) {
  double **arr[] = { &w->scratch.x0,        &w->scratch.v0,
                     &w->scratch.xs,        &w->scratch.vs,
                     &w->scratch.force,     &w->scratch.constraint_force,
                     &w->scratch.acc_try,   &w->scratch.impact_momentum,
                     &w->scratch.impact_dv, &w->scratch.v_try,
                     &w->scratch.x_held };
  int need = w->n > 0 ? w->n : 1, cap = w->cap_scratch;
  for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) {
    cap = w->cap_scratch;
    if (mr_grow((void **)arr[i], &cap, need, 3 * sizeof(double)) != 0) return -1;
  }
  cap = w->cap_scratch;
  if (mr_grow((void **)&w->reached, &cap, need, 1) != 0) return -1;
  cap = w->cap_scratch;
  if (mr_grow((void **)&w->scratch.k, &cap, need, 24 * sizeof(double)) != 0) return -1;
  w->cap_scratch = cap;
  return 0;
}

/* The whole mass of each puppet, for the §6.2 forces. */
static int puppet_masses(mr_world *w) {
  int np = 0;
  for (int i = 0; i < w->n; i++)
    if (w->puppet[i] + 1 > np) np = w->puppet[i] + 1;
  if (mr_grow((void **)&w->puppet_mass, &w->cap_puppets, np > 0 ? np : 1, sizeof(double)) != 0)
    return -1;
  memset(w->puppet_mass, 0, (size_t)w->cap_puppets * sizeof *w->puppet_mass);
  w->npuppets = np;
  for (int i = 0; i < w->n; i++) w->puppet_mass[w->puppet[i]] += w->mass[i];
  return 0;
}

/* The per-contact arrays hold at least the contacts of both lists. */
int mr_world_contact_capacity(mr_world *w, int need) {
  if (need <= w->cap_contact) return 0;
  int cap = w->cap_contact;
  if (mr_grow((void **)&w->contact_active, &cap, need, 1) != 0) return -1;
  cap = w->cap_contact;
  if (mr_grow((void **)&w->probe_valid, &cap, need, 1) != 0) return -1;
  cap = w->cap_contact;
  if (mr_grow((void **)&w->contact_pre, &cap, need, sizeof(double)) != 0) return -1;
  w->cap_contact = cap;
  return 0;
}

/* Room for every contact the world can have (each dynamic particle on each
 * plane, each pair of leaf spheres), up to a cap that keeps a large world's
 * reservation modest; past it the lists still grow, amortised. */
#define MR_CONTACT_RESERVE_MAX 16384
/* The solver's reservation is dense (rows² entries for J M⁻¹ Jᵀ, rows²/2 for
 * its factor): up to this many rows, about 3 MB, it is made; a larger
 * system grows the solver's arrays when it first meets a bigger size. */
#define MR_SOLVE_RESERVE_MAX_ROWS 512
#define MR_FRICTION_RESERVE       64

static int reserve_contacts(mr_world *w) {
  long dynamic = 0;
  for (int i = 0; i < w->n; i++) dynamic += w->inv_mass[i] > 0.0;
  long plane_pairs = (long)w->planes.n * dynamic;
  long sphere_pairs = (long)w->leaves.n * (w->leaves.n - 1) / 2;
  long most = plane_pairs + sphere_pairs + w->n_taut;
  int cap = most < MR_CONTACT_RESERVE_MAX ? (int)most : MR_CONTACT_RESERVE_MAX;
  if (cap > 0 &&
      (mr_grow((void **)&w->contacts.c, &w->contacts.cap, cap, sizeof(mr_contact)) != 0 ||
       mr_grow((void **)&w->probe.c, &w->probe.cap, cap, sizeof(mr_contact)) != 0 ||
       mr_grow((void **)&w->measured.c, &w->measured.cap, cap, sizeof(mr_contact)) != 0 ||
       mr_grow((void **)&w->held.c, &w->held.cap, cap, sizeof(mr_contact)) != 0 ||
       mr_grow((void **)&w->held_found.c, &w->held_found.cap, cap, sizeof(mr_contact)) != 0 ||
       mr_world_contact_capacity(w, cap) != 0))
    return -1;
  /* Rows and J entries: a distance has two particles, a pin or curve row
   * one, a plane contact one, a sphere contact up to four; the string
   * correction adds one per string, and the contacts it holds. */
  int rows = mr_constraint_row_count(w) + cap + MR_FORCES(w, STRINGS)->n;
  long plane_rows = plane_pairs < cap ? plane_pairs : cap;
  long entries =
      2L * w->distances.n + 3L * (w->pins.n + w->curves.n) + plane_rows + 4L * (cap - plane_rows);
  if (mr_rows_reserve(w, rows) != 0) return -1;
  /* Friction's W grows with the square of its contacts: room for a few
   * tens, and more when a scene meets them. */
  if (cap > 0 &&
      mr_friction_reserve(w, rows, cap < MR_FRICTION_RESERVE ? cap : MR_FRICTION_RESERVE))
    return -1;
  if (rows == 0 || rows > MR_SOLVE_RESERVE_MAX_ROWS) return 0;
  if (mr_jac_reserve(&w->J, rows, (int)entries) != MR_SOLVE_OK ||
      mr_jac_reserve(&w->island_J, rows, (int)entries) != MR_SOLVE_OK ||
      mr_csr_reserve(&w->A, rows, w->n, (int)entries) != MR_SOLVE_OK ||
      mr_solver_reserve(w->solver, rows) != MR_SOLVE_OK)
    return -1;
  return 0;
}

/* Derived data: scratch sized to the particles, puppet masses, sphere trees
 * and contact room. Rebuilt when elements were added. */
int mr_world_ensure_ready(mr_world *w) {
  if (!w->dirty && w->cap_scratch >= w->n) return 0;
  w->memo.valid = 0; /* elements added: the equations changed */
  if (size_scratch(w) != 0 || puppet_masses(w) != 0 || mr_restart_carriers(w) != 0 ||
      mr_islands_build(w) != 0)
    return -1;
  if (w->def.effects & (MR_EFFECT_SELF_COLLISION | MR_EFFECT_PUPPET_COLLISION))
    if (mr_trees_build(w) != 0) return -1;
  if (reserve_contacts(w) != 0) return -1;
  w->stable_dt = mr_forces_stable_dt(w);
  w->stats.stable_dt = w->stable_dt;
  if (w->dt_next > w->stable_dt) w->dt_next = w->stable_dt;
  w->dirty = 0;
  return 0;
}

/* Islands: rows of eq. 8 and eq. 9 that share no movable particle.
 *
 * A_ij = Σ_p w_p (∂C_i/∂x_p · ∂C_j/∂x_p) is zero unless rows i and j name
 * a common movable particle (assemble.c), so once the rows are grouped by
 * the sets of particles they join, J M⁻¹ Jᵀ is block diagonal and each
 * block is a system of its own: the same multipliers, to rounding, for a
 * fraction of the work. Two puppets that do not touch are two blocks.
 *
 * Solved whole, a crowd's system changes its pattern whenever any one
 * puppet's string snaps or a foot lands, and every change orders and
 * analyses the whole of it again: ten stick puppets on the capacity
 * benchmark's sway took 3.3 G instructions for 10 s, 2.7 times ten single
 * puppets, 60 % of it in orderings. Block by block, each puppet's rows are
 * numbered from 0 (its particles in the order its rows first name them),
 * so puppets built alike give the same patterns and the analyses and
 * assembly plans kept for one serve all.
 *
 * The constraints' blocks are fixed once the world is ready
 * (w->island_of); a solve joins the blocks that a contact between two of
 * them (two parts touching) links, by union–find over the blocks. Rows that
 * name no movable particle form one more block, whose rows come out
 * dependent as they do in the whole system. A world of one block, or a
 * solver other than LDLᵀ (whose iterations would stop on each block's own
 * residual), is solved whole, as before. */
#include "internal.h"

#include <string.h>

/* The constraint graph's blocks: particles joined by a distance (both
 * movable) share one; every other movable particle is one of its own;
 * kinematic particles belong to none (−1). Numbered in particle order. */
int mr_islands_build(mr_world *w) {
  /* One size for all five (island_start takes a block more than there are
   * and one past it), so that one capacity holds for each. */
  const int n = w->n, need = n + 2;
  int cap = w->cap_islands;
  if (mr_grow((void **)&w->island_of, &cap, need, sizeof(int)) != 0) return -1;
  cap = w->cap_islands;
  if (mr_grow((void **)&w->island_parent, &cap, need, sizeof(int)) != 0) return -1;
  cap = w->cap_islands;
  if (mr_grow((void **)&w->island_local, &cap, need, sizeof(int)) != 0) return -1;
  cap = w->cap_islands;
  if (mr_grow((void **)&w->island_mass, &cap, need, sizeof(double)) != 0) return -1;
  cap = w->cap_islands;
  if (mr_grow((void **)&w->island_start, &cap, need, sizeof(int)) != 0) return -1;
  w->cap_islands = cap;
  int *up = w->island_parent;
  for (int i = 0; i < n; i++) up[i] = i;
  for (int r = 0; r < w->distances.n; r++) {
    const mr_distance *d = &MR_AT(w->distances, mr_distance, r);
    if (!(w->inv_mass[d->a] > 0) || !(w->inv_mass[d->b] > 0)) continue;
    int a = d->a, b = d->b;
    while (up[a] != a) a = up[a] = up[up[a]];
    while (up[b] != b) b = up[b] = up[up[b]];
    if (a != b) up[a > b ? a : b] = a < b ? a : b;
  }
  int count = 0;
  for (int i = 0; i < n; i++) {
    int root = i;
    while (up[root] != root) root = up[root];
    /* A root is the lowest particle of its block, so it is numbered first. */
    w->island_of[i] = !(w->inv_mass[i] > 0) ? -1 : root == i ? count++ : w->island_of[root];
  }
  w->n_islands = count;
  for (int i = 0; i < n; i++) w->island_local[i] = -1;
  return 0;
}

static int block_root(int *up, int b) {
  while (up[b] != b) b = up[b] = up[up[b]];
  return b;
}

/* The block of row r's movable particles, joining the blocks it names
 * when join is set; n_islands when it names none; −1 when a movable
 * particle has no block (masses changed since the world was made ready:
 * then the system is solved whole). */
static int row_block(mr_world *w, int r, int join) {
  const int *rp = w->J.row_ptr, *part = w->J.particle, *of = w->island_of;
  const double *inv_mass = w->inv_mass;
  int *up = w->island_parent, block = w->n_islands;
  for (int e = rp[r]; e < rp[r + 1]; e++) {
    const int p = part[e];
    if (!(inv_mass[p] > 0)) continue;
    if (of[p] < 0) return -1;
    const int b = block_root(up, of[p]);
    if (block == w->n_islands) {
      block = b;
      if (!join) return block;
    } else if (b != block) {
      up[b > block ? b : block] = b < block ? b : block;
      block = b < block ? b : block;
    }
  }
  return block;
}

/* Groups J's rows by block into island_rows (island_start[g] the first of
 * group g). Returns the number of groups, or 1 when the system must be
 * solved whole. Only contact rows can join blocks: a constraint's
 * particles are in one block by the blocks' making. */
int mr_islands_group(mr_world *w) {
  const int k = w->J.rows, nb = w->n_islands;
  if (nb < 2 || w->opts.method != MR_SOLVE_LDLT || k < 2) return 1;
  int *up = w->island_parent, *key = w->island_key, *start = w->island_start;
  const int ncons = mr_constraint_row_count(w) < k ? mr_constraint_row_count(w) : k;
  for (int b = 0; b < nb; b++) up[b] = b;
  for (int r = ncons; r < k; r++)
    if (row_block(w, r, 1) < 0) return 1;
  /* start[b + 1] counts block b's rows, then becomes its first row's
   * slot: blocks keep their numbers' order, rows theirs within a block. */
  memset(start, 0, (size_t)(nb + 2) * sizeof *start);
  for (int r = 0; r < k; r++) {
    if ((key[r] = row_block(w, r, 0)) < 0) return 1;
    start[key[r] + 1]++;
  }
  int groups = 0;
  for (int b = 0; b <= nb; b++) {
    groups += start[b + 1] > 0;
    start[b + 1] += start[b];
  }
  if (groups < 2) return 1;
  for (int r = 0; r < k; r++) w->island_rows[start[key[r]]++] = r;
  /* Back to first rows, empty blocks dropped. */
  int g = 0, first = 0;
  for (int b = 0; b <= nb; b++) {
    const int end = start[b];
    if (end > first) start[g++] = first;
    first = end;
  }
  start[g] = k;
  return groups;
}

/* Group g's rows as a J of their own, particles numbered from 0 in the
 * order the rows name them, with their inverse masses, b, and each row's
 * contact (for the contact rows' compliance, eval.c). Written straight
 * into the block's J, reserved to the whole J's size. Returns the rows. */
static int island_system(mr_world *w, int g) {
  const int *rp = w->J.row_ptr, *part = w->J.particle;
  const double(*d)[3] = (const double(*)[3])w->J.d;
  const int *rows = w->island_rows + w->island_start[g];
  const int m = w->island_start[g + 1] - w->island_start[g];
  const int ncons = mr_constraint_row_count(w), contacts = w->contacts.n > 0 || w->held.n > 0;
  mr_jac *S = &w->island_J;
  if (mr_jac_reserve(S, w->J.rows, rp[w->J.rows]) != MR_SOLVE_OK) return -1;
  int *local = w->island_local, *srp = S->row_ptr, *spart = S->particle, np = 0, at = 0;
  double *mass = w->island_mass, (*sd)[3] = S->d;
  srp[0] = 0;
  for (int i = 0; i < m; i++) {
    const int r = rows[i];
    for (int e = rp[r]; e < rp[r + 1]; e++, at++) {
      const int p = part[e];
      if (local[p] < 0) {
        local[p] = np;
        mass[np++] = w->inv_mass[p];
      }
      spart[at] = local[p];
      sd[at][0] = d[e][0];
      sd[at][1] = d[e][1];
      sd[at][2] = d[e][2];
    }
    srp[i + 1] = at;
    w->island_b[i] = w->rhs[r];
    w->island_contact[i] = contacts && r >= ncons ? w->row_contact[r] : -1;
  }
  S->rows = m;
  S->n_particles = np;
  for (int i = 0; i < m; i++)
    for (int e = rp[rows[i]]; e < rp[rows[i] + 1]; e++) local[part[e]] = -1;
  return m;
}

/* Whether group g's b is zero, every row: its λ is then zero (A is
 * positive definite, or its dropped rows' λ are set to zero), as the
 * caller left it. Friction's probes push one contact, so every block but
 * its own is one (friction.c). */
static int rhs_zero(const mr_world *w, int g) {
  const int *rows = w->island_rows + w->island_start[g];
  const int m = w->island_start[g + 1] - w->island_start[g];
  for (int i = 0; i < m; i++)
    if (w->rhs[rows[i]] != 0.0) return 0;
  return 1;
}

/* Group g's system assembled and solved, its λ written out and its
 * iterations and dependent rows added to *sum; a failure, or NaN in this
 * block, is the caller's to handle for all. */
static mr_solve_status solve_block(mr_world *w, int g, mr_solve_result *sum) {
  const int m = island_system(w, g);
  if (m < 0) return MR_SOLVE_ERR_NOMEM;
  mr_solve_status a = mr_csr_assemble(&w->A, &w->island_J, w->island_mass);
  if (a != MR_SOLVE_OK) return a;
  mr_soften_contacts(&w->A, 0, w->island_contact);
  memset(w->island_x, 0, (size_t)m * sizeof *w->island_x);
  mr_solve_result r;
  mr_solve_status s = mr_solver_solve(w->solver, &w->opts, &w->A, w->island_b, w->island_x, &r);
  if (s < 0) {
    sum->status = s;
    return s;
  }
  const int *rows = w->island_rows + w->island_start[g];
  for (int i = 0; i < m; i++) w->lambda[rows[i]] = w->island_x[i];
  sum->iterations += r.iterations > 0 ? r.iterations : 0; /* what mr_solve_rows reads */
  sum->dependent += r.dependent;
  return MR_SOLVE_OK;
}

mr_solve_status mr_islands_solve(mr_world *w, int groups, mr_solve_result *sum) {
  memset(sum, 0, sizeof *sum);
  for (int g = 0; g < groups; g++) {
    if (rhs_zero(w, g)) continue;
    const mr_solve_status s = solve_block(w, g, sum);
    if (s < 0) return s;
  }
  /* LDLᵀ always finishes: what is left to say is whether rows dropped. */
  sum->status = sum->dependent > 0 ? MR_SOLVE_DEPENDENT : MR_SOLVE_OK;
  return sum->status;
}

mr_solve_status mr_islands_solve_one(mr_world *w, int g, mr_solve_result *sum) {
  memset(sum, 0, sizeof *sum);
  if (!rhs_zero(w, g)) {
    const mr_solve_status s = solve_block(w, g, sum);
    if (s < 0) return s;
  }
  sum->status = sum->dependent > 0 ? MR_SOLVE_DEPENDENT : MR_SOLVE_OK;
  return sum->status;
}

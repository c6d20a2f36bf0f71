/* Coulomb friction at resting contacts (§4.4), solved with the constraints.
 *
 * Friction is a force F_f along each contact's tangent plane, added to the
 * applied forces of eq. 8. The constraints then carry it too: what a
 * contact's side does under it is not what its particles alone would do.
 * A particle of a rigid body on a slope moves with the whole body, and the
 * body's normal forces shift as friction turns it. Working each contact's
 * friction from its own particles' mass undershoots by the rest of the
 * body's mass, and the contacts, each doing that, took 32 rounds and more
 * to agree where the masses differed (a tetrahedron of 0.3 to 2 kg on a
 * 20° slope crept 1.2 cm in 10 s with μ = 0.5 > tan 20°).
 *
 * So the response is measured through the solve. With A = J M⁻¹ Jᵀ
 * factored, a friction force f at contact j changes the multipliers by
 *   Δλ = −A⁻¹ J M⁻¹ S_j f
 * (eq. 8's b loses J M⁻¹ F), and the accelerations by
 *   Δq̈ = M⁻¹ (S_j f + Jᵀ Δλ),
 * S_j spreading f over the contact's carriers. Two probes per contact
 * (its tangent directions) give every contact's slip acceleration and
 * normal multiplier per unit friction at j: the Delassus operator W of
 * the tangent directions, and N of the normals. Friction is then linear
 * algebra on those, with no solve (friction_rounds.c): projected
 * Gauss–Seidel over the
 * contacts, each taking the friction f_stop that stops its sliding within
 * half a step (a_t + v_t/(h/2) = 0) against everything else, through its
 * own 2×2 block of W; if |f_stop| ≤ μN the contact sticks (static
 * friction), else it slides with μN against its sliding velocity. N moves
 * with every contact's friction. One last solve with the friction as an
 * applied force gives λ. Contacts in different blocks of eq. 8 (islands.c)
 * do not feel each other's friction, and each block is worked alone. */
#include "internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Friction reaches only the particles carrying the m contacts pt:
 * marks them (w->reached, clear on entry) and, where `reached` is given,
 * lists them there (at most 4m) and their number in *n_reached; lists in
 * w->row_reached the rows naming one of them, among `among` (count of
 * them; NULL: rows 0 to count − 1). Returns the number of rows listed. */
static int friction_reach(mr_world *w, const struct mr_fric_point *pt, int m, const int *among,
                          int count, int *reached_list, int *n_reached) {
  const int *rp = w->J.row_ptr, *part = w->J.particle;
  unsigned char *reached = w->reached;
  int np = 0;
  for (int i = 0; i < m; i++) {
    int p[4];
    const mr_contact *ct = &w->contacts.c[pt[i].contact];
    for (int k = mr_contact_carriers(w, ct, p) - 1; k >= 0; k--) {
      if (reached_list && !reached[p[k]]) reached_list[np++] = p[k];
      reached[p[k]] = 1;
    }
  }
  if (n_reached) *n_reached = np;
  int listed = 0;
  for (int l = 0; l < count; l++) {
    const int i = among ? among[l] : l;
    int any = 0;
    for (int e = rp[i]; e < rp[i + 1]; e++) any |= reached[part[e]];
    if (any) w->row_reached[listed++] = i;
  }
  return listed;
}

/* The marks friction_reach() made for pt, cleared. */
static void unreach(mr_world *w, const struct mr_fric_point *pt, int m) {
  for (int i = 0; i < m; i++) {
    int p[4];
    const mr_contact *ct = &w->contacts.c[pt[i].contact];
    for (int k = mr_contact_carriers(w, ct, p) - 1; k >= 0; k--) w->reached[p[k]] = 0;
  }
}

int mr_friction_present(const mr_world *w, int rows, int first) {
  for (int r = first; r < rows; r++)
    if (w->row_contact[r] >= 0 && w->contacts.c[w->row_contact[r]].friction > 0 && w->lambda[r] > 0)
      return 1;
  return 0;
}

/* Two unit vectors spanning the plane normal to n (n unit, or 0 for
 * coincident spheres, whose plane is then taken as any). */
static void tangent_basis(const double n[3], double t[2][3]) {
  int k = 0;
  for (int i = 1; i < 3; i++)
    if (fabs(n[i]) < fabs(n[k])) k = i;
  double e[3] = { 0, 0, 0 };
  e[k] = 1.0;
  const double en = n[k];
  double len = 0.0;
  for (int i = 0; i < 3; i++) {
    t[0][i] = e[i] - en * n[i];
    len += t[0][i] * t[0][i];
  }
  len = sqrt(len);
  for (int i = 0; i < 3; i++) t[0][i] /= len;
  t[1][0] = n[1] * t[0][2] - n[2] * t[0][1];
  t[1][1] = n[2] * t[0][0] - n[0] * t[0][2];
  t[1][2] = n[0] * t[0][1] - n[1] * t[0][0];
  if (!(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0.25)) /* no normal: any plane */
    for (int i = 0; i < 3; i++) t[1][i] = (i == (k + 1) % 3) ? 1.0 : 0.0;
}

static void project2(const double t[2][3], const double q[3], double out[2]) {
  out[0] = t[0][0] * q[0] + t[0][1] * q[1] + t[0][2] * q[2];
  out[1] = t[1][0] * q[0] + t[1][1] * q[1] + t[1][2] * q[2];
}

/* The frictional resting contacts of the solve, with what the probes and
 * the rounds need: their number, or −1 (out of memory). */
static int gather(mr_world *w, int rows, int first, const double *x, const double *v,
                  const double *acc) {
  int m = 0;
  for (int r = first; r < rows; r++) {
    const int c = w->row_contact[r];
    if (c < 0 || w->contacts.c[c].friction <= 0) continue;
    if (mr_grow((void **)&w->fric_points, &w->cap_fric_points, m + 1, sizeof *w->fric_points))
      return -1;
    const mr_contact *ct = &w->contacts.c[c];
    struct mr_fric_point *p = &w->fric_points[m];
    double n[3], q[3];
    p->row = r;
    p->contact = c;
    p->island = w->island_groups > 1 ? w->island_key[r] : 0;
    mr_contact_normal(w, ct, x, n);
    tangent_basis(n, p->t);
    p->inv = mr_contact_slip(w, ct, x, v, q);
    project2(p->t, q, p->vt);
    mr_contact_slip(w, ct, x, acc, q);
    project2(p->t, q, p->at);
    p->at0[0] = p->at[0];
    p->at0[1] = p->at[1];
    p->drive = sqrt(p->at[0] * p->at[0] + p->at[1] * p->at[1]);
    p->f[0] = p->f[1] = 0.0;
    p->n = p->n0 = w->lambda[r];
    p->mu = ct->friction;
    m++;
  }
  return m;
}

/* The probe of unit friction along tangent k of point j: column 2j+k of
 * W (2m × 2m, row-major) and of N (m × 2m). da and acc are 3n each; da
 * is zero on entry and left so. Only the rows naming a particle friction
 * reaches (the first `listed` of w->row_reached, whose b is all the
 * probe sets: every other row of the block is zero) see the push, and
 * only those particles' accelerations (`reached`, np of them) are read:
 * Jᵀ Δλ is summed there alone, row by row as mr_jac_tmul sums it. The
 * solve is of block `group` alone (−1: the whole system). */
typedef struct probe_rows {
  int listed, group, np;
  const int *reached;
} probe_rows;

static int probe(mr_world *w, const double *x, const struct mr_fric_point *pt, int m, int j, int k,
                 const probe_rows *pr, double *da, double *acc, double *W, double *N) {
  const int col = 2 * j + k, *list = w->row_reached, listed = pr->listed;
  const int *rp = w->J.row_ptr, *part = w->J.particle;
  const double(*jd)[3] = (const double(*)[3])w->J.d;
  const double *inv_mass = w->inv_mass;
  const unsigned char *reached = w->reached;
  const mr_contact *ct = &w->contacts.c[pt[j].contact];
  int cp[4];
  const int nc = mr_contact_carriers(w, ct, cp);
  mr_contact_spread(w, ct, pt[j].t[k], 1.0, da);
  for (int c = 0; c < nc; c++) {
    int seen = 0;
    for (int b = 0; b < c; b++) seen |= cp[b] == cp[c];
    for (int e = 0; e < 3 && !seen; e++) da[3 * cp[c] + e] *= inv_mass[cp[c]];
  }
  for (int l = 0; l < listed; l++) w->rhs[list[l]] = -mr_jac_row_mul(&w->J, list[l], da);
  if ((pr->group < 0 ? mr_solve_rows(w, 0) : mr_solve_block(w, pr->group)) != 0) return -1;
  for (int l = 0; l < listed; l++)
    for (int e = rp[list[l]]; e < rp[list[l] + 1]; e++)
      if (reached[part[e]]) memset(acc + 3 * part[e], 0, 3 * sizeof *acc);
  for (int l = 0; l < listed; l++) {
    const double z = w->lambda[list[l]];
    for (int e = rp[list[l]]; e < rp[list[l] + 1]; e++) {
      if (!reached[part[e]]) continue;
      double *o = acc + 3 * part[e];
      o[0] += jd[e][0] * z;
      o[1] += jd[e][1] * z;
      o[2] += jd[e][2] * z;
    }
  }
  for (int q = 0; q < pr->np; q++) {
    const int i = pr->reached[q];
    for (int e = 0; e < 3; e++) acc[3 * i + e] = da[3 * i + e] + acc[3 * i + e] * inv_mass[i];
  }
  for (int i = 0; i < m; i++) {
    double q[3], sl[2];
    mr_contact_slip(w, &w->contacts.c[pt[i].contact], x, acc, q);
    project2(pt[i].t, q, sl);
    W[(size_t)(2 * i) * (size_t)(2 * m) + (size_t)col] = sl[0];
    W[(size_t)(2 * i + 1) * (size_t)(2 * m) + (size_t)col] = sl[1];
    N[(size_t)i * (size_t)(2 * m) + (size_t)col] = w->lambda[pt[i].row];
  }
  for (int c = 0; c < nc; c++) memset(da + 3 * cp[c], 0, 3 * sizeof *da);
  return 0;
}

/* b kept, two probe vectors of 3n, and for the largest block's m points:
 * W (2m × 2m), N (m × 2m), reachable()'s factor, its normal matrix and
 * three vectors of 2m (then cone_on_normals()'s 4m), and the at most 4m
 * particles its probes reach, as ints in 2m. */
int mr_friction_reserve(mr_world *w, int rows, int points) {
  const size_t need =
      (size_t)rows + 6 * (size_t)w->n + 14 * (size_t)points * (size_t)points + 8 * (size_t)points;
  if (need > (size_t)INT32_MAX / sizeof(double) ||
      mr_grow((void **)&w->fric_work, &w->cap_fric_work, (int)need, sizeof(double)) != 0 ||
      mr_grow((void **)&w->fric_points, &w->cap_fric_points, points, sizeof *w->fric_points) != 0)
    return -1;
  return 0;
}

/* One block's friction: its points pt[0..m), its rows (among, count;
 * NULL: all of them), its group (−1: solved whole). Leaves each point's
 * f; 1, 0 when it needs none, or −1 (out of memory in a probe's solve).
 * da (3n, zero, left so), acc (3n) and work (14m² + 8m) are scratch. Its
 * own largest multiplier sets the tolerances (taken before any block's
 * probes, which overwrite λ), and its own slips whether it needs
 * probing: another block's friction is nothing to it (W and N have no
 * entries between blocks). Worked over every block at once, a crowd
 * lying on a floor cost the cube of all its contacts (16 puppets: 21 s
 * for 3 s); each probe now solves its own block alone. */
static int island_friction(mr_world *w, double h, const double *x, struct mr_fric_point *pt, int m,
                           const int *among, int count, int group, double *da, double *acc,
                           double *work) {
  const double scale = pt[0].scale;
  if (!mr_friction_asks(pt, m, 0.5 * h, 1e-9 * scale)) return 0;
  const size_t mm = (size_t)(2 * m);
  double *W = work, *N = W + mm * mm, *scratch = N + mm * (size_t)m;
  int *reached = (int *)(scratch + 4 * mm * (size_t)m + 6 * (size_t)m); /* past 8m² + 6m */
  probe_rows pr = { 0, group, 0, reached };
  pr.listed = friction_reach(w, pt, m, among, count, reached, &pr.np);
  for (int l = 0; l < count; l++) w->rhs[among ? among[l] : l] = 0.0;
  int rc = 0;
  for (int j = 0; j < m && rc == 0; j++)
    for (int k = 0; k < 2 && rc == 0; k++) rc = probe(w, x, pt, m, j, k, &pr, da, acc, W, N);
  unreach(w, pt, m);
  if (rc != 0) return -1;
  mr_friction_rounds(pt, m, 0.5 * h, W, N, 1e-9 * scale, scratch);
  return 1;
}

static int by_island(const void *a, const void *b) {
  const struct mr_fric_point *p = a, *q = b;
  if (p->island != q->island) return (p->island > q->island) - (p->island < q->island);
  return (p->row > q->row) - (p->row < q->row);
}

/* The largest |λ| among rows (among, count; NULL: 0 to count − 1), into
 * each of pt[0..m). */
static void block_scale(const mr_world *w, struct mr_fric_point *pt, int m, const int *among,
                        int count) {
  double scale = 0;
  for (int l = 0; l < count; l++) scale = fmax(scale, fabs(w->lambda[among ? among[l] : l]));
  for (int i = 0; i < m; i++) pt[i].scale = scale;
}

/* The next block, from group *group and point *first on, that has points
 * (sorted by_island, as the blocks are numbered): its group into *group
 * and its points [*first, *end); 0 when none is left. */
static int next_block(const mr_world *w, int m, int *group, int first, int *end) {
  const struct mr_fric_point *pt = w->fric_points;
  const int *start = w->island_start, *grouped = w->island_rows;
  for (; *group < w->island_groups && first < m; ++*group) {
    const int key = w->island_key[grouped[start[*group]]];
    int e = first;
    while (e < m && pt[e].island == key) e++;
    if (e > first) {
      *end = e;
      return 1;
    }
  }
  return 0;
}

/* island_friction() on each block that has points, with that block's
 * rows: how many made friction, or −1. */
static int each_island(mr_world *w, double h, const double *x, int m, int rows, double *da,
                       double *acc, double *work) {
  struct mr_fric_point *pt = w->fric_points;
  if (w->island_groups <= 1) {
    block_scale(w, pt, m, NULL, rows);
    return island_friction(w, h, x, pt, m, NULL, rows, -1, da, acc, work);
  }
  const int *start = w->island_start, *grouped = w->island_rows;
  for (int g = 0, i = 0, e = 0; next_block(w, m, &g, i, &e); g++, i = e)
    block_scale(w, pt + i, e - i, grouped + start[g], start[g + 1] - start[g]);
  int made = 0;
  for (int g = 0, i = 0, e = 0; next_block(w, m, &g, i, &e); g++, i = e) {
    const int r = island_friction(w, h, x, pt + i, e - i, grouped + start[g],
                                  start[g + 1] - start[g], g, da, acc, work);
    if (r < 0) return -1;
    made += r;
  }
  return made;
}

/* The most points one block holds (all of them when solved whole). */
static int largest_island(const mr_world *w, int m) {
  if (w->island_groups <= 1) return m;
  int most = 0;
  for (int i = 0, run = 0; i < m; i++) {
    run = (i > 0 && w->fric_points[i].island == w->fric_points[i - 1].island) ? run + 1 : 1;
    most = run > most ? run : most;
  }
  return most;
}

int mr_friction_solve(mr_world *w, double h, int rows, int first, const double *x, const double *v,
                      double *a) {
  const int n = w->n;
  const double *inv_mass = w->inv_mass;
  double *acc = w->scratch.acc_try, *f = w->scratch.force;
  mr_jac_tmul(&w->J, w->lambda, acc);
  for (int i = 0; i < n; i++) {
    const double im = inv_mass[i];
    for (int e = 0; e < 3; e++) acc[3 * i + e] = a[3 * i + e] + acc[3 * i + e] * im;
  }
  const int m = gather(w, rows, first, x, v, acc);
  if (m <= 0) return m;
  if (w->island_groups > 1) qsort(w->fric_points, (size_t)m, sizeof *w->fric_points, by_island);
  if (mr_friction_reserve(w, rows, largest_island(w, m)) != 0) return -1;
  double *rhs0 = w->fric_work, *da = rhs0 + rows, *pacc = da + 3 * n, *work = pacc + 3 * n;
  memcpy(rhs0, w->rhs, (size_t)rows * sizeof *rhs0);
  memset(da, 0, (size_t)(3 * n) * sizeof *da);
  memset(w->reached, 0, (size_t)n);
  const int made = each_island(w, h, x, m, rows, da, pacc, work);
  if (made <= 0) {
    memcpy(w->rhs, rhs0, (size_t)rows * sizeof *rhs0);
    return made;
  }
  /* The friction as an applied force, and eq. 8 solved once more. */
  for (int i = 0; i < m; i++) {
    const struct mr_fric_point *p = &w->fric_points[i];
    double fw[3];
    for (int e = 0; e < 3; e++) fw[e] = p->f[0] * p->t[0][e] + p->f[1] * p->t[1][e];
    mr_contact_spread(w, &w->contacts.c[p->contact], fw, 1.0, f);
  }
  const int listed = friction_reach(w, w->fric_points, m, NULL, rows, NULL, NULL);
  const unsigned char *reached = w->reached;
  for (int i = 0; i < n; i++) {
    if (!reached[i]) continue;
    for (int e = 0; e < 3; e++) a[3 * i + e] = f[3 * i + e] * inv_mass[i];
  }
  memcpy(w->rhs, rhs0, (size_t)rows * sizeof *rhs0);
  mr_rhs_rows(w, w->row_reached, listed, a);
  return mr_solve_rows(w, 0);
}

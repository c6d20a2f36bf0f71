/* A = J M⁻¹ Jᵀ, the matrix of §5.2 eq. 8 and §5.3 eq. 9.
 *
 * Entry (i, j) is Σ_p w_p (∂C_i/∂x_p · ∂C_j/∂x_p) over the particles p that
 * rows i and j share, with w_p = 1/m_p. Rows that share no movable particle
 * give a structural zero, so A is as sparse as the constraint graph: the
 * assembly walks particle → rows lists instead of forming 3n-wide products.
 * The diagonal is always stored (a zero row of J still gets A_ii = 0), so
 * every solver finds its pivot without a search and can flag such a row as
 * dependent.
 *
 * A's pattern depends only on which particles each row of J names and on
 * which particles are pinned (w_p = 0 adds nothing). The physics rebuilds J
 * every evaluation with the same rows, so a plan keeps that pattern, the
 * particle → rows lists and A's sorted columns, and a call that finds them
 * unchanged only recomputes the numbers.
 *
 * Several plans are kept, least recently used out. A step mixes row sets
 * (an impulse, evaluations with resting contacts, contacts released, the
 * projection of taut strings after the step), so J alternates among a few
 * patterns, and with one plan each switch built the pattern again: on the
 * taut-string stick marionette (10 s of sway) assembly took 20.5 % of all
 * instructions, about 11 % in rebuilding the plan. Plans are looked up by
 * a hash of J's pattern, and the one used before the current first: the
 * physics mostly swaps between two.
 *
 * A plan also lists the products each entry of A sums, as pairs of J's
 * entries and the entry of A they go to, in the order the sums are made,
 * so the numbers are one straight pass over that list and a copy onto the
 * upper triangle, with no search through the particle lists and no dense
 * work row: the stick figure's 25 rows assemble in about a third of the
 * instructions, with the same bits. */
#include "solver_internal.h"

#include <stdlib.h>
#include <string.h>

/* One pattern's plan. */
typedef struct csr_kept {
  mr_buf rp, col; /* A's pattern: A->row_ptr and col point here */
  /* The pattern the plan was built for: J's rows, their particles, and
   * which particles were pinned. */
  int valid, rows, np, ne, nnz;
  uint64_t hash; /* source_hash of the J it was built for */
  uint64_t id;   /* A->pattern_id while this plan is in use */
  mr_buf jrp, jpart, pinned;
  mr_buf masses; /* inv_mass as last seen: the same bits, the same pinned set */
  /* Particle → entries of J that name it (movable particles only): the
   * transpose of J's pattern. */
  mr_buf pstart, prow, pent;
  /* The products: J entry e's run [tstart[e], tstart[e + 1]) of terms,
   * each w_p (d_e · d_teb) added into val[tslot]; and the upper entries
   * val[mirror[2m + 1]] = val[mirror[2m]]. nterms < 0: the pattern needs
   * more terms than two per entry of A's lower triangle (rows sharing
   * many particles), and numeric() walks the particle lists instead. */
  mr_buf tstart, tslot, teb, mirror;
  int nterms, nmirror;
  unsigned long used; /* the plan set's clock when last used */
} csr_kept;

/* The largest J kept beside the first plan (rows): larger ones always use
 * plan 0, so a reserve gives the others room for a dense A of up to that
 * size only (about 260 KiB each with its lists of products). How many
 * plans are kept: MR_CSR_KEPT (solver_internal.h). The benchmark's
 * puppets assemble 7 to 31 rows. */
#define CSR_KEPT_MAX_ROWS 128

struct mr_csr_plan {
  csr_kept kept[MR_CSR_KEPT];
  int cur;                   /* the plan used last */
  int before;                /* the plan used before it */
  mr_buf val;                /* A's values: A->val points here */
  mr_buf mark, cursor, ucol; /* scratch of the pattern build and the symmetrising copy */
  mr_buf work;               /* one row of A, dense; zero between rows */
  /* The room every plan has (plan_reserve, plan_reserve_entries): a J
   * within it costs no pass over the plans. */
  size_t room_k, room_np, room_ne, room_nnz, room_terms;
  int roomy, roomy_entries; /* the rooms above were reserved */
  unsigned long builds, clock;
};

#define INTS(b) ((int *)(b).p)

static int pinned(const double *inv_mass, int p) {
  return !inv_mass || inv_mass[p] == 0.0;
}

/* The key a plan is looked up by: J's sizes and the particles its entries
 * name (the row starts and the pinned set, which seldom tell two of a
 * run's patterns apart, are left to same_source). */
static uint64_t source_hash(const mr_jac *J, int ne) {
  const int dims[3] = { J->rows, J->n_particles, ne };
  return mr_hash_ints(mr_hash_ints(14695981039346656037u, dims, 3), J->particle, (size_t)ne);
}

static int same_source(csr_kept *pl, const mr_jac *J, const double *inv_mass, int ne) {
  if (!pl->valid || pl->rows != J->rows || pl->np != J->n_particles || pl->ne != ne) return 0;
  if (J->rows > 0 && memcmp(pl->jrp.p, J->row_ptr, (size_t)(J->rows + 1) * sizeof(int)) != 0)
    return 0;
  if (ne > 0 && memcmp(pl->jpart.p, J->particle, (size_t)ne * sizeof(int)) != 0) return 0;
  /* The masses rarely change; comparing them whole is a quarter of the
   * particle by particle test. */
  const size_t mass_bytes = (size_t)J->n_particles * sizeof(double);
  if (!inv_mass || memcmp(pl->masses.p, inv_mass, mass_bytes) != 0) {
    const unsigned char *pin = pl->pinned.p;
    for (int p = 0; p < J->n_particles; p++)
      if (pin[p] != pinned(inv_mass, p)) return 0;
    if (inv_mass) memcpy(pl->masses.p, inv_mass, mass_bytes);
  }
  return 1;
}

/* The plans that a J of k rows may use: all of them, or plan 0 alone. */
static int plans_for(size_t k) {
  return k > CSR_KEPT_MAX_ROWS ? 1 : MR_CSR_KEPT;
}

/* Plans [0, count)'s arrays and the scratch for k rows, np particles and
 * ne entries of J. Every plan grows with the largest J it may hold, so a
 * pattern seen for the first time allocates nothing once a larger one was
 * seen: the physics allocates nothing after its first step. */
static int plan_reserve(struct mr_csr_plan *pl, int count, size_t k, size_t np, size_t ne) {
  const size_t si = sizeof(int);
  if (pl->roomy && k <= pl->room_k && np <= pl->room_np && ne <= pl->room_ne) return 0;
  for (int s = 0; s < count; s++) {
    csr_kept *kp = &pl->kept[s];
    if (mr_buf_reserve(&kp->rp, k + 1, si) || mr_buf_reserve(&kp->jrp, k + 1, si) ||
        mr_buf_reserve(&kp->jpart, ne, si) || mr_buf_reserve(&kp->pinned, np, 1) ||
        mr_buf_reserve(&kp->masses, np, sizeof(double)) ||
        mr_buf_reserve(&kp->pstart, np + 1, si) || mr_buf_reserve(&kp->prow, ne, si) ||
        mr_buf_reserve(&kp->pent, ne, si) || mr_buf_reserve(&kp->tstart, ne + 1, si))
      return MR_SOLVE_ERR_NOMEM;
  }
  if (mr_buf_reserve(&pl->mark, k, si) || mr_buf_reserve(&pl->cursor, k + 1, si) ||
      mr_buf_reserve(&pl->work, k, sizeof(double)))
    return MR_SOLVE_ERR_NOMEM;
  if (count == MR_CSR_KEPT && k <= CSR_KEPT_MAX_ROWS) {
    pl->room_k = k > pl->room_k ? k : pl->room_k;
    pl->room_np = np > pl->room_np ? np : pl->room_np;
    pl->room_ne = ne > pl->room_ne ? ne : pl->room_ne;
    pl->roomy = 1;
  }
  return 0;
}

/* A's entries: nnz columns in plans [0, count), and the values and
 * unsorted columns (shared: every assembly writes them whole). */
static int plan_reserve_entries(struct mr_csr_plan *pl, int count, size_t nnz, size_t ne) {
  const size_t si = sizeof(int);
  if (pl->roomy_entries && nnz <= pl->room_nnz && nnz + ne <= pl->room_terms) return 0;
  for (int s = 0; s < count; s++) {
    csr_kept *kp = &pl->kept[s];
    /* Terms: up to one per entry of J (the diagonal's) and one per
     * off-diagonal entry of A (two per lower one); the mirrored entries:
     * nnz − n ints. See build_terms(). */
    if (mr_buf_reserve(&kp->col, nnz, si) || mr_buf_reserve(&kp->tslot, nnz + ne, si) ||
        mr_buf_reserve(&kp->teb, nnz + ne, si) || mr_buf_reserve(&kp->mirror, nnz, si))
      return MR_SOLVE_ERR_NOMEM;
  }
  if (mr_buf_reserve(&pl->ucol, nnz, sizeof(int)) || mr_buf_reserve(&pl->val, nnz, sizeof(double)))
    return MR_SOLVE_ERR_NOMEM;
  if (count == MR_CSR_KEPT) {
    pl->room_nnz = nnz > pl->room_nnz ? nnz : pl->room_nnz;
    pl->room_terms = nnz + ne > pl->room_terms ? nnz + ne : pl->room_terms;
    pl->roomy_entries = 1;
  }
  return 0;
}

static void keep_source(csr_kept *pl, const mr_jac *J, const double *inv_mass, int ne) {
  const int k = J->rows, np = J->n_particles;
  if (k > 0) memcpy(pl->jrp.p, J->row_ptr, ((size_t)k + 1) * sizeof(int));
  if (ne > 0) memcpy(pl->jpart.p, J->particle, (size_t)ne * sizeof(int));
  unsigned char *pin = pl->pinned.p;
  for (int p = 0; p < np; p++) pin[p] = (unsigned char)pinned(inv_mass, p);
  if (inv_mass && np > 0) memcpy(pl->masses.p, inv_mass, (size_t)np * sizeof(double));
  pl->rows = k;
  pl->np = np;
  pl->ne = ne;
  pl->hash = source_hash(J, ne);
}

/* Particle → (row, entry) lists by a counting sort over J's entries; a
 * pinned particle gets an empty list. */
static void particle_lists(csr_kept *pl, const mr_jac *J, const double *inv_mass, int ne) {
  const int np = J->n_particles;
  int *pstart = INTS(pl->pstart), *prow = INTS(pl->prow), *pent = INTS(pl->pent);
  memset(pstart, 0, ((size_t)np + 1) * sizeof *pstart);
  for (int e = 0; e < ne; e++)
    if (!pinned(inv_mass, J->particle[e])) pstart[J->particle[e] + 1]++;
  for (int p = 0; p < np; p++) pstart[p + 1] += pstart[p];
  for (int i = 0; i < J->rows; i++) {
    for (int e = J->row_ptr[i]; e < J->row_ptr[i + 1]; e++) {
      int p = J->particle[e];
      if (pinned(inv_mass, p)) continue;
      int at = pstart[p]++;
      prow[at] = i;
      pent[at] = e;
    }
  }
  for (int p = np; p > 0; p--) pstart[p] = pstart[p - 1];
  pstart[0] = 0;
}

/* The columns of row i of A (the diagonal first, then the rows sharing a
 * movable particle, unsorted) into out when out is not NULL. Returns the
 * count. mark[j] == i marks column j as seen for row i. */
static int row_columns(const csr_kept *pl, const mr_jac *J, int i, int *mark, int *out) {
  const int *pstart = INTS(pl->pstart), *prow = INTS(pl->prow), *part = J->particle;
  int c = 0;
  mark[i] = i;
  if (out) out[c] = i;
  c++;
  for (int e = J->row_ptr[i]; e < J->row_ptr[i + 1]; e++) {
    for (int q = pstart[part[e]]; q < pstart[part[e] + 1]; q++) {
      int j = prow[q];
      if (mark[j] != i) {
        mark[j] = i;
        if (out) out[c] = j;
        c++;
      }
    }
  }
  return c;
}

/* A's row_ptr and sorted columns. Each row's columns are listed unsorted
 * into ucol, then one counting transpose sorts them all: A is symmetric,
 * so the transpose of its pattern is the pattern itself. */
static int build_pattern(struct mr_csr_plan *pl, csr_kept *kp, const mr_jac *J) {
  const int k = J->rows;
  int *mark = INTS(pl->mark), *cnt = INTS(pl->cursor);
  for (int i = 0; i < k; i++) mark[i] = -1;
  int nnz = 0;
  for (int i = 0; i < k; i++) nnz += row_columns(kp, J, i, mark, NULL);
  if (plan_reserve_entries(pl, plans_for((size_t)k), (size_t)nnz, (size_t)J->row_ptr[k]) != 0)
    return MR_SOLVE_ERR_NOMEM;
  int *ucol = INTS(pl->ucol), *rp = INTS(kp->rp), *col = INTS(kp->col);
  memset(cnt, 0, ((size_t)k + 1) * sizeof *cnt);
  for (int i = 0; i < k; i++) mark[i] = -1;
  for (int i = 0, at = 0; i < k; i++) {
    int c = row_columns(kp, J, i, mark, ucol + at);
    for (int t = at; t < at + c; t++) cnt[ucol[t] + 1]++;
    at += c;
  }
  for (int i = 0; i < k; i++) cnt[i + 1] += cnt[i];
  memcpy(rp, cnt, ((size_t)k + 1) * sizeof *rp);
  /* Row i lists as many columns as column i has rows (A's pattern is
   * symmetric: rows i and j share a particle or they do not). */
  for (int i = 0, at = 0; i < k; i++) {
    for (int end = at + (rp[i + 1] - rp[i]); at < end; at++) col[cnt[ucol[at]]++] = i;
  }
  kp->nnz = nnz;
  return 0;
}

/* The term lists of numeric(), in the order its particle-list walk sums
 * them: row by row, each entry e of row i in J's order, each earlier or
 * same row j that shares e's particle; so each entry of A gets its terms
 * in the same order, from 0, and the same bits. Scratch: slot (k ints,
 * row i's column j → its index in A) and cursor (k ints). */
static void build_terms(csr_kept *kp, const mr_jac *J, int *slot, int *cursor) {
  const int k = J->rows, ne = k > 0 ? J->row_ptr[k] : 0;
  const int *pstart = INTS(kp->pstart), *prow = INTS(kp->prow), *pent = INTS(kp->pent);
  const int *rp = INTS(kp->rp), *col = INTS(kp->col);
  int *tstart = INTS(kp->tstart), *tslot = INTS(kp->tslot), *teb = INTS(kp->teb);
  int t = 0, m = 0, *mirror = INTS(kp->mirror);
  for (int i = 0; i < k; i++) {
    for (int q = rp[i]; q < rp[i + 1] && col[q] <= i; q++) slot[col[q]] = q;
    for (int e = J->row_ptr[i]; e < J->row_ptr[i + 1]; e++) {
      tstart[e] = t;
      const int p = J->particle[e];
      for (int q = pstart[p]; q < pstart[p + 1] && prow[q] <= i; q++) {
        if (t == ne + kp->nnz) { /* over the lists' room: walk instead */
          kp->nterms = -1;
          return;
        }
        tslot[t] = slot[prow[q]];
        teb[t++] = pent[q];
      }
    }
  }
  tstart[ne] = t;
  kp->nterms = t;
  /* Row j's entries left of the diagonal, (j, i) with i < j, go to row
   * i's upper part: rows visited in order fill each row's upper entries
   * in column order, from just past its diagonal (one cursor per row). */
  for (int j = 0; j < k; j++) {
    for (int q = rp[j]; q < rp[j + 1]; q++) {
      const int i = col[q];
      if (i == j) {
        cursor[j] = q + 1;
        break;
      }
      mirror[m++] = q;
      mirror[m++] = cursor[i]++;
    }
  }
  kp->nmirror = m / 2;
}

/* A plan for J, built into the least recently used one (an empty one
 * first; plan 0 for a J too large to keep beside it). */
static int replan(struct mr_csr_plan *pl, const mr_jac *J, const double *inv_mass, int ne) {
  const size_t k = (size_t)J->rows;
  int s = 0;
  if (plans_for(k) > 1)
    for (int t = 1; t < MR_CSR_KEPT; t++)
      if (pl->kept[t].used < pl->kept[s].used) s = t;
  csr_kept *kp = &pl->kept[s];
  kp->valid = 0;
  if (plan_reserve(pl, plans_for(k), k, (size_t)J->n_particles, (size_t)ne) != 0)
    return MR_SOLVE_ERR_NOMEM;
  memset(pl->work.p, 0, k * sizeof(double));
  keep_source(kp, J, inv_mass, ne);
  particle_lists(kp, J, inv_mass, ne);
  if (build_pattern(pl, kp, J) != 0) return MR_SOLVE_ERR_NOMEM;
  build_terms(kp, J, INTS(pl->mark), INTS(pl->cursor));
  kp->id = mr_pattern_new_id();
  kp->valid = 1;
  pl->builds++;
  pl->cur = s;
  return 0;
}

/* Makes the plan for J's pattern pl->cur: the last one, a kept one, or a
 * new one. */
static int find_plan(struct mr_csr_plan *pl, const mr_jac *J, const double *inv_mass, int ne) {
  if (!same_source(&pl->kept[pl->cur], J, inv_mass, ne)) {
    const int was = pl->cur;
    /* Two patterns taking turns (ldlt.c, mr_ldlt_prepare): the one used
     * before is looked at before J is hashed. */
    int s = pl->before;
    if (!same_source(&pl->kept[s], J, inv_mass, ne)) {
      const uint64_t h = source_hash(J, ne);
      for (s = 0; s < MR_CSR_KEPT; s++)
        if (pl->kept[s].valid && pl->kept[s].hash == h &&
            same_source(&pl->kept[s], J, inv_mass, ne))
          break;
    }
    if (s < MR_CSR_KEPT)
      pl->cur = s;
    else if (replan(pl, J, inv_mass, ne) != 0)
      return MR_SOLVE_ERR_NOMEM;
    pl->before = was;
  }
  pl->kept[pl->cur].used = ++pl->clock;
  return 0;
}

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The numbers: row i's sums scattered into the dense work row, in J's
 * entry order, then gathered into A's sorted columns. Only the lower
 * triangle and the diagonal are summed (each particle's list is in row
 * order, so the rest of a list lies above): symmetrise() copies them up. */
static void numeric(mr_csr *A, const csr_kept *kp, double *work, const mr_jac *J,
                    const double *inv_mass) {
  const int *pstart = INTS(kp->pstart), *prow = INTS(kp->prow), *pent = INTS(kp->pent);
  const int *jrp = J->row_ptr, *part = J->particle, *rp = A->row_ptr, *col = A->col;
  const double(*d)[3] = (const double(*)[3])J->d;
  double *val = A->val;
  for (int i = 0; i < J->rows; i++) {
    for (int e = jrp[i], e_end = jrp[i + 1]; e < e_end; e++) {
      const int p = part[e];
      const double w = inv_mass[p]; /* a pinned particle's list is empty */
      for (int q = pstart[p], q_end = pstart[p + 1]; q < q_end && prow[q] <= i; q++)
        work[prow[q]] += w * dot3(d[e], d[pent[q]]);
    }
    for (int q = rp[i], q_end = rp[i + 1]; q < q_end && col[q] <= i; q++) {
      val[q] = work[col[q]];
      work[col[q]] = 0.0;
    }
  }
}

/* Rounding may leave A_ij and A_ji a few ulps apart (the two sums run over
 * the shared particles in different orders). Copy the lower triangle onto
 * the upper so every solver sees the same symmetric matrix, bit for bit.
 * Row j's lower entries come before its diagonal; rows are visited in
 * ascending order, so row i's upper entries are filled in ascending column
 * order, one cursor each, starting just past its diagonal. */
static void symmetrise(mr_csr *A, int *cursor) {
  for (int j = 0; j < A->n; j++) {
    for (int q = A->row_ptr[j]; q < A->row_ptr[j + 1]; q++) {
      int i = A->col[q];
      if (i == j) {
        cursor[j] = q + 1;
        break;
      }
      A->val[cursor[i]++] = A->val[q];
    }
  }
}

static int plan_of(mr_csr *A) {
  if (!A->plan && !(A->plan = calloc(1, sizeof *A->plan))) return MR_SOLVE_ERR_NOMEM;
  return 0;
}

mr_solve_status mr_csr_reserve(mr_csr *A, int rows, int particles, int entries) {
  if (!A || rows < 0 || particles < 0 || entries < 0) return MR_SOLVE_ERR_ARG;
  const size_t k = (size_t)rows, kept = k < CSR_KEPT_MAX_ROWS ? k : CSR_KEPT_MAX_ROWS;
  const size_t np = (size_t)particles, ne = (size_t)entries;
  if (plan_of(A) != 0 || plan_reserve(A->plan, 1, k, np, ne) != 0 ||
      plan_reserve_entries(A->plan, 1, k * k, ne) != 0 ||
      plan_reserve(A->plan, MR_CSR_KEPT, kept, np, ne) != 0 ||
      plan_reserve_entries(A->plan, MR_CSR_KEPT, kept * kept, ne) != 0)
    return MR_SOLVE_ERR_NOMEM;
  return MR_SOLVE_OK;
}

/* The numbers from the plan's term lists (build_terms). */
static void numeric_terms(mr_csr *A, const csr_kept *kp, const mr_jac *J, const double *inv_mass) {
  const int ne = kp->ne, *part = J->particle, *tstart = INTS(kp->tstart);
  const int *tslot = INTS(kp->tslot), *teb = INTS(kp->teb), *mirror = INTS(kp->mirror);
  const double(*d)[3] = (const double(*)[3])J->d;
  double *val = A->val;
  memset(val, 0, (size_t)kp->nnz * sizeof *val);
  for (int e = 0, t = 0; e < ne; e++) {
    /* Locals: a store into val might otherwise be a store into d. */
    const double w = inv_mass[part[e]], de[3] = { d[e][0], d[e][1], d[e][2] };
    for (const int end = tstart[e + 1]; t < end; t++) val[tslot[t]] += w * dot3(de, d[teb[t]]);
  }
  for (int m = 0; m < kp->nmirror; m++) val[mirror[2 * m + 1]] = val[mirror[2 * m]];
}

mr_solve_status mr_csr_assemble(mr_csr *A, const mr_jac *J, const double *inv_mass) {
  if (!J || !A) return MR_SOLVE_ERR_UNAVAILABLE;
  const int ne = J->rows > 0 ? J->row_ptr[J->rows] : 0;
  if (ne > 0 && !inv_mass) return MR_SOLVE_ERR_UNAVAILABLE;
  if (plan_of(A) != 0) return MR_SOLVE_ERR_NOMEM;
  struct mr_csr_plan *pl = A->plan;
  if (find_plan(pl, J, inv_mass, ne) != 0) return MR_SOLVE_ERR_NOMEM;
  const csr_kept *kp = &pl->kept[pl->cur];
  A->n = kp->rows;
  A->nnz = kp->nnz;
  A->row_ptr = kp->rp.p;
  A->col = kp->col.p;
  A->val = pl->val.p;
  A->pattern_id = kp->id;
  A->row_ptr[0] = 0;
  if (kp->nterms >= 0) {
    numeric_terms(A, kp, J, inv_mass);
  } else {
    numeric(A, kp, pl->work.p, J, inv_mass);
    symmetrise(A, pl->cursor.p);
  }
  return MR_SOLVE_OK;
}

unsigned long mr_csr_pattern_builds(const mr_csr *A) {
  return A && A->plan ? A->plan->builds : 0;
}

void mr_csr_free(mr_csr *A) {
  if (!A) return;
  struct mr_csr_plan *pl = A->plan;
  if (pl) {
    for (int s = 0; s < MR_CSR_KEPT; s++) {
      csr_kept *kp = &pl->kept[s];
      mr_buf *const kbufs[] = { &kp->rp,     &kp->col,    &kp->jrp,   &kp->jpart, &kp->pinned,
                                &kp->masses, &kp->pstart, &kp->prow,  &kp->pent,  &kp->tstart,
                                &kp->tslot,  &kp->teb,    &kp->mirror };
      mr_bufs_free(kbufs, sizeof kbufs / sizeof kbufs[0]);
    }
    mr_buf *const bufs[] = { &pl->val, &pl->mark, &pl->cursor, &pl->ucol, &pl->work };
    mr_bufs_free(bufs, sizeof bufs / sizeof bufs[0]);
    free(pl);
  }
  memset(A, 0, sizeof *A);
}

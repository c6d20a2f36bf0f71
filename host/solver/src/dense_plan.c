/* The dense LDLᵀ's plan (dense.c), made once for A's pattern: the order's
 * first columns f_k, L's symbolic pattern, the products each entry of L
 * sums and the triangular sweeps' columns, kept with the LDLᵀ analysis'
 * slot so that a pattern that comes back costs a copy; or, for a pattern
 * too large for the plan's room, the envelope walk's load lists. The
 * maths is dense.c's; README.md, "The factor's plan", says what the
 * layout buys. */
#include "solver_internal.h"

#include <math.h>
#include <string.h>

#define DBUF MR_DENSE_BUF
#define LD   MR_DENSE_LD

/* The plan's room, in ints, for n rows. Its size follows the products,
 * about n³/6 on a full pattern; a pattern that needs more than this fills
 * so much of its envelope that the envelope walk does as well. */
size_t mr_dense_plan_room(size_t n) {
  return 4 * n * n + 64;
}

/* f_k of each row of PAPᵀ, and iperm (old → new). */
static void find_firsts(mr_dense *dn, const mr_csr *A, int *iperm) {
  const int n = A->n, *perm = dn->perm;
  int *first = DBUF(dn, first, int);
  for (int k = 0; k < n; k++) iperm[perm[k]] = k;
  for (int k = 0; k < n; k++) {
    int f = k;
    for (int q = A->row_ptr[perm[k]]; q < A->row_ptr[perm[k] + 1]; q++)
      if (iperm[A->col[q]] < f) f = iperm[A->col[q]];
    first[k] = f;
  }
}

/* The two chains of a sum, ev[0..ne) and od[0..no), interleaved into
 * out, the shorter one padded with n (a product of two zeros: subtracting
 * +0 leaves any sum as it was). Returns the pairs written. */
static int interleave(const int *ev, int ne, const int *od, int no, int n, int *out) {
  const int pairs = ne > no ? ne : no;
  for (int i = 0; i < pairs; i++) {
    out[2 * i] = i < ne ? ev[i] : n;
    out[2 * i + 1] = i < no ? od[i] : n;
  }
  return pairs;
}

/* The m in [lo, hi) where both a[m] and b[m] are set, split into the two
 * chains a sum from lo makes (even offsets from lo in the first, odd ones
 * in the second) and interleaved into out, padded with n. Returns the
 * pairs written, and *count (when given) the m found. tmp: 2n ints. */
static int split(const unsigned char *a, const unsigned char *b, int lo, int hi, int n, int *out,
                 int *tmp, int *count) {
  int ne = 0, no = 0, *od = tmp + n;
  for (int m = lo; m < hi; m++) {
    if (!(a[m] & b[m])) continue;
    if ((m - lo) & 1)
      od[no++] = m;
    else
      tmp[ne++] = m;
  }
  if (count) *count = ne + no;
  return interleave(tmp, ne, od, no, n, out);
}

/* One entry (k, j) of the plan at out: the m < j where rows k and j of L
 * both have an entry, split as minus_dot() splits its sum from
 * lo = max(f_k, f_j). Returns the ints written, 0 when L_kj is no entry
 * (no such m and none in A: t_j is exactly 0). q: A_kj's index, or the +0
 * slot's (nnz) for a fill entry. tmp: 2n ints. */
static int plan_entry(const unsigned char *ink, const unsigned char *inj, int n, int j, int lo,
                      int q, int nnz, int *out, int *tmp) {
  int found;
  const int pairs = split(ink, inj, lo, j, n, out + 4, tmp, &found);
  if (found == 0 && q == nnz) return 0;
  out[0] = j;
  out[1] = j * (int)LD(n);
  out[2] = q;
  out[3] = 4 + 2 * pairs;
  return out[3];
}

/* The triangular sweeps' lists, after the factor's plan: for each row k,
 * the columns j of L's pattern (mark, n × n bytes) split as the envelope
 * walk splits its sums, by the parity of j − f_k, and interleaved in
 * pairs padded with n; the pair count before and after them, so that the
 * backward sweep finds each row's start from its end. A place of the
 * envelope outside the pattern holds +0, and the walk's sums, which start
 * at b's numbers or +0 and are never −0 but where b_k is (which s + odd
 * then makes +0), are the same bits without its product. Returns the
 * plan's ints, or −1 past its room. tmp: 2n ints. */
static int plan_sweeps(const mr_dense *dn, const unsigned char *mark, int *plan, int np, int room,
                       int *tmp) {
  const int n = dn->n, *first = DBUF(dn, first, const int);
  for (int k = 0; k < n; k++) {
    const unsigned char *ink = mark + (size_t)k * (size_t)n;
    if (np + (k - first[k]) + 3 > room) return -1; /* the most this row can take */
    const int pairs = split(ink, ink, first[k], k, n, plan + np + 1, tmp, NULL);
    plan[np] = pairs;
    np += 2 * pairs + 1;
    plan[np++] = pairs;
  }
  return np;
}

/* The factor's plan, made with the pattern: L's symbolic pattern in the
 * dense order (L_kj is an entry when A_kj is or when rows k and j share an
 * entry left of j), and for each entry the products its sum makes, in
 * minus_dot()'s order. Indices into A are into the factor's copy of it,
 * where index nnz holds +0: a number A does not store is read as one it
 * does, with no branch. Each row: its length in ints and A_kk's index;
 * each entry: j, row j's place in l, A_kj's index, its length in ints, the
 * pairs. Lengths, not counts: each loop's end is found with one add.
 * Returns 0, or −1 when the plan needs more than its room. iperm: from
 * find_firsts(). */
static int plan_pattern(mr_dense *dn, const mr_csr *A, const int *iperm) {
  const int n = A->n, *perm = dn->perm, *first = DBUF(dn, first, const int);
  const int room = (int)mr_dense_plan_room((size_t)n), nnz = A->row_ptr[n];
  int *plan = DBUF(dn, plan, int), *aq = DBUF(dn, aq, int), *tmp = aq + n;
  unsigned char *mark = DBUF(dn, mark, unsigned char);
  int np = 1;
  for (int k = 0; k < n; k++) {
    const int fk = first[k];
    unsigned char *ink = mark + (size_t)k * (size_t)n;
    for (int j = fk; j <= k; j++) aq[j] = nnz;
    for (int q = A->row_ptr[perm[k]]; q < A->row_ptr[perm[k] + 1]; q++)
      if (iperm[A->col[q]] <= k) aq[iperm[A->col[q]]] = q;
    if (np + 2 > room) return -1;
    const int head = np;
    plan[np++] = 2;
    plan[np++] = aq[k];
    for (int j = fk; j < k; j++) {
      const int lo = fk > first[j] ? fk : first[j];
      if (np + 5 + (j - lo) > room) return -1;
      const int w =
          plan_entry(ink, mark + (size_t)j * (size_t)n, n, j, lo, aq[j], nnz, plan + np, tmp);
      ink[j] = w > 0;
      plan[head] += w;
      np += w;
    }
  }
  plan[0] = np;
  np = plan_sweeps(dn, mark, plan, np, room, tmp);
  if (np < 0) return -1;
  dn->n_plan = np;
  return 0;
}

/* Column n of L, the padding products' 0 (the plan's factor writes every
 * place of L's pattern, and its sweeps read no other). */
static void clear_padding(mr_dense *dn) {
  const int n = dn->n;
  double *l = DBUF(dn, l, double);
  for (int k = 0; k < n; k++) l[(size_t)k * LD(n) + (size_t)n] = 0.0;
}

/* The envelope walk's share: where each entry of A's lower triangle and
 * diagonal lands in L (pairs: its index in A, its place in L); and the
 * places of each row's span that A leaves empty, which the factor fills
 * in. iperm: from find_firsts(). */
static void place_pattern(mr_dense *dn, const mr_csr *A, const int *iperm) {
  const int n = A->n, *perm = dn->perm, *first = DBUF(dn, first, const int);
  int *place = DBUF(dn, place, int), *zero = DBUF(dn, zero, int), np = 0, nz = 0;
  double *l = DBUF(dn, l, double);
  for (int k = 0; k < n; k++) {
    for (int q = A->row_ptr[perm[k]]; q < A->row_ptr[perm[k] + 1]; q++) {
      const int j = iperm[A->col[q]];
      if (j > k) continue;
      place[np++] = q;
      place[np++] = k * (n + 1) + j;
    }
  }
  /* A's places marked in L (NaN; every load writes L afresh), then the
   * unmarked places of the spans listed. */
  for (int k = 0; k < n; k++)
    for (int j = first[k]; j <= k; j++) l[k * (n + 1) + j] = 0.0;
  for (int p = 0; p < np; p += 2) l[place[p + 1]] = NAN;
  for (int k = 0; k < n; k++)
    for (int j = first[k]; j <= k; j++)
      if (!isnan(l[k * (n + 1) + j])) zero[nz++] = k * (n + 1) + j;
  dn->n_place = np / 2;
  dn->n_zero = nz;
}

/* PAPᵀ's lower triangle into L, zero elsewhere in each row's span. */
void mr_dense_load(mr_dense *dn, const mr_csr *A) {
  const int *place = DBUF(dn, place, int), *zero = DBUF(dn, zero, int);
  const double *val = A->val;
  double *l = DBUF(dn, l, double);
  for (int z = 0; z < dn->n_zero; z++) l[zero[z]] = 0.0;
  for (int p = 0; p < 2 * dn->n_place; p += 2) l[place[p + 1]] = val[place[p]];
}

/* The plan of the analysis in use, from its kept slot: 1, or 0 when the
 * slot has none. A pattern that comes back (the physics alternates among
 * a few: fig10 changed the analysis in use 1 145 times for 26 patterns)
 * then costs a copy, not a plan (about 17 k instructions on the stick
 * figure). */
static int take_plan(const mr_ldlt *f, mr_dense *dn) {
  if (f->in_use < 0) return 0;
  const mr_ldlt_kept *k = &f->kept[f->in_use];
  if (k->plan_ints == 0) return 0;
  memcpy(dn->first.p, k->dfirst.p, (size_t)dn->n * sizeof(int));
  memcpy(dn->plan.p, k->dplan.p, (size_t)k->plan_ints * sizeof(int));
  dn->n_plan = k->plan_ints;
  return 1;
}

/* The plan made for the analysis in use, kept in its slot when the slot's
 * room (reserved with the slot: MR_DENSE_KEPT_PLAN_ROOM) holds it. The
 * slot drops it when another analysis takes the slot (ldlt.c, keep). */
static void keep_plan(mr_ldlt *f, const mr_dense *dn) {
  if (f->in_use < 0) return;
  mr_ldlt_kept *k = &f->kept[f->in_use];
  if ((size_t)dn->n > k->dfirst.cap || (size_t)dn->n_plan > k->dplan.cap) return;
  memcpy(k->dfirst.p, dn->first.p, (size_t)dn->n * sizeof(int));
  memcpy(k->dplan.p, dn->plan.p, (size_t)dn->n_plan * sizeof(int));
  k->plan_ints = dn->n_plan;
}

/* The pattern's share of the work for the analysis in use: its kept plan,
 * or a plan made (then kept), or, when the plan outgrows its room, the
 * envelope walk's load lists. */
void mr_dense_pattern_work(mr_ldlt *f, mr_dense *dn, const mr_csr *A) {
  if (take_plan(f, dn)) {
    clear_padding(dn);
    return;
  }
  dn->plans++;
  find_firsts(dn, A, f->flag.p);
  if (plan_pattern(dn, A, f->flag.p) != 0) {
    dn->n_plan = -1;
    place_pattern(dn, A, f->flag.p);
    return;
  }
  clear_padding(dn);
  keep_plan(f, dn);
}

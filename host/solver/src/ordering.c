/* Reverse Cuthill–McKee: a breadth-first numbering of A's graph, started
 * from a low-degree node of each connected piece and visiting neighbours in
 * order of increasing degree, then reversed. It gathers each row's nonzeros
 * near the diagonal, and elimination in that order fills in only inside the
 * resulting envelope. Constraint graphs of puppets are chains and small
 * rigid clusters, for which this envelope is narrow. */
#include "solver_internal.h"

#include <string.h>

/* Each node's degree, counted once: the search and the insertion below ask
 * for a degree per neighbour visited, and counting it again each time made
 * the ordering cubic on a dense pattern (600 contact rows all touching the
 * same torsos: 4 G instructions in 70 orderings). */
static void degrees(const mr_csr *A, int *deg) {
  for (int i = 0; i < A->n; i++) {
    int d = 0;
    for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++) d += A->col[q] != i;
    deg[i] = d;
  }
}

/* The last node of a breadth-first search from start that has the smallest
 * degree in the last level: a node far from start, a better start than
 * start itself (George and Liu's pseudo-peripheral node, one pass). */
static int far_node(const mr_csr *A, const int *deg, int start, int *queue, int *seen, int stamp) {
  int head = 0, tail = 0;
  queue[tail++] = start;
  seen[start] = stamp;
  int level_start = 0;
  while (head < tail) {
    int level_end = tail;
    level_start = head;
    while (head < level_end) {
      int v = queue[head++];
      for (int q = A->row_ptr[v]; q < A->row_ptr[v + 1]; q++) {
        int u = A->col[q];
        if (seen[u] != stamp) {
          seen[u] = stamp;
          queue[tail++] = u;
        }
      }
    }
  }
  int best = queue[level_start];
  for (int t = level_start; t < tail; t++)
    if (deg[queue[t]] < deg[best]) best = queue[t];
  return best;
}

void mr_order_rcm(const mr_csr *A, int *perm, int *iw) {
  const int n = A->n;
  int *seen = iw;        /* n: stamps; -1 free, -2 numbered */
  int *queue = iw + n;   /* n */
  int *deg = iw + 2 * n; /* n */
  degrees(A, deg);
  for (int i = 0; i < n; i++) seen[i] = -1;
  int numbered = 0;
  for (int root = 0; root < n; root++) {
    if (seen[root] == -2) continue;
    int start = far_node(A, deg, root, queue, seen, root);
    /* far_node stamped the piece with root; number it from start. */
    int head = numbered, tail = numbered;
    perm[tail++] = start;
    seen[start] = -2;
    while (head < tail) {
      int v = perm[head++];
      int first = tail;
      for (int q = A->row_ptr[v]; q < A->row_ptr[v + 1]; q++) {
        int u = A->col[q];
        if (seen[u] != -2) {
          seen[u] = -2;
          /* Insert by degree; neighbour lists are short. */
          int du = deg[u], t = tail++;
          while (t > first && deg[perm[t - 1]] > du) {
            perm[t] = perm[t - 1];
            t--;
          }
          perm[t] = u;
        }
      }
    }
    numbered = tail;
  }
  for (int i = 0, j = n - 1; i < j; i++, j--) {
    int t = perm[i];
    perm[i] = perm[j];
    perm[j] = t;
  }
}

static int popcount64(uint64_t x) {
  x = x - ((x >> 1) & 0x5555555555555555u);
  x = (x & 0x3333333333333333u) + ((x >> 2) & 0x3333333333333333u);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fu;
  return (int)((x * 0x0101010101010101u) >> 56);
}

/* Index of the lowest set bit of a nonzero x. */
static int lowest_bit(uint64_t x) {
  return popcount64((x & (~x + 1)) - 1);
}

/* Minimum degree: eliminate, each time, the row with the fewest neighbours
 * in the graph that elimination has produced so far (eliminating v joins
 * all of v's neighbours to one another: exactly L's fill). The graph is
 * kept as one bitset row per node, so a join is a few word ORs; that costs
 * n²/8 bytes, which is why the caller uses it only up to
 * MR_MIN_DEGREE_MAX_N rows. Ties go to the lowest index, so the ordering
 * is deterministic. */
void mr_order_min_degree(const mr_csr *A, int *perm, uint64_t *bits, int *deg) {
  const int n = A->n;
  const size_t words = ((size_t)n + 63) / 64;
  memset(bits, 0, (size_t)n * words * sizeof *bits);
  for (int i = 0; i < n; i++) {
    uint64_t *row = bits + (size_t)i * words;
    deg[i] = 0;
    for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++) {
      int j = A->col[q];
      if (j != i && !(row[j / 64] >> (j % 64) & 1u)) {
        row[j / 64] |= (uint64_t)1 << (j % 64);
        deg[i]++;
      }
    }
  }
  for (int t = 0; t < n; t++) {
    int v = -1;
    for (int i = 0; i < n; i++)
      if (deg[i] >= 0 && (v < 0 || deg[i] < deg[v])) v = i;
    perm[t] = v;
    deg[v] = -1; /* eliminated */
    const uint64_t *rv = bits + (size_t)v * words;
    for (size_t w = 0; w < words; w++) {
      for (uint64_t m = rv[w]; m; m &= m - 1) {
        int u = (int)(w * 64) + lowest_bit(m);
        uint64_t *ru = bits + (size_t)u * words;
        int d = 0;
        for (size_t x = 0; x < words; x++) {
          ru[x] |= rv[x];
          d += popcount64(ru[x]);
        }
        ru[u / 64] &= ~((uint64_t)1 << (u % 64));
        ru[v / 64] &= ~((uint64_t)1 << (v % 64));
        deg[u] = d - 2; /* less u itself and v */
      }
    }
  }
}

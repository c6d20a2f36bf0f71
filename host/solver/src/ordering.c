/* Reverse Cuthill–McKee: a breadth-first numbering of A's graph, started
 * from a low-degree node of each connected piece and visiting neighbours in
 * order of increasing degree, then reversed. It gathers each row's nonzeros
 * near the diagonal, and elimination in that order fills in only inside the
 * resulting envelope. Constraint graphs of puppets are chains and small
 * rigid clusters, for which this envelope is narrow. */
#include "solver_internal.h"

static int degree(const mr_csr *A, int i)
{
    int d = 0;
    for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++)
        d += A->col[q] != i;
    return d;
}

/* The last node of a breadth-first search from start that has the smallest
 * degree in the last level: a node far from start, a better start than
 * start itself (George and Liu's pseudo-peripheral node, one pass). */
static int far_node(const mr_csr *A, int start, int *queue, int *seen, int stamp)
{
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
        if (degree(A, queue[t]) < degree(A, best))
            best = queue[t];
    return best;
}

void mr_order_rcm(const mr_csr *A, int *perm, int *iw)
{
    const int n = A->n;
    int *seen = iw;        /* n: stamps; -1 free, -2 numbered */
    int *queue = iw + n;   /* n */
    for (int i = 0; i < n; i++)
        seen[i] = -1;
    int numbered = 0;
    for (int root = 0; root < n; root++) {
        if (seen[root] == -2)
            continue;
        int start = far_node(A, root, queue, seen, root);
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
                    int du = degree(A, u), t = tail++;
                    while (t > first && degree(A, perm[t - 1]) > du) {
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

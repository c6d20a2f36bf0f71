/* A = J M⁻¹ Jᵀ, the matrix of §5.2 eq. 8 and §5.3 eq. 9.
 *
 * Entry (i, j) is Σ_p w_p (∂C_i/∂x_p · ∂C_j/∂x_p) over the particles p that
 * rows i and j share, with w_p = 1/m_p. Rows that share no movable particle
 * give a structural zero, so A is as sparse as the constraint graph: the
 * assembly walks particle → rows lists instead of forming 3n-wide products.
 * The diagonal is always stored (a zero row of J still gets A_ii = 0), so
 * every solver finds its pivot without a search and can flag such a row as
 * dependent. */
#include "mr_solver.h"

#include <stdlib.h>
#include <string.h>

static int csr_reserve(mr_csr *A, int n, int nnz)
{
    /* row_ptr always has room for cap + 1 entries and cap >= n (the diagonal
     * is stored), so one capacity governs all three arrays. */
    int need = nnz > n ? nnz : n;
    if (need <= A->cap && A->row_ptr)
        return 0;
    int cap = A->cap > 0 ? A->cap : 16;
    while (cap < need)
        cap *= 2;
    int *rp = realloc(A->row_ptr, (size_t)(cap + 1) * sizeof *rp);
    if (!rp)
        return MR_SOLVE_ENOMEM;
    A->row_ptr = rp;
    int *col = realloc(A->col, (size_t)cap * sizeof *col);
    if (!col)
        return MR_SOLVE_ENOMEM;
    A->col = col;
    double *val = realloc(A->val, (size_t)cap * sizeof *val);
    if (!val)
        return MR_SOLVE_ENOMEM;
    A->val = val;
    A->cap = cap;
    return 0;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int mr_assemble_jmjt(const mr_jac *J, const double *inv_mass, mr_csr *A)
{
    if (!J || !A)
        return MR_SOLVE_UNAVAILABLE;
    const int k = J->rows, np = J->n_particles;
    const int ne = k > 0 ? J->row_ptr[k] : 0;
    if (ne > 0 && !inv_mass)
        return MR_SOLVE_UNAVAILABLE;

    /* Scratch: particle → entry lists (the transpose of J's pattern), the
     * per-row column marker, and an unsorted copy of A that one transpose
     * turns into sorted rows (A is symmetric, so its transpose is itself). */
    size_t ints = (size_t)(np + 1) + (size_t)ne * 2 + (size_t)k * 3 + 1;
    int *iw = malloc(ints * sizeof *iw);
    if (!iw)
        return MR_SOLVE_ENOMEM;
    int *pstart = iw;              /* np + 1 */
    int *prow = pstart + np + 1;   /* ne: row of each listed entry */
    int *pent = prow + ne;         /* ne: the entry itself */
    int *mark = pent + ne;         /* k */
    int *slot = mark + k;          /* k */
    int *cnt = slot + k;           /* k + 1 */

    memset(pstart, 0, (size_t)(np + 1) * sizeof *pstart);
    for (int e = 0; e < ne; e++)
        if (inv_mass[J->particle[e]] != 0.0) /* a pinned particle adds nothing */
            pstart[J->particle[e] + 1]++;
    for (int p = 0; p < np; p++)
        pstart[p + 1] += pstart[p];
    for (int i = 0; i < k; i++) {
        for (int e = J->row_ptr[i]; e < J->row_ptr[i + 1]; e++) {
            int p = J->particle[e];
            if (inv_mass[p] == 0.0)
                continue;
            int at = pstart[p]++;
            prow[at] = i;
            pent[at] = e;
        }
    }
    for (int p = np; p > 0; p--)
        pstart[p] = pstart[p - 1];
    pstart[0] = 0;

    /* Symbolic pass: count each row's columns. */
    for (int i = 0; i < k; i++)
        mark[i] = -1;
    int nnz = 0;
    for (int i = 0; i < k; i++) {
        mark[i] = i;
        int c = 1;
        for (int e = J->row_ptr[i]; e < J->row_ptr[i + 1]; e++) {
            int p = J->particle[e];
            if (inv_mass[p] == 0.0)
                continue;
            for (int q = pstart[p]; q < pstart[p + 1]; q++) {
                int j = prow[q];
                if (mark[j] != i) {
                    mark[j] = i;
                    c++;
                }
            }
        }
        cnt[i] = c;
        nnz += c;
    }

    int *ucol = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *ucol);
    double *uval = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *uval);
    int *urp = malloc((size_t)(k + 1) * sizeof *urp);
    if (!ucol || !uval || !urp || csr_reserve(A, k, nnz) != 0) {
        free(ucol);
        free(uval);
        free(urp);
        free(iw);
        return MR_SOLVE_ENOMEM;
    }

    /* Numeric pass into the unsorted copy. */
    urp[0] = 0;
    for (int i = 0; i < k; i++)
        mark[i] = -1;
    for (int i = 0; i < k; i++) {
        int at = urp[i];
        mark[i] = i;
        slot[i] = at;
        ucol[at] = i;
        uval[at] = 0.0;
        at++;
        for (int e = J->row_ptr[i]; e < J->row_ptr[i + 1]; e++) {
            int p = J->particle[e];
            double w = inv_mass[p];
            if (w == 0.0)
                continue;
            for (int q = pstart[p]; q < pstart[p + 1]; q++) {
                int j = prow[q];
                if (mark[j] != i) {
                    mark[j] = i;
                    slot[j] = at;
                    ucol[at] = j;
                    uval[at] = 0.0;
                    at++;
                }
                uval[slot[j]] += w * dot3(J->d[e], J->d[pent[q]]);
            }
        }
        urp[i + 1] = at;
    }

    /* Transpose into A: rows come out with ascending columns. */
    A->n = k;
    A->nnz = nnz;
    memset(cnt, 0, (size_t)(k + 1) * sizeof *cnt);
    for (int q = 0; q < nnz; q++)
        cnt[ucol[q] + 1]++;
    for (int i = 0; i < k; i++)
        cnt[i + 1] += cnt[i];
    memcpy(A->row_ptr, cnt, (size_t)(k + 1) * sizeof *cnt);
    for (int i = 0; i < k; i++) {
        for (int q = urp[i]; q < urp[i + 1]; q++) {
            int at = cnt[ucol[q]]++;
            A->col[at] = i;
            A->val[at] = uval[q];
        }
    }

    /* Rounding may leave A_ij and A_ji a few ulps apart (the two sums run
     * over the shared particles in different orders). Copy the upper
     * triangle onto the lower so every solver sees the same symmetric
     * matrix, bit for bit. Rows are visited in ascending order, so row j's
     * lower entries are met in ascending column order: one cursor each. */
    for (int j = 0; j < k; j++)
        cnt[j] = A->row_ptr[j];
    for (int i = 0; i < k; i++) {
        for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++) {
            int j = A->col[q];
            if (j > i)
                A->val[cnt[j]++] = A->val[q];
        }
    }

    free(ucol);
    free(uval);
    free(urp);
    free(iw);
    return 0;
}

void mr_csr_free(mr_csr *A)
{
    if (!A)
        return;
    free(A->row_ptr);
    free(A->col);
    free(A->val);
    memset(A, 0, sizeof *A);
}

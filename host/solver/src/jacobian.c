/* The constraint Jacobian J = ∂C/∂q (§5.2), stored by rows in 3-wide
 * blocks: a distance or pin constraint touches one or two particles, so a
 * row holds a handful of (particle, ∂C_i/∂x_particle) pairs instead of 3n
 * numbers. */
#include "mr_solver.h"

#include <stdlib.h>
#include <string.h>

static int grow_rows(mr_jac *J, int need)
{
    if (need <= J->cap_rows)
        return 0;
    int cap = J->cap_rows ? J->cap_rows : 16;
    while (cap < need)
        cap *= 2;
    int *p = realloc(J->row_ptr, (size_t)(cap + 1) * sizeof *p);
    if (!p)
        return MR_SOLVE_ENOMEM;
    J->row_ptr = p;
    J->cap_rows = cap;
    return 0;
}

static int grow_entries(mr_jac *J, int need)
{
    if (need <= J->cap_entries)
        return 0;
    int cap = J->cap_entries ? J->cap_entries : 32;
    while (cap < need)
        cap *= 2;
    int *p = realloc(J->particle, (size_t)cap * sizeof *p);
    if (!p)
        return MR_SOLVE_ENOMEM;
    J->particle = p;
    double(*d)[3] = realloc(J->d, (size_t)cap * sizeof *d);
    if (!d)
        return MR_SOLVE_ENOMEM;
    J->d = d;
    J->cap_entries = cap;
    return 0;
}

int mr_jac_reset(mr_jac *J, int n_particles)
{
    if (!J || n_particles < 0)
        return MR_SOLVE_ENOMEM;
    J->rows = 0;
    J->n_particles = n_particles;
    if (grow_rows(J, 1) != 0)
        return MR_SOLVE_ENOMEM;
    J->row_ptr[0] = 0;
    return 0;
}

int mr_jac_begin_row(mr_jac *J)
{
    if (!J || !J->row_ptr)
        return -1;
    if (grow_rows(J, J->rows + 1) != 0)
        return -1;
    int end = J->row_ptr[J->rows];
    J->rows++;
    J->row_ptr[J->rows] = end;
    return J->rows - 1;
}

int mr_jac_add(mr_jac *J, int particle, const double d[3])
{
    if (!J || J->rows == 0 || particle < 0 || particle >= J->n_particles)
        return -1;
    int start = J->row_ptr[J->rows - 1];
    int end = J->row_ptr[J->rows];
    /* A constraint may name a particle twice (e.g. a term built from two
     * pieces); J must hold the sum, once, or JM⁻¹Jᵀ would miss the cross
     * terms' structure. Rows are short, so a linear scan is cheapest. */
    for (int e = start; e < end; e++) {
        if (J->particle[e] == particle) {
            J->d[e][0] += d[0];
            J->d[e][1] += d[1];
            J->d[e][2] += d[2];
            return 0;
        }
    }
    if (grow_entries(J, end + 1) != 0)
        return MR_SOLVE_ENOMEM;
    J->particle[end] = particle;
    memcpy(J->d[end], d, sizeof J->d[end]);
    J->row_ptr[J->rows] = end + 1;
    return 0;
}

void mr_jac_free(mr_jac *J)
{
    if (!J)
        return;
    free(J->row_ptr);
    free(J->particle);
    free(J->d);
    memset(J, 0, sizeof *J);
}

void mr_jac_mul(const mr_jac *J, const double *v3n, double *out_k)
{
    for (int i = 0; i < J->rows; i++) {
        double s = 0.0;
        for (int e = J->row_ptr[i]; e < J->row_ptr[i + 1]; e++) {
            const double *v = v3n + 3 * J->particle[e];
            s += J->d[e][0] * v[0] + J->d[e][1] * v[1] + J->d[e][2] * v[2];
        }
        out_k[i] = s;
    }
}

void mr_jac_tmul(const mr_jac *J, const double *lam_k, double *out_3n)
{
    memset(out_3n, 0, (size_t)J->n_particles * 3 * sizeof *out_3n);
    for (int i = 0; i < J->rows; i++) {
        for (int e = J->row_ptr[i]; e < J->row_ptr[i + 1]; e++) {
            double *o = out_3n + 3 * J->particle[e];
            o[0] += J->d[e][0] * lam_k[i];
            o[1] += J->d[e][1] * lam_k[i];
            o[2] += J->d[e][2] * lam_k[i];
        }
    }
}

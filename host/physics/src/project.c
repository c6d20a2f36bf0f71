/* Projection onto the constraints: the inverse-dynamics iteration of §6.2
 * ([19]: move the particles until the lengths hold again) applied to every
 * geometric constraint at once. The step falls back on it when a step at
 * the lower bound still deviates past the ATS threshold (§4.5, §7), and the
 * string-length correction (§6.2) uses it to keep the limbs whole.
 *
 * One round is a Newton step for C(x) = 0 of least mass-weighted size:
 *   Δx = M⁻¹ Jᵀ μ,   (J M⁻¹ Jᵀ) μ = −C,
 * the same matrix as eq. 8, so the same solver and its cached pattern. A
 * displacement of that form moves no centre of mass of a free body and
 * moves a heavy particle less than a light one. The velocities then lose
 * their component along the constraint normals the same way:
 *   Δv = M⁻¹ Jᵀ ν,   (J M⁻¹ Jᵀ) ν = −Ċ. */
#include "internal.h"

#include <math.h>
#include <string.h>

int mr_project_rows(mr_world *w, double t, const double *x, const double *v, int extra) {
  int nc = mr_constraint_row_count(w);
  if (nc + extra == 0) return 0;
  if (mr_rows_reserve(w, nc + extra) != 0 || mr_jac_reset(&w->J, w->n) != 0) return -1;
  if (nc == 0) return 0;
  int r = mr_constraints_rows(w, t, x, v, w->row_c, w->row_cdot, w->row_bias);
  for (int i = 0; i < r; i++) w->row_contact[i] = -1;
  return r;
}

static int constraint_rows(mr_world *w, double t, const double *x, const double *v) {
  return mr_project_rows(w, t, x, v, 0);
}

void mr_project_apply(mr_world *w, double *q) {
  double *d = w->scratch.acc_try;
  mr_jac_tmul(&w->J, w->lambda, d);
  for (int i = 0; i < 3 * w->n; i++) q[i] += d[i] * w->inv_mass[i / 3];
}

int mr_project_positions(mr_world *w, double t, double *x, const double *v, double tol,
                         int max_iter) {
  const size_t bytes = (size_t)(3 * w->n) * sizeof(double);
  double *last = w->scratch.xs; /* x before the round under way */
  double before = mr_constraints_deviation(w, t, x), e = before;
  if (!(before > tol)) return 0;
  int round = 0;
  while (e > tol && round < max_iter) {
    int rows = constraint_rows(w, t, x, v);
    if (rows <= 0) break;
    for (int i = 0; i < rows; i++) w->rhs[i] = -w->row_c[i];
    if (mr_solve_rows(w, 1) != 0) return -1;
    memcpy(last, x, bytes);
    mr_project_apply(w, x);
    double next = mr_constraints_deviation(w, t, x);
    if (!(next < e)) { /* no progress: undo the round that did harm */
      memcpy(x, last, bytes);
      break;
    }
    e = next;
    round++;
  }
  return e < before ? round : -1;
}

int mr_project_velocities(mr_world *w, double t, const double *x, double *v) {
  int rows = constraint_rows(w, t, x, v);
  if (rows <= 0) return rows;
  for (int i = 0; i < rows; i++) w->rhs[i] = -w->row_cdot[i];
  if (mr_solve_rows(w, 1) != 0) return -1;
  mr_project_apply(w, v);
  return 0;
}

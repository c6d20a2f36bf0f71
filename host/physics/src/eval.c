/* One evaluation of the equations of motion (§4.1 Fig. 4, §4.2, §5.2),
 * called once per integrator stage. Its stages, in order:
 *   1. place the control frames at time t;
 *   2. applied forces F_a (the world's force passes), q̈ = M⁻¹ F_a;
 *   3. constraint rows: C, J, Ċ and J̇q̇ of the constraints and of the
 *      touching contacts;
 *   4. the solve of eq. 8 for λ (contacts that would pull are released and
 *      the system solved again; friction at resting contacts), and
 *      q̈ += M⁻¹ Jᵀ λ. */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int mr_rows_reserve(mr_world *w, int rows) {
  if (rows <= w->cap_rows) return 0;
  double **arr[] = { &w->rhs, &w->lambda, &w->row_c, &w->row_cdot, &w->row_bias, &w->row_jv };
  for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) {
    int cap = w->cap_rows;
    if (mr_grow((void **)arr[i], &cap, rows, sizeof(double)) != 0) return -1;
  }
  double **blocks[] = { &w->island_b, &w->island_x };
  for (size_t i = 0; i < sizeof blocks / sizeof blocks[0]; i++) {
    int cap = w->cap_rows;
    if (mr_grow((void **)blocks[i], &cap, rows, sizeof(double)) != 0) return -1;
  }
  int **ints[] = { &w->row_contact, &w->row_reached, &w->island_key, &w->island_rows,
                   &w->island_contact };
  int cap = w->cap_rows;
  for (size_t i = 0; i < sizeof ints / sizeof ints[0]; i++) {
    cap = w->cap_rows;
    if (mr_grow((void **)ints[i], &cap, rows, sizeof(int)) != 0) return -1;
  }
  w->cap_rows = cap;
  return 0;
}

/* Contact rows are often redundant with each other and with the rigid
 * groups (a tetrahedron resting on three points of a floor, a puppet lying
 * down). A dependent row's multiplier is set to zero, which for a contact
 * means that point is left to sink and then bounces: the chatter of a body
 * that never comes to rest. A compliance of 1e-6 of its own diagonal on each
 * contact row (a soft contact: 1e-6 g of sag under its own weight) keeps
 * them independent, so redundant contacts share the load. Constraint rows
 * are exact, except those the solver finds nearly dependent on the others,
 * which it regularises (mr_solve_def.reg_tol, set in world.c). */
void mr_soften_contacts(mr_csr *A, int first, const int *row_contact) {
  for (int r = first; r < A->n; r++) {
    if (row_contact[r] < 0) continue;
    for (int e = A->row_ptr[r]; e < A->row_ptr[r + 1]; e++)
      if (A->col[e] == r) A->val[e] *= 1.0 + 1e-6;
  }
}

/* The whole system at once: assembled unless the caller kept A (friction's
 * rounds solve one A again with a new b). */
static mr_solve_status solve_whole(mr_world *w, int assemble, mr_solve_result *r) {
  if (assemble) {
    mr_solve_status a = mr_csr_assemble(&w->A, &w->J, w->inv_mass);
    if (a != MR_SOLVE_OK) return a;
    if (w->contacts.n > 0 || w->held.n > 0) /* contacts come after the constraints */
      mr_soften_contacts(&w->A, mr_constraint_row_count(w), w->row_contact);
  }
  return mr_solver_solve(w->solver, &w->opts, &w->A, w->rhs, w->lambda, r);
}

/* What a solve of `rows` rows (λ of them in `lambda`) came to, for the
 * world's counters: 0, or −1 with w->fail set. NaN or Inf in the system (a
 * callback curve, an exploded state) reaches the state, where the step sees
 * it and resets the world (§7). */
static int solved(mr_world *w, mr_solve_status st, const mr_solve_result *r, const int *rows,
                  int k) {
  w->stats.solver_iterations += (uint64_t)(r->iterations > 0 ? r->iterations : 0);
  if (st == MR_SOLVE_ERR_NONFINITE) {
    for (int i = 0; i < k; i++) w->lambda[rows ? rows[i] : i] = NAN;
    w->stats.solver_failures++;
    return 0;
  }
  if (st < 0) {
    w->stats.solver_failures++;
    w->fail =
        mr_fail(w, MR_ERR_SOLVER, "solver %s: %s (%d rows)", mr_solve_method_name(w->opts.method),
                st == MR_SOLVE_ERR_NOMEM         ? "out of memory"
                : st == MR_SOLVE_ERR_UNAVAILABLE ? "not built into this library"
                                                 : mr_solve_status_name(st),
                k);
    return -1;
  }
  if (st == MR_SOLVE_NOT_CONVERGED) w->stats.solver_failures++;
  if (r->dependent > w->last_dependent) w->last_dependent = r->dependent;
  w->stats.dependent_rows = r->dependent;
  return 0;
}

int mr_solve_rows(mr_world *w, int assemble) {
  int k = w->J.rows;
  memset(w->lambda, 0, (size_t)k * sizeof *w->lambda);
  mr_solve_result r;
  memset(&r, 0, sizeof r);
  w->pass_calls[MR_PASS_SOLVE]++;
  w->stats.solves++;
  w->system++;
  /* Blocks are assembled on their own each time: A holds the last one.
   * Their grouping reads J alone, which a solve of the kept A has not
   * changed: it is kept too. */
  if (assemble || w->island_groups < 1)
    w->island_groups = w->n_islands > 1 ? mr_islands_group(w) : 1;
  const int groups = w->island_groups;
  int st = groups > 1 ? mr_islands_solve(w, groups, &r) : solve_whole(w, assemble, &r);
  w->stats.blocks = groups;
  return solved(w, st, &r, NULL, k);
}

int mr_solve_block(mr_world *w, int g) {
  const int *rows = w->island_rows + w->island_start[g];
  const int k = w->island_start[g + 1] - w->island_start[g];
  for (int i = 0; i < k; i++) w->lambda[rows[i]] = 0.0;
  mr_solve_result r;
  memset(&r, 0, sizeof r);
  w->pass_calls[MR_PASS_SOLVE]++;
  w->stats.solves++;
  w->system++;
  return solved(w, mr_islands_solve_one(w, g, &r), &r, rows, k);
}

/* a = M⁻¹ f for every particle (0 on frame particles). The loops of this
 * file read the world through locals: a store into a double array might
 * otherwise be a store into the world, read again for every element. */
static void accelerations(const mr_world *w, const double *f, double *a) {
  const int n = w->n;
  const double *inv_mass = w->inv_mass;
  for (int i = 0; i < n; i++) {
    const double im = inv_mass[i]; /* written out: -O2 leaves a 3-loop rolled */
    a[3 * i] = f[3 * i] * im;
    a[3 * i + 1] = f[3 * i + 1] * im;
    a[3 * i + 2] = f[3 * i + 2] * im;
  }
}

/* Rows of the constraints and of the active contacts (w->contact_active)
 * into w->J, with C, Ċ and the bias J̇q̇ + ∂²C/∂t² per row, and for each
 * row the contact it stands for (-1 for a constraint). Given a_free, the
 * distance rows' right-hand sides of eq. 8 too (the first
 * w->distances.n). Returns the number of rows, or -1 when out of memory. */
static int rows_build(mr_world *w, double t, const double *x, const double *v,
                      const double *a_free) {
  int nc = mr_constraint_row_count(w);
  w->system++;
  if (mr_rows_reserve(w, nc + w->contacts.n) != 0 || mr_jac_reset(&w->J, w->n) != 0) return -1;
  int r = 0;
  if (nc > 0) {
    r = a_free ? mr_constraints_rows_eq8(w, t, x, v, a_free)
               : mr_constraints_rows(w, t, x, v, w->row_c, w->row_cdot, w->row_bias);
    if (r < 0) return -1;
  }
  for (int i = 0; i < r; i++) w->row_contact[i] = -1;
  for (int c = 0; c < w->contacts.n; c++) {
    if (!w->contact_active[c]) continue;
    const mr_contact *ct = &w->contacts.c[c];
    double chi, chidot, jdqd;
    /* With a_free this is eq. 8's solve, after select_resting_contacts()
     * at this x, v and time: a string's motion is the one it found. */
    int st = a_free && ct->kind == MR_CONTACT_STRING
                 ? mr_taut_row_seen(w, ct->a, v, &chi, &chidot, &jdqd)
                 : mr_contact_row(w, ct, x, v, &chi, &chidot, &jdqd);
    if (st != 0) return -1;
    w->row_c[r] = chi;
    w->row_cdot[r] = chidot;
    w->row_bias[r] = jdqd;
    w->row_contact[r] = c;
    r++;
  }
  return r;
}

/* The force solve (eq. 8) and the impulse solve (eq. 9, which does not
 * read the bias) share the rows. */
int mr_rows_build(mr_world *w, double t, const double *x, const double *v) {
  return rows_build(w, t, x, v, NULL);
}

/* §5.2, eq. 8: row i's b = −J̇q̇ − J M⁻¹ F_a − K_s C − K_d Ċ − ∂²C/∂t²,
 * J M⁻¹ F_a summed as mr_jac_mul sums it: the same bits. */
static inline double rhs_row(const mr_world *w, int i, const double *a_free) {
  const double jv = mr_jac_row_mul(&w->J, i, a_free);
  return -w->row_bias[i] - jv - w->def.ks * w->row_c[i] - w->def.kd * w->row_cdot[i];
}

/* eq. 8's b for the rows from `from` on (those before have theirs). */
static void rhs_eq8(mr_world *w, int from, int rows, const double *a_free) {
  double *rhs = w->rhs;
  for (int i = from; i < rows; i++) rhs[i] = rhs_row(w, i, a_free);
}

/* Every builder of rows puts the constraints' first, then the others:
 * the first row that may be a contact's (rows when there are none). */
static int first_contact_row(const mr_world *w, int rows) {
  return w->contacts.n > 0 ? mr_constraint_row_count(w) : rows;
}

void mr_rhs_rows(mr_world *w, const int *list, int count, const double *a) {
  double *rhs = w->rhs;
  for (int k = 0; k < count; k++) rhs[list[k]] = rhs_row(w, list[k], a);
}

/* Stage 2: F = F_a from the world's force passes, a = M⁻¹ F. */
static void applied_forces(mr_world *w, double t, const double *x, const double *v, double *a) {
  double *f = w->scratch.force;
  mr_forces_apply(w, t, x, v, f);
  accelerations(w, f, a);
}

/* §5.4: a touching contact takes part unless it is apart and clearly
 * separating (χ ≥ 0, χ̇ > rest_speed/10): holding that one back would do
 * work on it (a ball would bounce higher than it fell). The margin keeps a
 * body at rest, whose contact points move by rounding, from switching its
 * contacts off and on between the stages of one step, which made a lying
 * puppet jitter at 0.1 m/s. */
static void select_resting_contacts(mr_world *w, const double *x, const double *v) {
  const double separating = 0.1 * w->def.rest_speed;
  for (int c = 0; c < w->contacts.n; c++) {
    const mr_contact *ct = &w->contacts.c[c];
    if (ct->kind == MR_CONTACT_STRING)
      w->contact_active[c] = !mr_taut_separating(w, ct->a, x, v, separating);
    else
      w->contact_active[c] =
          !(mr_contact_gap(w, ct, x) >= 0.0 && mr_contact_rate(w, ct, x, v) > separating);
  }
}

/* Releases the contacts whose multiplier came out negative: whether any
 * was. */
static int release_pulling(mr_world *w, int rows) {
  int released = 0;
  for (int r = first_contact_row(w, rows); r < rows; r++) {
    int c = w->row_contact[r];
    if (c >= 0 && w->lambda[r] < 0) {
      w->contact_active[c] = 0;
      released = 1;
    }
  }
  return released;
}

/* Stages 3 and 4: rows and the solve of eq. 8. Resting contacts push and
 * never pull (§5.4, eq. 13b): a contact whose multiplier comes out negative
 * is released and the system solved again. The rounds from `round` on.
 * Returns the number of rows (0: nothing to solve), or −1. */
static int solve_eq8(mr_world *w, double t, const double *x, const double *v, const double *a,
                     int round) {
  int rows = 0;
  for (; round <= w->contacts.n; round++) {
    rows = rows_build(w, t, x, v, a);
    if (rows <= 0) return rows;
    rhs_eq8(w, w->distances.n, rows, a);
    if (mr_solve_rows(w, 1) != 0) return -1;
    if (!release_pulling(w, rows)) break;
  }
  return rows;
}

/* §5.2, eq. 5: F_c = Jᵀ λ, and a += M⁻¹ F_c. */
static void add_constraint_forces(mr_world *w, int rows, double *a) {
  const double *fc = w->scratch.constraint_force, *lambda = w->lambda, *inv_mass = w->inv_mass;
  const int n = w->n;
  mr_jac_tmul(&w->J, lambda, w->scratch.constraint_force);
  double big = 0;
  for (int r = 0; r < rows; r++) {
    double l = fabs(lambda[r]);
    if (l > big || l != l) big = l;
  }
  w->stats.max_multiplier = big;
  for (int i = 0; i < n; i++) {
    const double im = inv_mass[i];
    a[3 * i] += fc[3 * i] * im;
    a[3 * i + 1] += fc[3 * i + 1] * im;
    a[3 * i + 2] += fc[3 * i + 2] * im;
  }
}

/* After the solve's rounds: friction, then the constraint forces. The
 * system is kept for mr_eval_new_path unless friction changed b. */
static int finish(mr_world *w, double h, int rows, const double *x, const double *v, double *a) {
  /* Static friction aims at stopping within h/2: only then does the
   * answer depend on h (integrate.c's memo). */
  const int first = first_contact_row(w, rows);
  w->eval_used_h = mr_friction_present(w, rows, first);
  if (w->eval_used_h && mr_friction_solve(w, h, rows, first, x, v, a) != 0) return -1;
  if (!w->eval_used_h) w->kept_system = w->system;
  add_constraint_forces(w, rows, a);
  return 0;
}

int mr_eval(mr_world *w, double t, double h, double *x, double *v, double *a) {
  w->eval_used_h = 0;
  w->kept_system = 0;
  mr_frames_place(w, t, x, v); /* 1 */
  mr_taut_set_time(w, t);
  applied_forces(w, t, x, v, a); /* 2 */
  if (!w->has_solve) return 0;
  select_resting_contacts(w, x, v);
  int rows = solve_eq8(w, t, x, v, a, 0); /* 3, 4 */
  if (rows <= 0) return rows;
  return finish(w, h, rows, x, v, a);
}

/* Whether the kept rows stand for the constraints and then the contacts
 * now selected, in order: not when the last evaluation released one (its
 * rows are those of its last round), nor should the selection read the
 * new path's rates differently to the last bit. */
static int rows_selected(const mr_world *w, int rows) {
  int r = first_contact_row(w, rows);
  for (int c = 0; c < w->contacts.n; c++)
    if (w->contact_active[c] && (r >= rows || w->row_contact[r++] != c)) return 0;
  return r == rows;
}

/* A step's first stage where the last step's end was evaluated, and only
 * a frame's new path tells them apart (integrate.c's memo): the theater
 * plans a new segment at every step, and the path is C¹, so its
 * acceleration jumps there (Fig. 10: 4 553 of 44 770 evaluations). J,
 * A = J M⁻¹ Jᵀ and its factor read x alone, and b reads the frames'
 * acceleration only in the taut strings' rows (taut_string.c, row_of):
 * those rows are made again, the first round solved with the same A, and
 * the rest goes as mr_eval goes, every number the same bits. */
int mr_eval_new_path(mr_world *w, double t, double h, double *x, double *v, double *a) {
  if (!w->has_solve || w->kept_system == 0 || w->kept_system != w->system) return 0;
  w->eval_used_h = 0;
  w->kept_system = 0;
  mr_frames_place(w, t, x, v);
  mr_taut_set_time(w, t);
  applied_forces(w, t, x, v, a);
  select_resting_contacts(w, x, v);
  const int rows = w->J.rows;
  if (!rows_selected(w, rows)) return 0;
  for (int r = first_contact_row(w, rows); r < rows; r++) {
    const mr_contact *ct = &w->contacts.c[w->row_contact[r]];
    if (ct->kind == MR_CONTACT_STRING)
      mr_taut_row_again(w, ct->a, v, &w->row_c[r], &w->row_cdot[r], &w->row_bias[r]);
  }
  rhs_eq8(w, w->distances.n, rows, a);
  if (mr_solve_rows(w, 0) != 0) return -1;
  int done = rows;
  if (release_pulling(w, rows) && (done = solve_eq8(w, t, x, v, a, 1)) <= 0)
    return done < 0 ? -1 : 1;
  return finish(w, h, done, x, v, a) != 0 ? -1 : 1;
}

/* The world's private layout, shared by the files of mr_physics. Particle
 * state is kept as structure of arrays: x and v (3n, hot, touched by every
 * integrator stage) apart from mass, radius, puppet and frame data (cold). */
#ifndef MR_PHYSICS_INTERNAL_H
#define MR_PHYSICS_INTERNAL_H

#include "mr_physics.h"
#include "mr_solver.h"

#include <stdarg.h>

/* ------------------------------------------------------------- elements */

/* A frame's path (frame.c): a cubic Hermite curve from `from` at t0 to
 * `to` at t1, leaving at velocity v0 and angular velocity w0 and arriving at
 * v1 and at A(t1) w1 (w1 before the whole turn A(t1)); `turn` is the short
 * turn from `from` to `to` (axis × angle, world axes). */
typedef struct mr_frame {
  mr_pose home; /* the pose it was made at, which the start configuration
                   hangs from (restart.c) */
  mr_pose from, to;
  double t0, t1;
  double v0[3], v1[3], w0[3], w1[3], turn[3];
  int linear;  /* MR_FRAME_LINEAR: every tangent the chord rate */
  int turning; /* any of turn, w0, w1 not zero: the orientation moves */
} mr_frame;
/* Per frame in frame_state: p, q, ṗ, ω, p̈, ω̇. */
#define MR_FRAME_STATE 19

/* A taut string at one state: d = x_p − x_f, L = |d|, and its frame
 * end's velocity and acceleration on the frame's path. */
typedef struct mr_taut_motion {
  double d[3], len, vf[3], af[3];
} mr_taut_motion;

/* A string's element: forces.c pulls with it, string_correction.c shortens it. */
typedef struct mr_string {
  int frame_particle, puppet_particle;
  double rest, ks, kd;
  int taut; /* MR_STRING_TAUT: a contact row (taut_string.c), no force */
  /* What eval.c's choice of resting contacts found, which the rows of
   * the solve that follows, at the same state, read again. */
  mr_taut_motion seen;
} mr_string;

typedef struct mr_distance {
  int a, b;
  double length;
} mr_distance;
typedef struct mr_pin {
  int particle;
  double point[3];
} mr_pin;
typedef struct mr_curve {
  int particle;
  int key_count;
  double *times, *points;
  mr_curve_interp interp;
  mr_curve_fn fn;
  void *user;
} mr_curve;

typedef struct mr_plane {
  double n[3], offset, restitution, friction;
} mr_plane;

/* A leaf sphere of a part: centre (1−s)·x[p0] + s·x[p1]. */
typedef struct mr_leaf {
  int p0, p1;
  double s, r;
  int part, puppet;
} mr_leaf;
typedef struct mr_part {
  int first_leaf, leaf_count, puppet;
  double restitution, friction;
} mr_part;
/* A leaf pair overlapping as built: of one puppet (never tested), or of
 * two (left out until seen apart; out says whether it still is). */
typedef struct mr_built_overlap {
  int a, b;
  unsigned char same_puppet, out;
} mr_built_overlap;

typedef struct mr_tree_node {
  double c[3], r;
  int left, right, leaf;
} mr_tree_node;
typedef struct mr_tree {
  int puppet, first_node, node_count, root;
} mr_tree;

/* A string contact (taut_string.c): a, the string; b unused. */
typedef enum mr_contact_kind {
  MR_CONTACT_PLANE,
  MR_CONTACT_SPHERES,
  MR_CONTACT_STRING
} mr_contact_kind;
typedef struct mr_contact {
  mr_contact_kind kind;
  int a, b; /* plane: particle a, plane b; spheres: leaves a, b */
  double restitution, friction;
} mr_contact;

/* A force pass adds its forces into f (3n) for the state (x, v) at time t. */
typedef void (*mr_force_pass)(mr_world *w, double t, const double *x, const double *v, double *f);
typedef struct mr_contact_list {
  int n, cap;
  mr_contact *c;
} mr_contact_list;
/* One step's motion, for the swept tests: from (x0, v0) to (x1, v1) over h
 * (3n each). */
typedef struct mr_sweep {
  const double *x0, *v0, *x1, *v1;
  double h;
} mr_sweep;
/* A detector appends the contacts whose gap χ is at most `gap` in state x;
 * given a sweep (then x is its x1), those whose gap may be at most `gap`
 * anywhere along the step (mr_contact_swept_gap). */
typedef int (*mr_detect_pass)(mr_world *w, const double *x, const mr_sweep *sw, double gap,
                              mr_contact_list *out);

#define MR_MAX_PASSES 16

/* One growable list of elements. Every array of the world grows through
 * mr_grow, the one growth helper. */
typedef struct mr_list {
  void *data;
  int n, cap;
} mr_list;
#define MR_AT(list, type, i) (((type *)(list).data)[i])

/* The force kinds, numbered as their effect bits (they come first). */
enum {
#define MR_X_(id, stem, name) +1
  MR_FORCE_KIND_COUNT = 0 MR_FORCE_KINDS(MR_X_)
#undef MR_X_
};
#define MR_FORCES(w, id) (&(w)->forces[MR_EFFECT_BIT_##id])

/* integrate.c: an evaluation of the equations of motion kept with
 * everything it was computed from. Frame particles of x and v are as the
 * frames place them. */
typedef struct mr_eval_point {
  int valid, used_h, n_frames, n_contacts;
  int cap_n, cap_frames, cap_contacts;
  double t, h;     /* h only matters when used_h (friction's time scale) */
  uint64_t system; /* the world's system count just after it was made */
  double *x, *v, *a;
  mr_frame *frames;
  mr_contact *contacts;
} mr_eval_point;
/* Two kept evaluations, so that one at the same point is not computed
 * twice: the last (first same as last: a step's end evaluation is the
 * next step's first) and the last step's first stage (a retried or
 * located step starts where the rejected try did, and the tries between
 * evaluated elsewhere). valid = 0 drops both. */
typedef struct mr_eval_memo {
  int valid;
  mr_eval_point last, start;
  uint64_t recalled; /* evaluations not computed again */
} mr_eval_memo;

/* --------------------------------------------------------------- world */

struct mr_world {
  mr_world_def def;
  char err[256];
  double t;
  int started; /* a step has been taken: start config is fixed */
  int dirty;   /* elements added since the derived data was built */

  /* particles */
  int n, cap_n;
  double *x, *v; /* 3n, hot */
  double *mass, *inv_mass, *radius;
  double *x_start, *v_start; /* the start configuration (§7) */
  double *local;             /* 3n offsets in the particle's frame */
  int *puppet, *frame;

  mr_list frames;                      /* mr_frame */
  double *frame_state;                 /* per frame: MR_FRAME_STATE */
  double frame_state_t;                /* the time all of it is at, or NaN */
  double *kin_placed;                  /* per kin entry, its placement there (frame.c) */
  int cap_kin_placed;                  /* entries kin_placed holds */
  mr_list kin;                         /* int: particles carried by frames */
  mr_list forces[MR_FORCE_KIND_COUNT]; /* per force kind, its elements */
  mr_list distances;                   /* mr_distance */
  mr_list pins;                        /* mr_pin */
  mr_list curves;                      /* mr_curve */
  int n_groups;                        /* rigid groups added (ids) */
  mr_list planes;                      /* mr_plane */
  mr_list parts;                       /* mr_part */
  mr_list leaves;                      /* mr_leaf */

  /* derived at finalize */
  int npuppets, cap_puppets;
  /* The string correction's working set: per string, released from the
   * projection because holding it would push; per row, its string. */
  unsigned char *string_released;
  int *string_of_row;
  int cap_string_work;
  /* ... and the contacts it holds from going deeper, and what a
   * detection after it found; the first held_deep of them were deeper
   * than the slop and MR_SINK_MAX when it began, and are taken back to
   * that depth. */
  mr_contact_list held, held_found;
  int held_deep;
  int held_from; /* scratch.x_held holds this correction's start */
  /* The deepest any contact went along the last step taken (step.c),
   * m past touching. */
  double step_deepest;
  double *puppet_mass;
  int *carrier; /* per puppet: the frame a reset carries it by, or −1 (restart.c) */
  int cap_carrier;
  unsigned char *part_adjacent; /* nparts × nparts */
  /* Leaf pairs that overlap in the pose the trees were built in, sorted
   * by (a, b), a < b (sphere_tree.c says why they are left out). */
  mr_built_overlap *built_overlaps;
  int n_built_overlaps;
  int ntrees;
  mr_tree *trees;
  int nnodes;
  mr_tree_node *nodes;
  double *leaf_c;                  /* 3 per leaf, refitted per detection */
  int *tree_stack, cap_tree_stack; /* node pairs of a traversal */

  /* the passes this world runs, built at creation from its effects */
  int n_force_passes;
  mr_force_pass force_passes[MR_MAX_PASSES];
  mr_pass force_pass_ids[MR_MAX_PASSES];
  int n_detect_passes;
  mr_detect_pass detect_passes[4];
  mr_pass detect_pass_ids[4];
  int has_frames, has_solve, has_string_correction;
  int n_taut;    /* strings in MR_STRING_TAUT mode */
  double taut_t; /* the time their frame ends are evaluated at */
  uint64_t pass_calls[MR_PASS_COUNT];

  /* contacts: found before a step and held during it (resting set), and a
   * probe list for the end-of-step penetration test */
  mr_contact_list contacts, probe;
  mr_contact_list measured;          /* mr_world_penetration's own, kept between calls */
  int cap_contact;                   /* what the three per-contact arrays hold */
  unsigned char *contact_active;     /* in the system being solved (eq. 9 or 8) */
  double *contact_pre;               /* χ̇⁻ before an impulse */
  struct mr_fric_point *fric_points; /* friction.c: the contacts with friction */
  int cap_fric_points;
  double *fric_work; /* friction.c: b kept, probes, W, N, the projection's */
  int cap_fric_work;
  unsigned char *probe_valid; /* per probe contact: being located in time */

  /* solve workspace: rows of eq. 8 / eq. 9 */
  mr_jac J;
  mr_csr A;
  mr_solver *solver;
  mr_solve_def opts;
  int cap_rows;
  double *rhs, *lambda, *row_c, *row_cdot, *row_bias, *row_jv;
  int *row_contact; /* −1 constraint row, else contact index */
  int *row_reached; /* within friction: the rows naming a particle
                       friction reaches */
  int rows_pattern; /* constraint elements J's first rows are laid out for */

  /* islands.c: the blocks of J M⁻¹ Jᵀ, solved one by one */
  int n_islands, cap_islands;
  int island_groups;           /* what the last grouping of J's rows found (0: none yet) */
  int *island_of;              /* per particle: its constraint block, −1 kinematic */
  int *island_parent;          /* per block: union–find of the blocks a solve joins */
  int *island_local;           /* per particle: its number in the block being solved, −1 */
  double *island_mass;         /* per particle of that block: 1/m */
  int *island_start;           /* per group and one more: its first row in island_rows */
  int *island_key;             /* per row: its block */
  int *island_rows;            /* rows grouped by block */
  int *island_contact;         /* per row of the block being solved: its contact, −1 */
  double *island_b, *island_x; /* per row of that block: b and λ */
  mr_jac island_J;

  /* The end state of a step, traded with x and v when it is accepted. */
  double *x1, *v1;

  /* Per-step scratch, 3n each unless said (mr_world_ensure_ready sizes
   * them). Each buffer has one meaning throughout a step. */
  int cap_scratch;        /* particles the scratch holds */
  unsigned char *reached; /* per particle, within friction: friction
                             reaches it (a carrier of a resting contact) */
  struct {
    double *x0, *v0;          /* the state at the start of the step */
    double *xs, *vs;          /* integrator stage state; between a
                                 location's trials, its model's state */
    double *k;                /* stage derivatives, 8 × 3n (RK4) */
    double *force;            /* F of the evaluation under way */
    double *constraint_force; /* Jᵀ λ of the evaluation under way */
    double *acc_try;          /* a + M⁻¹ Jᵀ λ before friction */
    double *impact_momentum;  /* L_a, friction at an impact (eq. 9) */
    double *impact_dv;        /* M⁻¹ L_a */
    double *v_try;            /* q̇⁺ of a trial impulse */
    double *x_held;           /* positions the string correction started
                                 from: how deep its held contacts may go */
  } scratch;

  /* ATS */
  double dt_next;
  double stable_dt;     /* mr_forces_stable_dt, at ensure_ready */
  double drag_rate_cap; /* drag/m never exceeds this (1/s) */
  int recovering;       /* after a collision Δt doubles (§4.5) */

  mr_eval_memo memo;
  int eval_used_h; /* the last evaluation depended on h (friction ran) */
  /* system counts the builds of J and the solves; kept_system is its
   * value when an evaluation left J, b, A and A's factor as its last
   * round made them (no friction after it), else 0 (eval.c,
   * mr_eval_new_path). */
  uint64_t system, kept_system;

  mr_stats stats;
  int last_dependent;
  mr_status fail; /* why an inner stage returned −1 (0: memory) */
};

/* world.c */
/* The one growth helper: *data holds at least `need` elements of `elem`
 * bytes afterwards (capacity doubling from 16, in *cap); new bytes are
 * zeroed so none uninitialised can reach the state hash. 0, or -1 when out
 * of memory (then *data and *cap are unchanged). */
int mr_grow(void **data, int *cap, int need, size_t elem);
/* The start of every add call: world and definition not NULL, the
 * definition made by its default maker, the effect declared. MR_OK or the
 * failure (the world's message set). */
mr_status mr_add_check(mr_world *w, const void *def, uint32_t cookie, uint32_t effect,
                       const char *what);
#define MR_ADD_CHECK(w, def, effect, what) \
  mr_add_check((w), (def), (def) ? (def)->cookie : 0u, (effect), (what))
/* The end of every add call: appends the element to its list, returns its
 * id in *out_id (may be NULL) and marks the derived data stale. */
mr_status mr_add_push(mr_world *w, mr_list *list, const void *elem, size_t size, int *out_id,
                      const char *what);
mr_status mr_fail(mr_world *w, mr_status s, const char *fmt, ...);
int mr_world_ensure_ready(mr_world *w);
/* a × b into out (which may be a or b). */
static inline void mr_cross3(const double a[3], const double b[3], double out[3]) {
  const double r[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                        a[0] * b[1] - a[1] * b[0] };
  out[0] = r[0];
  out[1] = r[1];
  out[2] = r[2];
}
/* restart.c: each puppet's carrier, when the world is made ready; the
 * start configuration placed for a reset (§7). */
int mr_restart_carriers(mr_world *w);
void mr_restart_place(mr_world *w);
/* ready.c: the per-contact arrays hold at least need contacts. */
int mr_world_contact_capacity(mr_world *w, int need);
int mr_check_particle(mr_world *w, int id, const char *what);
int mr_finite3(const double v[3]);
int mr_require(mr_world *w, uint32_t effect, const char *what);

/* frame.c */
void mr_frame_motion(const mr_frame *fr, double t, double *st);
void mr_frame_eval(const mr_frame *fr, double t, mr_pose *pose, double vel[3], double omega[3]);
/* The velocity and acceleration at t of frame particle i at x (3n). */
void mr_frame_point_motion(const mr_world *w, int i, double t, const double *x, double v[3],
                           double a[3]);
void mr_frame_point_velocity(const mr_world *w, int i, double t, const double *x, double v[3]);
void mr_frames_place(mr_world *w, double t, double *x, double *v);
/* Particle i of a frame alone, at the world's time. */
void mr_frame_place_one(mr_world *w, int i);

/* curve.c */
void mr_curve_eval(const mr_curve *c, double t, double pos[3], double vel[3], double acc[3]);

/* forces.c */
int mr_forces_build_passes(mr_world *w);
/* F_a at (t, x, v): every force pass of the world into f (3n), from 0. */
void mr_forces_apply(mr_world *w, double t, const double *x, const double *v, double *f);

/* constraints.c: rows of C, J, J̇q̇ for eq. 8 */
int mr_constraints_rows(mr_world *w, double t, const double *x, const double *v, double *c,
                        double *cdot, double *bias);
/* The same into w->row_c, row_cdot and row_bias, with eq. 8's right-hand
 * side (w->rhs) for the distance rows, which come first, for a_free =
 * M⁻¹ F_a (3n). */
int mr_constraints_rows_eq8(mr_world *w, double t, const double *x, const double *v,
                            const double *a_free);
int mr_constraint_row_count(const mr_world *w);
double mr_constraints_deviation(const mr_world *w, double t, const double *x);
int mr_distance_add_internal(mr_world *w, int a, int b, double length, int *out_id);

/* collide.c */
int mr_collide_build_passes(mr_world *w);
int mr_colliders(const mr_world *w);
/* How deep past touching a contact may go before a step is retried
 * (step.c) or the correction after it takes the contact back out
 * (string_correction.c), besides the slop: half a millimetre. */
#define MR_SINK_MAX 5e-4
int mr_contacts_detect(mr_world *w, const double *x, double gap, mr_contact_list *out);
/* The contacts whose swept gap may reach `gap` during the step sw. */
int mr_contacts_sweep(mr_world *w, const mr_sweep *sw, double gap, mr_contact_list *out);
double mr_contact_gap(const mr_world *w, const mr_contact *c, const double *x);
/* A lower bound on the contact's gap over the whole step sw, not only at
 * its ends (collide.c explains the bound); with bulge 0, the gap along the
 * straight path between the ends alone. */
double mr_contact_swept_gap(const mr_world *w, const mr_contact *c, const mr_sweep *sw, int bulge);
/* The same for two leaf spheres (sphere_tree.c's leaf test). */
double mr_sphere_pair_swept_gap(const mr_world *w, int leaf_a, int leaf_b, const mr_sweep *sw);
/* How far a leaf's centre may stray from the straight path between its
 * step ends, m (collide.c). */
double mr_leaf_bulge(const mr_world *w, const mr_leaf *l, const mr_sweep *sw);
double mr_contact_rate(const mr_world *w, const mr_contact *c, const double *x, const double *v);
/* Writes the contact's J row into w->J and sets χ, χ̇ and J̇q̇; 0 or −1
 * (out of memory). A NaN state gives NaN values, not a failure. */
int mr_rows_build(mr_world *w, double t, const double *x, const double *v);
int mr_contact_row(mr_world *w, const mr_contact *c, const double *x, const double *v, double *chi,
                   double *chidot, double *jdqd);
int mr_contact_push(mr_contact_list *l, mr_contact_kind kind, int a, int b, double e, double mu);
void mr_contact_list_free(mr_contact_list *l);
/* Friction at a contact (§4.4) acts on the relative motion of its two sides:
 * the particle against a plane, or sphere b against sphere a.
 * mr_contact_slip: the tangential part of the relative q (a velocity or an
 * acceleration, 3n) into out; returns 1/m_eff = Σ w² / m over the particles
 * carrying the contact (w: their leaf weights), 0 if nothing can move.
 * mr_contact_spread: adds s·f to side b's particles (s·w·f) and −s·w·f to
 * side a's, into out (3n).
 * mr_contact_carriers: the particles those two reach, into p; returns their
 * number (at most 4; 0 for a string, which has no friction). */
double mr_contact_slip(const mr_world *w, const mr_contact *c, const double *x, const double *q,
                       double out[3]);
void mr_contact_spread(const mr_world *w, const mr_contact *c, const double f[3], double s,
                       double *out);
int mr_contact_carriers(const mr_world *w, const mr_contact *c, int p[4]);
/* The unit normal of a contact's plane of friction, from side a towards
 * side b (0 for two coincident spheres). */
void mr_contact_normal(const mr_world *w, const mr_contact *c, const double *x, double n[3]);

/* friction.c: Coulomb friction at the resting contacts of eq. 8's solve,
 * whose rows from `first` on are the contacts'. mr_friction_present:
 * whether one of them has friction and pushes. mr_friction_solve: given a
 * = M⁻¹ F_a and λ solved, adds the friction to F (w->scratch.force) and
 * to a where it reaches, and solves again for λ; 0 or −1. */
#define MR_FRICTION_ROUNDS 64
/* One frictional contact of a solve: gathered, probed and sent round by
 * friction.c, its friction found by friction_rounds.c. */
struct mr_fric_point {
  int row, contact;
  int island;     /* its block of eq. 8 (islands.c), 0 when solved whole */
  double scale;   /* the largest |λ| of that block, before any probe */
  double t[2][3]; /* the tangent plane's basis */
  double vt[2];   /* sliding velocity, in that basis */
  double at[2];   /* slip acceleration under the friction so far */
  double at0[2];  /* and before any friction */
  double drive;   /* |at0| */
  double f[2];    /* the friction so far */
  double n, mu;   /* normal multiplier, friction coefficient */
  double n0;      /* the normal multiplier before any friction */
  double inv;     /* Σ w²/m of the carriers alone: the most W_ii can be */
};
/* friction_rounds.c, on m points with W (2m × 2m) and N (m × 2m) measured:
 * whether any asks for friction stopping it within tau beyond tol (×
 * what its carriers alone weigh), and their friction f found, tol the
 * rounds' and the cone's tolerance. scratch holds 8m² + 6m. */
int mr_friction_asks(const struct mr_fric_point *pt, int m, double tau, double tol);
void mr_friction_rounds(struct mr_fric_point *pt, int m, double tau, const double *W,
                        const double *N, double tol, double *scratch);
/* Room for a solve of `rows` rows with `points` frictional contacts. */
int mr_friction_reserve(mr_world *w, int rows, int points);
int mr_friction_present(const mr_world *w, int rows, int first);
int mr_friction_solve(mr_world *w, double h, int rows, int first, const double *x, const double *v,
                      double *a);
/* The cone |f_i| ≤ μ_i max(n_i, 0) held on m contacts' friction f (2m),
 * whose normals n (m) move by N (m × 2m, row-major) per unit of it: each
 * contact over is cut back along its own direction and n follows, until
 * none is over by more than tol or MR_FRICTION_ROUNDS sweeps are done.
 * Friction only shrinks. */
void mr_friction_hold_cone(int m, double *f, double *n, const double *mu, const double *N,
                           double tol);

/* sphere_tree.c */
int mr_trees_build(mr_world *w);
/* The pairs of two puppets that overlapped as built and are apart in x
 * are tested from now on (called on each accepted state). */
void mr_trees_note_apart(mr_world *w, const double *x);
/* After a reset to the start: the pairs overlapping in the state it
 * restarts from are left out as those overlapping as built were. */
void mr_trees_restore_overlaps(mr_world *w);
/* A leaf's centre in x, (1 − s) x_p0 + s x_p1: inline, as the swept
 * tests call it four times a pair (a contact being located in time in a
 * pile of puppets tests each pair again for each trial time). */
static inline void mr_leaf_center(const mr_world *w, const mr_leaf *l, const double *x,
                                  double c[3]) {
  (void)w;
  const double *a = x + 3 * l->p0, *b = x + 3 * l->p1, s = l->s;
  for (int k = 0; k < 3; k++) c[k] = (1.0 - s) * a[k] + s * b[k];
}
int mr_detect_self(mr_world *w, const double *x, const mr_sweep *sw, double gap,
                   mr_contact_list *out);
int mr_detect_puppets(mr_world *w, const double *x, const mr_sweep *sw, double gap,
                      mr_contact_list *out);

/* eval.c: accelerations for a state, eq. 1 and eq. 8, during a step of
 * length h (static friction aims to stop sliding within h/2). */
int mr_eval(mr_world *w, double t, double h, double *x, double *v, double *a);
/* mr_eval where the last evaluation was made, at the same t, x, v and
 * contacts, with only a frame's path new: 1 done, 0 when the last
 * evaluation's system cannot serve (a, the frames' placing and the
 * contacts' selection may then be written: call mr_eval, which writes
 * them all again), −1 on failure. */
int mr_eval_new_path(mr_world *w, double t, double h, double *x, double *v, double *a);
int mr_rows_reserve(mr_world *w, int rows);
/* Assembles A = J M⁻¹ Jᵀ from w->J and solves A λ = w->rhs into w->lambda,
 * block by block where the rows fall into blocks (islands.c). */
int mr_solve_rows(mr_world *w, int assemble);
/* mr_solve_rows(w, 0) for group g of the grouping in use alone
 * (mr_islands_solve_one): only its rows' λ are written. */
int mr_solve_block(mr_world *w, int g);
/* eq. 8's b again for the listed rows, with the free accelerations a. */
void mr_rhs_rows(mr_world *w, const int *list, int count, const double *a);
/* The compliance of contact rows: A's rows from `first` on whose
 * row_contact is a contact. */
void mr_soften_contacts(mr_csr *A, int first, const int *row_contact);

/* islands.c: the blocks of J M⁻¹ Jᵀ */
int mr_islands_build(mr_world *w); /* the constraints' blocks, when the world is made ready */
int mr_islands_group(mr_world *w); /* groups J's rows: how many groups (1: solve whole) */
mr_solve_status mr_islands_solve(mr_world *w, int groups, mr_solve_result *sum);
/* Group g of the grouping in use alone (its λ; the other rows' are left
 * as they were): for friction's probes, whose b is zero in every other
 * block, so that a probe costs its own block and not the whole crowd. */
mr_solve_status mr_islands_solve_one(mr_world *w, int g, mr_solve_result *sum);

/* impulse.c: eq. 9 at contacts */
int mr_impulses_apply(mr_world *w, double t, int *collided);

/* integrate.c */
int mr_integrate(mr_world *w, double t, double h, const double *x0, const double *v0, double *x1,
                 double *v1, double *err);
void mr_eval_memo_free(mr_eval_memo *m);

/* project.c: the inverse-dynamics iteration of §6.2 [19] applied to the
 * constraints. mr_project_positions moves x (3n) along M⁻¹Jᵀ, so that
 * heavy particles move least and momentum is kept, until the largest
 * relative deviation is within tol or max_iter rounds ran; returns the
 * rounds used, or −1 (out of memory, or no progress: then x is unchanged).
 * mr_project_velocities then removes the velocity along the constraint
 * normals, J v = −∂C/∂t, in the same metric. 0 or −1. Frame particles do
 * not move; contacts are not rows here. */
int mr_project_positions(mr_world *w, double t, double *x, const double *v, double tol,
                         int max_iter);
int mr_project_velocities(mr_world *w, double t, const double *x, double *v);
/* The pieces of both: the constraint rows at (t, x, v) into w->J, w->row_c
 * and w->row_cdot, with room for `extra` rows after them (the number of
 * constraint rows, or −1); and q += M⁻¹ Jᵀ λ for the solve just made. */
int mr_project_rows(mr_world *w, double t, const double *x, const double *v, int extra);
void mr_project_apply(mr_world *w, double *q);

/* forces.c: the integrator's stability limit on Δt for the stiffest mode
 * of the applied forces (and eq. 8's feedback); links too stiff for a step
 * of dt_min/100 are softened to it first (counted in stats). */
double mr_forces_stable_dt(mr_world *w);

/* taut_string.c: strings in MR_STRING_TAUT mode as contacts (§5.4) with
 * the gap χ = rest − |x_p − x_f|, J = −uᵀ at the puppet particle. */
int mr_taut_detect(mr_world *w, const double *x, double gap, mr_contact_list *out);
double mr_taut_gap(const mr_world *w, int string, const double *x);
double mr_taut_rate(const mr_world *w, int string, const double *x, const double *v);
int mr_taut_row(mr_world *w, int string, const double *x, const double *v, double *chi,
                double *chidot, double *jdqd);
/* eval.c's force solve, which read each string's geometry and frame-end
 * motion three times at one state (the gap and the rate that choose the
 * resting contacts, then the row), finds them once: mr_taut_separating() keeps them with the
 * string and says whether it is apart and separating faster than
 * `separating` (the gap and rate bits of mr_taut_gap and mr_taut_rate);
 * mr_taut_row_seen() then builds mr_taut_row's row from them, for the
 * same x, v and time. */
int mr_taut_separating(mr_world *w, int string, const double *x, const double *v,
                       double separating);
int mr_taut_row_seen(mr_world *w, int string, const double *v, double *chi, double *chidot,
                     double *jdqd);
/* mr_taut_row_seen's numbers for a row J already holds
 * (mr_eval_new_path). */
void mr_taut_row_again(const mr_world *w, int string, const double *v, double *chi, double *chidot,
                       double *jdqd);
/* The time the frame ends of taut strings move at: rates are taken from
 * the frame segment under way at it, ends included (mr_frame_rates). */
void mr_taut_set_time(mr_world *w, double t);
/* How far past its rest length a taut string is left (m): neither
 * brought back (string_correction.c) nor stopped by an impulse
 * (impulse.c) within it. */
double mr_taut_hold(const mr_world *w, int string);
/* The largest relative over-length (L − rest)/rest of the taut strings in
 * x, 0 when none is over: held to the ATS thresholds with the deviation. */
double mr_taut_overlength(const mr_world *w, const double *x);

/* locate.c: a contact apart at the step's start and gone through by its
 * end (w->probe, the step to h ending in w->x1, w->v1) located in time
 * (§4.5, §5.4): the state at t + h* left in w->x1, w->v1, h* returned (h
 * when none was apart). *err set when an integration failed. */
double mr_locate_contact(mr_world *w, double t, double h, int *err);

/* string_correction.c */
/* 0, or -1 when its work arrays cannot grow (out of memory). deviation:
 * a bound on the state's constraint deviation the caller has measured
 * (the step's end error), which spares measuring it again, or NaN. */
int mr_strings_correct(mr_world *w, double deviation);

/* rigid_group.c */
mr_status mr_rigid_group_build(mr_world *w, const int *ids, int count, int *first, int *n);

#endif

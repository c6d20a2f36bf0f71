/* Sphere trees (§4.4, after Hubbard [16, 17]): each puppet's parts are
 * covered by leaf spheres that ride on its particles (one per particle, sized
 * by the model's extent, plus spheres along two-particle limbs). A binary
 * tree over a puppet's leaves is built once by median splits; because the
 * parts move and turn quickly, the tree's topology is kept and its spheres
 * are refitted bottom-up before every test. Trees are traversed against each
 * other (puppet–puppet) and against themselves (non-adjacent parts of one
 * puppet). */
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

mr_part_def mr_default_part_def(void) {
  return (mr_part_def){ .cookie = MR_DEF_COOKIE, .restitution = 0.5, .friction = 0.3 };
}

static int push_leaf(mr_world *w, int p0, int p1, double s, double r, int part, int puppet) {
  mr_leaf l = { p0, p1, s, r, part, puppet };
  return mr_add_push(w, &w->leaves, &l, sizeof l, NULL, "mr_world_add_part") == MR_OK ? 0 : -1;
}

mr_status mr_world_add_part(mr_world *w, const mr_part_def *def, int *out_id) {
  const char *what = "mr_world_add_part";
  mr_status st = MR_ADD_CHECK(w, def, 0, what);
  if (st != MR_OK) return st;
  if (!def->particles && def->count > 0) return mr_fail(w, MR_ERR_ARG, "%s: NULL particles", what);
  if (!(w->def.effects & (MR_EFFECT_SELF_COLLISION | MR_EFFECT_PUPPET_COLLISION)))
    return mr_fail(w, MR_ERR_NOT_DECLARED, "%s: the world declares no sphere-tree collisions",
                   what);
  if (def->count < 1) return mr_fail(w, MR_ERR_ARG, "%s: needs at least one particle", what);
  if (!isfinite(def->radius) || !isfinite(def->restitution) || !isfinite(def->friction))
    return mr_fail(w, MR_ERR_NONFINITE, "%s: radius, restitution or friction is NaN or Inf", what);
  if (def->radius < 0 || def->restitution < 0 || def->restitution > 1 || def->segment_spheres < 0 ||
      def->friction < 0)
    return mr_fail(
        w, MR_ERR_ARG,
        "%s: need radius >= 0, 0 <= restitution <= 1, friction >= 0, segment_spheres >= 0", what);
  if (def->segment_spheres > 0 && def->count != 2)
    return mr_fail(w, MR_ERR_ARG, "%s: segment_spheres needs a two-particle part", what);
  int puppet = -1;
  for (int i = 0; i < def->count; i++) {
    int p = def->particles[i];
    if (mr_check_particle(w, p, what) != 0) return MR_ERR_ID;
    if (w->frame[p] >= 0)
      return mr_fail(w, MR_ERR_ARG, "%s: particle %d is on a control frame", what, p);
    if (puppet >= 0 && w->puppet[p] != puppet)
      return mr_fail(w, MR_ERR_ARG, "%s: particle %d is in puppet %d, the part is in puppet %d",
                     what, p, w->puppet[p], puppet);
    puppet = w->puppet[p];
  }
  int id = w->parts.n, first = w->leaves.n;
  int ok = 0;
  for (int i = 0; i < def->count && ok == 0; i++) {
    int p = def->particles[i];
    double r = w->radius[p] > def->radius ? w->radius[p] : def->radius;
    ok = push_leaf(w, p, p, 0.0, r, id, puppet);
  }
  for (int j = 1; j <= def->segment_spheres && ok == 0; j++) {
    int a = def->particles[0], b = def->particles[1];
    double r = def->radius > 0 ? def->radius : fmax(w->radius[a], w->radius[b]);
    ok = push_leaf(w, a, b, (double)j / (def->segment_spheres + 1), r, id, puppet);
  }
  if (ok != 0) {
    w->leaves.n = first;
    return mr_fail(w, MR_ERR_NOMEM, "%s: out of memory", what);
  }
  mr_part part = { first, w->leaves.n - first, puppet, def->restitution, def->friction };
  st = mr_add_push(w, &w->parts, &part, sizeof part, out_id, what);
  if (st != MR_OK) w->leaves.n = first;
  return st;
}

/* ------------------------------------------------------------------ build */

/* Sorts leaf indices by their centre's coordinate on `axis` (ties by index,
 * a total order, so builds are reproducible). Insertion sort: a puppet has
 * tens of leaves, and it keeps no state outside the call. */
static void sort_by_axis(int *idx, int n, const double *c, int axis) {
  for (int i = 1; i < n; i++) {
    int v = idx[i], j = i - 1;
    double key = c[3 * v + axis];
    while (j >= 0 && (c[3 * idx[j] + axis] > key || (c[3 * idx[j] + axis] == key && idx[j] > v))) {
      idx[j + 1] = idx[j];
      j--;
    }
    idx[j + 1] = v;
  }
}

/* Builds the subtree over leaves idx[0..n) and returns its node index;
 * children are emitted before their parent, so refitting is one pass. */
static int build(mr_world *w, int *idx, int n) {
  int node;
  if (n == 1) {
    node = w->nnodes++;
    w->nodes[node] = (mr_tree_node){ { 0, 0, 0 }, 0, -1, -1, idx[0] };
    return node;
  }
  double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      double c = w->leaf_c[3 * idx[i] + k];
      lo[k] = fmin(lo[k], c);
      hi[k] = fmax(hi[k], c);
    }
  int axis = 0;
  for (int k = 1; k < 3; k++)
    if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
  sort_by_axis(idx, n, w->leaf_c, axis);
  int left = build(w, idx, n / 2);
  int right = build(w, idx + n / 2, n - n / 2);
  node = w->nnodes++;
  w->nodes[node] = (mr_tree_node){ { 0, 0, 0 }, 0, left, right, -1 };
  return node;
}

static int parts_touch(const mr_world *w, int i, int j) {
  const mr_part *a = &MR_AT(w->parts, mr_part, i), *b = &MR_AT(w->parts, mr_part, j);
  for (int u = 0; u < a->leaf_count; u++) {
    const mr_leaf *la = &MR_AT(w->leaves, mr_leaf, a->first_leaf + u);
    if (la->s != 0.0) continue;
    for (int v = 0; v < b->leaf_count; v++) {
      const mr_leaf *lb = &MR_AT(w->leaves, mr_leaf, b->first_leaf + v);
      if (lb->s == 0.0 && lb->p0 == la->p0) return 1;
    }
  }
  return 0;
}

static int part_has(const mr_world *w, int part, int p) {
  const mr_part *a = &MR_AT(w->parts, mr_part, part);
  for (int u = 0; u < a->leaf_count; u++) {
    const mr_leaf *l = &MR_AT(w->leaves, mr_leaf, a->first_leaf + u);
    if (l->s == 0.0 && l->p0 == p) return 1;
  }
  return 0;
}

static int find_built_overlaps(mr_world *w);

int mr_trees_build(mr_world *w) {
  free(w->built_overlaps);
  w->built_overlaps = NULL;
  w->n_built_overlaps = 0;
  free(w->nodes);
  free(w->trees);
  free(w->leaf_c);
  free(w->part_adjacent);
  w->nodes = NULL;
  w->trees = NULL;
  w->leaf_c = NULL;
  w->part_adjacent = NULL;
  w->nnodes = w->ntrees = 0;
  if (w->leaves.n == 0) return 0;
  int np = w->parts.n;
  w->leaf_c = malloc((size_t)w->leaves.n * 3 * sizeof *w->leaf_c);
  w->nodes = malloc((size_t)(2 * w->leaves.n) * sizeof *w->nodes);
  w->trees = malloc((size_t)w->leaves.n * sizeof *w->trees);
  w->part_adjacent = calloc((size_t)np * (size_t)np, 1);
  int *idx = malloc((size_t)w->leaves.n * sizeof *idx);
  if (!w->leaf_c || !w->nodes || !w->trees || !w->part_adjacent || !idx) {
    free(idx);
    return -1;
  }
  for (int i = 0; i < w->leaves.n; i++)
    mr_leaf_center(w, &MR_AT(w->leaves, mr_leaf, i), w->x, &w->leaf_c[3 * i]);
  /* One tree per puppet, in order of first appearance. */
  for (int i = 0; i < w->leaves.n; i++) {
    int puppet = MR_AT(w->leaves, mr_leaf, i).puppet, seen = 0;
    for (int t = 0; t < w->ntrees && !seen; t++) seen = w->trees[t].puppet == puppet;
    if (seen) continue;
    int n = 0;
    for (int j = i; j < w->leaves.n; j++)
      if (MR_AT(w->leaves, mr_leaf, j).puppet == puppet) idx[n++] = j;
    int first = w->nnodes;
    int root = build(w, idx, n);
    w->trees[w->ntrees++] = (mr_tree){ puppet, first, w->nnodes - first, root };
  }
  free(idx);
  /* Adjacent parts (sharing a particle or joined by a distance constraint)
   * touch by design and are never tested. */
  for (int i = 0; i < np; i++)
    for (int j = 0; j < np; j++)
      if (i == j || parts_touch(w, i, j)) w->part_adjacent[i * np + j] = 1;
  for (int d = 0; d < w->distances.n; d++)
    for (int i = 0; i < np; i++)
      if (part_has(w, i, MR_AT(w->distances, mr_distance, d).a))
        for (int j = 0; j < np; j++)
          if (part_has(w, j, MR_AT(w->distances, mr_distance, d).b))
            w->part_adjacent[i * np + j] = w->part_adjacent[j * np + i] = 1;
  return find_built_overlaps(w);
}

/* ----------------------------------------------------------------- refit */

/* A leaf's node sphere: the leaf in x, or, over a sweep, a sphere holding
 * everything the leaf may cover during the step (its chord, widened by the
 * bulge, collide.c). */
static void fit_leaf(const mr_world *w, mr_tree_node *nd, const double *x, const mr_sweep *sw) {
  const mr_leaf *l = &MR_AT(w->leaves, mr_leaf, nd->leaf);
  mr_leaf_center(w, l, x, nd->c);
  nd->r = l->r;
  if (!sw) return;
  double c0[3], len = 0.0;
  mr_leaf_center(w, l, sw->x0, c0);
  for (int k = 0; k < 3; k++) {
    len += (nd->c[k] - c0[k]) * (nd->c[k] - c0[k]);
    nd->c[k] = 0.5 * (nd->c[k] + c0[k]);
  }
  nd->r += 0.5 * sqrt(len) + mr_leaf_bulge(w, l, sw);
}

static void refit(mr_world *w, const mr_tree *t, const double *x, const mr_sweep *sw) {
  for (int i = t->first_node; i < t->first_node + t->node_count; i++) {
    mr_tree_node *nd = &w->nodes[i];
    if (nd->leaf >= 0) {
      fit_leaf(w, nd, x, sw);
      continue;
    }
    const mr_tree_node *a = &w->nodes[nd->left], *b = &w->nodes[nd->right];
    double d[3] = { b->c[0] - a->c[0], b->c[1] - a->c[1], b->c[2] - a->c[2] };
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (len + b->r <= a->r) {
      memcpy(nd->c, a->c, sizeof nd->c);
      nd->r = a->r;
    } else if (len + a->r <= b->r) {
      memcpy(nd->c, b->c, sizeof nd->c);
      nd->r = b->r;
    } else {
      double r = 0.5 * (len + a->r + b->r);
      double s = (r - a->r) / len;
      for (int k = 0; k < 3; k++) nd->c[k] = a->c[k] + s * d[k];
      nd->r = r;
    }
  }
}

double mr_world_tree_slack(mr_world *w) {
  if (w == NULL || w->ntrees == 0) return INFINITY;
  double worst = INFINITY;
  for (int t = 0; t < w->ntrees; t++) {
    const mr_tree *tr = &w->trees[t];
    refit(w, tr, w->x, NULL);
    for (int i = tr->first_node; i < tr->first_node + tr->node_count; i++) {
      const mr_tree_node *nd = &w->nodes[i];
      if (nd->leaf >= 0) continue;
      const int kids[2] = { nd->left, nd->right };
      for (int k = 0; k < 2; k++) {
        const mr_tree_node *c = &w->nodes[kids[k]];
        double d[3] = { c->c[0] - nd->c[0], c->c[1] - nd->c[1], c->c[2] - nd->c[2] };
        worst = fmin(worst, nd->r - (sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + c->r));
      }
    }
  }
  return worst;
}

/* ------------------------------------------------------------- traversal */

static double node_gap(const mr_tree_node *a, const mr_tree_node *b) {
  double d[3] = { b->c[0] - a->c[0], b->c[1] - a->c[1], b->c[2] - a->c[2] };
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - a->r - b->r;
}

/* ------------------------------------------------- overlaps as built
 *
 * Leaves that overlap in the pose the puppets were built in, deeper than
 * the contact slop (within it they touch, and rest on each other as
 * built), were not brought together by any motion: there is no moment of
 * collision for §5.4 to find (eq. 13a and 13b start from χ = 0), only a
 * depth no step made. Such a pair is left out of the contacts:
 *  - of one puppet, always, as adjacent parts are: the maker put a torso
 *    sphere round the top of an arm on purpose;
 *  - of two puppets, until it is seen no deeper than the slop at the start
 *    of a step (mr_trees_note_apart); from then on it collides as any
 *    other. A reset to the start configuration leaves such pairs out again.
 * Pushing them apart instead made every overlapping leaf pair a contact
 * row: three puppets whose torso spheres were written 5.07 m instead of
 * 0.07 m solved 600 contact rows, released a few at a time in nine rounds
 * per evaluation, 32 G instructions for 1 ms of simulation. */

static double leaves_gap(const mr_world *w, int a, int b, const double *x) {
  const mr_leaf *la = &MR_AT(w->leaves, mr_leaf, a), *lb = &MR_AT(w->leaves, mr_leaf, b);
  double ca[3], cb[3];
  mr_leaf_center(w, la, x, ca);
  mr_leaf_center(w, lb, x, cb);
  double d[3] = { cb[0] - ca[0], cb[1] - ca[1], cb[2] - ca[2] };
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - la->r - lb->r;
}

static int overlap_cmp(const void *p, const void *q) {
  const mr_built_overlap *a = p, *b = q;
  if (a->a != b->a) return a->a < b->a ? -1 : 1;
  return (a->b > b->b) - (a->b < b->b);
}

static int left_out(const mr_world *w, int a, int b) {
  const mr_built_overlap key = { a < b ? a : b, a < b ? b : a, 0, 0 };
  const mr_built_overlap *o =
      bsearch(&key, w->built_overlaps, (size_t)w->n_built_overlaps, sizeof key, overlap_cmp);
  return o != NULL && o->out;
}

static int traverse(mr_world *w, int ra, int rb, int same, const mr_sweep *sw, double gap,
                    mr_contact_list *out);

/* The leaf pairs (not of adjacent parts) that overlap in w->x by more than
 * the slop, found by the same traversal as the contacts, with nothing left
 * out yet. */
static int find_built_overlaps(mr_world *w) {
  mr_contact_list found = { 0 };
  int st = 0;
  for (int t = 0; t < w->ntrees; t++) refit(w, &w->trees[t], w->x, NULL);
  for (int a = 0; a < w->ntrees && st == 0; a++)
    for (int b = a; b < w->ntrees && st == 0; b++)
      st = traverse(w, w->trees[a].root, w->trees[b].root, a == b, NULL, 0.0, &found);
  int n = 0;
  if (st == 0 && found.n > 0 &&
      !(w->built_overlaps = malloc((size_t)found.n * sizeof(mr_built_overlap))))
    st = -1;
  for (int i = 0; st == 0 && i < found.n; i++) {
    int a = found.c[i].a, b = found.c[i].b;
    if (!(leaves_gap(w, a, b, w->x) < -w->def.contact_slop)) continue;
    int same = MR_AT(w->leaves, mr_leaf, a).puppet == MR_AT(w->leaves, mr_leaf, b).puppet;
    w->built_overlaps[n++] =
        (mr_built_overlap){ a < b ? a : b, a < b ? b : a, (unsigned char)same, 1 };
  }
  mr_contact_list_free(&found);
  if (st != 0) return -1;
  if (n > 1) qsort(w->built_overlaps, (size_t)n, sizeof *w->built_overlaps, overlap_cmp);
  w->n_built_overlaps = n;
  return 0;
}

void mr_trees_note_apart(mr_world *w, const double *x) {
  for (int i = 0; i < w->n_built_overlaps; i++) {
    mr_built_overlap *o = &w->built_overlaps[i];
    if (o->out && !o->same_puppet && !(leaves_gap(w, o->a, o->b, x) < -w->def.contact_slop))
      o->out = 0;
  }
}

/* A reset carries a puppet hanging from a frame to where its frame is now
 * (restart.c), which may be inside another puppet: its pairs are found
 * again in the state the world restarts from. The same puppet's pairs are
 * those as built (it moves as a whole). Out of memory, the pairs as built
 * are left out again, as they were before any step. */
void mr_trees_restore_overlaps(mr_world *w) {
  mr_built_overlap *kept = w->built_overlaps;
  const int n_kept = w->n_built_overlaps;
  w->built_overlaps = NULL;
  w->n_built_overlaps = 0;
  if (w->ntrees > 0 && find_built_overlaps(w) == 0) {
    free(kept);
    return;
  }
  free(w->built_overlaps);
  w->built_overlaps = kept;
  w->n_built_overlaps = n_kept;
  for (int i = 0; i < n_kept; i++) w->built_overlaps[i].out = 1;
}

/* Two leaves within the gap: a contact, unless their parts are adjacent.
 * Their node spheres were within it; over a sweep those only bound the
 * leaves' reach, and the swept gap itself decides. */
static int leaf_pair(mr_world *w, int leaf_a, int leaf_b, const mr_sweep *sw, double gap,
                     mr_contact_list *out) {
  const mr_leaf *la = &MR_AT(w->leaves, mr_leaf, leaf_a), *lb = &MR_AT(w->leaves, mr_leaf, leaf_b);
  if (w->part_adjacent[la->part * w->parts.n + lb->part]) return 0;
  if (w->n_built_overlaps > 0 && left_out(w, leaf_a, leaf_b)) return 0;
  if (sw && !(mr_sphere_pair_swept_gap(w, leaf_a, leaf_b, sw) <= gap)) return 0;
  const mr_part *pa = &MR_AT(w->parts, mr_part, la->part),
                *pb = &MR_AT(w->parts, mr_part, lb->part);
  double e = 0.5 * (pa->restitution + pb->restitution);
  double mu = 0.5 * (pa->friction + pb->friction);
  return mr_contact_push(out, MR_CONTACT_SPHERES, leaf_a, leaf_b, e, mu);
}

/* The child pairs of the node pair (a, b) to test next: (n, n) of one tree
 * expands to its three distinct pairs, otherwise the larger node (or the
 * one that is not a leaf) is split. */
static int expand(const mr_world *w, int a, int b, int same, int pairs[3][2]) {
  const mr_tree_node *na = &w->nodes[a], *nb = &w->nodes[b];
  if (a == b && same) {
    pairs[0][0] = na->left, pairs[0][1] = na->left;
    pairs[1][0] = na->right, pairs[1][1] = na->right;
    pairs[2][0] = na->left, pairs[2][1] = na->right;
    return 3;
  }
  if (nb->leaf >= 0 || (na->leaf < 0 && na->r >= nb->r)) {
    pairs[0][0] = na->left, pairs[0][1] = b;
    pairs[1][0] = na->right, pairs[1][1] = b;
  } else {
    pairs[0][0] = a, pairs[0][1] = nb->left;
    pairs[1][0] = a, pairs[1][1] = nb->right;
  }
  return 2;
}

/* Depth-first traversal of the node pair (a, b); same = a and b are the
 * same tree. */
static int traverse(mr_world *w, int ra, int rb, int same, const mr_sweep *sw, double gap,
                    mr_contact_list *out) {
  int top = 0;
  if (mr_grow((void **)&w->tree_stack, &w->cap_tree_stack, 2, sizeof(int)) != 0) return -1;
  int *stack = w->tree_stack;
  stack[top++] = ra;
  stack[top++] = rb;
  while (top > 0) {
    int b = stack[--top], a = stack[--top];
    const mr_tree_node *na = &w->nodes[a], *nb = &w->nodes[b];
    if (!(a == b && same) && !(node_gap(na, nb) <= gap)) continue;
    if (na->leaf >= 0 && nb->leaf >= 0) {
      if (a != b && leaf_pair(w, na->leaf, nb->leaf, sw, gap, out) != 0) return -1;
      continue;
    }
    int pairs[3][2];
    int np = expand(w, a, b, same, pairs);
    /* The stack is the world's, kept between calls: it grows to the
     * deepest traversal once and then the step allocates nothing. */
    if (mr_grow((void **)&w->tree_stack, &w->cap_tree_stack, top + 2 * np, sizeof(int)) != 0)
      return -1;
    stack = w->tree_stack;
    for (int i = 0; i < np; i++) {
      stack[top++] = pairs[i][0];
      stack[top++] = pairs[i][1];
    }
  }
  return 0;
}

int mr_detect_self(mr_world *w, const double *x, const mr_sweep *sw, double gap,
                   mr_contact_list *out) {
  w->pass_calls[MR_PASS_SELF_COLLISION]++;
  for (int t = 0; t < w->ntrees; t++) {
    refit(w, &w->trees[t], x, sw);
    if (traverse(w, w->trees[t].root, w->trees[t].root, 1, sw, gap, out) != 0) return -1;
  }
  return 0;
}

int mr_detect_puppets(mr_world *w, const double *x, const mr_sweep *sw, double gap,
                      mr_contact_list *out) {
  w->pass_calls[MR_PASS_PUPPET_COLLISION]++;
  for (int t = 0; t < w->ntrees; t++) refit(w, &w->trees[t], x, sw);
  for (int a = 0; a < w->ntrees; a++)
    for (int b = a + 1; b < w->ntrees; b++)
      if (traverse(w, w->trees[a].root, w->trees[b].root, 0, sw, gap, out) != 0) return -1;
  return 0;
}

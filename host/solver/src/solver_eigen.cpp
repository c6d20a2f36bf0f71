// MR_SOLVE_EIGEN: Eigen's SimplicialLDLT (a sparse up-looking LDLᵀ)
// behind the C interface in solver_internal.h. The only C++ in the physics; it is also the oracle the
// C solvers are tested against.
//
// Eigen has no pivot threshold, so dependent rows are found afterwards with
// the C LDLᵀ's rule: a pivot d_k ≤ pivot_tol · A_kk marks its row dependent.
// Such a row is replaced by the identity row (its λ is then 0 and it no
// longer couples to the others, exactly as if it were removed) and the
// matrix factored again. Which row of a dependent set goes depends on the
// ordering and on rounding, so λ may differ from the C LDLᵀ's, while the
// forces Jᵀλ agree.
//
// Storage: the ordering, the permuted upper triangle and Eigen's symbolic
// analysis depend only on A's pattern, and replacing a row keeps the
// pattern, so all three are made once per pattern and a call with the
// pattern of the last one only copies numbers and refactors. Eigen's own
// orderings and its public analyse and factorise calls allocate every
// time, and its vectors reallocate whenever their size changes. So the
// ordering is the C LDLᵀ's (minimum degree, RCM or natural, whichever
// fills least: Eigen's numbers, not its ordering, are what the oracle
// checks), the analysis and the factorisation are called on the kept
// matrix directly, and the matrix keeps the largest size seen, the rows
// beyond A's being identity rows. Once warm, no call allocates, whatever
// the pattern, as long as A is no larger than one seen before.
#include "solver_internal.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <cfloat>
#include <new>
#include <utility>
#include <vector>

namespace {

using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// SimplicialLDLT of a matrix this file has already ordered. Its public
// factorize() builds a fresh copy of the matrix on every call; this one
// factors the kept matrix directly.
class KeptLDLT : public Eigen::SimplicialLDLT<SpMat, Eigen::Upper, Eigen::NaturalOrdering<int>> {
public:
  // Eigen sizes L's storage exactly; it grows here instead, by doubling,
  // to nnz_l (known from the ordering), so that Eigen finds room.
  void reserve_l(Eigen::Index nnz_l) {
    auto &data = this->m_matrix.data();
    if (data.allocatedSize() < nnz_l)
      data.reserve(std::max(nnz_l, 2 * data.allocatedSize()) - data.size());
  }
  void analyse(const SpMat &upper, Eigen::Index nnz_l) {
    reserve_l(nnz_l);
    this->analyzePattern_preordered(upper, true);
  }
  void refactor(const SpMat &upper) {
    this->template factorize_preordered<true>(upper);
  }
  const Eigen::VectorXd &pivots() const {
    return this->m_diag;
  }
  void solve_in_place(Eigen::VectorXd &v) const {
    this->matrixL().solveInPlace(v);
    v = this->m_diag.asDiagonal().inverse() * v;
    this->matrixU().solveInPlace(v);
  }
};

struct EigenWorkspace {
  mr_pattern pattern = {}; // A's pattern the members below were made for
  mr_ldlt order = {};      // the ordering: order.perm is new → old
  int size = 0;            // the kept matrices' size: the largest n seen
  KeptLDLT ldlt;
  SpMat upper;          // the upper triangle of P A Pᵀ, identity beyond n
  std::vector<int> src; // upper's value t is A->val[src[t]]
  std::vector<int> outer, inner;
  std::vector<std::pair<int, int>> column;
  std::vector<char> dep; // by old index
  Eigen::VectorXd adiag, scale, rhs;
  Eigen::VectorXd reg; // by old index: what reg_tol adds to a nearly dependent row's diagonal
  ~EigenWorkspace() {
    mr_pattern_free(&pattern);
    mr_ldlt_free(&order);
  }
  const int *perm() const {
    return static_cast<const int *>(order.perm.p);
  }
};

// The kept matrices grow to hold n rows, by doubling as mr_grow does;
// they never shrink.
void grow(EigenWorkspace &w, int n) {
  if (n <= w.size) return;
  int size = w.size ? w.size : 16;
  while (size < n) size *= 2;
  w.size = size;
  w.dep.resize(size);
  w.adiag.resize(size);
  w.scale.resize(size);
  w.rhs.resize(size);
  w.reg.resize(size);
  w.outer.resize(size + 1);
}

// The ordering and the permuted upper triangle's pattern, each column's
// rows ascending, then Eigen's symbolic analysis of it.
void analyse(EigenWorkspace &w, const mr_csr *A) {
  const int n = A->n;
  size_t nnz_l = 0;
  if (mr_ldlt_order(&w.order, A, &nnz_l) != 0) throw std::bad_alloc();
  grow(w, n);
  const int *perm = w.perm(), *inv = static_cast<const int *>(w.order.iperm.p);
  // A is symmetric and stores both triangles: column c of the upper
  // triangle is row perm[c] of A, restricted to new indices ≤ c.
  w.inner.clear();
  w.src.clear();
  w.outer[0] = 0;
  for (int c = 0; c < w.size; c++) {
    w.column.clear();
    if (c >= n)
      w.column.emplace_back(c, -1);
    else
      for (int q = A->row_ptr[perm[c]]; q < A->row_ptr[perm[c] + 1]; q++)
        if (inv[A->col[q]] <= c) w.column.emplace_back(inv[A->col[q]], q);
    std::sort(w.column.begin(), w.column.end());
    for (const auto &e : w.column) {
      w.inner.push_back(e.first);
      w.src.push_back(e.second);
    }
    w.outer[c + 1] = (int)w.inner.size();
  }
  const int nnz = w.outer[w.size];
  w.upper.resize(w.size, w.size);
  if (w.upper.data().allocatedSize() < nnz)
    w.upper.data().reserve(2 * nnz); // doubling, as mr_grow does
  w.upper.resizeNonZeros(nnz);
  std::copy(w.outer.begin(), w.outer.begin() + w.size + 1, w.upper.outerIndexPtr());
  std::copy(w.inner.begin(), w.inner.end(), w.upper.innerIndexPtr());
  std::fill(w.upper.valuePtr(), w.upper.valuePtr() + nnz, 1.0); // the identity beyond n
  w.ldlt.analyse(w.upper, (Eigen::Index)nnz_l);
}

// Room for any pattern of up to rows rows: the ordering's scratch, the
// kept matrices at their size, the upper triangle and L dense, and Eigen's
// own arrays, made by analysing and factoring the identity once.
void reserve(EigenWorkspace &w, int rows) {
  const size_t n = (size_t)rows;
  if (mr_ldlt_reserve_order(&w.order, rows) != 0 || mr_pattern_reserve(&w.pattern, n, n * n) != 0)
    throw std::bad_alloc();
  grow(w, rows);
  const int size = w.size;
  const size_t dense = n * (n + 1) / 2 + (size_t)size - n;
  w.src.reserve(dense);
  w.inner.reserve(dense);
  w.column.reserve((size_t)size);
  w.pattern.valid = 0; // the identity below is no pattern of A's
  w.upper.resize(size, size);
  w.upper.data().reserve((Eigen::Index)dense);
  w.upper.resizeNonZeros(size);
  for (int c = 0; c < size; c++) {
    w.upper.outerIndexPtr()[c] = c;
    w.upper.innerIndexPtr()[c] = c;
    w.upper.valuePtr()[c] = 1.0;
  }
  w.upper.outerIndexPtr()[size] = size;
  w.ldlt.analyse(w.upper, (Eigen::Index)(n * (n > 0 ? n - 1 : 0) / 2));
  w.ldlt.refactor(w.upper);
}

// A's numbers into the upper triangle: a dependent row and column become
// the identity's; with scaled, the others are D^-½ A D^-½'s.
void load(EigenWorkspace &w, const mr_csr *A, bool scaled) {
  const int *outer = w.upper.outerIndexPtr(), *inner = w.upper.innerIndexPtr(), *perm = w.perm();
  double *val = w.upper.valuePtr();
  for (int c = 0; c < A->n; c++) {
    const int oc = perm[c];
    for (int t = outer[c]; t < outer[c + 1]; t++) {
      const int orow = perm[inner[t]];
      if (w.dep[orow] || w.dep[oc])
        val[t] = inner[t] == c ? 1.0 : 0.0;
      else if (scaled)
        val[t] = w.scale[orow] * A->val[w.src[t]] * w.scale[oc];
      else
        val[t] = A->val[w.src[t]] + (inner[t] == c ? w.reg[oc] : 0.0);
    }
  }
}

// The old index of the first row in elimination order whose pivot fails
// the test d ≤ tol · diag, or -1. Only the first is trusted: Eigen goes on
// dividing by the tiny pivot, which spoils every pivot after it.
int first_small_pivot(const EigenWorkspace &w, int n, double tol, bool unit_diag) {
  const Eigen::VectorXd &d = w.ldlt.pivots();
  for (int t = 0; t < n; t++) {
    const int old = w.perm()[t];
    if (!w.dep[old] && !(d[t] > tol * (unit_diag ? 1.0 : w.adiag[old]))) return old;
  }
  return -1;
}

// An exactly zero pivot stops Eigen before D is complete. Find the row on
// the unit-diagonal matrix S = D^-½ A D^-½ (whose pivots are the ratios
// d_k / A_kk the test uses) shifted by δ I: δ sits well below the
// threshold, so a dependent pivot (≈ δ) still fails the test, and a shift
// only raises the others. δ is kept above rounding so that it makes every
// pivot nonzero. Returns the row, or -1 when none can be found.
int find_zero_pivot(EigenWorkspace &w, const mr_csr *A, double pivot_tol) {
  const double shift = std::max(1e-3 * pivot_tol, 8.0 * DBL_EPSILON);
  const double threshold = std::max(pivot_tol, 16.0 * shift);
  for (int i = 0; i < A->n; i++) w.scale[i] = 1.0 / std::sqrt(w.adiag[i]);
  load(w, A, true);
  w.ldlt.setShift(shift, 1.0);
  w.ldlt.refactor(w.upper);
  if (w.ldlt.info() != Eigen::Success) return -1;
  return first_small_pivot(w, A->n, threshold, true);
}

int solve(EigenWorkspace &w, const mr_solve_def *o, const mr_csr *A, const double *b, double *x,
          mr_solve_result *r) {
  const int n = A->n;
  if (!mr_pattern_same(&w.pattern, A)) {
    w.pattern.valid = 0; // until the analysis below is complete
    analyse(w, A);
    if (mr_pattern_keep(&w.pattern, A) != 0) return MR_SOLVE_ERR_NOMEM;
  }
  mr_csr_diagonal(A, w.adiag.data());
  for (int i = 0; i < n; i++) {
    w.dep[i] = !(w.adiag[i] > DBL_MIN);
    w.reg[i] = 0.0;
  }
  // Each pass that does not solve marks a row dependent or raises one (a
  // row is raised at most once before it passes), so 2n + 1 passes end.
  for (int pass = 0; pass <= 2 * n; pass++) {
    load(w, A, false);
    w.ldlt.setShift(0.0, 1.0);
    w.ldlt.refactor(w.upper);
    const bool factored = w.ldlt.info() == Eigen::Success;
    int bad = factored ? first_small_pivot(w, n, o->pivot_tol, false)
                       : find_zero_pivot(w, A, o->pivot_tol);
    if (!factored && bad < 0) return MR_SOLVE_NOT_CONVERGED;
    if (bad >= 0) {
      w.dep[bad] = 1;
      continue;
    }
    // reg_tol as LDLᵀ applies it: a pivot d_k below reg_tol · A_kk is raised
    // to it. Adding the shortfall to A_kk raises that pivot by exactly as
    // much and the later ones by no less, so a refactor with the first
    // short row shifted settles it; each pass settles one more row.
    const int short_row = o->reg_tol > 0 ? first_small_pivot(w, n, o->reg_tol, false) : -1;
    if (short_row >= 0) {
      const Eigen::VectorXd &d = w.ldlt.pivots();
      int t = 0;
      while (w.perm()[t] != short_row) t++;
      // A hair over, so the raised pivot passes the test it failed.
      w.reg[short_row] += (o->reg_tol * (1.0 + 1e-9)) * w.adiag[short_row] - d[t];
      continue;
    }
    const int *perm = w.perm();
    for (int t = 0; t < w.size; t++) w.rhs[t] = t < n && !w.dep[perm[t]] ? b[perm[t]] : 0.0;
    w.ldlt.solve_in_place(w.rhs);
    for (int t = 0; t < n; t++) x[perm[t]] = w.rhs[t];
    break;
  }
  int count = 0, raised = 0;
  for (int i = 0; i < n; i++) {
    count += w.dep[i];
    raised += !w.dep[i] && w.reg[i] > 0.0;
    if (w.dep[i]) x[i] = 0.0;
  }
  r->dependent = count;
  r->regularised = raised;
  r->iterations = 1;
  return count ? MR_SOLVE_DEPENDENT : MR_SOLVE_OK;
}

} // namespace

extern "C" int mr_eigen_solve(void **ws, const mr_solve_def *o, const mr_csr *A, const double *b,
                              double *x, mr_solve_result *r) {
  try {
    if (!*ws) *ws = new EigenWorkspace();
    return solve(*static_cast<EigenWorkspace *>(*ws), o, A, b, x, r);
  } catch (const std::bad_alloc &) {
    return MR_SOLVE_ERR_NOMEM;
  } catch (...) {
    return MR_SOLVE_ERR_UNAVAILABLE;
  }
}

extern "C" int mr_eigen_reserve(void **ws, int rows) {
  try {
    if (!*ws) *ws = new EigenWorkspace();
    reserve(*static_cast<EigenWorkspace *>(*ws), rows);
    return MR_SOLVE_OK;
  } catch (const std::bad_alloc &) {
    return MR_SOLVE_ERR_NOMEM;
  } catch (...) {
    return MR_SOLVE_ERR_UNAVAILABLE;
  }
}

extern "C" void mr_eigen_free(void *ws) {
  delete static_cast<EigenWorkspace *>(ws);
}

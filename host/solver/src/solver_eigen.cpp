// MR_SOLVE_EIGEN: Eigen's SimplicialLDLT (approximate minimum degree
// ordering, then a sparse LDLᵀ) behind the C interface in
// solver_internal.h. The only C++ in the physics; it is also the oracle the
// C solvers are tested against.
//
// Eigen has no pivot threshold, so dependent rows are found afterwards with
// the C LDLᵀ's rule: a pivot d_k ≤ pivot_tol · A_kk marks its row dependent.
// Such a row is replaced by the identity row (its λ is then 0 and it no
// longer couples to the others, exactly as if it were removed) and the
// matrix factored again. Which row of a dependent set goes depends on the
// ordering, so λ may differ from the C LDLᵀ's, while the forces Jᵀλ agree.
//
// Storage: the ordering, the permuted upper triangle and Eigen's symbolic
// analysis depend only on A's pattern, and replacing a row keeps the
// pattern, so all three are made once per pattern. A call with the pattern
// of the last one only copies numbers and refactors: no allocation.
#include "solver_internal.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
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
  void refactor(const SpMat &upper) { this->template factorize_preordered<true>(upper); }
  const Eigen::VectorXd &pivots() const { return this->m_diag; }
  void solve_in_place(Eigen::VectorXd &v) const
  {
    this->matrixL().solveInPlace(v);
    v = this->m_diag.asDiagonal().inverse() * v;
    this->matrixU().solveInPlace(v);
  }
};

struct EigenWorkspace {
  mr_pattern pattern = {}; // A's pattern the members below were made for
  KeptLDLT ldlt;
  SpMat upper;           // the upper triangle of P A Pᵀ
  std::vector<int> perm; // new → old
  std::vector<int> src;  // upper's value t is A->val[src[t]]
  std::vector<char> dep; // by old index
  Eigen::VectorXd adiag, scale, rhs;
  ~EigenWorkspace() { mr_pattern_free(&pattern); }
};

// The ordering (Eigen's AMD on A's graph) and the permuted upper triangle's
// pattern, each column's rows ascending.
void analyse(EigenWorkspace &w, const mr_csr *A)
{
  const int n = A->n;
  const SpMat full = Eigen::Map<const SpMat>(n, n, A->row_ptr[n], A->row_ptr, A->col, A->val);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(full, order);
  w.perm.assign(order.indices().data(), order.indices().data() + n);
  std::vector<int> inv(n);
  for (int t = 0; t < n; t++)
    inv[w.perm[t]] = t;

  // A is symmetric and stores both triangles: column c of the upper
  // triangle is row perm[c] of A, restricted to new indices ≤ c.
  std::vector<int> outer(n + 1, 0), inner;
  std::vector<std::pair<int, int>> column;
  w.src.clear();
  for (int c = 0; c < n; c++) {
    column.clear();
    for (int q = A->row_ptr[w.perm[c]]; q < A->row_ptr[w.perm[c] + 1]; q++)
      if (inv[A->col[q]] <= c)
        column.emplace_back(inv[A->col[q]], q);
    std::sort(column.begin(), column.end());
    for (const auto &e : column) {
      inner.push_back(e.first);
      w.src.push_back(e.second);
    }
    outer[c + 1] = (int)inner.size();
  }
  w.upper.resize(n, n);
  w.upper.resizeNonZeros(outer[n]);
  std::copy(outer.begin(), outer.end(), w.upper.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), w.upper.innerIndexPtr());
  std::fill(w.upper.valuePtr(), w.upper.valuePtr() + outer[n], 0.0);
  w.ldlt.analyzePattern(w.upper);
  w.dep.resize(n);
  w.adiag.resize(n);
  w.scale.resize(n);
  w.rhs.resize(n);
}

// A's numbers into the upper triangle: a dependent row and column become
// the identity's; with scaled, the others are D^-½ A D^-½'s.
void load(EigenWorkspace &w, const mr_csr *A, bool scaled)
{
  const int *outer = w.upper.outerIndexPtr(), *inner = w.upper.innerIndexPtr();
  double *val = w.upper.valuePtr();
  for (int c = 0; c < A->n; c++) {
    const int oc = w.perm[c];
    for (int t = outer[c]; t < outer[c + 1]; t++) {
      const int orow = w.perm[inner[t]];
      if (w.dep[orow] || w.dep[oc])
        val[t] = inner[t] == c ? 1.0 : 0.0;
      else if (scaled)
        val[t] = w.scale[orow] * A->val[w.src[t]] * w.scale[oc];
      else
        val[t] = A->val[w.src[t]];
    }
  }
}

// The old index of the first row in elimination order whose pivot fails
// the test d ≤ tol · diag, or -1. Only the first is trusted: Eigen goes on
// dividing by the tiny pivot, which spoils every pivot after it.
int first_small_pivot(const EigenWorkspace &w, double tol, bool unit_diag)
{
  const Eigen::VectorXd &d = w.ldlt.pivots();
  for (int t = 0; t < d.size(); t++) {
    const int old = w.perm[t];
    if (!w.dep[old] && !(d[t] > tol * (unit_diag ? 1.0 : w.adiag[old])))
      return old;
  }
  return -1;
}

// An exactly zero pivot stops Eigen before D is complete. Find the row on
// the unit-diagonal matrix S = D^-½ A D^-½ (whose pivots are the ratios
// d_k / A_kk the test uses) shifted by δ I: δ sits well below the
// threshold, so a dependent pivot (≈ δ) still fails the test, and a shift
// only raises the others. δ is kept above rounding so that it makes every
// pivot nonzero. Returns the row, or -1 when none can be found.
int find_zero_pivot(EigenWorkspace &w, const mr_csr *A, double pivot_tol)
{
  const double shift = std::max(1e-3 * pivot_tol, 8.0 * DBL_EPSILON);
  const double threshold = std::max(pivot_tol, 16.0 * shift);
  w.scale = w.adiag.cwiseSqrt().cwiseInverse();
  load(w, A, true);
  w.ldlt.setShift(shift, 1.0);
  w.ldlt.refactor(w.upper);
  if (w.ldlt.info() != Eigen::Success)
    return -1;
  return first_small_pivot(w, threshold, true);
}

int solve(EigenWorkspace &w, const mr_solve_def *o, const mr_csr *A, const double *b, double *x,
          mr_solve_result *r)
{
  const int n = A->n;
  if (!mr_pattern_same(&w.pattern, A)) {
    w.pattern.valid = 0; // until the analysis below is complete
    analyse(w, A);
    if (mr_pattern_keep(&w.pattern, A) != 0)
      return MR_SOLVE_ENOMEM;
  }
  mr_csr_diagonal(A, w.adiag.data());
  for (int i = 0; i < n; i++)
    w.dep[i] = !(w.adiag[i] > DBL_MIN);
  // Each pass that does not solve marks a row, so n + 1 passes end.
  for (int pass = 0; pass <= n; pass++) {
    load(w, A, false);
    w.ldlt.setShift(0.0, 1.0);
    w.ldlt.refactor(w.upper);
    const bool factored = w.ldlt.info() == Eigen::Success;
    int bad = factored ? first_small_pivot(w, o->pivot_tol, false)
                       : find_zero_pivot(w, A, o->pivot_tol);
    if (!factored && bad < 0)
      return MR_SOLVE_NOT_CONVERGED;
    if (bad >= 0) {
      w.dep[bad] = 1;
      continue;
    }
    for (int t = 0; t < n; t++)
      w.rhs[t] = w.dep[w.perm[t]] ? 0.0 : b[w.perm[t]];
    w.ldlt.solve_in_place(w.rhs);
    for (int t = 0; t < n; t++)
      x[w.perm[t]] = w.rhs[t];
    break;
  }
  int count = 0;
  for (int i = 0; i < n; i++) {
    count += w.dep[i];
    if (w.dep[i])
      x[i] = 0.0;
  }
  r->dependent = count;
  r->iterations = 1;
  return count ? MR_SOLVE_DEPENDENT : MR_SOLVE_OK;
}

} // namespace

extern "C" int mr_eigen_solve(void **ws, const mr_solve_def *o, const mr_csr *A, const double *b,
                              double *x, mr_solve_result *r)
{
  try {
    if (!*ws)
      *ws = new EigenWorkspace();
    return solve(*static_cast<EigenWorkspace *>(*ws), o, A, b, x, r);
  } catch (const std::bad_alloc &) {
    return MR_SOLVE_ENOMEM;
  } catch (...) {
    return MR_SOLVE_UNAVAILABLE;
  }
}

extern "C" void mr_eigen_free(void *ws)
{
  delete static_cast<EigenWorkspace *>(ws);
}

// MR_SOLVE_EIGEN: Eigen's SimplicialLDLT (approximate minimum degree
// ordering, then a sparse LDLᵀ) behind the C interface in
// solver_internal.h. The only C++ in the physics; it is also the oracle the
// C solvers are tested against.
//
// Eigen has no pivot threshold, so dependent rows are found afterwards with
// the C LDLᵀ's rule: a pivot d_k ≤ pivot_tol · A_kk marks its row dependent.
// Those rows are removed (λ = 0) and the rest factored again. Which row of
// a dependent set is removed depends on the ordering, so λ may differ from
// the C LDLᵀ's, while the forces Jᵀλ agree.
#include "solver_internal.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cfloat>
#include <new>
#include <vector>

namespace {

using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

struct EigenWorkspace {
    Eigen::SimplicialLDLT<SpMat> ldlt;
    SpMat reduced, scaled;
    std::vector<int> keep;      // reduced index → row of A
    std::vector<Eigen::Triplet<double, int>> triplets;
    Eigen::VectorXd rhs, sol;
};

// The row of M (by M's index) whose pivot fails the test first in the
// factor's elimination order, or -1. Only the first is trusted: Eigen goes
// on dividing by the tiny pivot, which spoils every pivot after it.
int first_small_pivot(const Eigen::SimplicialLDLT<SpMat> &ldlt, const Eigen::VectorXd &diag_of_m, double pivot_tol)
{
    const Eigen::VectorXd d = ldlt.vectorD();
    const auto &idx = ldlt.permutationP().indices();
    int row = -1;
    for (int i = 0; i < diag_of_m.size(); i++)
        if (!(d[idx[i]] > pivot_tol * diag_of_m[i]) && (row < 0 || idx[i] < idx[row]))
            row = i;
    return row;
}

int solve(EigenWorkspace &w, const mr_solve_opts *o, const mr_csr *A, const double *b, double *x,
          mr_solve_result *r)
{
    const int n = A->n;
    std::vector<char> dep(n, 0);
    Eigen::VectorXd adiag = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; i++)
        for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++)
            if (A->col[q] == i)
                adiag[i] = A->val[q];
    for (int i = 0; i < n; i++)
        if (!(adiag[i] > DBL_MIN))
            dep[i] = 1;

    // Each pass that does not solve drops a row, so n + 1 passes end.
    for (int pass = 0; pass <= n; pass++) {
        w.keep.clear();
        std::vector<int> where(n, -1);
        for (int i = 0; i < n; i++)
            if (!dep[i]) {
                where[i] = (int)w.keep.size();
                w.keep.push_back(i);
            }
        const int m = (int)w.keep.size();
        if (m == 0)
            break;
        w.triplets.clear();
        for (int i : w.keep)
            for (int q = A->row_ptr[i]; q < A->row_ptr[i + 1]; q++)
                if (where[A->col[q]] >= 0)
                    w.triplets.emplace_back(where[i], where[A->col[q]], A->val[q]);
        w.reduced.resize(m, m);
        w.reduced.setFromTriplets(w.triplets.begin(), w.triplets.end());
        Eigen::VectorXd mdiag(m);
        for (int t = 0; t < m; t++)
            mdiag[t] = adiag[w.keep[t]];

        w.ldlt.setShift(0.0, 1.0);
        w.ldlt.compute(w.reduced);
        int bad;
        if (w.ldlt.info() == Eigen::Success) {
            bad = first_small_pivot(w.ldlt, mdiag, o->pivot_tol);
        } else {
            // An exactly zero pivot stops Eigen before D is complete. Find
            // the row on the unit-diagonal matrix S = D^-½ M D^-½ (whose
            // pivots are the ratios d_k / M_kk the test uses) shifted by
            // δ I: δ sits well below the threshold, so a dependent pivot
            // (≈ δ) still fails the test, and a shift only raises the
            // others. δ is kept above rounding so that it makes every pivot
            // nonzero.
            double shift = std::max(1e-3 * o->pivot_tol, 8.0 * DBL_EPSILON);
            double threshold = std::max(o->pivot_tol, 16.0 * shift);
            Eigen::VectorXd scale = mdiag.cwiseSqrt().cwiseInverse();
            w.scaled = scale.asDiagonal() * w.reduced * scale.asDiagonal();
            w.ldlt.setShift(shift, 1.0);
            w.ldlt.compute(w.scaled);
            if (w.ldlt.info() != Eigen::Success)
                return MR_SOLVE_NOT_CONVERGED;
            bad = first_small_pivot(w.ldlt, Eigen::VectorXd::Ones(m), threshold);
            if (bad < 0)
                return MR_SOLVE_NOT_CONVERGED;
        }
        if (bad >= 0) {
            dep[w.keep[bad]] = 1;
            continue;
        }
        w.rhs.resize(m);
        for (int t = 0; t < m; t++)
            w.rhs[t] = b[w.keep[t]];
        w.sol = w.ldlt.solve(w.rhs);
        for (int i = 0; i < n; i++)
            x[i] = 0.0;
        for (int t = 0; t < m; t++)
            x[w.keep[t]] = w.sol[t];
        break;
    }
    int count = 0;
    for (int i = 0; i < n; i++) {
        count += dep[i];
        if (dep[i])
            x[i] = 0.0;
    }
    r->dependent = count;
    r->iterations = 1;
    return count ? MR_SOLVE_DEPENDENT : MR_SOLVE_OK;
}

} // namespace

extern "C" int mr_eigen_solve(void **ws, const mr_solve_opts *o, const mr_csr *A, const double *b, double *x,
                              mr_solve_result *r)
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

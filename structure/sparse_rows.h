#pragma once
/// @file sparse_rows.h
/// Row-wise products with the shear building's sparse matrices (M diagonal, K and C
/// tridiagonal, Γ two entries per damper) for the step loop: the CSR arrays of an Eigen
/// row-major SparseMatrix read directly, without the iterator's bookkeeping. A row's sum runs
/// over its nonzeros in column order.

#include <Eigen/SparseCore>

#include <cstdlib>
#include <vector>

namespace structure {

using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// The nonzeros of `dense` (exact zeros dropped) as a compressed row-major matrix.
inline SparseRows sparse_rows(const Eigen::MatrixXd& dense) {
  SparseRows s = dense.sparseView();
  s.makeCompressed();
  return s;
}

/// Σ_j a(row, j)·x[j] over the nonzeros of the row (a must be compressed).
inline double row_dot(const SparseRows& a, int row, const double* x) {
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const double* value = a.valuePtr();
  double s = 0.0;
  for (int k = outer[row]; k < outer[row + 1]; ++k) s += value[k] * x[inner[k]];
  return s;
}

/// A square matrix whose nonzeros all lie on the three central diagonals (a shear building's
/// M, K, C = αM + βK, and M⁻¹K, M⁻¹C with M diagonal), as three arrays; a missing entry is an
/// exact 0. Row i's product l_i x_{i−1} + d_i x_i + u_i x_{i+1} is summed in column order from
/// +0.0, as row_dot sums the compressed row: the exact zeros row_dot skips add nothing to a
/// finite sum (x + ±0 = x, and +0 + ±0 = +0), so the two give the same bits. Without the
/// index indirection and the loop over a row's nonzeros it costs about half as much
/// (docs/step-loop-profile.md).
struct Tridiagonal {
  std::vector<double> lower, diag, upper;  ///< lower[0] and upper[n−1] are 0 (never read)
  int n = 0;
  bool valid = false;  ///< false: the matrix is not square or has a nonzero off the band
};

inline Tridiagonal tridiagonal(const SparseRows& a) {
  Tridiagonal t;
  if (a.rows() != a.cols()) return t;
  t.n = static_cast<int>(a.rows());
  t.lower.assign(t.n, 0.0);
  t.diag.assign(t.n, 0.0);
  t.upper.assign(t.n, 0.0);
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const double* value = a.valuePtr();
  for (int i = 0; i < t.n; ++i) {
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const int j = inner[k];
      if (j == i - 1) t.lower[i] = value[k];
      else if (j == i) t.diag[i] = value[k];
      else if (j == i + 1) t.upper[i] = value[k];
      else return Tridiagonal{};  // off the band: not tridiagonal
    }
  }
  t.valid = true;
  return t;
}

/// Σ_j t(row, j)·x[j] for a valid Tridiagonal: the same bits as row_dot of its sparse rows.
inline double tri_dot(const Tridiagonal& t, int row, const double* x) {
  double s = 0.0;
  if (row > 0) s += t.lower[row] * x[row - 1];
  s += t.diag[row] * x[row];
  if (row + 1 < t.n) s += t.upper[row] * x[row + 1];
  return s;
}

}  // namespace structure

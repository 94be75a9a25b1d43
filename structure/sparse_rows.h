#pragma once
/// @file sparse_rows.h
/// Row-wise products with the shear building's sparse matrices (M diagonal, K and C
/// tridiagonal, Γ two entries per damper) for the step loop: the CSR arrays of an Eigen
/// row-major SparseMatrix read directly, without the iterator's bookkeeping. A row's sum runs
/// over its nonzeros in column order.

#include <Eigen/SparseCore>

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

}  // namespace structure

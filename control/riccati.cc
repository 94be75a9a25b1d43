#include "control/riccati.h"

#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" {
// SLICOT SB02OD (Fortran 77; gfortran passes character lengths as trailing hidden arguments).
void sb02od_(const char* dico, const char* jobb, const char* fact, const char* uplo, const char* jobl,
             const char* sort, const int* n, const int* m, const int* p, double* a, const int* lda, double* b,
             const int* ldb, double* q, const int* ldq, double* r, const int* ldr, double* l, const int* ldl,
             double* rcond, double* x, const int* ldx, double* alfar, double* alfai, double* beta, double* s,
             const int* lds, double* t, const int* ldt, double* u, const int* ldu, const double* tol, int* iwork,
             double* dwork, const int* ldwork, int* bwork, int* info, std::size_t, std::size_t, std::size_t,
             std::size_t, std::size_t, std::size_t);
}

namespace control {

Eigen::MatrixXd solve_dare(const Eigen::MatrixXd& a_in, const Eigen::MatrixXd& b_in, const Eigen::MatrixXd& q_in,
                           const Eigen::MatrixXd& r_in) {
  const int n = static_cast<int>(a_in.rows()), m = static_cast<int>(b_in.cols()), p = 1;
  if (a_in.cols() != n || b_in.rows() != n || q_in.rows() != n || q_in.cols() != n || r_in.rows() != m || r_in.cols() != m)
    throw std::invalid_argument("solve_dare: matrix sizes do not match");
  Eigen::MatrixXd a = a_in, b = b_in, q = 0.5 * (q_in + q_in.transpose()), r = 0.5 * (r_in + r_in.transpose());
  Eigen::MatrixXd l(1, 1), x(n, n);
  const int nn = 2 * n, nnm = 2 * n + m;
  Eigen::VectorXd alfar(nn), alfai(nn), beta(nn);
  Eigen::MatrixXd s(nnm, nnm), t(nnm, nn), u(nn, nn);
  const int liwork = std::max({1, m, nn});
  std::vector<int> iwork(liwork), bwork(nn);
  const int ldwork = std::max({7 * (2 * n + 1) + 16, 16 * n, 2 * n + m, 3 * m}) * 4;
  std::vector<double> dwork(ldwork);
  const int one = 1;
  const double tol = 0.0;
  double rcond = 0.0;
  int info = 0;
  sb02od_("D", "B", "N", "U", "Z", "S", &n, &m, &p, a.data(), &n, b.data(), &n, q.data(), &n, r.data(), &m, l.data(),
          &one, &rcond, x.data(), &n, alfar.data(), alfai.data(), beta.data(), s.data(), &nnm, t.data(), &nnm, u.data(),
          &nn, &tol, iwork.data(), dwork.data(), &ldwork, bwork.data(), &info, 1, 1, 1, 1, 1, 1);
  if (info != 0) throw std::runtime_error("SLICOT SB02OD failed to solve the Riccati equation (INFO = " + std::to_string(info) + ")");
  return 0.5 * (x + x.transpose());
}

void discretize_zoh(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double dt, Eigen::MatrixXd& ad,
                    Eigen::MatrixXd& bd) {
  const Eigen::Index n = a.rows(), m = b.cols();
  Eigen::MatrixXd big = Eigen::MatrixXd::Zero(n + m, n + m);
  big.topLeftCorner(n, n) = a * dt;
  big.topRightCorner(n, m) = b * dt;
  const Eigen::MatrixXd e = big.exp();
  ad = e.topLeftCorner(n, n);
  bd = e.topRightCorner(n, m);
}

Eigen::MatrixXd lqr_gain(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const Eigen::MatrixXd& q,
                         const Eigen::MatrixXd& r) {
  const Eigen::MatrixXd x = solve_dare(a, b, q, r);
  return (r + b.transpose() * x * b).ldlt().solve(b.transpose() * x * a);
}

Eigen::MatrixXd kalman_gain(const Eigen::MatrixXd& a, const Eigen::MatrixXd& c, const Eigen::MatrixXd& gwg,
                            const Eigen::MatrixXd& v) {
  const Eigen::MatrixXd p = solve_dare(a.transpose(), c.transpose(), gwg, v);
  const Eigen::MatrixXd s = c * p * c.transpose() + v;
  return s.ldlt().solve(c * p).transpose();  // L = P C' S^-1 (S symmetric)
}

}  // namespace control

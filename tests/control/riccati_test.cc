// SLICOT SB02OD through control/riccati.h against closed forms and the Riccati residual.
#include "control/riccati.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

TEST(Riccati, ScalarDareClosedForm) {
  // x = a²x - a²b²x²/(r + b²x) + q  ->  b²x² + (r - a²r - q b²) x - q r = 0
  const double a = 1.2, b = 0.5, q = 2.0, r = 0.3;
  const double bb = b * b, c1 = r - a * a * r - q * bb;
  const double x = (-c1 + std::sqrt(c1 * c1 + 4 * bb * q * r)) / (2 * bb);
  const Eigen::MatrixXd sol = control::solve_dare(Eigen::MatrixXd::Constant(1, 1, a), Eigen::MatrixXd::Constant(1, 1, b),
                                                  Eigen::MatrixXd::Constant(1, 1, q), Eigen::MatrixXd::Constant(1, 1, r));
  EXPECT_NEAR(sol(0, 0), x, 1e-10 * x);
}

TEST(Riccati, DiscretizedOscillatorResidualAndStability) {
  // 2-dof shear building, sampled at 1024 Hz: residual of the DARE and |eig(A - BK)| < 1.
  Eigen::MatrixXd ac(4, 4), bc(4, 1);
  ac << 0, 0, 1, 0, 0, 0, 0, 1, -1600, 800, -0.8, 0.4, 800, -800, 0.4, -0.4;
  bc << 0, 0, -50, 0;
  Eigen::MatrixXd ad, bd;
  control::discretize_zoh(ac, bc, 1.0 / 1024, ad, bd);
  EXPECT_NEAR(ad(0, 0), 1.0 - 1600.0 / 2 / 1024 / 1024, 1e-6);  // e^{A dt} ≈ I + A dt + A² dt²/2
  const Eigen::MatrixXd q = Eigen::MatrixXd::Identity(4, 4), r = Eigen::MatrixXd::Constant(1, 1, 0.01);
  const Eigen::MatrixXd x = control::solve_dare(ad, bd, q, r);
  const Eigen::MatrixXd res =
      ad.transpose() * x * ad - ad.transpose() * x * bd * (r + bd.transpose() * x * bd).inverse() * bd.transpose() * x * ad + q - x;
  EXPECT_LT(res.norm(), 1e-8 * x.norm());
  const Eigen::MatrixXd k = control::lqr_gain(ad, bd, q, r);
  const Eigen::VectorXcd ev = (ad - bd * k).eigenvalues();
  for (int i = 0; i < ev.size(); ++i) EXPECT_LT(std::abs(ev[i]), 1.0);
  // Kalman: the estimator error dynamics (I - LC) A are stable too.
  Eigen::MatrixXd c(1, 4);
  c << -1600, 800, -0.8, 0.4;
  const Eigen::MatrixXd l = control::kalman_gain(ad, c, bd * bd.transpose(), Eigen::MatrixXd::Constant(1, 1, 1.0));
  const Eigen::VectorXcd ee = ((Eigen::MatrixXd::Identity(4, 4) - l * c) * ad).eigenvalues();
  for (int i = 0; i < ee.size(); ++i) EXPECT_LT(std::abs(ee[i]), 1.0);
}

}  // namespace

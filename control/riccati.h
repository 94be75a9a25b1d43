#pragma once
/// @file riccati.h
/// Discrete-time algebraic Riccati equations through SLICOT's SB02OD (Debian libslicot0;
/// generalized Schur method on the extended pencil, Van Dooren 1981), and what the
/// clipped-optimal law builds on them: the ZOH discretization of a continuous model (Eigen's
/// matrix exponential), the discrete LQR gain and the steady-state Kalman gain.
///   DARE:  X = A'XA - A'XB (R + B'XB)^-1 B'XA + Q

#include <Eigen/Dense>

namespace control {

/// Stabilizing solution X of the DARE. @throws std::runtime_error with SB02OD's INFO on failure.
Eigen::MatrixXd solve_dare(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const Eigen::MatrixXd& q,
                           const Eigen::MatrixXd& r);

/// ZOH discretization of dx/dt = A x + B u over dt: Ad = e^{A dt}, Bd = ∫0^dt e^{A s} ds B.
void discretize_zoh(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double dt_s, Eigen::MatrixXd& ad,
                    Eigen::MatrixXd& bd);

/// Discrete LQR: u_k = -K x_k minimizing Σ x'Qx + u'Ru for x_{k+1} = A x + B u.
Eigen::MatrixXd lqr_gain(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const Eigen::MatrixXd& q,
                         const Eigen::MatrixXd& r);

/// Steady-state Kalman filter of x_{k+1} = A x + B u + G w, y = C x + D u + v with
/// cov(w) = W, cov(v) = V: the a-priori covariance P (DARE of the dual) and the measurement
/// update gain L = P C' (C P C' + V)^-1 (x̂_k|k = x̂_k|k-1 + L (y - C x̂_k|k-1 - D u)).
Eigen::MatrixXd kalman_gain(const Eigen::MatrixXd& a, const Eigen::MatrixXd& c, const Eigen::MatrixXd& gwg,
                            const Eigen::MatrixXd& v);

}  // namespace control

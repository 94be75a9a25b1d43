// KR-α (Kolay & Ricles 2014) against its closed-form spectral properties, CR, and stability on
// a stiff 20-story building. The closed form is written here independently of the
// implementation: the amplification matrix of the method for a damped SDOF, built from the
// paper's scalar recurrences, and its eigenvalues.
#include "test_buildings.h"
#include "structure/cr_integrator.h"
#include "structure/ground_motion.h"
#include "structure/integrator.h"
#include "structure/kr_alpha_integrator.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <complex>
#include <cstdio>

namespace structure {
namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kRecords = PROJECT_RECORDS_DIR;

// ---- Closed form (independent of kr_alpha_integrator.cc) ----------------------------------
// SDOF ẍ + 2ξω ẋ + ω² x = 0, Ω = ωΔt, state s_n = [x_n, Δt·ẋ_n, Δt²·ẍ_n], s_{n+1} = A s_n with
//   D = 1 + 2ξΩγ + βΩ²,  a1 = 1/D,  a3 = (α_m + 2ξΩ α_f γ + α_f β Ω²)/D
//   x_{n+1}    = x_n + Δt ẋ_n + (½ + γ) a1 Δt² ẍ_n
//   Δt ẋ_{n+1} = Δt ẋ_n + a1 Δt² ẍ_n
//   (1 − a3) Δt² ẍ_{n+1} = −a3 Δt² ẍ_n − 2ξΩ[(1 − α_f) Δt ẋ_{n+1} + α_f Δt ẋ_n]
//                          − Ω²[(1 − α_f) x_{n+1} + α_f x_n]
Eigen::Matrix3d amplification(double rho, double big_omega, double xi) {
  const double am = (2 * rho - 1) / (rho + 1), af = rho / (rho + 1);
  const double g = 0.5 - am + af, b = 0.25 * (1 - am + af) * (1 - am + af);
  const double c = 2 * xi * big_omega, k = big_omega * big_omega;
  const double d = 1 + c * g + k * b;
  const double a1 = 1 / d, a3 = (am + c * af * g + k * af * b) / d;
  Eigen::Matrix3d x_row_v_row;
  Eigen::RowVector3d x_next(1, 1, (0.5 + g) * a1), v_next(0, 1, a1);
  Eigen::RowVector3d rhs = -a3 * Eigen::RowVector3d(0, 0, 1) - c * ((1 - af) * v_next + af * Eigen::RowVector3d(0, 1, 0)) -
                           k * ((1 - af) * x_next + af * Eigen::RowVector3d(1, 0, 0));
  Eigen::Matrix3d a;
  a.row(0) = x_next;
  a.row(1) = v_next;
  a.row(2) = rhs / (1 - a3);
  return a;
}

struct Spectral {
  double period_elongation;  // T̄/T − 1
  double damping_ratio;      // ξ̄ (numerical + physical)
};

// From a principal root λ = exp(Ω̄(−ξ̄ + i√(1 − ξ̄²))): Ω̄ = |ln λ|, ξ̄ = −Re(ln λ)/Ω̄, T̄/T = Ω/Ω̄.
Spectral from_root(std::complex<double> lambda, double big_omega) {
  const std::complex<double> l = std::log(lambda);
  const double bar = std::abs(l);
  return {big_omega / bar - 1.0, -l.real() / bar};
}

Spectral closed_form(double rho, double big_omega, double xi) {
  const Eigen::EigenSolver<Eigen::Matrix3d> es(amplification(rho, big_omega, xi));
  std::complex<double> principal(0, 0);
  for (int i = 0; i < 3; ++i)
    if (es.eigenvalues()(i).imag() > principal.imag()) principal = es.eigenvalues()(i);
  return from_root(principal, big_omega);
}

double spectral_radius(double rho, double big_omega, double xi) {
  // Similar matrix for the state [x, Δt·ẋ, Δt²·ẍ/Ω²] (same eigenvalues, well scaled at large Ω).
  const Eigen::Vector3d scale(1.0, 1.0, big_omega * big_omega);
  const Eigen::Matrix3d a = scale.cwiseInverse().asDiagonal() * amplification(rho, big_omega, xi) * scale.asDiagonal();
  const Eigen::EigenSolver<Eigen::Matrix3d> es(a);
  return es.eigenvalues().cwiseAbs().maxCoeff();
}

using test_buildings::sdof;

// Measured from the integrator: free vibration from x0 = 1, then the principal pair of the
// sequence by Prony's method (least squares x_{n+1} = p x_n − q x_{n−1}) on steps [skip, skip + len],
// after the spurious root (|λ₃| ≤ 0.5 at these Ω) has died out.
Spectral measured(double rho, double big_omega) {
  const double m = 0.2, k = 150.0, omega = std::sqrt(k / m);
  const ShearBuilding b(sdof(m, k, 0.0));
  KrAlphaIntegrator kr(b, big_omega / omega, rho);
  kr.initialize(Eigen::VectorXd::Constant(1, 1.0), Eigen::VectorXd::Zero(1), 0.0, Eigen::VectorXd(0));
  const int skip = 80, len = 60;
  std::vector<double> x{kr.displacement_in()(0)};
  for (int n = 0; n < skip + len + 1; ++n) {
    kr.predict();
    kr.complete(0.0, Eigen::VectorXd(0));
    x.push_back(kr.displacement_in()(0));
  }
  Eigen::MatrixXd a(len, 2);
  Eigen::VectorXd y(len);
  for (int r = 0; r < len; ++r) {
    const int n = skip + r;
    a(r, 0) = x[n];
    a(r, 1) = -x[n - 1];
    y(r) = x[n + 1];
  }
  const Eigen::Vector2d pq = a.colPivHouseholderQr().solve(y);
  const double p = pq(0), q = pq(1);
  EXPECT_LT(p * p, 4 * q) << "the fitted pair is not oscillatory";
  const std::complex<double> lambda(0.5 * p, 0.5 * std::sqrt(std::max(0.0, 4 * q - p * p)));
  return from_root(lambda, big_omega);
}

// The closed form itself against properties the paper states: ρ∞ = 1 is non-dissipative with the
// trapezoidal period elongation Ω/(2·atan(Ω/2)) − 1, and the spectral radius tends to ρ∞.
TEST(KrAlphaClosedForm, MatchesStatedProperties) {
  for (double big_omega : {0.1, 0.5, 1.0}) {
    const Spectral s = closed_form(1.0, big_omega, 0.0);
    EXPECT_NEAR(s.damping_ratio, 0.0, 1e-12);
    EXPECT_NEAR(s.period_elongation, big_omega / (2 * std::atan(big_omega / 2)) - 1, 1e-12);
  }
  for (double rho : {1.0, 0.5, 0.0}) {
    std::printf("[ measured ] closed-form spectral radius at Omega 1e6, rho_inf %.1f: %.6f\n", rho, spectral_radius(rho, 1e6, 0.0));
    EXPECT_NEAR(spectral_radius(rho, 1e6, 0.0), rho, 1e-3) << rho;
  }
}

// Period elongation and numerical damping ratio of free vibration, measured from the
// integrator's output, within 1 % of the closed form (absolute 1e-6 where the value is ~0).
TEST(KrAlphaIntegrator, SdofSpectralPropertiesMatchClosedForm) {
  for (double rho : {1.0, 0.5, 0.0}) {
    for (double big_omega : {0.1, 0.5, 1.0}) {
      const Spectral cf = closed_form(rho, big_omega, 0.0);
      const Spectral me = measured(rho, big_omega);
      std::printf("[ measured ] KR-alpha rho_inf %.1f, Omega %.1f: period elongation %.6e (closed form %.6e), "
                  "numerical damping ratio %.6e (closed form %.6e)\n",
                  rho, big_omega, me.period_elongation, cf.period_elongation, me.damping_ratio, cf.damping_ratio);
      EXPECT_NEAR(me.period_elongation, cf.period_elongation, std::max(0.01 * std::abs(cf.period_elongation), 1e-6));
      EXPECT_NEAR(me.damping_ratio, cf.damping_ratio, std::max(0.01 * std::abs(cf.damping_ratio), 1e-6));
      if (rho < 1) {
        EXPECT_GT(me.damping_ratio, 1e-5) << "rho_inf < 1 must dissipate";
      }
    }
  }
}

TEST(KrAlphaIntegrator, ParametersAndMatrices) {
  const KrAlphaParameters p = KrAlphaParameters::from_rho_inf(0.5);
  EXPECT_NEAR(p.alpha_m, 0.0, 1e-15);
  EXPECT_NEAR(p.alpha_f, 1.0 / 3, 1e-15);
  EXPECT_NEAR(p.gamma, 0.5 + 1.0 / 3, 1e-15);
  EXPECT_NEAR(p.beta, 0.25 * 16.0 / 9, 1e-15);
  BuildingParams bp;
  bp.story_mass_kip_s2_per_in = {0.2, 0.3};
  bp.story_stiffness_kip_per_in = {150, 100};
  const ShearBuilding b(bp);
  const double dt = 0.01;
  KrAlphaIntegrator kr(b, dt, 0.5);
  const Eigen::MatrixXd lhs = b.mass() + p.gamma * dt * b.damping() + p.beta * dt * dt * b.stiffness();
  EXPECT_LT((lhs * kr.alpha1() - b.mass()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((kr.alpha2() - (0.5 + p.gamma) * kr.alpha1()).cwiseAbs().maxCoeff(), 1e-15);
  const Eigen::MatrixXd rhs3 = p.alpha_m * b.mass() + p.alpha_f * p.gamma * dt * b.damping() +
                               p.alpha_f * p.beta * dt * dt * b.stiffness();
  EXPECT_LT((lhs * kr.alpha3() - rhs3).cwiseAbs().maxCoeff(), 1e-14);
  // ρ∞ = 1: α₃ = ½I and α₁ = CR's α.
  KrAlphaIntegrator one(b, dt, 1.0);
  EXPECT_LT((one.alpha3() - 0.5 * Eigen::MatrixXd::Identity(2, 2)).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((one.alpha1() - CrIntegrator(b, dt).alpha()).cwiseAbs().maxCoeff(), 1e-14);
}

BuildingParams three_story_with_damper() { return test_buildings::uniform_three_story(0.2, 150, true); }

// ρ∞ = 1 reproduces CR (see kr_alpha_integrator.h) with a nonlinear damper force fed back at
// x_{n+1}: El Centro 10 s, viscous-friction force 2·tanh(ẋ_drum/0.5) kip. Bound 1e-9 of the peak.
TEST(KrAlphaIntegrator, RhoOneReproducesCr) {
  const GroundMotion gm = read_ground_motion(kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2");
  const ShearBuilding b(three_story_with_damper());
  const double dt = 1.0 / 1024;
  CrIntegrator cr(b, dt);
  KrAlphaIntegrator kr(b, dt, 1.0);
  Eigen::VectorXd f_cr = Eigen::VectorXd::Zero(1), f_kr = Eigen::VectorXd::Zero(1);
  cr.initialize(gm.accel_in_per_s2(0), f_cr);
  kr.initialize(gm.accel_in_per_s2(0), f_kr);
  double diff = 0.0, peak = 0.0;
  for (long n = 1; n <= 10 * 1024; ++n) {
    cr.predict();
    kr.predict();
    f_cr(0) = 2.0 * std::tanh(b.damper_gamma().col(0).dot(cr.next_velocity_in_per_s()) / 0.5);
    f_kr(0) = 2.0 * std::tanh(b.damper_gamma().col(0).dot(kr.next_velocity_in_per_s()) / 0.5);
    cr.complete(gm.accel_in_per_s2(n * dt), f_cr);
    kr.complete(gm.accel_in_per_s2(n * dt), f_kr);
    diff = std::max(diff, (cr.displacement_in() - kr.displacement_in()).cwiseAbs().maxCoeff());
    peak = std::max(peak, cr.displacement_in().cwiseAbs().maxCoeff());
  }
  std::printf("[ measured ] KR-alpha(rho_inf 1) vs CR, 3-story + friction, El Centro 10 s: max |dx| %.2e in, peak %.3f in\n",
              diff, peak);
  EXPECT_LT(diff, 1e-9 * peak);
}

// A deliberately stiff 20-story building: 0.03 kip·s²/in floors, 60 000 kip/in stories
// (T₁ = 0.058 s, ω₂₀Δt = 2.75 at Δt = 1/1024 s), 2 % Rayleigh on modes 1–2.
BuildingParams stiff_twenty_story(double k) {
  BuildingParams p;
  p.story_mass_kip_s2_per_in.assign(20, 0.03);
  p.story_stiffness_kip_per_in.assign(20, k);
  p.damping_modes = {1, 2};
  p.damping_ratios = {0.02, 0.02};
  return p;
}

// Stability at Δt = 1/1024 with ρ∞ < 1 where ω_max·Δt > 2 (the central-difference method
// diverges there): (a) under El Centro the response stays bounded and its peak drifts equal
// CR's within 3 % (the two methods' period elongations at Ω₁ = 0.105 differ by up to 0.4 %,
// which over 15 s = 260 periods of mode 1 moves the peaks by ~2 %); (b) see below.
TEST(KrAlphaIntegrator, StiffTwentyStoryStableAtHybridRate) {
  const double dt = 1.0 / 1024;
  const ShearBuilding b(stiff_twenty_story(60000.0));
  const ModalProperties& modal = b.modal();
  const double omega_max = modal.omega_rad_per_s(19);
  std::printf("[ measured ] stiff 20-story: T1 %.4f s, omega_max*dt %.2f\n", modal.period_s(0), omega_max * dt);
  ASSERT_GT(omega_max * dt, 2.0);

  const GroundMotion gm = read_ground_motion(kRecords + "/ImperialValley1940_ElCentroArray9_180_NS_RSN6.AT2");
  for (double rho : {0.5, 0.0}) {
    auto kr = make_integrator(b, dt, {"kr_alpha", rho});
    auto cr = make_integrator(b, dt, {"cr", 1.0});
    kr->initialize(gm.accel_in_per_s2(0), Eigen::VectorXd(0));
    cr->initialize(gm.accel_in_per_s2(0), Eigen::VectorXd(0));
    Eigen::VectorXd peak_kr = Eigen::VectorXd::Zero(20), peak_cr = Eigen::VectorXd::Zero(20);
    for (long n = 1; n <= 15 * 1024; ++n) {
      for (auto* in : {kr.get(), cr.get()}) {
        in->predict();
        in->complete(gm.accel_in_per_s2(n * dt), Eigen::VectorXd(0));
      }
      peak_kr = peak_kr.cwiseMax(b.interstory_drift(kr->displacement_in()).cwiseAbs());
      peak_cr = peak_cr.cwiseMax(b.interstory_drift(cr->displacement_in()).cwiseAbs());
    }
    ASSERT_TRUE(peak_kr.allFinite());
    const double rel = ((peak_kr - peak_cr).cwiseAbs().array() / peak_cr.array()).maxCoeff();
    std::printf("[ measured ] stiff 20-story, El Centro 15 s, rho_inf %.1f: story-1 peak drift %.5f in (CR %.5f), "
                "max relative difference %.2e\n", rho, peak_kr(0), peak_cr(0), rel);
    EXPECT_LT(rel, 0.03);

    // (b) Highest mode from rest at x₀ = φ₂₀: its modal coordinate q_n = φ₂₀ᵀM x_n must follow
    // the closed-form SDOF recurrence s_{n+1} = A(Ω₂₀, ξ₂₀) s_n (ξ₂₀ its Rayleigh ratio), and so
    // decay like the spectral radius^n.
    const double w = omega_max;
    const double xi = b.rayleigh_alpha() / (2 * w) + b.rayleigh_beta() * w / 2;
    const Eigen::Matrix3d amp = amplification(rho, w * dt, xi);
    Eigen::Vector3d state(1.0, 0.0, -w * w * dt * dt);  // [q, Δt q̇, Δt² q̈] at rest, q₀ = 1
    KrAlphaIntegrator free(b, dt, rho);
    free.initialize(modal.mode_shapes.col(19), Eigen::VectorXd::Zero(20), 0.0, Eigen::VectorXd(0));
    const Eigen::VectorXd phi_m = b.mass() * modal.mode_shapes.col(19);
    double err = 0.0;
    const int steps = 40;
    for (int n = 1; n <= steps; ++n) {
      free.predict();
      free.complete(0.0, Eigen::VectorXd(0));
      state = amp * state;
      err = std::max(err, std::abs(phi_m.dot(free.displacement_in()) - state(0)));
    }
    const double radius = spectral_radius(rho, w * dt, xi);
    const double q_end = std::abs(phi_m.dot(free.displacement_in()));
    std::printf("[ measured ] highest mode (Omega %.2f, xi %.3f), rho_inf %.1f: |q_40|/q_0 %.3e, spectral radius^40 "
                "%.3e, max deviation from the closed-form recurrence %.2e\n", w * dt, xi, rho, q_end, std::pow(radius, steps), err);
    EXPECT_LT(err, 1e-9);
    EXPECT_LT(q_end, 2.0 * std::pow(radius, steps));
  }
}

TEST(KrAlphaIntegrator, MisuseThrows) {
  const ShearBuilding b(sdof(0.2, 150, 0.02));
  EXPECT_THROW(KrAlphaIntegrator(b, 0.0, 0.5), std::invalid_argument);
  EXPECT_THROW(KrAlphaIntegrator(b, 0.01, 1.5), std::invalid_argument);
  EXPECT_THROW(KrAlphaIntegrator(b, 0.01, -0.1), std::invalid_argument);
  EXPECT_THROW(make_integrator(b, 0.01, {"newmark", 0.5}), std::invalid_argument);
  KrAlphaIntegrator kr(b, 0.01, 0.5);
  EXPECT_THROW(kr.predict(), std::logic_error);
  kr.initialize(0.0, Eigen::VectorXd(0));
  EXPECT_THROW(kr.complete(0.0, Eigen::VectorXd(0)), std::logic_error);
  kr.predict();
  EXPECT_THROW(kr.complete(0.0, Eigen::VectorXd::Zero(2)), std::invalid_argument);
  kr.complete(0.0, Eigen::VectorXd(0));
  EXPECT_EQ(kr.step_index(), 1);
  EXPECT_EQ(make_integrator(b, 0.01, {"kr_alpha", 0.0})->name(), "kr_alpha");
  EXPECT_EQ(make_integrator(b, 0.01, {"cr", 0.0})->name(), "cr");
}

}  // namespace
}  // namespace structure

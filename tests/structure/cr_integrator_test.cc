#include "test_buildings.h"
#include "structure/cr_integrator.h"
#include "structure/energy.h"
#include "structure/kr_alpha_integrator.h"
#include "structure/ground_motion.h"

#include "sdof_closed_form.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>

// ---- Allocation counter: malloc is interposed for the whole test binary (glibc only) and
// forwards to glibc's own allocator. Counting is switched on only around the code under test.
#if defined(__GLIBC__)
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* __libc_realloc(void* ptr, std::size_t size);
extern "C" void* __libc_calloc(std::size_t n, std::size_t size);
namespace {
std::atomic<bool> g_count_allocations{false};
std::atomic<long> g_allocations{0};
void note_allocation() {
  if (g_count_allocations.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace
extern "C" void* malloc(std::size_t size) {
  note_allocation();
  return __libc_malloc(size);
}
extern "C" void* realloc(void* ptr, std::size_t size) {
  note_allocation();
  return __libc_realloc(ptr, size);
}
extern "C" void* calloc(std::size_t n, std::size_t size) {
  note_allocation();
  return __libc_calloc(n, size);
}
#define STRUCTURE_CAN_COUNT_ALLOCATIONS 1
#endif

namespace structure {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDt = 1.0 / 1024;  // the hybrid-simulation rate

using test_buildings::sdof;

// Max |x_CR − x_exact| over [0, t_end] for SDOF free vibration from (x0, v0) with step dt.
double sdof_free_vibration_error(double dt, double t_end, double x0, double v0) {
  const double m = 0.2, k = 150.0, zeta = 0.05;
  const ShearBuilding b(sdof(m, k, zeta));
  const testing::Sdof exact{std::sqrt(k / m), zeta};
  CrIntegrator cr(b, dt);
  cr.initialize(Eigen::VectorXd::Constant(1, x0), Eigen::VectorXd::Constant(1, v0), 0.0, Eigen::VectorXd(0));
  double err = 0.0;
  const long steps = std::lround(t_end / dt);
  for (long n = 1; n <= steps; ++n) {
    cr.predict();
    cr.complete(0.0, Eigen::VectorXd(0));
    err = std::max(err, std::abs(cr.displacement_in()(0) - exact.free_disp(cr.time_s(), x0, v0)));
  }
  return err;
}

// Error model of CR for a linear SDOF (see cr_integrator.h): its displacement recurrence is
// the trapezoidal rule's (period elongation ΔT/T ≈ (ωΔt)²/12, so a phase error of
// ω·t·(ωΔt)²/12 rad after time t), plus a start-up error ½Δt²·a₀ in x₁ that persists as an
// oscillation of amplitude ≈ ½Δt²|a₀|/sin(ωΔt) ≈ ½ωΔt·x0 when a₀ = −ω²x0.
double phase_error_bound(double omega, double dt, double t_end, double amplitude) {
  return omega * t_end * std::pow(omega * dt, 2) / 12.0 * amplitude;
}

// From an initial velocity (a₀ = 0): only the phase error. Bound: 1.2 × the estimate.
TEST(CrIntegrator, SdofFreeVibrationFromVelocityMatchesClosedForm) {
  const double omega = std::sqrt(150.0 / 0.2), v0 = 10.0, t_end = 3.0;
  const double bound = 1.2 * phase_error_bound(omega, kDt, t_end, v0 / omega);
  const double err = sdof_free_vibration_error(kDt, t_end, 0.0, v0);
  std::printf("[ measured ] CR SDOF free vibration from v0 = 10 in/s, dt = 1/1024 s, 3 s: max error %.3e in "
              "(%.4f%% of amplitude %.4f in), bound %.3e in\n", err, 100 * err / (v0 / omega), v0 / omega, bound);
  EXPECT_LT(err, bound);
}

// From an initial displacement (a₀ = −ω²x0 ≠ 0): start-up error + phase error, × 1.2.
TEST(CrIntegrator, SdofFreeVibrationFromDisplacementMatchesClosedForm) {
  const double omega = std::sqrt(150.0 / 0.2), x0 = 1.0, t_end = 3.0;
  const double startup = 0.5 * kDt * kDt * omega * omega * x0 / std::sin(omega * kDt);
  const double bound = 1.2 * (startup + phase_error_bound(omega, kDt, t_end, x0));
  const double err = sdof_free_vibration_error(kDt, t_end, x0, 0.0);
  std::printf("[ measured ] CR SDOF free vibration from x0 = 1 in, dt = 1/1024 s, 3 s: max error %.3e in, "
              "bound %.3e in (start-up part %.3e)\n", err, bound, startup);
  EXPECT_LT(err, bound);
}

// Convergence: second order when a₀ = 0 (error ratio ~4 for Δt halved, accepted 3.6 to 4.4);
// first order (ratio ~2, accepted 1.8 to 2.2) from the start-up error when a₀ ≠ 0.
TEST(CrIntegrator, SdofConvergenceOrder) {
  const double from_v = sdof_free_vibration_error(1.0 / 256, 2.0, 0.0, 10.0) /
                        sdof_free_vibration_error(1.0 / 512, 2.0, 0.0, 10.0);
  const double from_x = sdof_free_vibration_error(1.0 / 256, 2.0, 1.0, 0.0) /
                        sdof_free_vibration_error(1.0 / 512, 2.0, 1.0, 0.0);
  std::printf("[ measured ] CR error ratio for dt halved: %.3f from v0 (a0 = 0), %.3f from x0 (a0 != 0)\n",
              from_v, from_x);
  EXPECT_GT(from_v, 3.6);
  EXPECT_LT(from_v, 4.4);
  EXPECT_GT(from_x, 1.8);
  EXPECT_LT(from_x, 2.2);
}

// Harmonic ground acceleration 0.3 g at 3 Hz (ω = 4.36 Hz), from rest (a₀ = 0), 4 s. Bound:
// 1.2 × the phase-error estimate at the natural frequency applied to the peak response (the
// transient), and second-order convergence (error ratio 3.6 to 4.4 for Δt halved).
double sdof_harmonic_error(double dt, double* peak_out) {
  const double m = 0.2, k = 150.0, zeta = 0.05;
  const ShearBuilding b(sdof(m, k, zeta));
  const testing::Sdof exact{std::sqrt(k / m), zeta};
  const double a = 0.3 * kGravity_in_per_s2, big_omega = 2 * kPi * 3.0, t_end = 4.0;
  CrIntegrator cr(b, dt);
  cr.initialize(0.0, Eigen::VectorXd(0));
  double err = 0.0, peak = 0.0;
  for (long n = 1; n <= std::lround(t_end / dt); ++n) {
    cr.predict();
    const double t = n * dt;
    cr.complete(a * std::sin(big_omega * t), Eigen::VectorXd(0));
    const double xe = exact.harmonic_disp(t, a, big_omega);
    err = std::max(err, std::abs(cr.displacement_in()(0) - xe));
    peak = std::max(peak, std::abs(xe));
  }
  if (peak_out) *peak_out = peak;
  return err;
}

TEST(CrIntegrator, SdofHarmonicMatchesClosedForm) {
  double peak = 0.0;
  const double err = sdof_harmonic_error(kDt, &peak);
  const double bound = 1.2 * phase_error_bound(std::sqrt(150.0 / 0.2), kDt, 4.0, peak);
  const double ratio = sdof_harmonic_error(1.0 / 512, nullptr) / err;
  std::printf("[ measured ] CR SDOF harmonic: max error %.3e in = %.4f%% of peak %.4f in, bound %.3e in; "
              "error ratio dt 1/512 vs 1/1024: %.3f\n", err, 100 * err / peak, peak, bound, ratio);
  EXPECT_LT(err, bound);
  EXPECT_GT(ratio, 3.6);
  EXPECT_LT(ratio, 4.4);
}

// Three-story free vibration vs modal superposition (Rayleigh damping is classical, so each
// mode is an exact SDOF free vibration). Started from velocities only (a₀ = 0). Bound: 1.2 ×
// the SDOF phase-error estimate summed over the modes.
TEST(CrIntegrator, ThreeStoryFreeVibrationMatchesModalSuperposition) {
  BuildingParams p;
  p.story_mass_kip_s2_per_in = {0.2, 0.2, 0.2};
  p.story_stiffness_kip_per_in = {150, 150, 150};
  const ShearBuilding b(p);
  const Eigen::Vector3d x0(0.0, 0.0, 0.0), v0(3.0, 6.0, -4.0);
  const ModalProperties& modal = b.modal();
  const Eigen::Vector3d q0 = modal.mode_shapes.transpose() * b.mass() * x0;
  const Eigen::Vector3d qd0 = modal.mode_shapes.transpose() * b.mass() * v0;
  CrIntegrator cr(b, kDt);
  cr.initialize(x0, v0, 0.0, Eigen::VectorXd(0));
  const double t_end = 2.0;
  double err = 0.0;
  for (long n = 1; n <= std::lround(t_end / kDt); ++n) {
    cr.predict();
    cr.complete(0.0, Eigen::VectorXd(0));
    Eigen::Vector3d xe = Eigen::Vector3d::Zero();
    for (int j = 0; j < 3; ++j) {
      const double w = modal.omega_rad_per_s(j);
      const double zeta = b.rayleigh_alpha() / (2 * w) + b.rayleigh_beta() * w / 2;
      const testing::Sdof mode{w, zeta};
      xe += modal.mode_shapes.col(j) * mode.free_disp(cr.time_s(), q0(j), qd0(j));
    }
    err = std::max(err, (cr.displacement_in() - xe).cwiseAbs().maxCoeff());
  }
  // Σ_j max|φ_j| · (modal amplitude) · (phase error of mode j after t_end), × 1.2.
  double bound = 0.0;
  for (int j = 0; j < 3; ++j) {
    const double w = modal.omega_rad_per_s(j);
    const double amplitude = std::hypot(q0(j), qd0(j) / w);
    bound += modal.mode_shapes.col(j).cwiseAbs().maxCoeff() * amplitude * w * t_end * std::pow(w * kDt, 2) / 12.0;
  }
  bound *= 1.2;
  std::printf("[ measured ] CR 3-story free vibration: max error %.3e in, bound %.3e in\n", err, bound);
  EXPECT_LT(err, bound);
}

TEST(CrIntegrator, StepsAllocateNothing) {
#if defined(STRUCTURE_CAN_COUNT_ALLOCATIONS)
  const ShearBuilding b(test_buildings::uniform_three_story(0.2, 150, true));
  CrIntegrator cr(b, kDt);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(1);
  cr.initialize(1.0, force);
  g_allocations = 0;
  g_count_allocations = true;
  for (int n = 0; n < 100; ++n) {
    cr.predict();
    force(0) = 0.5 * cr.next_velocity_in_per_s()(0);
    cr.complete(std::sin(0.1 * n), force);
  }
  g_count_allocations = false;
  EXPECT_EQ(g_allocations.load(), 0);
  // The counter works: an Eigen temporary is counted.
  g_count_allocations = true;
  const Eigen::VectorXd copy = cr.displacement_in() * 2.0;
  g_count_allocations = false;
  EXPECT_GT(g_allocations.load(), 0);
  EXPECT_EQ(copy.size(), 3);
#else
  GTEST_SKIP() << "allocation counting needs glibc";
#endif
}

// KR-α's predict/complete and the centred-difference energy ledger allocate nothing either.
TEST(KrAlphaIntegrator, StepsAndLedgerAllocateNothing) {
#if defined(STRUCTURE_CAN_COUNT_ALLOCATIONS)
  const ShearBuilding b(test_buildings::uniform_three_story(0.2, 150, true));
  KrAlphaIntegrator kr(b, kDt, 0.5);
  EnergyLedger ledger(b);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(1);
  kr.initialize(1.0, force);
  ledger.start(kr.displacement_in(), kr.velocity_in_per_s(), 1.0, force);
  g_allocations = 0;
  g_count_allocations = true;
  for (int n = 0; n < 100; ++n) {
    kr.predict();
    force(0) = 0.5 * kr.next_velocity_in_per_s()(0);
    kr.complete(std::sin(0.1 * n), force);
    ledger.add_step(kDt, kr.displacement_in(), kr.velocity_in_per_s(), std::sin(0.1 * n), force);
  }
  g_count_allocations = false;
  EXPECT_EQ(g_allocations.load(), 0);
#else
  GTEST_SKIP() << "allocation counting needs glibc";
#endif
}

TEST(CrIntegrator, MisuseThrows) {
  const ShearBuilding b(sdof(0.2, 150, 0.02));
  EXPECT_THROW(CrIntegrator(b, 0.0), std::invalid_argument);
  EXPECT_THROW(CrIntegrator(b, std::nan("")), std::invalid_argument);
  CrIntegrator cr(b, kDt);
  EXPECT_THROW(cr.predict(), std::logic_error);
  EXPECT_THROW(cr.initialize(0.0, Eigen::VectorXd::Zero(1)), std::invalid_argument);  // no dampers
  cr.initialize(0.0, Eigen::VectorXd(0));
  EXPECT_THROW(cr.complete(0.0, Eigen::VectorXd(0)), std::logic_error);  // no predict
  cr.predict();
  EXPECT_THROW(cr.complete(0.0, Eigen::VectorXd::Zero(2)), std::invalid_argument);
  cr.complete(0.0, Eigen::VectorXd(0));
  EXPECT_EQ(cr.step_index(), 1);
  EXPECT_DOUBLE_EQ(cr.time_s(), kDt);
}

// α = (M + Δt/2·C + Δt²/4·K)⁻¹·M and the initial acceleration M a₀ = −M ι ü_g − Γ F₀.
TEST(CrIntegrator, AlphaAndInitialAcceleration) {
  BuildingParams p;
  p.story_mass_kip_s2_per_in = {0.2, 0.3};
  p.story_stiffness_kip_per_in = {150, 100};
  p.dampers = {{2, 2.0}};
  const ShearBuilding b(p);
  CrIntegrator cr(b, 0.01);
  const Eigen::MatrixXd lhs = b.mass() + 0.005 * b.damping() + 0.25e-4 * b.stiffness();
  EXPECT_LT((lhs * cr.alpha() - b.mass()).cwiseAbs().maxCoeff(), 1e-14);
  cr.initialize(10.0, Eigen::VectorXd::Constant(1, 1.5));
  // Γ = [-2, 2]ᵀ → floor forces −ΓF = [3, −3] kip.
  EXPECT_NEAR(cr.acceleration_in_per_s2()(0), -10.0 + 3.0 / 0.2, 1e-12);
  EXPECT_NEAR(cr.acceleration_in_per_s2()(1), -10.0 - 3.0 / 0.3, 1e-12);
}

}  // namespace
}  // namespace structure

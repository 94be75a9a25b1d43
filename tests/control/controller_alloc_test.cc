// Controller::compute allocates nothing: the global operator new of this test binary counts.
#include "control/controller.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace {

TEST(ControllerAllocations, ComputeIsAllocationFreeForEveryLaw) {
  const int n = 10, nd = 3;
  control::BuildingMatrices b;
  b.mass = 0.03 * Eigen::MatrixXd::Identity(n, n);
  b.stiffness = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    const double k = 40.0 - 2.0 * i, kup = i + 1 < n ? 40.0 - 2.0 * (i + 1) : 0.0;
    b.stiffness(i, i) = k + kup;
    if (i + 1 < n) b.stiffness(i, i + 1) = b.stiffness(i + 1, i) = -kup;
  }
  b.damping = 0.2 * b.mass + 0.002 * b.stiffness;
  b.gamma = Eigen::MatrixXd::Zero(n, nd);
  for (int k = 0; k < nd; ++k) {
    b.gamma(k, k) = 1.0;
    if (k > 0) b.gamma(k - 1, k) = -1.0;
  }
  damper::BrfdParams semiactive;
  semiactive.kind = damper::DamperKind::semiactive;
  damper::BrfdParams band_brake;  // the band-brake model's inverse (capstan ratio at the drum)
  band_brake.kind = damper::DamperKind::band_brake;
  band_brake.band_brake.actuator_tension_kip_per_in = {0.25, 0.23, 0.48, 0.48};
  for (const damper::BrfdParams& p : {semiactive, band_brake})
  for (control::Law law : {control::Law::passive_off, control::Law::passive_on, control::Law::lyapunov,
                           control::Law::clipped_optimal, control::Law::modulated_homogeneous}) {
    control::ControlConfig c;
    c.enabled = true;
    c.law = law;
    c.accel_noise_g = 0.01;  // the noise path too
    c.drift_noise_in = 0.001;
    c.delay_steps = 3;
    control::Controller ctl(c, b, p, 1.0 / 1024);
    Eigen::VectorXd accel = Eigen::VectorXd::Zero(n), drift = Eigen::VectorXd::Zero(n), force = Eigen::VectorXd::Zero(nd),
                    drum = Eigen::VectorXd::Zero(nd);
    Eigen::MatrixX2d targets(nd, 2);
    const control::Measurements m{&accel, &drift, &force, &drum};
    const long before = g_allocations.load();
    for (int i = 0; i < 2000; ++i) {
      const double t = i / 1024.0;
      accel.setConstant(50.0 * std::sin(6.0 * t));
      drift.setConstant(0.2 * std::sin(6.0 * t));
      drum = drift.head(nd);
      force.setConstant(2.0 * std::cos(6.0 * t));
      ctl.compute(m, targets);
    }
    EXPECT_EQ(g_allocations.load() - before, 0) << control::to_string(law) << " " << damper::to_string(p.kind);
    EXPECT_TRUE(targets.allFinite());
  }
}

}  // namespace

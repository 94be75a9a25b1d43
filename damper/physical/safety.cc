#include "damper/physical/safety.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace damper::physical {

namespace {
std::string fmt(const char* f, double a, double b) {
  char buf[200];
  std::snprintf(buf, sizeof buf, f, a, b);
  return buf;
}
}  // namespace

SafetyLayer::SafetyLayer(const SafetyLimits& limits, double period_s) : limits_(limits), period_s_(period_s) {}

bool SafetyLayer::command_ok(const ActuatorSetpoint& sp, std::string& why) const {
  if (!std::isfinite(sp.drum_in) || !std::isfinite(sp.actuator1_in) || !std::isfinite(sp.actuator2_in)) {
    why = "command limit: non-finite actuator command";
    return false;
  }
  if (std::abs(sp.drum_in) > limits_.stroke_in) {
    why = fmt("stroke limit: drum displacement command %.4f in beyond +-%.4f in (limits.stroke_in)", sp.drum_in,
              limits_.stroke_in);
    return false;
  }
  if (has_published_) {
    const double rate = std::abs(sp.drum_in - last_.drum_in) / period_s_;
    if (rate > limits_.velocity_in_per_s) {
      why = fmt("command rate limit: drum command changes at %.3f in/s, limit %.3f in/s (limits.velocity_in_per_s)",
                rate, limits_.velocity_in_per_s);
      return false;
    }
    for (int k = 0; k < 2; ++k) {
      const double a_rate =
          std::abs(k == 0 ? sp.actuator1_in - last_.actuator1_in : sp.actuator2_in - last_.actuator2_in) / period_s_;
      if (a_rate > limits_.actuator_velocity_in_per_s) {
        why = fmt("electric actuator rate limit: actuator %.0f command changes at %.3f in/s", k + 1.0, a_rate) +
              fmt(", limit %.3f in/s (limits.actuator_velocity_in_per_s)", limits_.actuator_velocity_in_per_s, 0.0);
        return false;
      }
    }
  }
  for (int k = 0; k < 2; ++k) {
    const double x = k == 0 ? sp.actuator1_in : sp.actuator2_in;
    if (x < limits_.actuator_min_in || x > limits_.actuator_max_in) {
      why = fmt("electric actuator stroke limit: actuator %.0f position command %.4f in", k + 1.0, x) +
            fmt(" outside [%.4f, %.4f] in (limits.actuator_min_in/max_in)", limits_.actuator_min_in,
                limits_.actuator_max_in);
      return false;
    }
  }
  return true;
}

void SafetyLayer::published(const ActuatorSetpoint& sp) {
  last_ = sp;
  has_published_ = true;
}

bool SafetyLayer::target_ok(double target_in, std::string& why) const {
  if (!std::isfinite(target_in) || std::abs(target_in) > limits_.drift_in) {
    why = fmt("drift limit: the server asks for drum displacement %.4f in beyond +-%.4f in (limits.drift_in)",
              target_in, limits_.drift_in);
    return false;
  }
  return true;
}

bool SafetyLayer::frame_ok(const hybrid_lcm::sensor_frame_t& f, std::string& why) const {
  if (!std::isfinite(f.drum_displacement_in) || !std::isfinite(f.friction_force_kip) ||
      !std::isfinite(f.actuator1_position_in) || !std::isfinite(f.actuator2_position_in) ||
      !std::isfinite(f.actuator1_force_lb) || !std::isfinite(f.actuator2_force_lb)) {
    why = "sensor fault: sensor frame " + std::to_string(f.sequence) + " carries a non-finite value";
    return false;
  }
  for (int k = 0; k < 2; ++k) {
    const double force = k == 0 ? f.actuator1_force_lb : f.actuator2_force_lb;
    if (std::abs(force) > limits_.actuator_force_lb) {
      why = fmt("actuator force limit: electric actuator %.0f load cell reads %.1f lb", k + 1.0, force) +
            fmt(", limit %.1f lb (limits.actuator_force_lb, frame %.0f)", limits_.actuator_force_lb,
                static_cast<double>(f.sequence));
      return false;
    }
  }
  return true;
}

bool SafetyLayer::tracking_ok(double target_in, double measured_in, std::string& why) const {
  const double e = measured_in - target_in;
  if (!(std::abs(e) <= limits_.tracking_error_in)) {
    why = fmt("tracking error limit: measured drum displacement is %.4f in off the target, limit %.4f in "
              "(limits.tracking_error_in)",
              e, limits_.tracking_error_in);
    return false;
  }
  return true;
}

double ramp_factor(double t, double duration) {
  if (duration <= 0.0 || t >= duration) return 1.0;
  if (t <= 0.0) return 0.0;
  return 0.5 * (1.0 - std::cos(M_PI * t / duration));
}

SetpointRamp::SetpointRamp(const ActuatorSetpoint& from, const ActuatorSetpoint& to, double duration_s)
    : from_(from), to_(to), duration_s_(duration_s) {}

double SetpointRamp::duration_for(const ActuatorSetpoint& from, const ActuatorSetpoint& to, double min_s,
                                  double peak_velocity, double actuator_peak_velocity) {
  if (!(actuator_peak_velocity > 0.0)) actuator_peak_velocity = peak_velocity;
  const double act = std::max(std::abs(to.actuator1_in - from.actuator1_in), std::abs(to.actuator2_in - from.actuator2_in));
  // Peak velocity of a cosine move of distance d over T is (π/2) d / T.
  return std::max({min_s, 0.5 * M_PI * std::abs(to.drum_in - from.drum_in) / peak_velocity,
                   0.5 * M_PI * act / std::min(peak_velocity, actuator_peak_velocity)});
}

ActuatorSetpoint SetpointRamp::at(double t) const {
  const double w = ramp_factor(t, duration_s_);
  return {from_.drum_in + w * (to_.drum_in - from_.drum_in),
          from_.actuator1_in + w * (to_.actuator1_in - from_.actuator1_in),
          from_.actuator2_in + w * (to_.actuator2_in - from_.actuator2_in)};
}

}  // namespace damper::physical

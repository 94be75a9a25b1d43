#include "damper/model/electric_actuator.h"

#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace damper {

ElectricActuatorParams electric_actuator_params_from_yaml(const common::YamlSection& s) {
  s.allow_only({"min_in", "max_in", "velocity_limit_in_per_s", "order", "time_constant_s", "damping_ratio",
                "force_limit_lb"});
  ElectricActuatorParams p;
  p.min_in = s.get_double_in("min_in", p.min_in, -10.0, 10.0);
  p.max_in = s.get_double_in("max_in", p.max_in, -10.0, 10.0);
  if (!(p.max_in > p.min_in)) s.fail("max_in", "must be greater than min_in (" + std::to_string(p.min_in) + ")");
  p.velocity_limit_in_per_s = s.get_double_in("velocity_limit_in_per_s", p.velocity_limit_in_per_s, 1e-6, 1e3);
  p.order = s.get_int("order", p.order);
  if (p.order != 1 && p.order != 2) s.fail("order", "must be 1 (first-order lag) or 2 (second-order response)");
  p.time_constant_s = s.get_double_in("time_constant_s", p.time_constant_s, 0.0, 10.0);
  p.damping_ratio = s.get_double_in("damping_ratio", p.damping_ratio, 0.05, 10.0);
  if (p.order == 2 && !(p.time_constant_s > 0.0)) s.fail("time_constant_s", "must be > 0 for order 2");
  p.force_limit_lb = s.get_double_in("force_limit_lb", p.force_limit_lb, 1.0, 1e6);
  return p;
}

std::string electric_actuator_params_to_yaml(const ElectricActuatorParams& p) {
  std::ostringstream o;
  o << std::setprecision(10) << "  min_in: " << p.min_in << "\n  max_in: " << p.max_in
    << "\n  velocity_limit_in_per_s: " << p.velocity_limit_in_per_s << "\n  order: " << p.order
    << "\n  time_constant_s: " << p.time_constant_s << "\n  damping_ratio: " << p.damping_ratio
    << "\n  force_limit_lb: " << p.force_limit_lb << "\n";
  return o.str();
}

ElectricActuator::ElectricActuator(const ElectricActuatorParams& params) : p_(params) { reset(0.5 * (p_.min_in + p_.max_in)); }

void ElectricActuator::reset(double x0) {
  x_ = clamp_to_stroke(x0);
  v_ = 0.0;
}

double ElectricActuator::clamp_to_stroke(double r) const { return std::clamp(r, p_.min_in, p_.max_in); }

double ElectricActuator::step(double target, double dt) {
  const double r = clamp_to_stroke(target);
  const double max_move = p_.velocity_limit_in_per_s * dt;
  double x_new;
  if (p_.order == 1) {
    const double w = p_.time_constant_s > 0.0 ? 1.0 - std::exp(-dt / p_.time_constant_s) : 1.0;
    x_new = x_ + std::clamp((r - x_) * w, -max_move, max_move);
    v_ = (x_new - x_) / dt;
  } else {
    // Exact transition of the linear second-order servo over dt (target held), Eigen's expm.
    const double wn = 1.0 / p_.time_constant_s;
    Eigen::Matrix2d a;
    a << 0.0, 1.0, -wn * wn, -2.0 * p_.damping_ratio * wn;
    const Eigen::Matrix2d phi = (a * dt).exp();
    const Eigen::Vector2d s = phi * Eigen::Vector2d(x_ - r, v_);
    x_new = x_ + std::clamp(s[0] + r - x_, -max_move, max_move);
    v_ = std::clamp(s[1], -p_.velocity_limit_in_per_s, p_.velocity_limit_in_per_s);
  }
  if (x_new <= p_.min_in || x_new >= p_.max_in) v_ = 0.0;  // hard stop at the stroke ends
  x_ = clamp_to_stroke(x_new);
  return x_;
}

}  // namespace damper

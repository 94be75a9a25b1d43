#include "damper/model/band_brake_config.h"

#include <iomanip>
#include <sstream>

namespace damper {

BandBrakeParams band_brake_params_from_yaml(const common::YamlSection& b) {
  b.allow_only({"friction_coefficient", "wrap_angle_fwd_rad", "wrap_angle_bwd_rad", "wrap_change_rad_per_in",
                "lever_ratio", "slack_tension_fwd_kip", "slack_tension_bwd_kip", "band_stiffness_kip_per_in",
                "band_hardening_per_in", "backlash_in", "viscous_kip_s_per_in", "transition_exponent",
                "actuator_tension_kip_per_in", "actuator1_initial_in", "actuator2_initial_in"});
  BandBrakeParams p;
  p.friction_coefficient = b.get_double_in("friction_coefficient", 1e-3, 2.0);
  p.wrap_angle_fwd_rad = b.get_double_in("wrap_angle_fwd_rad", 0.1, 100.0);
  p.wrap_angle_bwd_rad = b.get_double_in("wrap_angle_bwd_rad", 0.1, 100.0);
  p.wrap_change_rad_per_in = b.get_double_in("wrap_change_rad_per_in", 0.0, -100.0, 100.0);
  p.lever_ratio = b.get_double_in("lever_ratio", 1e-3, 100.0);
  p.slack_tension_fwd_kip = b.get_double_in("slack_tension_fwd_kip", 1e-6, 100.0);
  p.slack_tension_bwd_kip = b.get_double_in("slack_tension_bwd_kip", 1e-6, 100.0);
  p.band_stiffness_kip_per_in = b.get_double_in("band_stiffness_kip_per_in", 1e-6, 1e9);
  p.band_hardening_per_in = b.get_double_in("band_hardening_per_in", 0.0, 0.0, 1e6);
  p.backlash_in = b.get_double_in("backlash_in", 0.0, 0.0, 10.0);
  p.viscous_kip_s_per_in = b.get_double_in("viscous_kip_s_per_in", 0.0, 0.0, 1e3);
  p.transition_exponent = b.get_double_in("transition_exponent", 1.0, 0.1, 100.0);
  if (b.has("actuator_tension_kip_per_in")) {
    const std::vector<double> k = b.get_double_list("actuator_tension_kip_per_in");
    if (k.size() != 4)
      b.fail("actuator_tension_kip_per_in", "expected 4 values: fwd-act1, fwd-act2, bwd-act1, bwd-act2 (kip/in)");
    for (int i = 0; i < 4; ++i) p.actuator_tension_kip_per_in[i] = k[i];
  }
  p.actuator1_initial_in = b.get_double_in("actuator1_initial_in", p.actuator1_initial_in, -10.0, 10.0);
  p.actuator2_initial_in = b.get_double_in("actuator2_initial_in", p.actuator2_initial_in, -10.0, 10.0);
  return p;
}

std::string band_brake_params_to_yaml(const BandBrakeParams& p) {
  std::ostringstream o;
  o << std::setprecision(17);
  const std::array<double, 4>& k = p.actuator_tension_kip_per_in;
  o << "model: band_brake\n"
    << "band_brake:\n"
    << "  friction_coefficient: " << p.friction_coefficient << "\n"
    << "  wrap_angle_fwd_rad: " << p.wrap_angle_fwd_rad << "\n"
    << "  wrap_angle_bwd_rad: " << p.wrap_angle_bwd_rad << "\n"
    << "  wrap_change_rad_per_in: " << p.wrap_change_rad_per_in << "\n"
    << "  lever_ratio: " << p.lever_ratio << "\n"
    << "  slack_tension_fwd_kip: " << p.slack_tension_fwd_kip << "\n"
    << "  slack_tension_bwd_kip: " << p.slack_tension_bwd_kip << "\n"
    << "  band_stiffness_kip_per_in: " << p.band_stiffness_kip_per_in << "\n"
    << "  band_hardening_per_in: " << p.band_hardening_per_in << "\n"
    << "  backlash_in: " << p.backlash_in << "\n"
    << "  viscous_kip_s_per_in: " << p.viscous_kip_s_per_in << "\n"
    << "  transition_exponent: " << p.transition_exponent << "\n"
    << "  actuator_tension_kip_per_in: [" << k[0] << ", " << k[1] << ", " << k[2] << ", " << k[3] << "]\n"
    << "  actuator1_initial_in: " << p.actuator1_initial_in << "\n"
    << "  actuator2_initial_in: " << p.actuator2_initial_in << "\n";
  return o.str();
}

}  // namespace damper

#include "damper/model/brfd_config.h"
#include "common/number_format.h"

#include "damper/model/band_brake_config.h"

#include <iomanip>
#include <sstream>

namespace damper {

BrfdParams brfd_params_from_yaml(const common::YamlSection& s) {
  BrfdParams p;
  p.kind = damper_kind_from_string(
      s.get_choice("model", {"passive_lugre", "semiactive", "paper_semiactive", "band_brake"}));
  if (p.kind == DamperKind::band_brake) {
    // The band-brake model (damper/model/band_brake_model.h): its own block and the electric
    // actuators that set its slack-end tensions (B2).
    s.allow_only({"model", "band_brake", "electric_actuators"});
    p.band_brake = band_brake_params_from_yaml(s.section("band_brake"));
    if (s.has("electric_actuators"))
      p.electric_actuators = electric_actuator_params_from_yaml(s.section("electric_actuators"));
    p.semiactive.actuator1_initial_in = p.band_brake.actuator1_initial_in;
    p.semiactive.actuator2_initial_in = p.band_brake.actuator2_initial_in;
    return p;
  }
  s.allow_only({"model", "lugre", "semiactive", "b_of_velocity", "effects", "electric_actuators"});
  const common::YamlSection l = s.section("lugre");
  l.allow_only({"sigma0_kip_per_in", "sigma1_kip_s_per_in", "sigma2_kip_s_per_in", "fs_fwd_kip",
                "fs_bwd_kip", "fc_fwd_kip", "fc_bwd_kip", "vs_in_per_s"});
  LugreParams& g = p.lugre;
  g.sigma0_kip_per_in = l.get_double_in("sigma0_kip_per_in", 1e-6, 1e9);
  g.sigma1_kip_s_per_in = l.get_double_in("sigma1_kip_s_per_in", 0.0, 1e6);
  g.sigma2_kip_s_per_in = l.get_double_in("sigma2_kip_s_per_in", 0.0, 1e3);
  g.fs_fwd_kip = l.get_double_in("fs_fwd_kip", 1e-6, 1e3);
  g.fs_bwd_kip = l.get_double_in("fs_bwd_kip", 1e-6, 1e3);
  g.fc_fwd_kip = l.get_double_in("fc_fwd_kip", 1e-6, 1e3);
  g.fc_bwd_kip = l.get_double_in("fc_bwd_kip", 1e-6, 1e3);
  g.vs_in_per_s = l.get_double_in("vs_in_per_s", 1e-6, 1e3);
  if (s.has("semiactive")) {
    const common::YamlSection a = s.section("semiactive");
    a.allow_only({"slopes_kip_per_in", "scaling", "actuator1_initial_in", "actuator2_initial_in",
                  "fc_floor_kip"});
    SemiActiveParams& sa = p.semiactive;
    if (a.has("slopes_kip_per_in")) {
      const std::vector<double> m = a.get_double_list("slopes_kip_per_in");
      if (m.size() != 8) a.fail("slopes_kip_per_in", "expected 8 slopes m11 m12 m21 m22 m31 m32 m41 m42");
      for (int i = 0; i < 4; ++i) sa.slopes_kip_per_in[i] = {m[2 * i], m[2 * i + 1]};
    }
    if (a.has("scaling")) {
      const std::vector<double> c = a.get_double_list("scaling");
      if (c.size() != 4) a.fail("scaling", "expected 4 scaling factors C1 C2 C3 C4");
      for (int i = 0; i < 4; ++i) sa.scaling[i] = c[i];
    }
    sa.actuator1_initial_in = a.get_double_in("actuator1_initial_in", sa.actuator1_initial_in, -10, 10);
    sa.actuator2_initial_in = a.get_double_in("actuator2_initial_in", sa.actuator2_initial_in, -10, 10);
    sa.fc_floor_kip = a.get_double_in("fc_floor_kip", sa.fc_floor_kip, 0.0, 1e3);
  }
  if (s.has("b_of_velocity")) {
    // Optional b = F(v) of Eq. (4): piecewise linear in |v| per direction.
    const common::YamlSection b = s.section("b_of_velocity");
    b.allow_only({"speed_in_per_s", "fwd_kip", "bwd_kip"});
    KineticFrictionCurve& c = p.b_of_velocity;
    c.speed_in_per_s = b.get_double_list("speed_in_per_s");
    c.fwd_kip = b.get_double_list("fwd_kip");
    c.bwd_kip = b.get_double_list("bwd_kip");
    if (c.speed_in_per_s.empty()) b.fail("speed_in_per_s", "needs at least one speed");
    if (c.fwd_kip.size() != c.speed_in_per_s.size())
      b.fail("fwd_kip", "needs one value per speed (" + std::to_string(c.speed_in_per_s.size()) + ")");
    if (c.bwd_kip.size() != c.speed_in_per_s.size())
      b.fail("bwd_kip", "needs one value per speed (" + std::to_string(c.speed_in_per_s.size()) + ")");
    for (std::size_t i = 0; i < c.speed_in_per_s.size(); ++i) {
      if (c.speed_in_per_s[i] < 0.0 || (i > 0 && c.speed_in_per_s[i] <= c.speed_in_per_s[i - 1]))
        b.fail("speed_in_per_s", "must be >= 0 and strictly increasing");
      if (!(c.fwd_kip[i] > 0.0)) b.fail("fwd_kip", "values must be > 0");
      if (!(c.bwd_kip[i] > 0.0)) b.fail("bwd_kip", "values must be > 0");
    }
  }
  // Optional physical extensions found by `hybridsim diagnose` (damper/model/effects.h).
  if (s.has("effects")) p.effects = effects_from_yaml(s.section("effects"));
  if (s.has("electric_actuators")) p.electric_actuators = electric_actuator_params_from_yaml(s.section("electric_actuators"));
  return p;
}

BrfdParams load_brfd_params(const std::string& path) {
  return brfd_params_from_yaml(common::YamlSection::load_file(path));
}

std::string brfd_params_to_yaml(const BrfdParams& p) {
  if (p.kind == DamperKind::band_brake)
    return band_brake_params_to_yaml(p.band_brake) + "electric_actuators:\n" +
           electric_actuator_params_to_yaml(p.electric_actuators);
  std::ostringstream o;
  common::use_shortest_round_trip(o);
  const LugreParams& g = p.lugre;
  o << "model: " << to_string(p.kind) << "\n"
    << "lugre:\n"
    << "  sigma0_kip_per_in: " << g.sigma0_kip_per_in << "\n"
    << "  sigma1_kip_s_per_in: " << g.sigma1_kip_s_per_in << "\n"
    << "  sigma2_kip_s_per_in: " << g.sigma2_kip_s_per_in << "\n"
    << "  fs_fwd_kip: " << g.fs_fwd_kip << "\n"
    << "  fs_bwd_kip: " << g.fs_bwd_kip << "\n"
    << "  fc_fwd_kip: " << g.fc_fwd_kip << "\n"
    << "  fc_bwd_kip: " << g.fc_bwd_kip << "\n"
    << "  vs_in_per_s: " << g.vs_in_per_s << "\n";
  const SemiActiveParams& a = p.semiactive;
  o << "semiactive:\n  slopes_kip_per_in: [";
  for (int i = 0; i < 4; ++i)
    o << a.slopes_kip_per_in[i][0] << ", " << a.slopes_kip_per_in[i][1] << (i < 3 ? ", " : "]\n");
  o << "  scaling: [" << a.scaling[0] << ", " << a.scaling[1] << ", " << a.scaling[2] << ", "
    << a.scaling[3] << "]\n"
    << "  actuator1_initial_in: " << a.actuator1_initial_in << "\n"
    << "  actuator2_initial_in: " << a.actuator2_initial_in << "\n"
    << "  fc_floor_kip: " << a.fc_floor_kip << "\n";
  const KineticFrictionCurve& c = p.b_of_velocity;
  if (!c.empty()) {
    auto list = [&o](const std::vector<double>& v) {
      o << "[";
      for (std::size_t i = 0; i < v.size(); ++i) o << (i ? ", " : "") << v[i];
      o << "]\n";
    };
    o << "b_of_velocity:\n  speed_in_per_s: ";
    list(c.speed_in_per_s);
    o << "  fwd_kip: ";
    list(c.fwd_kip);
    o << "  bwd_kip: ";
    list(c.bwd_kip);
  }
  o << effects_to_yaml(p.effects);
  o << "electric_actuators:\n" << electric_actuator_params_to_yaml(p.electric_actuators);
  return o.str();
}

}  // namespace damper

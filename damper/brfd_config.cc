#include "damper/brfd_config.h"

#include <iomanip>
#include <sstream>

namespace damper {

BrfdParams brfd_params_from_yaml(const common::YamlSection& s) {
  s.allow_only({"model", "lugre", "semiactive"});
  BrfdParams p;
  p.kind = damper_kind_from_string(s.get_choice("model", {"passive_lugre", "semiactive"}));
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
  return p;
}

BrfdParams load_brfd_params(const std::string& path) {
  return brfd_params_from_yaml(common::YamlSection::load_file(path));
}

std::string brfd_params_to_yaml(const BrfdParams& p) {
  std::ostringstream o;
  o << std::setprecision(10);
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
  return o.str();
}

}  // namespace damper

#include "structure/shear_building.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace structure {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string to_text(double v) {
  std::ostringstream o;
  o << std::setprecision(17) << v;
  return o.str();
}

// ConfigError for entry [i] of a list, with the entry's own line:
//   file:12: building.story_mass_kip_s2_per_in[1]: must be > 0, got -1
[[noreturn]] void fail_entry(const common::YamlSection& s, const std::string& key, std::size_t i,
                             const std::string& message) {
  const YAML::Node entry = s.node()[key][i];
  const YAML::Mark m = entry.Mark();
  const std::string line = m.line >= 0 ? ":" + std::to_string(m.line + 1) : std::string();
  throw common::ConfigError(s.file() + line + ": " + s.key_path(key) + "[" + std::to_string(i) +
                            "]: " + message);
}

std::vector<double> positive_list(const common::YamlSection& s, const std::string& key) {
  std::vector<double> values = s.get_double_list(key);
  if (values.empty()) s.fail(key, "must list at least one story");
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!(values[i] > 0.0)) fail_entry(s, key, i, "must be > 0, got " + to_text(values[i]));
  }
  return values;
}

}  // namespace

BuildingParams building_params_from_yaml(const common::YamlSection& s) {
  s.allow_only({"story_mass_kip_s2_per_in", "story_stiffness_kip_per_in", "damping", "dampers"});
  BuildingParams p;
  p.story_mass_kip_s2_per_in = positive_list(s, "story_mass_kip_s2_per_in");
  p.story_stiffness_kip_per_in = positive_list(s, "story_stiffness_kip_per_in");
  const int n = static_cast<int>(p.story_mass_kip_s2_per_in.size());
  if (p.story_stiffness_kip_per_in.size() != p.story_mass_kip_s2_per_in.size()) {
    s.fail("story_stiffness_kip_per_in",
           "has " + std::to_string(p.story_stiffness_kip_per_in.size()) + " entries but " +
               s.key_path("story_mass_kip_s2_per_in") + " has " + std::to_string(n) +
               " (one stiffness per story)");
  }

  if (s.has("damping")) {
    const common::YamlSection d = s.section("damping");
    d.allow_only({"modes", "ratios"});
    const std::vector<int> modes = d.get_int_list("modes");
    if (modes.size() != 2) d.fail("modes", "expected two 1-based mode numbers, e.g. [1, 2]");
    for (std::size_t i = 0; i < 2; ++i) {
      if (modes[i] < 1 || modes[i] > n) {
        fail_entry(d, "modes", i,
                   "mode " + std::to_string(modes[i]) + " out of range 1.." + std::to_string(n) +
                       (n == 1 ? " (a single-story building uses modes [1, 1])" : ""));
      }
    }
    const std::vector<double> ratios = d.get_double_list("ratios");
    if (ratios.size() != 2) d.fail("ratios", "expected two damping ratios, e.g. [0.02, 0.02]");
    for (std::size_t i = 0; i < 2; ++i) {
      if (!(ratios[i] >= 0.0 && ratios[i] < 1.0)) {
        fail_entry(d, "ratios", i, "must be in [0, 1), got " + to_text(ratios[i]));
      }
    }
    if (modes[0] == modes[1] && ratios[0] != ratios[1]) {
      d.fail("ratios", "the two modes are the same, so the two ratios must be equal");
    }
    p.damping_modes = {modes[0], modes[1]};
    p.damping_ratios = {ratios[0], ratios[1]};
  }

  if (s.has("dampers")) {
    for (const common::YamlSection& ds : s.section_list("dampers")) {
      ds.allow_only({"story", "drum_per_drift"});
      DamperPlacement placement;
      placement.story = ds.get_int("story");
      if (placement.story < 1 || placement.story > n) {
        ds.fail("story", "must be in 1.." + std::to_string(n) + " (number of stories), got " +
                             std::to_string(placement.story));
      }
      placement.drum_per_drift = ds.get_double("drum_per_drift", 1.0);
      if (placement.drum_per_drift == 0.0 || std::abs(placement.drum_per_drift) > 1e3) {
        ds.fail("drum_per_drift", "must be nonzero and within ±1000, got " +
                                      to_text(placement.drum_per_drift));
      }
      p.dampers.push_back(placement);
    }
  }
  // Anything the checks above missed (none expected) still surfaces with the section named.
  try {
    validate_building_params(p);
  } catch (const std::invalid_argument& e) {
    throw common::ConfigError(s.file() + ": " + e.what());
  }
  return p;
}

std::string building_params_to_yaml(const BuildingParams& p) {
  std::ostringstream o;
  o << std::setprecision(17);
  auto list = [&o](const std::vector<double>& v) {
    o << "[";
    for (std::size_t i = 0; i < v.size(); ++i) o << (i ? ", " : "") << v[i];
    o << "]\n";
  };
  o << "story_mass_kip_s2_per_in: ";
  list(p.story_mass_kip_s2_per_in);
  o << "story_stiffness_kip_per_in: ";
  list(p.story_stiffness_kip_per_in);
  o << "damping:\n"
    << "  modes: [" << p.damping_modes[0] << ", " << p.damping_modes[1] << "]\n"
    << "  ratios: [" << p.damping_ratios[0] << ", " << p.damping_ratios[1] << "]\n";
  if (p.dampers.empty()) {
    o << "dampers: []\n";
  } else {
    o << "dampers:\n";
    for (const DamperPlacement& d : p.dampers) {
      o << "  - story: " << d.story << "\n"
        << "    drum_per_drift: " << d.drum_per_drift << "\n";
    }
  }
  return o.str();
}

void validate_building_params(const BuildingParams& p) {
  const std::size_t n = p.story_mass_kip_s2_per_in.size();
  if (n == 0) throw std::invalid_argument("building: no stories (story_mass_kip_s2_per_in is empty)");
  if (p.story_stiffness_kip_per_in.size() != n) {
    throw std::invalid_argument("building: " + std::to_string(n) + " masses but " +
                                std::to_string(p.story_stiffness_kip_per_in.size()) +
                                " story stiffnesses");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double m = p.story_mass_kip_s2_per_in[i];
    const double k = p.story_stiffness_kip_per_in[i];
    if (!(m > 0.0) || !std::isfinite(m)) {
      throw std::invalid_argument("building: story_mass_kip_s2_per_in[" + std::to_string(i) +
                                  "] must be finite and > 0, got " + to_text(m));
    }
    if (!(k > 0.0) || !std::isfinite(k)) {
      throw std::invalid_argument("building: story_stiffness_kip_per_in[" + std::to_string(i) +
                                  "] must be finite and > 0, got " + to_text(k));
    }
  }
  for (int i = 0; i < 2; ++i) {
    const int mode = p.damping_modes[i];
    if (mode < 1 || mode > static_cast<int>(n)) {
      throw std::invalid_argument("building: damping mode " + std::to_string(mode) +
                                  " out of range 1.." + std::to_string(n) +
                                  (n == 1 ? " (a single-story building uses modes [1, 1])" : ""));
    }
    const double z = p.damping_ratios[i];
    if (!(z >= 0.0 && z < 1.0)) {
      throw std::invalid_argument("building: damping ratio must be in [0, 1), got " + to_text(z));
    }
  }
  if (p.damping_modes[0] == p.damping_modes[1] && p.damping_ratios[0] != p.damping_ratios[1]) {
    throw std::invalid_argument("building: damping modes are the same, so the ratios must be equal");
  }
  for (std::size_t j = 0; j < p.dampers.size(); ++j) {
    const DamperPlacement& d = p.dampers[j];
    if (d.story < 1 || d.story > static_cast<int>(n)) {
      throw std::invalid_argument("building: dampers[" + std::to_string(j) + "].story " +
                                  std::to_string(d.story) + " out of range 1.." + std::to_string(n));
    }
    if (d.drum_per_drift == 0.0 || !std::isfinite(d.drum_per_drift)) {
      throw std::invalid_argument("building: dampers[" + std::to_string(j) +
                                  "].drum_per_drift must be finite and nonzero");
    }
  }
}

ShearBuilding::ShearBuilding(const BuildingParams& params) : params_(params) {
  validate_building_params(params_);
  const int n = num_stories();
  const int nd = num_dampers();

  mass_ = Eigen::MatrixXd::Zero(n, n);
  stiffness_ = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    mass_(i, i) = params_.story_mass_kip_s2_per_in[i];
    // Story i+1 (0-based i) joins floor i-1 and floor i.
    const double k = params_.story_stiffness_kip_per_in[i];
    stiffness_(i, i) += k;
    if (i > 0) {
      stiffness_(i - 1, i - 1) += k;
      stiffness_(i - 1, i) -= k;
      stiffness_(i, i - 1) -= k;
    }
  }
  influence_ = Eigen::VectorXd::Ones(n);

  gamma_ = Eigen::MatrixXd::Zero(n, nd);
  for (int j = 0; j < nd; ++j) {
    const DamperPlacement& d = params_.dampers[j];
    gamma_(d.story - 1, j) += d.drum_per_drift;
    if (d.story > 1) gamma_(d.story - 2, j) -= d.drum_per_drift;
  }

  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(stiffness_, mass_);
  if (eig.info() != Eigen::Success) {
    throw std::invalid_argument("building: eigen solution of K φ = ω² M φ failed");
  }
  modal_.omega_rad_per_s = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  modal_.period_s = (2.0 * kPi) * modal_.omega_rad_per_s.cwiseInverse();
  modal_.mode_shapes = eig.eigenvectors();  // φᵀMφ = I for the ABx_lx problem
  for (int j = 0; j < n; ++j) {
    if (modal_.mode_shapes(n - 1, j) < 0.0) modal_.mode_shapes.col(j) *= -1.0;
  }

  // Rayleigh coefficients from ζ_j = α/(2ω_j) + βω_j/2 at the two chosen modes.
  const double wi = modal_.omega_rad_per_s(params_.damping_modes[0] - 1);
  const double wj = modal_.omega_rad_per_s(params_.damping_modes[1] - 1);
  const double zi = params_.damping_ratios[0];
  const double zj = params_.damping_ratios[1];
  if (zi == zj) {
    // Also covers wi == wj (same mode twice).
    beta_ = 2.0 * zi / (wi + wj);
    alpha_ = 2.0 * zi * wi * wj / (wi + wj);
  } else {
    const double den = wj * wj - wi * wi;
    beta_ = 2.0 * (zj * wj - zi * wi) / den;
    alpha_ = 2.0 * wi * wj * (zi * wj - zj * wi) / den;
  }
  damping_ = alpha_ * mass_ + beta_ * stiffness_;
}

Eigen::VectorXd ShearBuilding::interstory_drift(const Eigen::VectorXd& floor_disp_in) const {
  const int n = num_stories();
  if (floor_disp_in.size() != n) {
    throw std::invalid_argument("interstory_drift: expected " + std::to_string(n) +
                                " floor displacements, got " + std::to_string(floor_disp_in.size()));
  }
  Eigen::VectorXd drift(n);
  drift(0) = floor_disp_in(0);
  for (int i = 1; i < n; ++i) drift(i) = floor_disp_in(i) - floor_disp_in(i - 1);
  return drift;
}

}  // namespace structure

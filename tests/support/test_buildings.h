#pragma once
// The buildings the structure and validation tests share (one definition each): an SDOF shear
// building, a uniform 3-story building, the 3-story frame compared with OpenSees
// (tests/structure/opensees_regression_test.cc). The damper: test_dampers.h.
#include "structure/shear_building.h"

namespace test_buildings {

/// One story of mass m (kip·s²/in), stiffness k (kip/in), ζ of critical (Rayleigh on mode 1).
inline structure::BuildingParams sdof(double m, double k, double zeta) {
  structure::BuildingParams p;
  p.story_mass_kip_s2_per_in = {m};
  p.story_stiffness_kip_per_in = {k};
  p.damping_modes = {1, 1};
  p.damping_ratios = {zeta, zeta};
  return p;
}

/// Three equal stories (2 % Rayleigh damping on modes 1 and 2, the defaults), with or without a
/// damper in story 1 (drum displacement = drift).
inline structure::BuildingParams uniform_three_story(double m, double k, bool damper_in_story1) {
  structure::BuildingParams p;
  p.story_mass_kip_s2_per_in = {m, m, m};
  p.story_stiffness_kip_per_in = {k, k, k};
  if (damper_in_story1) p.dampers = {{1, 1.0}};
  return p;
}

/// The 3-story frame of the OpenSees comparison: 0.5 kip·s²/in floors, 300/250/200 kip/in, 5 %
/// on modes 1 and 2, no damper.
inline structure::BuildingParams opensees_three_story() {
  structure::BuildingParams p;
  p.story_mass_kip_s2_per_in = {0.5, 0.5, 0.5};
  p.story_stiffness_kip_per_in = {300, 250, 200};
  p.damping_modes = {1, 2};
  p.damping_ratios = {0.05, 0.05};
  return p;
}

}  // namespace test_buildings

#pragma once
// The damper the validation tests share (one definition): a passive LuGre BRFD.
#include "damper/model/brfd_model.h"

namespace test_dampers {

/// A passive LuGre damper (σ0 60 kip/in, σ1 0.5, σ2 0.05 kip·s/in, v_s 0.5 in/s) with static and
/// kinetic friction fs_kip, fc_kip in both directions.
inline damper::BrfdParams lugre_damper(double fs_kip = 2.4, double fc_kip = 2.0) {
  damper::BrfdParams d;
  d.kind = damper::DamperKind::passive_lugre;
  d.lugre.sigma0_kip_per_in = 60.0;
  d.lugre.sigma1_kip_s_per_in = 0.5;
  d.lugre.sigma2_kip_s_per_in = 0.05;
  d.lugre.fs_fwd_kip = d.lugre.fs_bwd_kip = fs_kip;
  d.lugre.fc_fwd_kip = d.lugre.fc_bwd_kip = fc_kip;
  d.lugre.vs_in_per_s = 0.5;
  return d;
}

}  // namespace test_dampers

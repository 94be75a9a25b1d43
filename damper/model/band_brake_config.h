#pragma once
/// @file band_brake_config.h
/// Strict YAML reader/writer of BandBrakeParams (damper/model/band_brake_model.h): a damper
/// config with `model: band_brake` and a `band_brake:` block (configs/brfd-band-brake.yaml).
/// Unknown keys, wrong types and values out of physical range are errors naming file and key.

#include "common/strict_yaml.h"
#include "damper/model/band_brake_model.h"

#include <string>

namespace damper {

/// Reads the `band_brake:` block (keys as the BandBrakeParams fields, see the shipped config).
BandBrakeParams band_brake_params_from_yaml(const common::YamlSection& block);
/// Writes a whole damper config: `model: band_brake` and the `band_brake:` block.
std::string band_brake_params_to_yaml(const BandBrakeParams& params);

}  // namespace damper

#pragma once
/// @file brfd_config.h
/// Reads BrfdParams from YAML (configs/brfd-default.yaml, configs/brfd-semiactive.yaml).
/// Strict: unknown keys, wrong types and out-of-range values are errors naming file and key.

#include "common/strict_yaml.h"
#include "damper/model/brfd_model.h"

#include <string>

namespace damper {

/// Reads a damper block: keys `model`, `lugre`, `semiactive`, optional `b_of_velocity` and
/// `effects` (damper/model/effects.h; see configs/brfd-default.yaml).
BrfdParams brfd_params_from_yaml(const common::YamlSection& section);
/// Loads a damper config file whose top level is a damper block.
BrfdParams load_brfd_params(const std::string& path);
/// Writes the params back as YAML (for the effective config written next to results).
std::string brfd_params_to_yaml(const BrfdParams& params);

}  // namespace damper

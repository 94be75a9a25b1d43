#pragma once
/// @file guarded.h
/// The exit-code rule of the damper and diagnose commands (docs/error-policy.md).

#include "common/run_guard.h"
#include "damper/data/brfd_data.h"
#include "common/strict_yaml.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <stdexcept>

// Runs `body`, turning the project's user-input errors into exit code 2 and any other
// failure into 1 (README "Exit codes"), with the message on stderr (CLI11's App::exit()
// prints nothing for a RuntimeError, so it is printed here).
template <typename F>
void guarded(F&& body) {
  try {
    body();
  } catch (const CLI::Error&) {
    throw;
  } catch (const damper::BrfdDataError& e) {
    std::cerr << "error: " << e.what() << std::endl;
    throw CLI::RuntimeError(common::kExitBadInput);
  } catch (const common::ConfigError& e) {
    std::cerr << "error: " << e.what() << std::endl;
    throw CLI::RuntimeError(common::kExitBadInput);
  } catch (const std::invalid_argument& e) {
    std::cerr << "error: " << e.what() << std::endl;
    throw CLI::RuntimeError(common::kExitBadInput);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << std::endl;
    throw CLI::RuntimeError(common::kExitRunFailed);
  }
}


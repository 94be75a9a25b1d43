#pragma once
/// @file node_main.h
/// The command line rule of the LCM node executables (brfd-substructure, brfd-rig), once:
/// a command-line error is bad input (exit 2, README "Exit codes"), `--run-id` may be left out
/// (answer any run) but not given empty, and an error while starting (bad config, key file,
/// URL) is exit 2 with "<program>: <message>" on stderr. Header-only; needs CLI11.

#include "common/run_guard.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <stdexcept>
#include <string>

namespace messages {

/// Parses argv into `app`, checks `--run-id` (if the app has one), then returns body()'s exit
/// code; see above for the errors.
template <typename Body>
int run_node_main(const char* program, CLI::App& app, int argc, char** argv, Body&& body) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? common::kExitOk : common::kExitBadInput;
  }
  try {
    const CLI::Option* run_id = app.get_option_no_throw("--run-id");
    if (run_id != nullptr && run_id->count() > 0 && run_id->as<std::string>().empty())
      throw std::invalid_argument("--run-id: must not be empty (omit it to answer any run)");
    return body();
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return common::kExitBadInput;
  }
}

}  // namespace messages

#pragma once
/// @file damper_commands.h
/// The `hybridsim damper ...` subcommands (predict, identify, relationships). The logic lives
/// in damper/ (predict.h, identification.h, relationships.h); this file only wires CLI11.

#include <CLI/CLI.hpp>

/// Adds the `damper` subcommand group to `app`. Each subcommand runs in its callback; a
/// user-input error (bad data file, config, window) prints "error: <message>" on stderr and
/// throws CLI::RuntimeError(1), which App::exit() turns into exit code 1.
void add_damper_commands(CLI::App& app);

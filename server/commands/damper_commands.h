#pragma once
/// @file damper_commands.h
/// The `hybridsim damper ...` subcommands (predict, identify, relationships). The logic lives
/// in damper/ (predict.h, identification.h, relationships.h); this file only wires CLI11.

#include <CLI/CLI.hpp>

/// Adds the `damper` subcommand group to `app`. Each subcommand runs in its callback; errors
/// are reported as CLI::RuntimeError (exit code 1) with the message on stderr.
void add_damper_commands(CLI::App& app);

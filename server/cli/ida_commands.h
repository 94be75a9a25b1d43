#pragma once
/// @file ida_commands.h
/// The `hybridsim ida ...` command: incremental dynamic analysis with fragility curves
/// (server/ida/ida.h). This file only wires CLI11.

#include <CLI/CLI.hpp>

/// Adds `ida` to `app`. The exit code (0 all ok, 1 some runs failed or not finished, 2 bad
/// input, 130 interrupted) is passed on as CLI::RuntimeError(code).
void add_ida_commands(CLI::App& app);

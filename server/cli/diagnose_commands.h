#pragma once
/// @file diagnose_commands.h
/// The `hybridsim diagnose` command (model-discrepancy workflow, docs/diagnose.md). The logic
/// lives in damper/diagnose/diagnose.h; this file only wires CLI11.

#include <CLI/CLI.hpp>

/// Adds `diagnose` to `app`. It runs in its callback; a user-input error (bad model config,
/// data file, option) prints "error: <message>" on stderr and throws CLI::RuntimeError(1),
/// which App::exit() turns into exit code 1. The last line on stdout is
/// `effects=<names or none> nrmse_before=<mean> nrmse_after=<mean> nrmse_after_max=<max>`.
void add_diagnose_commands(CLI::App& app);

#pragma once
/// @file batch_commands.h
/// The `hybridsim batch ...` command: many records, N at a time, resumable, MPI and Slurm,
/// summary and plots (server/batch/batch.h). This file only wires CLI11.

#include <CLI/CLI.hpp>

/// Adds `batch` (with its `merge` subcommand and the internal `worker`) to `app`. The exit
/// code (0 all ok, 1 some failed or not run, 2 bad input) is passed on as
/// CLI::RuntimeError(code), which App::exit() returns.
void add_batch_commands(CLI::App& app);

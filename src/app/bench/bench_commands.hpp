#pragma once
// `mallet bench`'s subcommands, each registered by its own file in this folder
// (cli/cmd_bench.cpp adds them to `mallet bench`).
#include <CLI/CLI.hpp>

#include "app/common/command_support.hpp"

namespace mallet::app {

//! `mallet bench` subcommands, each in its own file.
void add_bench_audio(CLI::App& bench);
void add_bench_input(CLI::App& bench);
void add_bench_render(CLI::App& bench);
void add_bench_report(CLI::App& bench);
void add_bench_latency(CLI::App& bench);
void add_bench_prediction(CLI::App& bench);
void add_bench_soak(CLI::App& bench);

}  // namespace mallet::app

#pragma once
// `mallet-bench`'s subcommands, each registered by its own file in this folder
// (bench_main.cpp adds them, at the top or under `mallet bench`).
#include <CLI/CLI.hpp>

#include "app/common/command_support.hpp"

namespace mallet::app {

//! The benchmarks' subcommands, each in its own file.
void add_bench_audio(CLI::App& bench);
void add_bench_input(CLI::App& bench);
void add_bench_render(CLI::App& bench);
void add_bench_report(CLI::App& bench);
void add_bench_latency(CLI::App& bench);
void add_bench_prediction(CLI::App& bench);
void add_bench_soak(CLI::App& bench);
void add_bench_actuator(CLI::App& bench);

}  // namespace mallet::app

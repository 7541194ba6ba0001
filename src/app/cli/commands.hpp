#pragma once
// The `mallet` command line: every product's subcommands, registered in one place (main.cpp
// parses them). Each cmd_*.cpp registers one command; it may include every product.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/common/command_support.hpp"

namespace mallet::app {

//! Adds every subcommand to the command line; each runs from its parse callback.
void register_commands(CLI::App& app);

void register_simulate(CLI::App& app);
void register_scene(CLI::App& app);
void register_analyze(CLI::App& app);
void register_trajectory(CLI::App& app);
void register_audio(CLI::App& app);
void register_bench(CLI::App& app);
//! `mallet bench ARGS…`: execs mallet-bench (beside this program, else on PATH) with ARGS;
//! returns 1, having said in one line which package to install, when it is not installed.
int run_bench_program(const std::vector<std::string>& args);
void register_wiimote(CLI::App& app);
void register_camera(CLI::App& app);
void register_calibrate(CLI::App& app);
//! `mallet calibrate actuator` (cmd_calibrate_actuator.cpp), under `calibrate`.
void add_calibrate_actuator(CLI::App& calibrate);
//! `mallet calibrate latency` (cmd_calibrate_latency.cpp), under `calibrate`.
void add_calibrate_latency(CLI::App& calibrate);
void register_render(CLI::App& app);
void register_run(CLI::App& app);
void register_study(CLI::App& app);
void register_config(CLI::App& app);
void register_doctor(CLI::App& app);

}  // namespace mallet::app

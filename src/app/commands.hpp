#pragma once
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace mallet::app {

//! A flag's check for a number in (0, `most`] (no upper bound when `most` is 0), worded
//! "must be > 0 and at most 60, got 0". CLI11's own PositiveNumber would quote the largest
//! double as its bound.
CLI::Validator positive_at_most(double most = 0);

//! Adds every subcommand to the command line; each runs from its parse callback.
void register_commands(CLI::App& app);

//! The status the last command asked to exit with (0 unless it said otherwise).
int exit_status();
void set_exit_status(int status);

//! A line for stderr once the command has succeeded (which settings it used): said after
//! its work, so that a command refusing bad input still says exactly one line.
void say_when_done(std::string line);
//! The lines said so far (main prints them when the command ends with status 0).
const std::vector<std::string>& lines_when_done();

void register_simulate(CLI::App& app);
void register_scene(CLI::App& app);
void register_analyze(CLI::App& app);
void register_trajectory(CLI::App& app);
void register_audio(CLI::App& app);
void register_bench(CLI::App& app);
void register_wiimote(CLI::App& app);
void register_calibrate(CLI::App& app);
void register_render(CLI::App& app);
void register_run(CLI::App& app);
void register_study(CLI::App& app);
void register_config(CLI::App& app);
void register_doctor(CLI::App& app);

//! `mallet bench` subcommands, each in its own file.
void add_bench_audio(CLI::App& bench);
void add_bench_input(CLI::App& bench);
void add_bench_render(CLI::App& bench);
void add_bench_report(CLI::App& bench);
void add_bench_latency(CLI::App& bench);
void add_bench_prediction(CLI::App& bench);
void add_bench_soak(CLI::App& bench);

}  // namespace mallet::app

#pragma once
// What every command of `mallet` shares, whichever product it runs: how it ends with a
// status, the line said once it has succeeded, and the flags' own checks beyond CLI11's.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/enum_names.hpp"

namespace mallet::app {

//! A flag's check for a number in (0, `most`] (no upper bound when `most` is 0), worded
//! "must be > 0 and at most 60, got 0". CLI11's own PositiveNumber would quote the largest
//! double as its bound.
CLI::Validator positive_at_most(double most = 0);

//! A flag's check for a time in seconds that the int64 nanosecond clock holds (finite, at
//! most 9.2e9 s either way: core/time.hpp's from_seconds), worded "must be a finite number of
//! seconds".
CLI::Validator seconds();

//! A flag's check for a size in pixels, WIDTHxHEIGHT with each side 16..8192
//! (core/pixel_size.hpp), worded as the parser words it.
CLI::Validator pixel_size();

//! A flag naming one of an enum's values by the table the settings read
//! (core/enum_names.hpp): CLI11 refuses any other word, and `value` takes the one named.
//! The help shows TEXT:{a,b,c}=default.
template <typename E, std::size_t N>
CLI::Option* add_choice(CLI::App& cmd, const std::string& flag, E& value, const EnumNames<E, N>& names,
                        const std::string& help) {
  std::vector<std::string> words;
  for (const auto& [v, name] : names) words.emplace_back(name);
  const auto take = [&value, &names](const std::string& word) { value = *value_named(names, word); };
  return cmd.add_option_function<std::string>(flag, take, help)
      ->check(CLI::IsMember(words))
      ->default_str(name_in(names, value));
}

//! Ends the running command with `status`; nothing when it is 0. It throws CLI11's own
//! RuntimeError, which main turns into the process's exit status without a message of its
//! own (the command has said why).
void finish_with(int status);

//! Runs `body` with SIGINT and SIGTERM setting the flag it is given (Ctrl+C ends a monitor
//! with its summary instead of killing it), the previous handlers restored afterwards, also
//! when it throws. Returns what `body` returns.
int run_until_interrupted(const std::function<int(const std::atomic<bool>& interrupted)>& body);

//! A line for stderr once the command has succeeded (which settings it used): said after
//! its work, so that a command refusing bad input still says exactly one line.
void say_when_done(std::string line);
//! The lines said so far (main prints them when the command ends with status 0).
const std::vector<std::string>& lines_when_done();

//! Parses the command line and runs the command it names; returns the process's exit status:
//! 0 ok, 1 a failure (I/O, a device), 2 bad input (a flag, or a file: FileError), or the
//! command's own (finish_with). A failure is one line on stderr, "PROGRAM: what went wrong";
//! help and version print as CLI11 prints them. Both programs' main (`mallet`, `mallet-bench`).
int run_command_line(CLI::App& app, int argc, char** argv);

//! The footer of every command's help: the exit statuses, and where each command's options
//! are ("Run `PROGRAM <command> --help` …"). CLI11 hands it on to the subcommands.
std::string exit_status_footer(const std::string& program);

}  // namespace mallet::app

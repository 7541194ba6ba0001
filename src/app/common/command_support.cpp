#include "app/common/command_support.hpp"

#include <csignal>
#include <cstdio>

#include <fmt/format.h>

#include "core/file_error.hpp"
#include "core/pixel_size.hpp"
#include "core/time.hpp"

namespace mallet::app {

namespace {
std::vector<std::string> g_when_done;
}  // namespace

void finish_with(int status) {
  if (status != 0) throw CLI::RuntimeError(status);
}

CLI::Validator positive_at_most(double most) {
  const std::string hi = most > 0 ? fmt::format("{:g}", most) : "";
  const std::string want = most > 0 ? std::string("must be > 0 and at most ") + hi : "must be > 0";
  return CLI::Validator(
      [most, want](std::string& value) {
        double v = 0;
        if (!CLI::detail::lexical_cast(value, v) || !(v > 0) || (most > 0 && v > most)) return want + ", got " + value;
        return std::string();
      },
      most > 0 ? std::string("in (0, ") + hi + "]" : "> 0");
}

CLI::Validator seconds() {
  return CLI::Validator(
      [](std::string& value) {
        double s = 0;
        if (CLI::detail::lexical_cast(value, s) && from_seconds(s)) return std::string();
        return "must be a finite number of seconds, got " + value;
      },
      "");
}

CLI::Validator pixel_size() {
  return CLI::Validator(
      [](std::string& value) {
        const Result<PixelSize, std::string> size = parse_pixel_size(value);
        return size ? std::string() : size.error();
      },
      "WIDTHxHEIGHT");
}

void say_when_done(std::string line) { g_when_done.push_back(std::move(line)); }
const std::vector<std::string>& lines_when_done() { return g_when_done; }

std::string exit_status_footer(const std::string& program) {
  return "Exit status: 0 ok, 1 failure (I/O, device), 2 bad input.\nRun `" + program +
         " <command> --help` for each command's options and file formats.";
}

int run_command_line(CLI::App& app, int argc, char** argv) {
  const std::string program = app.get_name();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::RuntimeError& e) {  // a command's own status (finish_with): it said why
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  } catch (const FileError& e) {
    std::fprintf(stderr, "%s: %s\n", program.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program.c_str(), e.what());
    return 1;
  }
  for (const std::string& line : lines_when_done()) std::fprintf(stderr, "%s\n", line.c_str());
  return 0;
}

namespace {
std::atomic<bool> g_interrupted{false};
void on_interrupt(int) { g_interrupted.store(true); }
}  // namespace

int run_until_interrupted(const std::function<int(const std::atomic<bool>& interrupted)>& body) {
  g_interrupted.store(false);
  const auto previous_int = std::signal(SIGINT, on_interrupt);
  const auto previous_term = std::signal(SIGTERM, on_interrupt);
  struct Restore {
    decltype(previous_int) int_handler, term_handler;
    ~Restore() {
      std::signal(SIGINT, int_handler);
      std::signal(SIGTERM, term_handler);
    }
  } restore{previous_int, previous_term};
  return body(g_interrupted);
}

}  // namespace mallet::app

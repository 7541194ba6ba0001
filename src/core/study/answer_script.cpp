#include "core/study/answer_script.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>

#include "core/file_error.hpp"

namespace mallet::study {

std::vector<ObserverAnswer> read_answer_script(const std::filesystem::path& path,
                                               const std::vector<std::string>& choices) {
  std::ifstream in(path);
  if (!in) throw FileError(path.string(), 0, 0, "cannot open (does it exist?)");
  std::vector<ObserverAnswer> out;
  std::string line;
  std::uint32_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::size_t end = line.find_first_of(" \t", first);
    ObserverAnswer a;
    a.answer = line.substr(first, end == std::string::npos ? std::string::npos : end - first);
    if (std::find(choices.begin(), choices.end(), a.answer) == choices.end()) {
      std::string known;
      for (const std::string& c : choices) known += (known.empty() ? "" : ", ") + c;
      throw FileError(path.string(), line_no, static_cast<std::uint32_t>(first + 1),
                      "\"" + a.answer + "\" is not an answer of this protocol (" + known + ")");
    }
    double ms = 800.0;
    if (end != std::string::npos) {
      const std::size_t t0 = line.find_first_not_of(" \t", end);
      if (t0 != std::string::npos) {
        const auto [p, ec] = std::from_chars(line.data() + t0, line.data() + line.size(), ms);
        if (ec != std::errc() || p != line.data() + line.size() || !(ms >= 0 && ms <= 3.6e6))
          throw FileError(path.string(), line_no, static_cast<std::uint32_t>(t0 + 1),
                          "expected a response time in milliseconds (0 to 3600000) after the answer");
      }
    }
    a.response_time = static_cast<Nanos>(std::llround(ms * 1e6));
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace mallet::study

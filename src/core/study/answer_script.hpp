#pragma once
// Answers given in advance (`mallet study --answers FILE`): one per line, in the order the
// trials of this run are presented — "1" or "2" (2AFC: the interval that felt harder) or a
// material's name — optionally followed by the response time in milliseconds (default
// 800). Blank lines and lines starting with '#' are skipped. A line that is not one of
// the protocol's answers is a FileError naming FILE:LINE.
#include <filesystem>
#include <string>
#include <vector>

#include "core/study/simulated_observer.hpp"

namespace mallet::study {

std::vector<ObserverAnswer> read_answer_script(const std::filesystem::path& path,
                                               const std::vector<std::string>& choices);

}  // namespace mallet::study

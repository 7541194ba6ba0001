#pragma once
// Reads a study protocol (config/study/*.toml) with every problem reported as
// FILE:LINE:COL: key: problem (a FileError: exit status 2), unknown keys refused.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/material.hpp"
#include "core/study/study_protocol.hpp"

namespace mallet::study {

//! `materials`: those a stimulus may name (the scene's); `bar_count`: the scene's bars
//! (reference_bar must name one).
StudyProtocol load_study_protocol(const std::filesystem::path& path, const std::vector<Material>& materials,
                                  std::size_t bar_count);
StudyProtocol parse_study_protocol(std::string_view text, const std::string& name,
                                   const std::vector<Material>& materials, std::size_t bar_count);

//! Letters, digits, '_', '-' and '.', 1 to 64 of them: safe in a CSV field and a file name.
bool is_plain_name(std::string_view s);

}  // namespace mallet::study

#pragma once
// Where a program of Mallet's, or one it starts, is found: on PATH, or beside this
// executable. `mallet` and `mallet-bench` are two programs of one build, installed side by
// side (/usr/bin in the packages, build/<preset>/ in a build tree): each finds the other
// beside itself first, so that a build tree's pair never mixes with an installed one.
#include <filesystem>
#include <string>

namespace mallet::app {

//! The full path of `program` on PATH (or `program` itself when it names a path and is
//! executable); empty when it is not installed.
std::string find_program(const std::string& program);

//! `program` beside this executable (/proc/self/exe), else on PATH; empty when neither has it.
std::filesystem::path sibling_program(const std::string& program);

}  // namespace mallet::app

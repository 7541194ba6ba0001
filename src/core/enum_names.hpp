#pragma once
// An enum's names, written once. The same table turns a value into the word the settings,
// the journal and the CSVs use, reads that word back, and lists the words for a message
// that says what is allowed, so a name cannot be spelt one way when written and another
// when read.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace mallet {

//! Each value with its name, in the order messages list them.
template <typename E, std::size_t N>
using EnumNames = std::array<std::pair<E, const char*>, N>;

//! `value`'s name in `names`, or `unknown` for a value the table lacks.
template <typename E, std::size_t N>
constexpr const char* name_in(const EnumNames<E, N>& names, E value, const char* unknown = "?") {
  for (const auto& [v, name] : names)
    if (v == value) return name;
  return unknown;
}

//! The value `name` names, or nothing.
template <typename E, std::size_t N>
constexpr std::optional<E> value_named(const EnumNames<E, N>& names, std::string_view name) {
  for (const auto& [v, n] : names)
    if (n == name) return v;
  return std::nullopt;
}

//! The names quoted for a message: "\"a\", \"b\" or \"c\"".
template <typename E, std::size_t N>
std::string quoted_names(const EnumNames<E, N>& names) {
  std::string out;
  for (std::size_t i = 0; i < N; ++i)
    out += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + ('"' + std::string(names[i].second) + '"');
  return out;
}

}  // namespace mallet

#pragma once
// What the settings name (materials, instrument presets, study stimuli): found by its name,
// and the names listed for a message that says what is known.
#include <string>
#include <string_view>
#include <vector>

namespace mallet {

//! The first of `items` whose `name` is `name`, or null.
template <typename T>
const T* find_named(const std::vector<T>& items, std::string_view name) {
  for (const T& item : items)
    if (item.name == name) return &item;
  return nullptr;
}

//! The items' names in order, "wood, metal, rubber".
template <typename T>
std::string names_of(const std::vector<T>& items) {
  std::string names;
  for (const T& item : items) names += (names.empty() ? "" : ", ") + item.name;
  return names;
}

}  // namespace mallet

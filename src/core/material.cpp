#include "core/material.hpp"

namespace mallet {

const Material* MaterialLibrary::find(std::string_view name) const {
  for (const Material& m : materials_)
    if (m.name == name) return &m;
  return nullptr;
}

std::string MaterialLibrary::names() const {
  std::string out;
  for (const Material& m : materials_) out += (out.empty() ? "" : ", ") + m.name;
  return out;
}

}  // namespace mallet

#include "core/material.hpp"

#include "core/named.hpp"

namespace mallet {

const Material* MaterialLibrary::find(std::string_view name) const { return find_named(materials_, name); }

std::string MaterialLibrary::names() const { return names_of(materials_); }

}  // namespace mallet

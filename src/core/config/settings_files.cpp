#include "core/config/settings_files.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

#include "core/config/app_config_table.hpp"
#include "core/config/toml_reader.hpp"

namespace mallet::config {
namespace fs = std::filesystem;

namespace {

//! Merges `from` over `into`: tables key by key, everything else replaced. The nodes are
//! moved, not copied, so each keeps the file and line it was written at (toml++ copies
//! drop source positions): errors and `show_settings` name the drop-in.
void merge_into(toml::table& into, toml::table&& from) {
  for (auto&& [key, node] : from) {
    const std::string name(key.str());  // a named copy: clang 14 cannot capture a binding
    if (toml::table* sub = node.as_table())
      if (toml::table* existing = into.get_as<toml::table>(name)) {
        merge_into(*existing, std::move(*sub));
        continue;
      }
    node.visit([&into, &name](auto&& n) { into.insert_or_assign(name, std::move(n)); });
  }
}

//! The settings file then each drop-in, parsed afresh and merged in order.
toml::table merged(const std::optional<fs::path>& file, const std::vector<fs::path>& drop_ins) {
  toml::table root = file ? parse_file(*file) : toml::table{};
  for (const fs::path& d : drop_ins) merge_into(root, parse_file(d));
  return root;
}

bool bare_key(std::string_view k) {
  return !k.empty() && std::all_of(k.begin(), k.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

std::string key_text(std::string_view k) {
  if (bare_key(k)) return std::string(k);
  std::ostringstream out;
  out << toml::value<std::string>(std::string(k));  // a quoted TOML string
  return out.str();
}

std::string from_text(const toml::node& n) {
  const auto& path = n.source().path;
  std::string out = "  # from " + (path ? *path : std::string("?"));
  if (n.source().begin.line > 0) out += ":" + std::to_string(n.source().begin.line);
  return out;
}

//! A value as TOML, floats in their shortest form that reads back exactly (0.05, not
//! toml++'s 0.050000000000000003).
std::string value_text(const toml::node& v) {
  if (const auto* d = v.as_floating_point()) {
    const double x = d->get();
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    char buf[32];
    const auto end = std::to_chars(buf, buf + sizeof buf, x).ptr;
    std::string text(buf, end);
    if (text.find_first_of(".eEn") == std::string::npos) text += ".0";  // still a float
    return text;
  }
  if (const auto* a = v.as_array()) {
    std::string text = "[";
    for (std::size_t i = 0; i < a->size(); ++i) text += (i ? ", " : "") + value_text(*a->get(i));
    return text + "]";
  }
  if (const auto* t = v.as_table()) {  // an inline table inside an array
    std::string text = "{";
    bool first = true;
    for (auto&& [k, e] : *t) {
      text += (first ? " " : ", ") + key_text(k.str()) + " = " + value_text(e);
      first = false;
    }
    return text + " }";
  }
  std::ostringstream out;
  v.visit([&out](const auto& n) { out << toml::toml_formatter{n, toml::format_flags::none}; });
  return out.str();
}

void emit(std::ostringstream& out, const toml::table& t, const std::string& prefix) {
  for (auto&& [k, v] : t) {
    if (v.is_table() || v.is_array_of_tables()) continue;
    out << key_text(k.str()) << " = " << value_text(v) << from_text(v) << '\n';
  }
  for (auto&& [k, v] : t) {
    const std::string name = prefix + key_text(k.str());
    if (const toml::table* sub = v.as_table()) {
      out << "\n[" << name << "]\n";
      emit(out, *sub, name + ".");
    } else if (v.is_array_of_tables()) {
      for (const toml::node& el : *v.as_array()) {
        out << "\n[[" << name << "]]\n";
        emit(out, *el.as_table(), name + ".");
      }
    }
  }
}

}  // namespace

std::string LoadedSettings::describe() const {
  std::string out = file ? file->string() : std::string("built-in defaults");
  if (!drop_ins.empty()) {
    out += " + " + std::to_string(drop_ins.size()) + (drop_ins.size() == 1 ? " drop-in (" : " drop-ins (");
    for (std::size_t i = 0; i < drop_ins.size(); ++i) out += (i ? ", " : "") + drop_ins[i].filename().string();
    out += ")";
  }
  if (!refused.empty())
    out += "; " + std::to_string(refused.size()) + (refused.size() == 1 ? " drop-in refused" : " drop-ins refused");
  return out;
}

fs::path drop_in_dir_of(const fs::path& settings_file) {
  fs::path dir = settings_file;
  dir += ".d";
  return dir;
}

std::vector<fs::path> drop_in_files(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".toml" && e.is_regular_file(ec)) out.push_back(e.path());
  // Lexical order of the names, byte by byte (as systemd orders its drop-ins).
  std::sort(out.begin(), out.end(),
            [](const fs::path& a, const fs::path& b) { return a.filename().string() < b.filename().string(); });
  return out;
}

LoadedSettings load_settings(const std::optional<fs::path>& file, const std::vector<fs::path>& drop_ins) {
  LoadedSettings s;
  s.file = file;
  const std::string name = file ? file->string() : std::string("built-in defaults");
  s.config = read_app_config(merged(file, {}), name);  // a bad settings file throws, as before
  for (const fs::path& d : drop_ins) {
    std::vector<fs::path> candidate = s.drop_ins;
    candidate.push_back(d);
    try {
      s.config = read_app_config(merged(file, candidate), name);
      s.drop_ins = std::move(candidate);
    } catch (const FileError& e) {
      // The drop-in alone is refused; a problem the merge exposes elsewhere (e.g. a routing
      // channel now out of range) is reported where it is, named as this drop-in's doing.
      const std::string what = e.what();
      s.refused.push_back(e.file() == d.string() ? what + " (drop-in refused)"
                                                 : what + " (after the drop-in " + d.string() + ", refused)");
    }
  }
  return s;
}

LoadedSettings load_kept_settings(const fs::path& kept, const std::optional<fs::path>& as_if) {
  LoadedSettings s;
  s.file = kept;
  s.config = read_app_config(parse_file(kept), (as_if ? *as_if : kept).string());
  return s;
}

std::string at_kept_origin(const fs::path& kept, const std::string& message) {
  const std::string prefix = kept.string() + ":";
  std::string out;
  std::size_t from = 0;
  std::vector<std::string> lines;  // the kept file's, read at the first place found
  bool read = false;
  for (std::size_t at = message.find(prefix); at != std::string::npos; at = message.find(prefix, from)) {
    std::size_t end = at + prefix.size();
    std::size_t number = 0;
    while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end])))
      number = number * 10 + static_cast<std::size_t>(message[end++] - '0');
    out += message.substr(from, at - from);
    from = end;
    if (!read) {
      std::ifstream in(kept);
      for (std::string l; std::getline(in, l);) lines.push_back(l);
      read = true;
    }
    const std::string place = message.substr(at, end - at);
    const std::string marker = "  # from ";
    const std::size_t origin =
        number >= 1 && number <= lines.size() ? lines[number - 1].rfind(marker) : std::string::npos;
    if (origin == std::string::npos) {
      out += place;
      continue;
    }
    // The operator's place, and then what followed the kept one (":COL: problem") unchanged.
    out += lines[number - 1].substr(origin + marker.size()) + " (kept as " + place + ")";
    if (from < message.size() && message[from] == ':') {  // the kept column means nothing there
      std::size_t col = from + 1;
      while (col < message.size() && std::isdigit(static_cast<unsigned char>(message[col]))) ++col;
      if (col > from + 1) from = col;
    }
  }
  return out + message.substr(from);
}

std::string show_settings(const LoadedSettings& settings) {
  std::ostringstream out;
  out << "# mallet settings: " << (settings.file ? settings.file->string() : std::string("built-in defaults"));
  for (const fs::path& d : settings.drop_ins) out << "\n#   + " << d.string();
  out << "\n# Keys not listed keep their built-in defaults (the shipped config/mallet.toml).\n";
  emit(out, merged(settings.file, settings.drop_ins), "");
  return out.str();
}

}  // namespace mallet::config

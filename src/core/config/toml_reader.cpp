#include "core/config/toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mallet::config {

namespace {

// A TOML number as a double. An integer is rounded to the nearest double: toml++'s own
// conversion (value<double>) gives nothing for an integer beyond 2^53, such as the
// 10362658707436286 that "{:.17g}" writes for a large error.
std::optional<double> number_of(const toml::node& node) {
  if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = node.as_floating_point()) return f->get();
  return std::nullopt;
}

std::string describe_value(const toml::node& node) {
  std::ostringstream out;
  if (node.is_string()) {
    out << '"' << node.as_string()->get() << '"';
  } else if (const auto v = number_of(node)) {
    out << *v;
  } else if (const auto* b = node.as_boolean()) {
    out << (b->get() ? "true" : "false");
  } else {
    out << "a " << node.type();
  }
  return out.str();
}

ConfigError error_from(const toml::parse_error& e, const std::string& name) {
  return ConfigError(name, e.source().begin.line, e.source().begin.column,
                     std::string(e.description()));
}

}  // namespace

toml::table parse_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw ConfigError(path.string(), 0, 0, "file not found");
  if (std::filesystem::is_directory(path, ec))
    throw ConfigError(path.string(), 0, 0, "is a directory, expected a TOML file");
  try {
    return toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    throw error_from(e, path.string());
  }
}

toml::table parse_text(std::string_view text, const std::string& name) {
  try {
    return toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    throw error_from(e, name);
  }
}

TableReader::TableReader(const toml::table& table, std::string file, std::string key_path)
    : table_(&table), file_(std::move(file)), key_path_(std::move(key_path)) {}

std::string TableReader::dotted(std::string_view key) const {
  if (key_path_.empty()) return std::string(key);
  if (key.empty()) return key_path_;
  return key_path_ + "." + std::string(key);
}

FilePlace TableReader::place_of(const toml::node* node) const {
  const toml::source_region& where = node ? node->source() : table_->source();
  // A node merged in from a drop-in (settings_files.hpp) keeps the file it was written in.
  return {where.path && !where.path->empty() ? *where.path : file_, where.begin.line, where.begin.column};
}

FilePlace TableReader::place(std::string_view key) const { return place_of(table_->get(key)); }

void TableReader::fail_at(const toml::node* node, std::string_view key,
                          const std::string& message) const {
  throw ConfigError(place_of(node), dotted(key) + ": " + message);
}

void TableReader::fail(std::string_view key, const std::string& message) const {
  fail_at(table_->get(key), key, message);
}

bool TableReader::has(std::string_view key) const { return table_->contains(key); }

bool TableReader::has_table(std::string_view key) const {
  const toml::node* node = table_->get(key);
  return node && node->is_table();
}

const toml::node& TableReader::required(std::string_view key) {
  used_.emplace(key);
  const toml::node* node = table_->get(key);
  if (!node) fail_at(nullptr, key, "missing (required)");
  return *node;
}

double TableReader::number(std::string_view key) {
  const toml::node& node = required(key);
  const std::optional<double> v = number_of(node);
  if (!v) fail_at(&node, key, "expected a number, got " + describe_value(node));
  if (!std::isfinite(*v)) fail_at(&node, key, "must be finite, got " + describe_value(node));
  return *v;
}

template <typename T>
T TableReader::scalar(std::string_view key, const char* expected) {
  const toml::node& node = required(key);
  const toml::value<T>* value = node.as<T>();
  if (!value) fail_at(&node, key, std::string("expected ") + expected + ", got " + describe_value(node));
  return value->get();
}

double TableReader::number_or(std::string_view key, double fallback) {
  return or_fallback(key, fallback, &TableReader::number);
}

std::int64_t TableReader::integer(std::string_view key) { return scalar<std::int64_t>(key, "an integer"); }

std::int64_t TableReader::integer_or(std::string_view key, std::int64_t fallback) {
  return or_fallback(key, fallback, &TableReader::integer);
}

std::string TableReader::string(std::string_view key) { return scalar<std::string>(key, "a string"); }

std::string TableReader::string_or(std::string_view key, std::string fallback) {
  return or_fallback(key, std::move(fallback), &TableReader::string);
}

bool TableReader::boolean_or(std::string_view key, bool fallback) {
  return or_fallback(key, fallback,
                     [](TableReader& t, std::string_view k) { return t.scalar<bool>(k, "true or false"); });
}

template <typename T, typename Get>
std::vector<T> TableReader::array_of(std::string_view key, const char* elements, const char* element, Get get) {
  const toml::node& node = required(key);
  const toml::array* array = node.as_array();
  if (!array) fail_at(&node, key, std::string("expected an array of ") + elements + ", got " + describe_value(node));
  std::vector<T> out;
  for (const toml::node& el : *array) {
    std::optional<T> v = get(el);
    if (!v) fail_at(&el, key, std::string("expected ") + element + ", got " + describe_value(el));
    out.push_back(std::move(*v));
  }
  return out;
}

std::vector<double> TableReader::numbers(std::string_view key) {
  return array_of<double>(key, "numbers", "a finite number", [](const toml::node& el) -> std::optional<double> {
    const std::optional<double> v = number_of(el);
    if (!v || !std::isfinite(*v)) return std::nullopt;
    return v;
  });
}

std::vector<std::int64_t> TableReader::integers(std::string_view key) {
  return array_of<std::int64_t>(key, "integers", "an integer", [](const toml::node& el) -> std::optional<std::int64_t> {
    if (!el.is_integer()) return std::nullopt;
    return el.as_integer()->get();
  });
}

std::vector<std::string> TableReader::strings(std::string_view key) {
  return array_of<std::string>(key, "strings", "a string", [](const toml::node& el) -> std::optional<std::string> {
    if (!el.is_string()) return std::nullopt;
    return el.as_string()->get();
  });
}

TableReader TableReader::table(std::string_view key) {
  const toml::node& node = required(key);
  const toml::table* t = node.as_table();
  if (!t) fail_at(&node, key, "expected a table, got " + describe_value(node));
  return TableReader(*t, file_, dotted(key));
}

std::optional<TableReader> TableReader::optional_table(std::string_view key) {
  used_.emplace(key);
  if (!has(key)) return std::nullopt;
  return table(key);
}

std::vector<TableReader> TableReader::tables(std::string_view key) {
  const toml::node& node = required(key);
  const toml::array* array = node.as_array();
  if (!array || !array->is_array_of_tables())
    fail_at(&node, key, "expected one or more [[" + dotted(key) + "]] tables");
  std::vector<TableReader> out;
  std::size_t i = 0;
  for (const toml::node& el : *array)
    out.emplace_back(*el.as_table(), file_, dotted(key) + "[" + std::to_string(i++) + "]");
  return out;
}

std::vector<std::string> TableReader::keys() const {
  std::vector<std::pair<std::uint32_t, std::string>> ordered;
  for (const auto& [k, v] : *table_) ordered.emplace_back(v.source().begin.line, std::string(k.str()));
  std::stable_sort(ordered.begin(), ordered.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  for (auto& [line, k] : ordered) out.push_back(std::move(k));
  return out;
}

void TableReader::finish() const {
  for (const auto& [k, v] : *table_) {
    if (!used_.contains(k.str()))
      fail_at(&v, k.str(), "unknown key (misspelt? see the comments in the shipped file)");
  }
}

std::string number_text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

double TableReader::positive(std::string_view key) {
  const double v = number(key);
  require_positive(key, v);
  return v;
}

double TableReader::non_negative(std::string_view key) {
  const double v = number(key);
  require_non_negative(key, v);
  return v;
}

double TableReader::positive_or(std::string_view key, double fallback) {
  const double v = number_or(key, fallback);
  require_positive(key, v);
  return v;
}

double TableReader::non_negative_or(std::string_view key, double fallback) {
  const double v = number_or(key, fallback);
  require_non_negative(key, v);
  return v;
}

void TableReader::require_positive(std::string_view key, double value) const {
  if (!(value > 0.0)) fail(key, "must be > 0, got " + number_text(value));
}

void TableReader::require_non_negative(std::string_view key, double value) const {
  if (!(value >= 0.0)) fail(key, "must be >= 0, got " + number_text(value));
}

void TableReader::require_range(std::string_view key, double value, double lo, double hi) const {
  if (!(value >= lo && value <= hi)) {
    std::ostringstream msg;
    msg << "must be in [" << lo << ", " << hi << "], got " << value;
    fail(key, msg.str());
  }
}

void TableReader::read(std::string_view key, double& value, double lo, double hi) {
  value = number_or(key, value);
  require_range(key, value, lo, hi);
}

void TableReader::read(std::string_view key, int& value, int lo, int hi) {
  const std::int64_t v = integer_or(key, value);
  require_range(key, static_cast<double>(v), lo, hi);
  value = static_cast<int>(v);
}

}  // namespace mallet::config

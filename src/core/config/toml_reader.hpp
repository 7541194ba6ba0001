#pragma once
// Reading a TOML table with every problem reported as file:line:column and the dotted
// key, and with unknown keys refused (a misspelt key is the most common operator
// mistake, and silently using a default instead would change a stimulus).
// Only the config loaders include this (toml++ is heavy to compile).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "core/enum_names.hpp"
#include "core/file_error.hpp"

namespace mallet::config {

//! A number as the messages quote it ("0.3", "1e+09").
std::string number_text(double v);

//! Parses a whole file; a syntax error becomes a ConfigError with its position.
toml::table parse_file(const std::filesystem::path& path);

//! Parses text held in memory (tests, and files read by the caller); `name` is what
//! error messages call it.
toml::table parse_text(std::string_view text, const std::string& name);

class TableReader {
 public:
  TableReader(const toml::table& table, std::string file, std::string key_path = {});

  double number(std::string_view key);
  double number_or(std::string_view key, double fallback);
  std::int64_t integer(std::string_view key);
  std::int64_t integer_or(std::string_view key, std::int64_t fallback);
  std::string string(std::string_view key);
  std::string string_or(std::string_view key, std::string fallback);
  bool boolean_or(std::string_view key, bool fallback);
  std::vector<double> numbers(std::string_view key);
  std::vector<std::int64_t> integers(std::string_view key);
  std::vector<std::string> strings(std::string_view key);
  bool has(std::string_view key) const;
  //! Whether `key` holds a table (a [key] or key = { … }), for a key that may be a table or a list.
  bool has_table(std::string_view key) const;

  TableReader table(std::string_view key);
  std::optional<TableReader> optional_table(std::string_view key);
  std::vector<TableReader> tables(std::string_view key);  //!< an array of tables [[key]]
  std::vector<std::string> keys() const;                  //!< in file order

  //! Throws if the table holds a key nobody asked for.
  void finish() const;

  //! A ConfigError located at `key` (or at the table itself if the key is absent).
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

  //! A number that must be > 0 (>= 0), typed once: the key's value, else `fallback` (the
  //! _or forms), refused with the value quoted when out of range.
  double positive(std::string_view key);
  double non_negative(std::string_view key);
  double positive_or(std::string_view key, double fallback);
  double non_negative_or(std::string_view key, double fallback);

  //! A word from a fixed set, typed once: `key`'s string read through `names` (the _or
  //! form: `fallback` when the key is absent); any other word is refused with the words
  //! allowed: expected "a", "b" or "c", got "x".
  template <typename E, std::size_t N>
  E choice(std::string_view key, const EnumNames<E, N>& names) {
    const std::string word = string(key);
    if (const std::optional<E> value = value_named(names, word)) return *value;
    fail(key, "expected " + quoted_names(names) + ", got \"" + word + "\"");
  }
  template <typename E, std::size_t N>
  E choice_or(std::string_view key, const EnumNames<E, N>& names, E fallback) {
    return or_fallback(key, fallback, [&names](TableReader& t, std::string_view k) { return t.choice(k, names); });
  }

  //! Range checks with the value quoted in the message.
  void require_positive(std::string_view key, double value) const;
  void require_non_negative(std::string_view key, double value) const;
  void require_range(std::string_view key, double value, double lo, double hi) const;

  //! A setting typed once: `value` takes `key`'s number when the table has it (else it
  //! keeps its default), which must lie in [lo, hi] (the message quotes it).
  void read(std::string_view key, double& value, double lo, double hi);
  //! The same for a whole number (checked before it is narrowed to an int).
  void read(std::string_view key, int& value, int lo, int hi);

  //! Where `key` was written (the table itself if it is absent): its own file for a value
  //! merged in from a drop-in.
  FilePlace place(std::string_view key) const;

  const std::string& file() const { return file_; }
  std::string dotted(std::string_view key) const;

 private:
  const toml::node& required(std::string_view key);
  //! `key`'s value of TOML type T, refused as not `expected` ("an integer").
  template <typename T>
  T scalar(std::string_view key, const char* expected);
  //! `reader(key)` when the table has `key`, else `fallback` (the key counts as asked for).
  template <typename T, typename Reader>
  T or_fallback(std::string_view key, T fallback, Reader reader) {
    if (!has(key)) return used_.emplace(key), fallback;
    return std::invoke(reader, *this, key);
  }
  //! The array at `key`, each element read by `get` (nothing: refused as not `element`).
  template <typename T, typename Get>
  std::vector<T> array_of(std::string_view key, const char* elements, const char* element, Get get);
  FilePlace place_of(const toml::node* node) const;
  [[noreturn]] void fail_at(const toml::node* node, std::string_view key,
                            const std::string& message) const;

  const toml::table* table_;
  std::string file_;
  std::string key_path_;
  std::set<std::string, std::less<>> used_;
};

}  // namespace mallet::config

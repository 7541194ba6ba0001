#pragma once
// One way for a function to return a value or why not: Result<T, E>, Debian's tl::expected
// (libexpected-dev; std::expected is C++23). E is the area's own error: an enum, or a struct
// with its kind and what to say, with to_string or message(). Callers test it (`if (!r)`),
// take the value (`*r`, `r->`) or the error (`r.error()`), and pass an error on with
// `return tl::unexpected(r.error());`.
//
// Exceptions stay where a constructor cannot return (a device, a file that must load for
// the object to exist) and for a bad file or flag that ends a command (FileError, one line
// naming the file, the place and the problem, printed by main).
#include <string>
#include <utility>

#include <tl/expected.hpp>

namespace mallet {

template <typename T, typename E>
using Result = tl::expected<T, E>;

//! A check with nothing to return: it passed, or the sentence that says why not
//! (`return refused("rows must be >= 2");`, and `return {};` when it passed).
using Check = Result<void, std::string>;
inline tl::unexpected<std::string> refused(std::string why) { return tl::unexpected(std::move(why)); }
//! Why a result said no; empty when it holds a value.
template <typename T>
std::string why_not(const Result<T, std::string>& result) {
  return result ? std::string() : result.error();
}

}  // namespace mallet

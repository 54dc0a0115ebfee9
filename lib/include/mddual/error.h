// Exception types thrown by mddual. Every error the library raises derives
// from mddual::Error, so callers can catch the library's errors apart from
// anything else; the message names what is wrong and where.
#pragma once

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace mddual {

/// Base of every exception thrown by mddual.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The caller passed something unusable: empty or non-finite coordinates, too
/// few points, a zero or non-finite direction, a null polytope.
class InvalidInputError : public Error {
 public:
  using Error::Error;
};

/// The input is well formed but geometrically degenerate in a way the library
/// does not accept (all points collinear or coincident).
class DegenerateGeometryError : public InvalidInputError {
 public:
  using InvalidInputError::InvalidInputError;
};

/// A third-party geometry kernel (qhull) failed on input we passed it.
class HullError : public Error {
 public:
  using Error::Error;
};

/// An internal consistency check failed (iteration cap reached, inconsistent
/// topology). This is a bug or a numerical corner we did not foresee: the
/// message carries the query in a form that can be pasted into a test.
class NumericalError : public Error {
 public:
  using Error::Error;
};

/// Bytes of a user's text quoted in a message (a 10 MB name or value is cut).
inline constexpr std::size_t kMaxQuotedChars = 200;

/// A user's text as messages quote it: control bytes (NUL, newline, escape)
/// shown as '?', and at most `max_bytes` bytes (kMaxQuotedChars unless
/// given; cut at the start of a UTF-8 character) followed by "... (N bytes)".
/// Shared by the library, the planning layer and the CLI.
inline std::string clipForMessage(const std::string& text, std::size_t max_bytes = kMaxQuotedChars) {
  std::size_t cut = std::min(text.size(), max_bytes);
  while (cut > 0 && cut < text.size() && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  std::string out = text.substr(0, cut);
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  if (cut < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

}  // namespace mddual

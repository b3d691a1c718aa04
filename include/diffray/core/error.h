#pragma once
// Errors. InputError is for anything a user supplied (a file, a field, an option value): its message is
// one line naming what was wrong, and the CLI prints it and exits non-zero. DIFFRAY_CHECK guards internal
// invariants (a failure is a bug in diffray, not in the input) and throws InternalError.
#include <stdexcept>
#include <cstddef>
#include <string>

namespace diffray::core {

/// `text` on one line for the terminal: control characters (a newline in a file name, an escape byte from a
/// file) written as \\n, \\t or \\xNN. For errors and warnings that quote names from the user or a file.
std::string oneLine(const std::string& text);
/// The Levenshtein distance between two strings (to suggest what a typo was meant to be).
std::size_t editDistance(const std::string& a, const std::string& b);
/// An ASCII control character (below 0x20, or DEL): what oneLine escapes and gnuplot scripts may not hold.
inline bool isControlCharacter(char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }

/// Bad user input. `where` names the file, option or field (may be empty); `what` says what is wrong.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& where, const std::string& what)
      : std::runtime_error(where.empty() ? what : where + ": " + what), where_(where) {}
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

/// A broken internal invariant: a diffray bug.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// Throws InputError unless `value` is finite and > 0.
void requirePositive(const std::string& where, double value);
/// Throws InputError unless `value` is finite.
void requireFinite(const std::string& where, double value);
/// ceil(count) as an int, for sizes computed in double (table rows, cells). Throws InputError naming
/// `where` unless it is finite and at most `limit`: never a silent overflow.
int checkedCount(const std::string& where, double count, double limit);

}  // namespace diffray::core

#define DIFFRAY_CHECK(cond)                                                                       \
  do {                                                                                            \
    if (!(cond))                                                                                  \
      throw ::diffray::core::InternalError(std::string(__FILE__) + ":" + std::to_string(__LINE__) + \
                                           ": check failed: " #cond);                             \
  } while (0)

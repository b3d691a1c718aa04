#include "diffray/core/error.h"

#include <cmath>
#include <sstream>

namespace diffray::core {

std::string oneLine(const std::string& text) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (const char ch : text) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (isControlCharacter(ch)) out += std::string("\\x") + hex[c >> 4] + hex[c & 15];
    else out += ch;
  }
  return out;
}

void requireFinite(const std::string& where, double value) {
  if (!std::isfinite(value)) throw InputError(where, "must be a finite number, got " + std::to_string(value));
}

void requirePositive(const std::string& where, double value) {
  requireFinite(where, value);
  if (!(value > 0.0)) {
    std::ostringstream s;
    s << "must be > 0, got " << value;
    throw InputError(where, s.str());
  }
}

int checkedCount(const std::string& where, double count, double limit) {
  const double c = std::ceil(count);
  if (!(std::isfinite(c) && c <= limit && c <= 2147483647.0)) {
    std::ostringstream msg;
    msg << "needs " << c << " cells or rows, more than the limit of " << limit
        << "; the parameters are too far apart (e.g. a width of very many wavelengths)";
    throw InputError(where, msg.str());
  }
  return c < 1.0 ? 1 : static_cast<int>(c);
}

}  // namespace diffray::core

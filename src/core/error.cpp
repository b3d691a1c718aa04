#include "diffray/core/error.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

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

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace diffray::core

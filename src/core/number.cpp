#include "diffray/core/number.h"

#include <cstdlib>

namespace diffray::core {

bool isDecimalNumber(const std::string& text) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t from = i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
    return i - from;
  };
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t mantissa = digits();
  if (i < text.size() && text[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == text.size();
}

bool parseDecimal(const std::string& text, double& value) {
  if (!isDecimalNumber(text)) return false;
  value = std::strtod(text.c_str(), nullptr);  // ERANGE: ±HUGE_VAL (infinite) or a value near 0
  return true;
}

}  // namespace diffray::core

#include "diffray/core/error.h"

#include <cmath>
#include <sstream>

namespace diffray::core {

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

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

}  // namespace diffray::core

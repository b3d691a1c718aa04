#pragma once
// The one number syntax diffray reads, in every option and every file reader (OBJ vertices, profile CSVs):
// decimal only. C's strtod alone would also read hex floats (0x10 as 16), "nan" and "inf"; these are
// refused here, so that a number means the same everywhere. Pure functions, safe from any thread.
#include <string>

namespace diffray::core {

/// Whether `text` is a decimal number: an optional sign, digits with an optional point (or a point and
/// digits), an optional exponent. Not hex, not "nan" or "inf", no surrounding spaces.
bool isDecimalNumber(const std::string& text);

/// Reads `text` into `value` when it is a decimal number (isDecimalNumber) and returns true; false
/// otherwise, `value` untouched. Beyond the double range the value is ±infinity (for the caller's
/// finiteness check); below it, 0 or a denormal.
bool parseDecimal(const std::string& text, double& value);

}  // namespace diffray::core

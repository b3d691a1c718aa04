#pragma once
// JsonField: a JSON value together with where it came from (the file and the field path inside it,
// e.g. "materials.carpet.absorption[3]"), so that every check on user input can throw one
// core::InputError line "FILE: PATH: what is wrong". The checks are strict on purpose: unknown keys
// (typos) are errors, numbers must be finite, and a value of the wrong type names the type it got.
// A JsonField refers to the json it wraps (which must outlive it); cheap to copy; not synchronised.
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "diffray/core/math.h"

namespace diffray::room {

/// The largest coordinate (metres, or a direction's component) a scene may use: Embree holds scenes and rays
/// in float, where 1e6 m still resolves 0.06 m and anything near 3.4e38 becomes infinite (an Embree assertion).
inline constexpr double kMaxCoordinateM = 1e6;

class JsonField {
 public:
  JsonField(const nlohmann::json& value, std::string file, std::string path = "");

  const nlohmann::json& json() const { return *value_; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  /// "FILE: PATH" (or "FILE" for the top level): the `where` of this field's errors.
  std::string where() const;
  /// Throws core::InputError(where(), what).
  [[noreturn]] void fail(const std::string& what) const;

  bool has(const std::string& key) const;
  /// The member `key`, which must exist (an object is required).
  JsonField operator[](const std::string& key) const;
  /// Element i of an array.
  JsonField at(std::size_t i) const;
  /// Requires an object whose keys are all in `allowed`; an unknown key fails with a suggestion.
  void allowKeys(std::initializer_list<const char*> allowed) const;
  /// Requires an object and returns its keys (sorted: nlohmann::json keeps objects in a std::map).
  std::vector<std::string> keys() const;
  /// Requires an array (of `n` elements when n >= 0) and returns its size.
  std::size_t arraySize(int n = -1) const;

  double number() const;  ///< a finite number
  double numberIn(double lo, double hi) const;
  double positive() const;
  /// A positive length in metres, at most 2·kMaxCoordinateM (a size of something in the scene).
  double length() const;
  std::string string() const;  ///< a non-empty string
  bool boolean() const;        ///< true or false
  core::Vec3 vec3() const;     ///< an array of 3 finite numbers, each within ±kMaxCoordinateM
  std::int64_t integerIn(std::int64_t lo, std::int64_t hi) const;

 private:
  const nlohmann::json* value_;
  std::string file_, path_;
};

/// "is a directory" or "is not a regular file" (a FIFO, a device) for a path that exists but is no input
/// file, else "" (a missing file is the caller's to report).
std::string notRegularFile(const std::string& path);

/// Reads and parses a JSON file (// and /* */ comments allowed). A missing file or a syntax error
/// throws core::InputError naming "FILE:LINE:COLUMN"; a key repeated within one object throws
/// "FILE: PATH.KEY: duplicate key".
nlohmann::json parseJsonFile(const std::string& path);
/// The same for text already read; `file` names it in messages.
nlohmann::json parseJsonText(const std::string& text, const std::string& file);

/// "null", "a string", "an array", … for messages.
std::string describeJson(const nlohmann::json& v);
/// A number for messages, without trailing zeros (1.2, not 1.200000).
std::string formatNumber(double v);

}  // namespace diffray::room

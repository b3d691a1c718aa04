#include "diffray/room/json_fields.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "diffray/core/error.h"

namespace diffray::room {
namespace {

// Follows the parser's events to refuse a key repeated within one object (nlohmann would keep the last
// one silently) and to name where it is ("materials.m", "geometry[2].box.name").
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(std::string file) : file_(std::move(file)) {}

  bool operator()(int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start: childStarts(), stack_.push_back({true, {}, {}, -1}); break;
      case E::array_start: childStarts(), stack_.push_back({false, {}, {}, -1}); break;
      case E::object_end:
      case E::array_end: stack_.pop_back(); break;
      case E::value: childStarts(); break;
      case E::key: {
        Frame& f = stack_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second) throw core::InputError(file_ + ": " + path(), "duplicate key");
        break;
      }
    }
    return true;
  }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string key;  // the object's current key
    long index;       // the array's current element
  };

  void childStarts() {
    if (!stack_.empty() && !stack_.back().object) ++stack_.back().index;
  }

  std::string path() const {
    std::string p;
    for (const Frame& f : stack_)
      p += f.object ? (p.empty() ? "" : ".") + f.key : "[" + std::to_string(f.index) + "]";
    return p;
  }

  std::string file_;
  std::vector<Frame> stack_;
};

}  // namespace

std::string notRegularFile(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status)) return "is a directory";
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) return "is not a regular file";
  return "";
}

nlohmann::json parseJsonText(const std::string& text, const std::string& file) {
  try {
    return nlohmann::json::parse(text, DuplicateKeyCheck(file), true, /*ignore_comments=*/true);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is 1-based and points just past the offending character; count lines up to it.
    const std::size_t end = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') ++line, column = 1;
      else ++column;
    }
    // Keep nlohmann's explanation but drop its "[json.exception…] parse error at line L, column C: ".
    std::string why = e.what();
    const std::size_t colon = why.find(": ");
    if (colon != std::string::npos) why = why.substr(colon + 2);
    throw core::InputError(file + ":" + std::to_string(line) + ":" + std::to_string(column),
                           "JSON syntax error: " + why);
  } catch (const nlohmann::json::exception& e) {
    // A number too large for a double (1e999): nlohmann gives no position for it.
    std::string why = e.what();
    if (const std::size_t end = why.find("] "); end != std::string::npos) why = why.substr(end + 2);
    throw core::InputError(file, why + " (numbers must be finite)");
  }
}

nlohmann::json parseJsonFile(const std::string& path) {
  if (const std::string problem = notRegularFile(path); !problem.empty()) throw core::InputError(path, problem);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::InputError(path, "cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  return parseJsonText(text.str(), path);
}

std::string describeJson(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::object: return "an object";
    case nlohmann::json::value_t::array: return "an array";
    case nlohmann::json::value_t::string: return "the string \"" + v.get<std::string>() + "\"";
    case nlohmann::json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
    case nlohmann::json::value_t::number_float: return formatNumber(v.get<double>());
    default: return "a value of another type";
  }
}

std::string formatNumber(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

JsonField::JsonField(const nlohmann::json& value, std::string file, std::string path)
    : value_(&value), file_(std::move(file)), path_(std::move(path)) {}

std::string JsonField::where() const { return path_.empty() ? file_ : file_ + ": " + path_; }

void JsonField::fail(const std::string& what) const { throw core::InputError(where(), what); }

bool JsonField::has(const std::string& key) const { return value_->is_object() && value_->contains(key); }

JsonField JsonField::operator[](const std::string& key) const {
  if (!value_->is_object()) fail("must be an object, got " + describeJson(*value_));
  const std::string child = path_.empty() ? key : path_ + "." + key;
  const auto it = value_->find(key);
  if (it == value_->end()) JsonField(*value_, file_, child).fail("missing (required)");
  return JsonField(*it, file_, child);
}

JsonField JsonField::at(std::size_t i) const {
  DIFFRAY_CHECK(value_->is_array() && i < value_->size());
  return JsonField((*value_)[i], file_, path_ + "[" + std::to_string(i) + "]");
}

void JsonField::allowKeys(std::initializer_list<const char*> allowed) const {
  if (!value_->is_object()) fail("must be an object, got " + describeJson(*value_));
  for (const auto& item : value_->items()) {
    bool known = false;
    std::string best, list;
    std::size_t best_d = 3;  // suggest only near misses
    for (const char* a : allowed) {
      if (item.key() == a) known = true;
      const std::size_t d = core::editDistance(item.key(), a);
      if (d < best_d) best_d = d, best = a;
      list += (list.empty() ? "" : ", ") + std::string(a);
    }
    if (known) continue;
    const std::string child = path_.empty() ? item.key() : path_ + "." + item.key();
    JsonField(item.value(), file_, child)
        .fail("unknown key" + (best.empty() ? std::string() : " (did you mean \"" + best + "\"?)") +
              "; allowed here: " + list);
  }
}

std::vector<std::string> JsonField::keys() const {
  if (!value_->is_object()) fail("must be an object, got " + describeJson(*value_));
  std::vector<std::string> k;
  for (const auto& item : value_->items()) k.push_back(item.key());
  return k;
}

std::size_t JsonField::arraySize(int n) const {
  if (!value_->is_array()) fail("must be an array, got " + describeJson(*value_));
  if (n >= 0 && value_->size() != static_cast<std::size_t>(n))
    fail("must have " + std::to_string(n) + " elements, got " + std::to_string(value_->size()));
  return value_->size();
}

double JsonField::number() const {
  // JSON has no NaN or Infinity: nlohmann writes them as null, and 1e999 parses to infinity.
  if (!value_->is_number())
    fail("must be a number, got " + describeJson(*value_) + (value_->is_null() ? " (NaN is not allowed)" : ""));
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail("must be a finite number, got " + formatNumber(v));
  return v;
}

double JsonField::numberIn(double lo, double hi) const {
  const double v = number();
  if (v < lo || v > hi) fail("must be in [" + formatNumber(lo) + ", " + formatNumber(hi) + "], got " + formatNumber(v));
  return v;
}

double JsonField::positive() const {
  const double v = number();
  if (!(v > 0.0)) fail("must be > 0, got " + formatNumber(v));
  return v;
}

double JsonField::length() const {
  const double v = positive();
  if (v > 2.0 * kMaxCoordinateM) fail("must be at most " + formatNumber(2.0 * kMaxCoordinateM) + " m, got " + formatNumber(v));
  return v;
}

bool JsonField::boolean() const {
  if (!value_->is_boolean()) fail("must be true or false, got " + describeJson(*value_));
  return value_->get<bool>();
}

std::string JsonField::string() const {
  if (!value_->is_string()) fail("must be a string, got " + describeJson(*value_));
  std::string s = value_->get<std::string>();
  if (s.empty()) fail("must not be empty");
  return s;
}

core::Vec3 JsonField::vec3() const {
  arraySize(3);
  double c[3];
  for (int i = 0; i < 3; ++i) {
    c[i] = at(i).number();
    if (std::abs(c[i]) > kMaxCoordinateM)
      at(i).fail("must be within ±" + formatNumber(kMaxCoordinateM) + " (scenes are in float metres), got " +
                 formatNumber(c[i]));
  }
  return core::Vec3(c[0], c[1], c[2]);
}

std::int64_t JsonField::integerIn(std::int64_t lo, std::int64_t hi) const {
  const double v = number();
  if (v != std::floor(v)) fail("must be a whole number, got " + formatNumber(v));
  if (v < static_cast<double>(lo) || v > static_cast<double>(hi))
    fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + formatNumber(v));
  return static_cast<std::int64_t>(v);
}

}  // namespace diffray::room

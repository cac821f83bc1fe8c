// Typed, checked access to a JSON document that remembers where each value sits, so that every
// error can say "<file>: shapes[2].medium.sigma_s[1]: expected a number >= 0, got -1".
// Objects are opened with the list of keys they may hold and reject any other key at once: a
// misspelt key must never be silently ignored.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/math.h"
#include "scene/scene_error.h"

namespace snee {

// An allowed interval for numbers; each end open or closed.
struct NumberRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;

  bool contains(double x) const;
  std::string describe() const;  // e.g. "a number >= 0", "a number in (0, 180)"
};

inline constexpr NumberRange kAnyNumber{};
inline constexpr NumberRange kNonNegative{0.0};
inline constexpr NumberRange kPositive{0.0, std::numeric_limits<double>::infinity(), true};
inline constexpr NumberRange kUnitInterval{0.0, 1.0};

class JsonObject;

struct Direction {
  Vec3 given;  // as written, for the canonical document
  Vec3 unit;
};

class JsonValue {
 public:
  JsonValue(const nlohmann::json& value, std::string path, const std::string& origin)
      : value_(&value), path_(std::move(path)), origin_(&origin) {}

  const nlohmann::json& json() const { return *value_; }
  const std::string& path() const { return path_; }
  const std::string& origin() const { return *origin_; }

  // Throws "<origin>: <path>: <message>".
  [[noreturn]] void fail(const std::string& message) const;
  // Throws "<origin>: <path>: expected <expectation>, got <the value>".
  [[noreturn]] void expected(const std::string& expectation) const;

  double number(const NumberRange& range = kAnyNumber) const;
  // A number that is finite and inside `range` after rounding to float, the precision the
  // program computes in.
  float real(const NumberRange& range = kAnyNumber) const;
  int64_t integer(int64_t min, int64_t max) const;
  bool boolean() const;
  std::string string() const;  // non-empty
  // One of `choices`; the message lists them.
  std::string choice(std::initializer_list<std::string_view> choices) const;
  Vec3 vec3() const;                                     // [x, y, z]
  Direction direction() const;                           // [x, y, z], non-zero
  Rgb rgb(const NumberRange& range = kAnyNumber) const;  // a number (grey) or [r, g, b]
  std::vector<JsonValue> array() const;
  std::vector<JsonValue> array(size_t size) const;  // exactly `size` elements
  JsonObject object(std::initializer_list<std::string_view> allowed_keys) const;
  // A member read before the object's key set is known (e.g. the "type" that decides it).
  JsonValue member(std::string_view key) const;

 private:
  const nlohmann::json* value_;
  std::string path_;
  const std::string* origin_;
};

class JsonObject {
 public:
  JsonObject(const JsonValue& value, std::initializer_list<std::string_view> allowed_keys);

  bool has(std::string_view key) const;
  JsonValue required(std::string_view key) const;
  std::optional<JsonValue> optional(std::string_view key) const;
  const JsonValue& value() const { return value_; }

 private:
  JsonValue value_;
};

// "a.b", "a[2]" or just "b" at the top level.
std::string json_child_path(const std::string& parent, std::string_view key);

// The deepest nesting of arrays and objects a document may have. Scenes need about six levels;
// the bound keeps every walk of a document that recurses (copying, dumping, comparing) far from
// the end of the stack, whatever the file holds.
inline constexpr int kMaxJsonDepth = 100;

// Parses JSON text (comments allowed). Every problem, including nesting deeper than
// kMaxJsonDepth and numbers beyond double range, is a SceneError
// "<origin>:<line>:<column>: <what is wrong and what was expected>".
nlohmann::json parse_json_document(std::string_view text, const std::string& origin);

}  // namespace snee

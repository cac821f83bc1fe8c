#include "scene/json_reader.h"

#include <cmath>
#include <sstream>

namespace snee {

namespace {

std::string format_number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

std::string join(std::initializer_list<std::string_view> words) {
  std::string out;
  for (std::string_view w : words) {
    if (!out.empty()) out += ", ";
    out += w;
  }
  return out;
}

// Short rendering of the offending value for messages.
std::string preview(const nlohmann::json& value) {
  std::string text = value.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

}  // namespace

bool NumberRange::contains(double x) const {
  if (std::isnan(x)) return false;
  const bool above = min_open ? x > min : x >= min;
  const bool below = max_open ? x < max : x <= max;
  return above && below;
}

std::string NumberRange::describe() const {
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  if (has_min && has_max) {
    return "a number in " + std::string(min_open ? "(" : "[") + format_number(min) + ", " +
           format_number(max) + (max_open ? ")" : "]");
  }
  if (has_min) return "a number " + std::string(min_open ? "> " : ">= ") + format_number(min);
  if (has_max) return "a number " + std::string(max_open ? "< " : "<= ") + format_number(max);
  return "a number";
}

std::string json_child_path(const std::string& parent, std::string_view key) {
  if (parent.empty()) return std::string(key);
  return parent + "." + std::string(key);
}

void JsonValue::fail(const std::string& message) const {
  const std::string where = path_.empty() ? "" : path_ + ": ";
  throw SceneError(*origin_ + ": " + where + message);
}

void JsonValue::expected(const std::string& expectation) const {
  fail("expected " + expectation + ", got " + preview(*value_));
}

double JsonValue::number(const NumberRange& range) const {
  if (!value_->is_number()) expected(range.describe());
  const double x = value_->get<double>();
  if (!range.contains(x)) expected(range.describe());
  return x;
}

float JsonValue::real(const NumberRange& range) const {
  const double x = number(range);
  const float f = static_cast<float>(x);
  if (!std::isfinite(f)) expected("a number within single-precision range");
  return f;
}

int64_t JsonValue::integer(int64_t min, int64_t max) const {
  const std::string expectation =
      "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  if (!value_->is_number_integer()) expected(expectation);
  // Unsigned first: a large unsigned value would wrap if read as signed.
  if (value_->is_number_unsigned() && value_->get<uint64_t>() > static_cast<uint64_t>(max)) {
    expected(expectation);
  }
  const int64_t i = value_->get<int64_t>();
  if (i < min || i > max) expected(expectation);
  return i;
}

bool JsonValue::boolean() const {
  if (!value_->is_boolean()) expected("true or false");
  return value_->get<bool>();
}

std::string JsonValue::string() const {
  if (!value_->is_string() || value_->get_ref<const std::string&>().empty()) {
    expected("a non-empty string");
  }
  return value_->get<std::string>();
}

std::string JsonValue::choice(std::initializer_list<std::string_view> choices) const {
  const std::string expectation = "one of: " + join(choices);
  if (!value_->is_string()) expected(expectation);
  const std::string& s = value_->get_ref<const std::string&>();
  for (std::string_view c : choices) {
    if (s == c) return s;
  }
  expected(expectation);
}

Vec3 JsonValue::vec3() const {
  if (!value_->is_array() || value_->size() != 3) expected("an array of 3 numbers");
  const std::vector<JsonValue> items = array();
  return {items[0].real(), items[1].real(), items[2].real()};
}

Vec3 JsonValue::direction() const {
  const Vec3 v = vec3();
  if (!(length(v) > 0)) expected("a non-zero direction");
  return v;
}

Rgb JsonValue::rgb(const NumberRange& range) const {
  if (value_->is_number()) return Rgb(real(range));
  if (!value_->is_array() || value_->size() != 3) {
    expected(range.describe() + " or an array of 3 such numbers");
  }
  const std::vector<JsonValue> items = array();
  return {items[0].real(range), items[1].real(range), items[2].real(range)};
}

std::vector<JsonValue> JsonValue::array() const {
  if (!value_->is_array()) expected("an array");
  std::vector<JsonValue> items;
  items.reserve(value_->size());
  for (size_t i = 0; i < value_->size(); ++i) {
    items.emplace_back((*value_)[i], path_ + "[" + std::to_string(i) + "]", *origin_);
  }
  return items;
}

std::vector<JsonValue> JsonValue::array(size_t size) const {
  if (!value_->is_array() || value_->size() != size) {
    expected("an array of " + std::to_string(size) + " elements");
  }
  return array();
}

JsonObject JsonValue::object(std::initializer_list<std::string_view> allowed_keys) const {
  return JsonObject(*this, allowed_keys);
}

JsonValue JsonValue::member(std::string_view key) const {
  if (!value_->is_object()) expected("an object");
  const auto it = value_->find(key);
  const std::string child_path = json_child_path(path_, key);
  if (it == value_->end()) fail("missing required key '" + std::string(key) + "'");
  return JsonValue(*it, child_path, *origin_);
}

JsonObject::JsonObject(const JsonValue& value, std::initializer_list<std::string_view> allowed)
    : value_(value) {
  if (!value.json().is_object()) value.expected("an object");
  for (const auto& [key, item] : value.json().items()) {
    bool known = false;
    for (std::string_view a : allowed) known = known || key == a;
    if (!known) {
      JsonValue(item, json_child_path(value.path(), key), value.origin())
          .fail("unknown key (allowed keys: " + join(allowed) + ")");
    }
  }
}

bool JsonObject::has(std::string_view key) const {
  return value_.json().contains(key);
}

JsonValue JsonObject::required(std::string_view key) const {
  return value_.member(key);
}

std::optional<JsonValue> JsonObject::optional(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return value_.member(key);
}

}  // namespace snee

#include "scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>

namespace snee {

namespace {

using nlohmann::json;

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

constexpr size_t kPreviewLength = 40;

// Appends `value` as compact JSON until `out` holds more than `limit` characters. Not dump(),
// which recurses through the whole value: a deeply nested one would overflow the stack. Every
// level writes a bracket before it descends, so the recursion stops within `limit` levels.
void append_preview(const json& value, std::string& out, size_t limit) {
  if (!value.is_structured()) {
    out += value.dump();
    return;
  }
  out += value.is_array() ? '[' : '{';
  for (auto it = value.begin(); it != value.end(); ++it) {
    if (out.size() > limit) return;
    if (it != value.begin()) out += ',';
    if (value.is_object()) out += json(it.key()).dump() + ':';
    append_preview(*it, out, limit);
  }
  out += value.is_array() ? ']' : '}';
}

// Short rendering of the offending value for messages.
std::string preview(const json& value) {
  std::string text;
  append_preview(value, text, kPreviewLength);
  if (text.size() > kPreviewLength) text = text.substr(0, kPreviewLength - 3) + "...";
  return text;
}

// Gives nlohmann's lexer the text one character at a time and records how far it has read, so
// that an error found while building the document (which the SAX interface does not locate)
// can still name a line and column.
class TrackingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackingIterator(const char* at, const char** read_end) : at_(at), read_end_(read_end) {}
  reference operator*() const {
    *read_end_ = at_ + 1;
    return *at_;
  }
  TrackingIterator& operator++() {
    ++at_;
    return *this;
  }
  TrackingIterator operator++(int) {
    const TrackingIterator before = *this;
    ++at_;
    return before;
  }
  bool operator==(const TrackingIterator& other) const { return at_ == other.at_; }

 private:
  const char* at_;
  const char** read_end_;
};

// Builds the document from nlohmann's SAX events, refusing nesting deeper than kMaxJsonDepth and
// keys given twice in one object (which nlohmann's own parser silently resolves to the last).
class DocumentBuilder final : public nlohmann::json_sax<json> {
 public:
  DocumentBuilder(std::string_view text, std::string origin)
      : text_(text), origin_(std::move(origin)), read_end_(text.data()) {}

  json parse() {
    const TrackingIterator begin(text_.data(), &read_end_);
    const TrackingIterator end(text_.data() + text_.size(), &read_end_);
    if (!json::sax_parse(begin, end, this, json::input_format_t::json, /*strict=*/true,
                         /*ignore_comments=*/true)) {
      throw SceneError(error_);
    }
    return std::move(document_);
  }

  bool null() override { return add(nullptr); }
  bool boolean(bool value) override { return add(value); }
  bool number_integer(number_integer_t value) override { return add(value); }
  bool number_unsigned(number_unsigned_t value) override { return add(value); }
  bool number_float(number_float_t value, const string_t&) override { return add(value); }
  bool string(string_t& value) override { return add(std::move(value)); }
  bool binary(binary_t& value) override { return add(json::binary(std::move(value))); }
  bool start_object(std::size_t) override { return open(json::object()); }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(json::array()); }
  bool end_array() override { return close(); }

  bool key(string_t& name) override {
    if (open_.back()->contains(name)) {
      return fail_here("the key " + json(name).dump() +
                       " appears twice in one object; expected each key at most once");
    }
    key_ = std::move(name);
    return true;
  }

  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& e) override {
    // 406 is nlohmann's "number overflow": a literal such as 1e400 that no double holds.
    if (e.id == 406) {
      return fail_at(position, "the number " + last_token +
                                   " is beyond double range; expected a finite number");
    }
    // nlohmann's message reads "[json.exception.parse_error.101] parse error at line L, column
    // C: ..."; the bracketed id means nothing to a user and the place is given in front.
    std::string message = e.what();
    const size_t id_end = message.find("] ");
    if (id_end != std::string::npos) message.erase(0, id_end + 2);
    if (message.starts_with("parse error")) {
      const size_t place_end = message.find(": ");
      if (place_end != std::string::npos) message.erase(0, place_end + 2);
    }
    return fail_at(position, "malformed JSON: " + message);
  }

 private:
  // Puts `value` where the document is being built: the root, the next element of the open
  // array, or the member of the open object under the last key.
  json& place(json value) {
    if (open_.empty()) return document_ = std::move(value);
    json& parent = *open_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(value));
      return parent.back();
    }
    return parent[key_] = std::move(value);
  }
  bool add(json value) {
    place(std::move(value));
    return true;
  }
  // Pointers into the open containers stay valid: a container only grows while none of its
  // children is open.
  bool open(json container) {
    if (open_.size() >= static_cast<size_t>(kMaxJsonDepth)) {
      return fail_here("arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth) +
                       " levels; expected at most " + std::to_string(kMaxJsonDepth));
    }
    open_.push_back(&place(std::move(container)));
    return true;
  }
  bool close() {
    open_.pop_back();
    return true;
  }

  bool fail_here(const std::string& message) {
    return fail_at(static_cast<size_t>(read_end_ - text_.data()), message);
  }
  // `offset` counts the characters read, so the one at fault is the last of them; the column is
  // 1-based, as in nlohmann's messages.
  bool fail_at(size_t offset, const std::string& message) {
    const std::string_view before = text_.substr(0, std::min(offset, text_.size()));
    const size_t line = 1 + static_cast<size_t>(std::count(before.begin(), before.end(), '\n'));
    const size_t line_start =
        before.rfind('\n') == std::string_view::npos ? 0 : before.rfind('\n') + 1;
    error_ = origin_ + ":" + std::to_string(line) + ":" +
             std::to_string(before.size() - line_start) + ": " + message;
    return false;
  }

  std::string_view text_;
  std::string origin_;
  const char* read_end_;
  json document_;
  std::vector<json*> open_;
  string_t key_;
  std::string error_;
};

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

json parse_json_document(std::string_view text, const std::string& origin) {
  return DocumentBuilder(text, origin).parse();
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
  if (!std::isfinite(f)) expected("a number within single-precision range (below 3.4e38)");
  // A value inside the interval in double may round onto an open end (g = 0.99999999 becomes 1)
  // or, near 0, to 0.
  if (!range.contains(f)) {
    expected(range.describe() + " in single precision, where it is " + format_number(f));
  }
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

Direction JsonValue::direction() const {
  const Vec3 v = vec3();
  // Scaled to a largest component of magnitude 1 before normalizing: the squared length of
  // [3e38, 3e38, 3e38] overflows and that of [1e-30, 0, 0] underflows, and either would
  // normalize to no direction. Scaled, the squared length lies in [1, 3].
  const float largest = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  if (!(largest > 0)) expected("a non-zero direction");
  return {v, normalize(v / largest)};
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

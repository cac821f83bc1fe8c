#include "scene/exr_header_check.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <utility>

#include "scene/scene_error.h"

namespace snee {

namespace {

constexpr std::string_view kExrMagic("\x76\x2f\x31\x01", 4);
constexpr uint32_t kExrVersion = 2;
// Version-field flags of OpenEXR 2 (the low byte is the version number).
constexpr uint32_t kSingleTileFlag = 0x200;
constexpr uint32_t kLongNamesFlag = 0x400;
constexpr uint32_t kNonImageFlag = 0x800;
constexpr uint32_t kMultipartFlag = 0x1000;
constexpr uint32_t kKnownFlags = kSingleTileFlag | kLongNamesFlag | kNonImageFlag | kMultipartFlag;

uint32_t little_endian_u32(std::string_view bytes, size_t at) {
  uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = value << 8 | static_cast<unsigned char>(bytes[at + i]);
  return value;
}

class HeaderScanner {
 public:
  HeaderScanner(std::string_view bytes, const std::string& path, bool multipart, size_t max_name)
      : bytes_(bytes), path_(path), multipart_(multipart), max_name_(max_name) {}

  void scan() {
    for (int part = 0;; ++part) {
      part_ = part;
      // A multi-part file ends its list of headers with an empty one.
      if (part > 0 && next_is_terminator()) return;
      scan_one_header();
      if (!multipart_) return;
    }
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    std::string where = "EXR header";
    if (multipart_) where += " of part " + std::to_string(part_);
    throw SceneError(path_ + ": " + where + ": " + what);
  }

  bool next_is_terminator() {
    if (at_ >= bytes_.size()) fail("the file ends before the end of the headers");
    if (bytes_[at_] != '\0') return false;
    ++at_;
    return true;
  }

  // A NUL-terminated name of at most max_name_ bytes.
  std::string_view read_name(const char* what, std::string_view attribute) {
    const size_t limit = std::min(bytes_.size(), at_ + max_name_ + 1);
    const size_t end = bytes_.find('\0', at_);
    const auto context = [&] {
      return attribute.empty() ? std::string() : " of attribute '" + std::string(attribute) + "'";
    };
    if (end == std::string_view::npos || end >= limit) {
      if (limit == bytes_.size() && end == std::string_view::npos)
        fail(std::string("the file ends inside the ") + what + context());
      fail(std::string("the ") + what + context() + " is longer than " + std::to_string(max_name_) +
           " bytes");
    }
    const std::string_view name = bytes_.substr(at_, end - at_);
    at_ = end + 1;
    return name;
  }

  void scan_one_header() {
    while (!next_is_terminator()) {
      const std::string_view name = read_name("attribute name", {});
      const std::string_view type = read_name("type name", name);
      const std::string attribute =
          "attribute '" + std::string(name) + "' (" + std::string(type) + ")";
      if (bytes_.size() - at_ < 4) fail("the file ends inside the size of " + attribute);
      const int32_t size = static_cast<int32_t>(little_endian_u32(bytes_, at_));
      at_ += 4;
      const size_t left = bytes_.size() - at_;
      if (size < 0) fail(attribute + " declares a negative size (" + std::to_string(size) + ")");
      if (static_cast<size_t>(size) > left) {
        fail(attribute + " declares " + std::to_string(size) + " bytes, but only " +
             std::to_string(left) + " bytes follow in the file");
      }
      const size_t value_start = at_;
      check_value(type, static_cast<size_t>(size), attribute);
      at_ = value_start + static_cast<size_t>(size);
    }
  }

  // OpenEXR's Header::readFrom reads a value of a type it knows by that type's own layout and
  // then goes on from wherever that left it, not from the end the size declares: a channel list
  // declared as 55 bytes but ending after 19 made it read the next attribute from inside this
  // one, with a 1.9 GB string size (a fuzzer finding). So each known type's value must take
  // exactly the bytes declared. Types OpenEXR does not know are read as `size` opaque bytes.
  void check_value(std::string_view type, size_t size, const std::string& attribute) {
    const auto mismatch = [&](const std::string& what, uint64_t takes) {
      fail(attribute + " declares " + std::to_string(size) + " bytes, but " + what + " takes " +
           std::to_string(takes));
    };
    if (const auto fixed = fixed_value_size(type)) {
      if (size != *fixed) mismatch("a value of its type", *fixed);
    } else if (type == "floatvector") {
      if (size % 4 != 0) mismatch("a whole number of floats", size / 4 * 4);
    } else if (type == "chlist") {
      // Channels, each a name and 16 bytes (type, linearity, 3 reserved, x and y sampling),
      // until an empty name.
      const size_t start = at_;
      while (!next_is_terminator()) {
        read_name("channel name", attribute);
        if (bytes_.size() - at_ < 16) fail("the file ends inside a channel of " + attribute);
        at_ += 16;
      }
      if (at_ - start != size) mismatch("its channel list", at_ - start);
    } else if (type == "preview") {
      // Width and height, then 4 bytes per pixel; OpenEXR allocates the pixels before reading.
      if (size < 8) mismatch("a preview's width and height", 8);
      const uint64_t width = little_endian_u32(bytes_, at_);
      const uint64_t height = little_endian_u32(bytes_, at_ + 4);
      const uint64_t takes = 8 + width * height * 4;
      if (takes != size)
        mismatch("its " + std::to_string(width) + "x" + std::to_string(height) + " preview", takes);
    } else if (type == "stringvector") {
      // Strings, each a 32-bit length and its bytes, until the declared size is used up; OpenEXR
      // sizes each string from its length before reading it.
      size_t used = 0;
      while (used < size) {
        if (size - used < 4) mismatch("its strings", used + 4);
        const int32_t length = static_cast<int32_t>(little_endian_u32(bytes_, at_ + used));
        if (length < 0 || static_cast<size_t>(length) > size - used - 4) {
          fail(attribute + " holds a string of " + std::to_string(length) + " bytes where only " +
               std::to_string(size - used - 4) + " are left of its " + std::to_string(size));
        }
        used += 4 + static_cast<size_t>(length);
      }
    }
  }

  // The value sizes of OpenEXR's fixed-layout attribute types.
  static std::optional<size_t> fixed_value_size(std::string_view type) {
    static constexpr std::pair<std::string_view, size_t> kSizes[] = {{"box2f", 16},
                                                                     {"box2i", 16},
                                                                     {"chromaticities", 32},
                                                                     {"compression", 1},
                                                                     {"deepImageState", 1},
                                                                     {"double", 8},
                                                                     {"envmap", 1},
                                                                     {"float", 4},
                                                                     {"int", 4},
                                                                     {"keycode", 28},
                                                                     {"lineOrder", 1},
                                                                     {"m33d", 72},
                                                                     {"m33f", 36},
                                                                     {"m44d", 128},
                                                                     {"m44f", 64},
                                                                     {"rational", 8},
                                                                     {"tiledesc", 9},
                                                                     {"timecode", 8},
                                                                     {"v2d", 16},
                                                                     {"v2f", 8},
                                                                     {"v2i", 8},
                                                                     {"v3d", 24},
                                                                     {"v3f", 12},
                                                                     {"v3i", 12}};
    for (const auto& [name, value_size] : kSizes) {
      if (name == type) return value_size;
    }
    return std::nullopt;
  }

  std::string_view bytes_;
  const std::string& path_;
  bool multipart_;
  size_t max_name_;
  size_t at_ = 8;
  int part_ = 0;
};

}  // namespace

bool has_exr_magic(std::string_view bytes) {
  return bytes.substr(0, 4) == kExrMagic;
}

void check_exr_header(std::string_view bytes, const std::string& path) {
  if (!has_exr_magic(bytes)) return;
  if (bytes.size() < 8) throw SceneError(path + ": EXR header: the file ends inside the version");
  const uint32_t field = little_endian_u32(bytes, 4);
  const uint32_t version = field & 0xff;
  const uint32_t flags = field & ~uint32_t{0xff};
  if (version != kExrVersion) {
    throw SceneError(path + ": EXR header: version " + std::to_string(version) + " (expected " +
                     std::to_string(kExrVersion) + ")");
  }
  if ((flags & ~kKnownFlags) != 0) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%x", flags & ~kKnownFlags);
    throw SceneError(path + ": EXR header: unknown flags " + hex + " in the version field");
  }
  const size_t max_name = (flags & kLongNamesFlag) != 0 ? 255 : 31;
  HeaderScanner(bytes, path, (flags & kMultipartFlag) != 0, max_name).scan();
}

}  // namespace snee

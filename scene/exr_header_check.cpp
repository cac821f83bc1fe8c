#include "scene/exr_header_check.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>

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
      at_ += static_cast<size_t>(size);
    }
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

// OpenImageIO's view of an image held in memory (an image inside a .glb, or a file read whole
// so that its size was checked first), whose every read stays inside the bytes. OpenImageIO
// 2.4's own IOMemReader checks a read's end by adding the position and the size as unsigned
// numbers, which wraps around for a negative position: a corrupt EXR whose line offset table
// points before the file made it copy from before its buffer (found by fuzzing). Here a read at
// a position outside the bytes reads nothing, which the format readers report as a short file.
// It stays an IOMemReader (proxy type "memreader") because the JPEG reader takes the whole
// buffer from one and refuses any other proxy.
#pragma once

#include <OpenImageIO/filesystem.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace snee {

class MemoryReader final : public OIIO::Filesystem::IOMemReader {
 public:
  // `bytes` must outlive the reader.
  explicit MemoryReader(std::string_view bytes);

  size_t read(void* destination, size_t size) override;
  size_t pread(void* destination, size_t size, int64_t offset) override;
};

}  // namespace snee

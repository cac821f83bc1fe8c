#include "scene/memory_reader.h"

#include <algorithm>
#include <cstring>

namespace snee {

MemoryReader::MemoryReader(std::string_view bytes) : IOMemReader(bytes.data(), bytes.size()) {}

size_t MemoryReader::read(void* destination, size_t size) {
  const size_t count = pread(destination, size, m_pos);
  m_pos += static_cast<int64_t>(count);
  return count;
}

size_t MemoryReader::pread(void* destination, size_t size, int64_t offset) {
  const int64_t length = m_buf.size();
  if (offset < 0 || offset >= length) return 0;
  const size_t count = std::min(size, static_cast<size_t>(length - offset));
  std::memcpy(destination, m_buf.data() + offset, count);
  return count;
}

}  // namespace snee

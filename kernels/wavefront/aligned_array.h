// Arrays of a work unit's queues and scratch: 64-byte aligned (a cache line, and the alignment of
// every x86 SIMD load), sized once, never grown.
#pragma once

#include <cstddef>
#include <memory>
#include <new>

namespace snee {

template <typename T>
class AlignedArray {
 public:
  AlignedArray() = default;
  explicit AlignedArray(size_t n)
      : data_(static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{64}))), size_(n) {}
  T* data() const { return data_.get(); }
  T& operator[](size_t i) { return data_.get()[i]; }
  const T& operator[](size_t i) const { return data_.get()[i]; }
  size_t size() const { return size_; }

 private:
  struct Delete {
    void operator()(T* p) const { ::operator delete (p, std::align_val_t{64}); }
  };
  std::unique_ptr<T, Delete> data_;
  size_t size_ = 0;
};

// Scratch arrays indexed by queue position are rounded up to 16 entries, a whole number of
// batches at every x86 SIMD width, so a short last chunk is stored with whole vector stores.
inline size_t padded_capacity(size_t n) {
  return (n + 15) / 16 * 16;
}

}  // namespace snee

// The memory budget: the most bytes that one large allocation sized by the input may take (a
// mesh's arrays, an environment image, the whole input file, a render's film and work buffers).
// Each is checked before it is made, so a scene or file asking for more than the machine holds
// fails with a message naming what needs how much, instead of std::bad_alloc or the OOM killer
// part-way through. The default is the machine's physical memory (what the kernel reports
// through sysconf, ignoring cgroup limits and swap), or kFallbackMemoryBudget where it reports
// nothing; `snee render --max-memory` sets it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace snee {

inline constexpr uint64_t kFallbackMemoryBudget = uint64_t{16} << 30;

uint64_t physical_memory_bytes();

struct MemoryBudget {
  uint64_t bytes = physical_memory_bytes();

  bool allows(uint64_t needed) const { return needed <= bytes; }
  // "<what> need 12.0 GiB, more than the memory budget of 4.0 GiB (--max-memory)"; callers
  // prefix the file or scene it is about.
  std::string exceeded(std::string_view what, uint64_t needed) const;
};

// A byte count as a person writes it: "1000000", "512M", "4G", "1.5GiB", "2t". K, M, G and T
// are powers of 1024, with an optional "B" or "iB"; case does not matter. Nothing for text that
// is not such a size, or for zero or more than 2^64 - 1 bytes.
std::optional<uint64_t> parse_byte_size(std::string_view text);
// "177 bytes", "64.0 KiB", "12.0 GiB".
std::string format_bytes(uint64_t bytes);

// Sizes computed from untrusted counts (file headers, image sizes) saturate at UINT64_MAX
// instead of wrapping round to something small that would pass the budget.
uint64_t saturating_multiply(uint64_t a, uint64_t b);
uint64_t saturating_add(uint64_t a, uint64_t b);

}  // namespace snee

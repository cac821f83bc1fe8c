// libFuzzer hands each input over as bytes, but snee's readers take a path: tinyobjloader and
// OpenImageIO open the file themselves, and the scene loader resolves mesh and image paths
// against the scene file's directory. So every input is written to a file of a scratch
// directory made once per process under the temporary directory ($TMPDIR, which
// scripts/fuzz.sh points at a tmpfs so that the per-run write costs no disk IO).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace snee::fuzz {

inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "snee-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      std::perror("snee fuzz: mkdtemp");
      std::abort();
    }
    // Runs when libFuzzer ends normally (-max_total_time, -runs); after a crash the directory
    // stays, which is why scripts/fuzz.sh gives each run its own $TMPDIR and removes it.
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(scratch_dir(), ignored);
    });
    return std::filesystem::path(pattern);
  }();
  return dir;
}

// Replaces `name` in the scratch directory with the bytes and returns its path.
inline std::string write_file(std::string_view name, const uint8_t* data, size_t size) {
  const std::filesystem::path path = scratch_dir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out.flush()) {
    std::perror("snee fuzz: writing the input file");
    std::abort();
  }
  return path.string();
}

inline std::string write_file(std::string_view name, std::string_view text) {
  return write_file(name, reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

}  // namespace snee::fuzz

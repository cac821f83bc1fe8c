#include "scene/density_grid_io.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "scene/input_file.h"
#include "scene/scene_error.h"

namespace snee {

namespace {

constexpr size_t kHeaderBytes = 4 + 4 + 3 * 4 + 4 + 6 * 4;

template <class T>
T read_le(const std::string& bytes, size_t offset) {
  static_assert(sizeof(T) == 4);
  uint8_t b[4];
  std::memcpy(b, bytes.data() + offset, 4);
  const uint32_t v =
      uint32_t{b[0]} | (uint32_t{b[1]} << 8) | (uint32_t{b[2]} << 16) | (uint32_t{b[3]} << 24);
  T out;
  std::memcpy(&out, &v, 4);
  return out;
}

template <class T>
void write_le(std::vector<char>& bytes, T value) {
  static_assert(sizeof(T) == 4);
  uint32_t v;
  std::memcpy(&v, &value, 4);
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}

std::string describe_box(Vec3 lo, Vec3 hi) {
  std::ostringstream s;
  s << "(" << lo.x << ", " << lo.y << ", " << lo.z << ") to (" << hi.x << ", " << hi.y << ", "
    << hi.z << ")";
  return s.str();
}

}  // namespace

void validate_density_grid(DensityGrid& grid, const std::string& where) {
  if (grid.nx < 1 || grid.ny < 1 || grid.nz < 1) {
    throw SceneError(where + ": resolution " + std::to_string(grid.nx) + " x " +
                     std::to_string(grid.ny) + " x " + std::to_string(grid.nz) +
                     "; expected at least 1 voxel along each axis");
  }
  const Vec3 extent = grid.hi - grid.lo;
  if (!(extent.x > 0 && extent.y > 0 && extent.z > 0) || !std::isfinite(extent.x) ||
      !std::isfinite(extent.y) || !std::isfinite(extent.z)) {
    throw SceneError(where + ": the box " + describe_box(grid.lo, grid.hi) +
                     " is empty or not finite; expected a finite box with min below max on "
                     "every axis");
  }
  const uint64_t voxels = grid.voxel_count();
  if (grid.values.size() != voxels) {
    throw SceneError(where + ": " + std::to_string(grid.values.size()) + " values for " +
                     std::to_string(grid.nx) + " x " + std::to_string(grid.ny) + " x " +
                     std::to_string(grid.nz) + " voxels; expected one value per voxel");
  }
  grid.max_value = 0;
  for (size_t i = 0; i < grid.values.size(); ++i) {
    const float v = grid.values[i];
    if (!(v >= 0) || !std::isfinite(v)) {
      const size_t x = i % static_cast<size_t>(grid.nx);
      const size_t y = i / static_cast<size_t>(grid.nx) % static_cast<size_t>(grid.ny);
      const size_t z = i / (static_cast<size_t>(grid.nx) * static_cast<size_t>(grid.ny));
      throw SceneError(where + ": voxel (" + std::to_string(x) + ", " + std::to_string(y) + ", " +
                       std::to_string(z) + ") has density " + std::to_string(v) +
                       "; expected a finite density of at least 0");
    }
    grid.max_value = std::max(grid.max_value, v);
  }
}

DensityGrid read_density_grid(const std::string& path, const MemoryBudget& budget) {
  const std::string bytes = read_input_file(path, "density grid", budget);
  if (bytes.size() < kHeaderBytes) {
    throw SceneError(path + ": " + std::to_string(bytes.size()) +
                     " bytes, shorter than the 48-byte header of a .vol density grid");
  }
  if (bytes.compare(0, 3, "VOL") != 0) {
    throw SceneError(path + ": does not start with 'VOL'; expected a .vol density grid");
  }
  if (static_cast<uint8_t>(bytes[3]) != 3) {
    throw SceneError(path + ": .vol version " + std::to_string(static_cast<uint8_t>(bytes[3])) +
                     "; expected version 3");
  }
  const int32_t encoding = read_le<int32_t>(bytes, 4);
  if (encoding != 1) {
    throw SceneError(path + ": .vol encoding " + std::to_string(encoding) +
                     "; expected 1 (float32)");
  }
  DensityGrid grid;
  grid.nx = read_le<int32_t>(bytes, 8);
  grid.ny = read_le<int32_t>(bytes, 12);
  grid.nz = read_le<int32_t>(bytes, 16);
  const int32_t channels = read_le<int32_t>(bytes, 20);
  if (channels != 1) {
    throw SceneError(path + ": " + std::to_string(channels) + " channels; expected 1 (a density)");
  }
  grid.lo = {read_le<float>(bytes, 24), read_le<float>(bytes, 28), read_le<float>(bytes, 32)};
  grid.hi = {read_le<float>(bytes, 36), read_le<float>(bytes, 40), read_le<float>(bytes, 44)};
  grid.source = path;
  if (grid.nx < 1 || grid.ny < 1 || grid.nz < 1) validate_density_grid(grid, path);
  const uint64_t voxels = grid.voxel_count();
  const uint64_t data_bytes = saturating_multiply(voxels, 4);
  if (!budget.allows(data_bytes))
    throw SceneError(path + ": " + budget.exceeded("its voxels", data_bytes));
  if (bytes.size() - kHeaderBytes != data_bytes) {
    throw SceneError(path + ": " + std::to_string(bytes.size() - kHeaderBytes) +
                     " bytes of data after the header; expected " + std::to_string(data_bytes) +
                     " (4 per voxel of " + std::to_string(grid.nx) + " x " +
                     std::to_string(grid.ny) + " x " + std::to_string(grid.nz) + ")");
  }
  grid.values.resize(voxels);
  for (uint64_t i = 0; i < voxels; ++i) {
    grid.values[i] = read_le<float>(bytes, kHeaderBytes + 4 * i);
  }
  validate_density_grid(grid, path);
  return grid;
}

void write_density_grid(const std::string& path, const DensityGrid& grid) {
  std::vector<char> bytes = {'V', 'O', 'L', 3};
  write_le<int32_t>(bytes, 1);
  write_le<int32_t>(bytes, grid.nx);
  write_le<int32_t>(bytes, grid.ny);
  write_le<int32_t>(bytes, grid.nz);
  write_le<int32_t>(bytes, 1);
  for (float v : {grid.lo.x, grid.lo.y, grid.lo.z, grid.hi.x, grid.hi.y, grid.hi.z}) {
    write_le<float>(bytes, v);
  }
  for (float v : grid.values) write_le<float>(bytes, v);
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw SceneError(path + ": cannot write the density grid");
}

}  // namespace snee

#include "apps/checkpoint_file.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include "apps/output_files.h"
#include "apps/render_settings.h"
#include "apps/stats_json.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

// The layout, all numbers in this machine's byte order (little-endian on every platform snee
// builds for): the magic; the header's length (uint64) and the header, JSON; per tile its
// chunk count and converged flag (two uint32); the sums (doubles); a checksum (uint64) of every
// byte before it.
constexpr std::string_view kMagic = "snee checkpoint\n";
constexpr int kFormat = 1;

// FNV-1a over 64-bit words (the tail byte by byte): it finds a flipped or lost byte; fast
// enough for hundreds of megabytes of sums.
uint64_t checksum(std::string_view bytes) {
  uint64_t h = 0xcbf29ce484222325ull;
  size_t i = 0;
  for (; i + 8 <= bytes.size(); i += 8) {
    uint64_t word;
    std::memcpy(&word, bytes.data() + i, 8);
    h = (h ^ word) * 0x100000001b3ull;
  }
  for (; i < bytes.size(); ++i) h = (h ^ static_cast<unsigned char>(bytes[i])) * 0x100000001b3ull;
  return h;
}

template <typename T>
void append(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

[[noreturn]] void refuse(const fs::path& file, const std::string& why) {
  throw std::runtime_error("cannot resume from '" + file.string() + "': " + why);
}

// Reads consecutive values out of the file's bytes; refuses a file that ends too soon.
class Reader {
 public:
  Reader(const fs::path& file, std::string_view bytes) : file_(file), bytes_(bytes) {}
  template <typename T>
  T next() {
    T value;
    std::memcpy(&value, take(sizeof value).data(), sizeof value);
    return value;
  }
  std::string_view take(size_t n) {
    if (n > bytes_.size() - at_)
      refuse(file_, "it is truncated (" + std::to_string(bytes_.size()) + " bytes)");
    const std::string_view part = bytes_.substr(at_, n);
    at_ += n;
    return part;
  }
  size_t left() const { return bytes_.size() - at_; }

 private:
  const fs::path& file_;
  const std::string_view bytes_;
  size_t at_ = 0;
};

std::string shown(const nlohmann::ordered_json& value) {
  return value.is_string() ? value.get<std::string>() : value.dump();
}

// Each field of `wanted` that `saved` lacks or has otherwise, as "NAME VALUE (this render:
// VALUE)", joined by "; ".
std::string differences(const nlohmann::ordered_json& saved, const nlohmann::ordered_json& wanted) {
  std::string text;
  for (const auto& [name, value] : wanted.items()) {
    const bool has = saved.contains(name);
    if (has && saved[name] == value) continue;
    if (!text.empty()) text += "; ";
    text +=
        name + " " + (has ? shown(saved[name]) : "(none)") + " (this render: " + shown(value) + ")";
  }
  return text;
}

}  // namespace

fs::path checkpoint_path(const fs::path& exr, int shard, int shard_count) {
  fs::path file = exr;
  file += ".checkpoint";
  if (shard_count > 1) {
    file += ".";
    file += std::to_string(shard);
    file += "-of-";
    file += std::to_string(shard_count);
  }
  return file;
}

uintmax_t checkpoint_bytes_bound(int width, int height) {
  const uintmax_t pixels = static_cast<uintmax_t>(width) * static_cast<uintmax_t>(height);
  // Every pixel's sums, and at most one tile (two uint32) per pixel; the header is small.
  return pixels * (kSumsPerPixel * sizeof(double) + 2 * sizeof(uint32_t)) + (uintmax_t{1} << 16);
}

CheckpointIdentity checkpoint_identity(const std::string& scene_spec, const LoadedScene& loaded,
                                       const RenderOptions& options) {
  CheckpointIdentity id;
  const Camera& camera = loaded.scene.camera;
  id.fields = {
      {"snee version", SNEE_VERSION},
      {"scene", scene_digest(scene_spec, loaded)},
      {"integrator", options.integrator},
      {"seed", options.seed},
      {"max depth", options.max_depth},
      {"resolution", std::to_string(camera.width) + "x" + std::to_string(camera.height)},
      {"tile size", options.tile_size},
      {"samples per unit", options.samples_per_unit},
      {"noise target", options.noise_target},
      {"light selection", light_selection_name(options.light_selection)},
      {"sample clamp", options.sample_clamp},
      {"snee options", snee_options_json(options.snee)},
      {"process", std::to_string(options.shard) + " of " + std::to_string(options.shard_count)},
  };
  id.spp = options.spp;
  id.samples_per_unit = options.samples_per_unit;
  return id;
}

void write_checkpoint(const fs::path& file, const CheckpointIdentity& identity,
                      const FilmState& state) {
  const nlohmann::ordered_json header = {
      {"format", kFormat},        {"identity", identity.fields}, {"spp", identity.spp},
      {"seconds", state.seconds}, {"tiles", state.tiles.size()}, {"sums", state.sums.size()}};
  const std::string text = header.dump();
  std::string bytes(kMagic);
  bytes.reserve(kMagic.size() + 16 + text.size() + 8 * state.tiles.size() +
                sizeof(double) * state.sums.size());
  append(bytes, static_cast<uint64_t>(text.size()));
  bytes += text;
  for (const TileState& t : state.tiles) {
    append(bytes, t.chunks);
    append(bytes, static_cast<uint32_t>(t.converged ? 1 : 0));
  }
  bytes.append(reinterpret_cast<const char*>(state.sums.data()),
               sizeof(double) * state.sums.size());
  append(bytes, checksum(bytes));
  replace_file(file, [&](const std::string& partial) {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot write '" + partial + "'");
  });
}

namespace {

FilmState read_checked_bytes(const fs::path& file, const std::string& bytes,
                             const CheckpointIdentity& identity) {
  if (!std::string_view(bytes).starts_with(kMagic))
    refuse(file, "it is not a snee checkpoint file");
  if (bytes.size() < kMagic.size() + 2 * sizeof(uint64_t))
    refuse(file, "it is truncated (" + std::to_string(bytes.size()) + " bytes)");
  const std::string_view body(bytes.data(), bytes.size() - sizeof(uint64_t));
  uint64_t stored = 0;
  std::memcpy(&stored, bytes.data() + body.size(), sizeof stored);
  if (stored != checksum(body))
    refuse(file, "it is corrupt or truncated (its checksum does not match its contents)");

  Reader read(file, body);
  read.take(kMagic.size());
  const uint64_t header_size = read.next<uint64_t>();
  if (header_size > read.left()) refuse(file, "it is truncated (the header runs past the end)");
  const nlohmann::ordered_json header =
      nlohmann::ordered_json::parse(read.take(static_cast<size_t>(header_size)), nullptr, false);
  if (header.is_discarded() || !header.is_object() || header.value("format", 0) != kFormat ||
      !header.contains("identity") || !header["identity"].is_object())
    refuse(file, "its header is not one this snee writes (format " + std::to_string(kFormat) + ")");
  const std::string differ = differences(header["identity"], identity.fields);
  if (!differ.empty()) refuse(file, "it was made by a different render: " + differ);

  const int spp = header.value("spp", 0);
  if (spp != identity.spp && (spp % identity.samples_per_unit != 0 || identity.spp < spp)) {
    refuse(file, "it was rendered with --spp " + std::to_string(spp) + ", this render has " +
                     std::to_string(identity.spp) +
                     " (a render goes on to the same spp, or to more when its spp is a multiple "
                     "of --samples-per-unit)");
  }
  FilmState state;
  state.seconds = header.value("seconds", 0.0);
  const uint64_t tiles = header.value("tiles", uint64_t{0});
  const uint64_t sums = header.value("sums", uint64_t{0});
  if (tiles * 2 * sizeof(uint32_t) + sums * sizeof(double) != read.left())
    refuse(file, "its size does not match its header (" + std::to_string(tiles) + " tiles, " +
                     std::to_string(sums) + " sums)");
  state.tiles.resize(tiles);
  for (TileState& t : state.tiles) {
    t.chunks = read.next<uint32_t>();
    t.converged = read.next<uint32_t>() != 0;
  }
  state.sums.resize(sums);
  std::memcpy(state.sums.data(), read.take(sums * sizeof(double)).data(), sums * sizeof(double));
  return state;
}

}  // namespace

FilmState read_checkpoint(const fs::path& file, const CheckpointIdentity& identity) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    refuse(file,
           "no such file (a render keeps its state beside its EXR when it is stopped or "
           "checkpointed; a split render needs as many processes as made it)");
  std::ifstream in(file, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) refuse(file, "it cannot be read");
  try {
    return read_checked_bytes(file, bytes, identity);
  } catch (const nlohmann::json::exception& e) {
    refuse(file, std::string("its header is malformed: ") + e.what());
  }
}

}  // namespace snee

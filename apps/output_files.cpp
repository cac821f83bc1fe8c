#include "apps/output_files.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

#include "apps/interrupt_request.h"

namespace snee {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void cannot_write(const fs::path& file, const std::string& why) {
  throw std::runtime_error("cannot write '" + file.string() + "': " + why);
}

fs::path directory_of(const fs::path& file) {
  return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

void create_directory_of(const fs::path& file) {
  if (!file.has_parent_path()) return;
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec)
    cannot_write(file,
                 "cannot create directory '" + file.parent_path().string() + "': " + ec.message());
}

// Compressed images are rarely larger than raw, but noise compresses badly: a percent and a
// mebibyte of headroom cover zip's worst case and the headers.
uintmax_t with_headroom(uintmax_t raw) {
  return raw + raw / 100 + (uintmax_t{1} << 20);
}

}  // namespace

// The partial path of `file` for the process `pid` (partial_path's name for that process).
fs::path partial_path_of(const fs::path& file, long pid) {
  std::string suffix(1, '.');
  suffix.append(std::to_string(pid)).append(".partial").append(file.extension().string());
  std::string stem = file.stem().string();
  const size_t room = NAME_MAX - 1 - suffix.size();
  if (stem.size() > room) {
    stem.resize(room);
    // Never end inside a UTF-8 sequence: drop continuation bytes and the byte they follow.
    while (!stem.empty() && (static_cast<unsigned char>(stem.back()) & 0xC0) == 0x80)
      stem.pop_back();
    if (!stem.empty() && static_cast<unsigned char>(stem.back()) >= 0xC0) stem.pop_back();
  }
  std::string name(1, '.');
  name.append(stem).append(suffix);
  return file.parent_path() / name;
}

fs::path partial_path(const fs::path& file) {
  return partial_path_of(file, ::getpid());
}

void remove_stale_partial_files(const fs::path& file, std::chrono::seconds min_age) {
  const fs::path extension_tail = ".partial" + file.extension().string();
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  for (fs::directory_iterator it(directory_of(file), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::string tail = extension_tail.string();
    if (name.size() <= tail.size() || name.front() != '.' ||
        name.compare(name.size() - tail.size(), tail.size(), tail) != 0) {
      continue;
    }
    // ".<stem>.<pid>.partial<ext>": the pid is the last dot-separated field before the tail.
    const std::string head = name.substr(0, name.size() - tail.size());
    const size_t dot = head.rfind('.');
    if (dot == std::string::npos || dot + 1 >= head.size()) continue;
    const std::string digits = head.substr(dot + 1);
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(digits);
    // Only this file's name for that process, a process that no longer exists, and a file old
    // enough that no writer on another host sharing the directory can still be at it.
    if (pid == ::getpid() || partial_path_of(file, pid).filename() != it->path().filename()) {
      continue;
    }
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    std::error_code time_ec;
    const auto written = fs::last_write_time(it->path(), time_ec);
    if (time_ec || now - written < min_age) continue;
    std::error_code ignored;
    fs::remove(it->path(), ignored);
  }
}

void replace_file(const fs::path& file, const std::function<void(const std::string&)>& write) {
  create_directory_of(file);
  remove_stale_partial_files(file, kStalePartialAge);
  const fs::path partial = partial_path(file);
  const FileInFlight in_flight(partial.string());
  try {
    write(partial.string());
    std::error_code ec;
    fs::rename(partial, file, ec);
    if (ec) cannot_write(file, "cannot rename '" + partial.string() + "' over it: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(partial, ignored);
    throw;
  }
}

bool is_output_extension(const fs::path& extension) {
  for (const char* known : {".exr", ".png", ".jpg", ".jpeg", ".hdr"})
    if (extension == known) return true;
  return false;
}

OutputImages output_images(const fs::path& requested) {
  OutputImages images;
  if (requested.extension() == ".exr") {
    images.exr = requested;
    images.view = fs::path(requested).replace_extension(".png");
  } else {
    images.exr = fs::path(requested).replace_extension(".exr");
    images.view = requested;
  }
  return images;
}

void write_images(const Film& film, const OutputImages& images) {
  replace_file(images.exr, [&](const std::string& p) { write_exr(film, p, images.attributes); });
  replace_file(images.view, [&](const std::string& p) {
    if (images.view.extension() == ".hdr")
      write_hdr(film, p);
    else
      write_preview(film, p, images.tone);
  });
}

uintmax_t exr_bytes_bound(int width, int height) {
  constexpr uintmax_t kBytesPerPixel = 6 * sizeof(float);  // RGB and its variance
  return with_headroom(static_cast<uintmax_t>(width) * static_cast<uintmax_t>(height) *
                       kBytesPerPixel);
}

uintmax_t view_bytes_bound(int width, int height) {
  // Radiance .hdr stores 4 bytes (RGBE) a pixel, the 8-bit previews 3.
  return with_headroom(static_cast<uintmax_t>(width) * static_cast<uintmax_t>(height) * 4);
}

void check_destination(const fs::path& file, uintmax_t bytes) {
  create_directory_of(file);
  const fs::path dir = directory_of(file);
  const long name_max = ::pathconf(dir.c_str(), _PC_NAME_MAX);
  const size_t name_length = file.filename().string().size();
  if (name_max > 0 && name_length > static_cast<size_t>(name_max)) {
    cannot_write(file, "the name is " + std::to_string(name_length) +
                           " bytes long, the file system allows " + std::to_string(name_max));
  }
  std::error_code ec;
  if (fs::is_directory(file, ec)) cannot_write(file, "a directory of that name is in the way");

  const fs::path partial = partial_path(file);
  const int fd = ::open(partial.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0)
    cannot_write(file, std::string("cannot create a file beside it: ") + std::strerror(errno));
  ::close(fd);
  ::unlink(partial.c_str());

  const fs::space_info space = fs::space(dir, ec);
  if (!ec && space.available < bytes) {
    cannot_write(file, "it needs up to " + std::to_string(bytes) + " bytes but '" + dir.string() +
                           "' has " + std::to_string(space.available) + " bytes free");
  }
}

}  // namespace snee

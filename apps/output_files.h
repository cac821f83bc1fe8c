// Writing the files of a render so that no fault loses them silently: every destination is
// checked before rendering starts, each file is written beside its final name under a short
// hidden temporary name and renamed over it, and the temporary file is removed on any failure
// (and by a second Ctrl-C, interrupt_request.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>

#include "scene/film.h"
#include "scene/tone_map.h"

namespace snee {

// Where `file` is written before it is renamed over `file`: a hidden name in the same
// directory, with this process's id and the same extension (the image writers choose the
// format by it), never longer than NAME_MAX whatever the length of `file`'s name.
std::filesystem::path partial_path(const std::filesystem::path& file);

// Removes the partial files of `file` left by processes that no longer exist (killed outright
// while writing: SIGKILL, the out-of-memory killer) and last written at least `min_age` ago,
// so that no writer on another host sharing the directory loses its file.
inline constexpr std::chrono::seconds kStalePartialAge{600};
void remove_stale_partial_files(const std::filesystem::path& file, std::chrono::seconds min_age);

// Writes `file` as a whole: `write` writes the partial_path, which is then renamed over
// `file`; creates the directory if it is missing (it may have been removed since the last
// write). Throws std::runtime_error naming the file, leaving no partial file behind; partial
// files of `file` that dead processes left are removed first (remove_stale_partial_files).
void replace_file(const std::filesystem::path& file,
                  const std::function<void(const std::string&)>& write);

// The files of a render: the EXR (always: it alone keeps the variance and the settings) and
// one view of it, whose extension picks its kind: .png, .jpg or .jpeg an 8-bit preview through
// `tone`, .hdr the linear mean radiance.
struct OutputImages {
  std::filesystem::path exr;
  std::filesystem::path view;
  ToneMap tone;
  ExrAttributes attributes;  // written into the EXR after the film's own metadata
};

// The extensions `-o` accepts, in the words of its error message.
bool is_output_extension(const std::filesystem::path& extension);
inline constexpr const char* kOutputExtensions = ".exr, .png, .jpg, .jpeg or .hdr";

// `-o FILE`: FILE.exr gets FILE.png beside it as its preview, any other accepted FILE gets the
// EXR beside it with the same stem.
OutputImages output_images(const std::filesystem::path& requested);

// The EXR, then its view, each with replace_file.
void write_images(const Film& film, const OutputImages& images);

// Upper bounds of the files write_images makes for a width x height film (before compression).
uintmax_t exr_bytes_bound(int width, int height);
uintmax_t view_bytes_bound(int width, int height);

// Makes sure `file` can be written later: creates its directory, checks that its name fits
// the file system and that no directory is in the way, creates and removes its partial file,
// and checks that the file system has `bytes` free. Throws std::runtime_error naming the file
// and the reason.
void check_destination(const std::filesystem::path& file, uintmax_t bytes);

}  // namespace snee

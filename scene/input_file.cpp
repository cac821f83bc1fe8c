#include "scene/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>

#include "scene/scene_error.h"

namespace snee {

namespace {

const char* file_type_name(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a plain file";
}

// strerror's text, lower-cased to read as part of a sentence ("no such file or directory").
std::string system_error_text(int error) {
  std::string text = std::strerror(error);
  if (!text.empty()) text[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
  return text;
}

SceneError cannot_read(const std::string& path, std::string_view what, const std::string& why) {
  return SceneError(path + ": cannot read " + std::string(what) + ": " + why);
}

void require_regular(const std::string& path, std::string_view what, const struct stat& info) {
  if (!S_ISREG(info.st_mode)) {
    throw cannot_read(
        path, what, std::string("it is ") + file_type_name(info.st_mode) + ", not a regular file");
  }
}

class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

void require_regular_file(const std::string& path, std::string_view what) {
  struct stat info;
  if (::stat(path.c_str(), &info) != 0) throw cannot_read(path, what, system_error_text(errno));
  require_regular(path, what, info);
}

std::string read_input_file(const std::string& path, std::string_view what,
                            const MemoryBudget& budget) {
  require_regular_file(path, what);
  const FileDescriptor file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (file.get() < 0) throw cannot_read(path, what, system_error_text(errno));
  struct stat info;
  if (::fstat(file.get(), &info) != 0) throw cannot_read(path, what, system_error_text(errno));
  require_regular(path, what, info);

  // One spare byte lets the read that finds the end of a file of the size stat gave land
  // without growing the buffer.
  const uint64_t size = saturating_add(static_cast<uint64_t>(info.st_size), 1);
  if (!budget.allows(size))
    throw cannot_read(path, what, budget.exceeded("the file's bytes", size));
  std::string data(size, '\0');
  size_t filled = 0;
  for (;;) {
    // A file that grows while it is read may not outgrow the budget either.
    if (filled == data.size()) {
      const uint64_t grown = saturating_add(data.size(), uint64_t{1} << 16);
      if (!budget.allows(grown))
        throw cannot_read(path, what, budget.exceeded("the file's bytes", grown));
      data.resize(grown);
    }
    const ssize_t n = ::read(file.get(), data.data() + filled, data.size() - filled);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw cannot_read(path, what, system_error_text(errno));
    }
    if (n == 0) break;
    filled += static_cast<size_t>(n);
  }
  data.resize(filled);
  return data;
}

}  // namespace snee

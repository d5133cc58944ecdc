#include "core/mesh/file_check.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/mesh/mesh_io.h"
#include "core/mesh/path_quote.h"

namespace trispline::core {
namespace {

// Throws unless `st` describes a regular file within the budget.
void check_stat(const std::filesystem::path& path, const struct stat& st, std::uintmax_t max_bytes,
                const std::string& what) {
  const char* kind = nullptr;
  if (S_ISDIR(st.st_mode)) throw MeshIoError(quoted(path) + ": is a directory");
  if (S_ISFIFO(st.st_mode)) kind = "a FIFO (named pipe)";
  if (S_ISCHR(st.st_mode)) kind = "a character device";
  if (S_ISBLK(st.st_mode)) kind = "a block device";
  if (S_ISSOCK(st.st_mode)) kind = "a socket";
  if (!kind && !S_ISREG(st.st_mode)) kind = "a special file";
  if (kind) throw MeshIoError(quoted(path) + ": is " + kind + ", not a regular file");
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > max_bytes)
    throw MeshIoError(quoted(path) + ": " + format_bytes(size) +
                      (size >= 1024 ? " (" + std::to_string(size) + " bytes)" : std::string()) + " is over the " +
                      format_bytes(max_bytes) + " limit for " + what);
}

[[noreturn]] void throw_errno(const std::filesystem::path& path, int err, const char* doing) {
  if (err == ENOENT || err == ENOTDIR) throw MeshIoError(quoted(path) + ": file not found");
  throw MeshIoError(quoted(path) + ": " + doing + ": " + std::strerror(err));
}

}  // namespace

std::string format_bytes(std::uintmax_t bytes) {
  static const char* const units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  double v = static_cast<double>(bytes);
  int u = -1;
  while (v >= 1024 && u < 5) v /= 1024, ++u;
  char text[32];
  if (v == static_cast<double>(static_cast<std::uintmax_t>(v)))
    std::snprintf(text, sizeof text, "%.0f %s", v, units[u]);
  else
    std::snprintf(text, sizeof text, "%.1f %s", v, units[u]);
  return text;
}

void check_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw_errno(path, errno, "cannot access");
  check_stat(path, st, max_bytes, what);
}

std::vector<unsigned char> read_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes,
                                           const std::string& what) {
  // O_NONBLOCK: opening a FIFO without a writer must not hang before fstat can refuse it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw_errno(path, errno, "cannot open");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw_errno(path, errno, "cannot access");
  check_stat(path, st, max_bytes, what);
  std::vector<unsigned char> bytes(static_cast<std::size_t>(st.st_size));
  std::size_t got = 0;
  for (;;) {
    if (got == bytes.size()) {  // at the size fstat gave: confirm the end rather than trusting it
      if (bytes.size() >= max_bytes)
        bytes.resize(bytes.size() + 1);  // one byte more tells a grown file apart
      else
        bytes.resize(std::min<std::uintmax_t>(max_bytes + 1, bytes.size() + 65536));
    }
    const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw_errno(path, errno, "cannot read");
    }
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
    if (got > max_bytes)
      throw MeshIoError(quoted(path) + ": grew past the " + format_bytes(max_bytes) + " limit for " + what +
                        " while being read");
  }
  bytes.resize(got);
  return bytes;
}

}  // namespace trispline::core

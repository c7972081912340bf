#include "core/fd_io.h"

#include <unistd.h>

#include <cerrno>

namespace lwc {
namespace {

// Moves `size` bytes with `step(at)` (one read or write from offset `at`).
template <typename Step>
bool all_bytes(size_t size, Step step) {
  for (size_t at = 0; at < size;) {
    ssize_t n = step(at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += static_cast<size_t>(n);
  }
  return true;
}

}  // namespace

bool write_all(int fd, std::string_view bytes) {
  return all_bytes(bytes.size(), [&](size_t at) { return ::write(fd, bytes.data() + at, bytes.size() - at); });
}

bool read_all(int fd, char* data, size_t size) {
  return all_bytes(size, [&](size_t at) { return ::read(fd, data + at, size - at); });
}

}  // namespace lwc

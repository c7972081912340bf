#pragma once
#include <cstddef>
#include <string>
#include <string_view>

namespace lwc {

// Whole writes and reads on a file descriptor (a pipe, a file), again where a signal interrupts
// them: false on an error, or for a read at the end before `size` bytes came.
bool write_all(int fd, std::string_view bytes);
bool read_all(int fd, char* data, size_t size);

}  // namespace lwc

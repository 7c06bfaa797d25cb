// SPDX-License-Identifier: MIT
#include "input_file.hpp"

#include <fstream>
#include <system_error>

namespace odeskin {

Result<std::string> readInputFile(const std::filesystem::path& path, std::size_t max_pipe_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) return ioError(path.string() + ": is a directory, not a file");
  if (fs::is_character_file(status) || fs::is_block_file(status) || fs::is_socket(status)) {
    return ioError(path.string() + ": is a device, not a file");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) return ioError(path.string() + ": cannot open for reading");
  std::string bytes;
  if (fs::is_regular_file(status)) {
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec) bytes.reserve(static_cast<std::size_t>(size));
  }
  // In blocks, so a pipe stops at its bound rather than at the end of memory.
  char block[1 << 16];
  while (file.read(block, sizeof block) || file.gcount() > 0) {
    bytes.append(block, static_cast<std::size_t>(file.gcount()));
    if (fs::is_fifo(status) && bytes.size() > max_pipe_bytes) {
      return ioError(path.string() + ": more than " + std::to_string(max_pipe_bytes) + " bytes from a pipe");
    }
  }
  if (file.bad()) return ioError(path.string() + ": read failed");
  return bytes;
}

}  // namespace odeskin

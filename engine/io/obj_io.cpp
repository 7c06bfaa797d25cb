// SPDX-License-Identifier: MIT
#include "obj_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <optional>
#include <random>
#include <system_error>

#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"
#include "../core/pending_files.hpp"
#include "../core/result.hpp"

namespace odeskin {

namespace {

// The path a chain of symbolic links names (which may not exist yet), at most 40 links deep as
// the kernel allows. Renaming onto a link would replace the link itself; the user meant its file.
Result<std::filesystem::path> followLinks(const std::filesystem::path& path) {
  std::filesystem::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!std::filesystem::is_symlink(p, ec)) return p;
    const std::filesystem::path next = std::filesystem::read_symlink(p, ec);
    if (ec) return ioError(path.string() + ": cannot follow the symbolic link: " + ec.message());
    p = next.is_absolute() ? next : p.parent_path() / next;
  }
  return ioError(path.string() + ": too many levels of symbolic links");
}

std::string errnoText(int error) { return std::generic_category().message(error); }

// Writes all of `content` to `fd` and closes it; kIoError naming `shown` with the cause. With
// `durable`, the data reach the disk before the close: a temporary renamed into place before its
// data are on disk can, after a power cut, leave the target empty on ext4 and XFS, which is the
// half-written output the rename was there to prevent.
Status writeAndClose(int fd, const std::string& content, const std::filesystem::path& shown, bool durable) {
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      ::close(fd);
      return ioError(shown.string() + ": write failed: " + errnoText(error));
    }
    done += static_cast<std::size_t>(n);
  }
  if (durable && ::fsync(fd) != 0 && errno != EINVAL) {  // EINVAL: a file system without fsync
    const int error = errno;
    ::close(fd);
    return ioError(shown.string() + ": write failed: " + errnoText(error));
  }
  // close, too, can report a failed write (a full disk on a network file system).
  if (::close(fd) != 0) return ioError(shown.string() + ": write failed: " + errnoText(errno));
  return okStatus();
}

// A device or FIFO that exists, written through (the same loop as a temporary file).
Status writeInPlace(const std::filesystem::path& path, const std::string& content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) return ioError(path.string() + ": cannot open for writing: " + errnoText(errno));
  return writeAndClose(fd, content, path, /*durable=*/false);
}

// After a rename, the directory entry itself reaches the disk only when the directory is synced.
// Best effort: the file is already complete under its name, and some file systems refuse to open
// or sync a directory.
void syncDirectory(const std::filesystem::path& directory) {
  const int fd = ::open(directory.empty() ? "." : directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  static_cast<void>(::fsync(fd));  // nothing to undo if it fails
  ::close(fd);
}

}  // namespace

Status writeFileAtomically(const std::filesystem::path& path, const std::string& content) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);  // through every link
  if (std::filesystem::is_directory(status)) return ioError(path.string() + ": is a directory");
  // Renaming over a device or FIFO would replace the node itself: as root, `-o /dev/null` made
  // /dev/null a regular file holding the output. A stream has no half-written state to avoid.
  // (The kernel opens /dev/stdout's /proc link to a pipe, which no path names.)
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    return writeInPlace(path, content);
  }
  ODESKIN_ASSIGN_OR_RETURN(const std::filesystem::path target, followLinks(path));
  // The temporary lives beside the target so the rename stays on one file system (atomic). It is
  // created exclusively: a name already taken (another writer's temporary, or a link planted in a
  // shared folder to make a root process truncate what it names) is never opened, only skipped.
  // Each name is registered for the signal handler before the open: a signal is delivered as the
  // open returns, and a file registered only after it stayed behind.
  std::random_device seed;
  std::filesystem::path temp;
  std::optional<PendingFile> pending;
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    temp = target;
    temp += ".tmp" + std::to_string(seed() % 1000000);
    pending.emplace(temp);
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) {
      const int error = errno;
      pending.reset();
      if (error != EEXIST) return ioError(path.string() + ": cannot create file: " + errnoText(error));
    }
  }
  if (fd < 0) return ioError(path.string() + ": cannot create file: every temporary name beside it is taken");
  if (Status written = writeAndClose(fd, content, path, /*durable=*/true); !written.ok()) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    return written;
  }
  // A replaced file keeps its mode: a group-writable output in a shared folder stays so.
  if (std::filesystem::exists(status)) {
    std::error_code ignored;
    std::filesystem::permissions(temp, status.permissions(), ignored);
  }
  std::filesystem::rename(temp, target, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    return ioError(path.string() + ": cannot rename into place: " + ec.message());
  }
  syncDirectory(target.parent_path());
  return okStatus();
}

Status writeObj(const std::filesystem::path& path, std::span<const Vec3> positions, const FaceList& faces,
                const std::string& comment, std::span<const Vec2> uvs, std::span<const std::uint32_t> position_of_uv) {
  const bool split = !position_of_uv.empty();
  const std::size_t corner_count = split ? position_of_uv.size() : positions.size();  // what face indices name
  if (!uvs.empty() && uvs.size() != corner_count) {
    return invalidArgument(path.string() + ": " + std::to_string(uvs.size()) + " texture coordinates for " +
                           std::to_string(corner_count) + (split ? " corner vertices" : " vertices"));
  }
  for (std::size_t r = 0; r < position_of_uv.size(); ++r) {
    if (position_of_uv[r] >= positions.size()) {
      return invalidArgument(path.string() + ": texture coordinate " + std::to_string(r) + " belongs to vertex " +
                             std::to_string(position_of_uv[r]) + " of " + std::to_string(positions.size()));
    }
  }
  std::string text;
  text.reserve(positions.size() * 40 + uvs.size() * 28 + faces.indices.size() * 16 + 64);
  if (!comment.empty()) text += "# " + comment + "\n";
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const Vec3& p = positions[i];
    if (!isFinite(p)) {
      return invalidArgument(path.string() + ": vertex " + std::to_string(i) + " is not finite");
    }
    // %.9g round-trips float32 exactly and keeps double output readable; to_chars, not snprintf,
    // so the host's locale cannot turn the points into commas.
    text += 'v';
    for (const double c : {p.x, p.y, p.z}) {
      text += ' ';
      appendNumber(text, c, 9);
    }
    text += '\n';
  }
  for (std::size_t i = 0; i < uvs.size(); ++i) {
    if (!isFinite(uvs[i])) {
      return invalidArgument(path.string() + ": texture coordinate " + std::to_string(i) + " is not finite");
    }
    text += "vt ";
    appendNumber(text, uvs[i].x, 9);
    text += ' ';
    appendNumber(text, 1.0 - uvs[i].y, 9);
    text += '\n';
  }
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    text += 'f';
    for (std::uint32_t k = faces.face_offsets[f]; k < faces.face_offsets[f + 1]; ++k) {
      const std::uint32_t index = faces.indices[k];
      if (index >= corner_count) {
        return invalidArgument(path.string() + ": face " + std::to_string(f) + " references vertex " +
                               std::to_string(index) + " of " + std::to_string(corner_count));
      }
      text += ' ';
      text += std::to_string((split ? position_of_uv[index] : index) + 1);
      if (!uvs.empty()) text += '/' + std::to_string(index + 1);
    }
    text += '\n';
  }
  return writeFileAtomically(path, text);
}

}  // namespace odeskin

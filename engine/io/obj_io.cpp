// SPDX-License-Identifier: MIT
#include "obj_io.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <system_error>

#include "../core/pending_files.hpp"
#include "../core/result.hpp"

namespace odeskin {

namespace {

Status writeInPlace(const std::filesystem::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  if (!out) return ioError(path.string() + ": cannot open for writing");
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  out.close();
  if (!out) return ioError(path.string() + ": write failed");
  return okStatus();
}

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
  // The temporary lives beside the target so the rename stays on one file system (atomic).
  std::random_device seed;
  std::filesystem::path temp = target;
  temp += ".tmp" + std::to_string(seed() % 1000000);
  const PendingFile pending(temp);  // removed by the command line's SIGINT/SIGTERM handler
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) return ioError(path.string() + ": cannot create file");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();  // close, not only flush: the last buffered bytes can fail here too (a full disk)
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temp, ignored);
      return ioError(path.string() + ": write failed (disk full?)");
    }
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
  return okStatus();
}

Status writeObj(const std::filesystem::path& path, std::span<const Vec3> positions, const FaceList& faces,
                const std::string& comment) {
  std::string text;
  text.reserve(positions.size() * 40 + faces.indices.size() * 8 + 64);
  if (!comment.empty()) text += "# " + comment + "\n";
  char line[96];
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const Vec3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      return invalidArgument(path.string() + ": vertex " + std::to_string(i) + " is not finite");
    }
    // %.9g round-trips float32 exactly and keeps double output readable.
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    text += line;
  }
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    text += 'f';
    for (std::uint32_t k = faces.face_offsets[f]; k < faces.face_offsets[f + 1]; ++k) {
      if (faces.indices[k] >= positions.size()) {
        return invalidArgument(path.string() + ": face " + std::to_string(f) + " references vertex " +
                               std::to_string(faces.indices[k]) + " of " + std::to_string(positions.size()));
      }
      text += ' ';
      text += std::to_string(faces.indices[k] + 1);
    }
    text += '\n';
  }
  return writeFileAtomically(path, text);
}

}  // namespace odeskin

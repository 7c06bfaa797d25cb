// SPDX-License-Identifier: MIT
#include "libigl_io.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "../core/json_path.hpp"
#include "../core/number_text.hpp"
#include "text_tokens.hpp"

namespace odeskin {
namespace {

std::string at(const std::string& source, std::size_t line) { return source + ":" + std::to_string(line) + ": "; }

Vec3 toGlm(const Eigen::Vector3d& v) { return Vec3(v.x(), v.y(), v.z()); }

// Parents by libigl directed_edge_parents: the bone ending where b starts. A joint that ends two
// bones would make the parent ambiguous, and parents that loop have no root to start FK from.
Status resolveParents(const std::string& source, const std::vector<std::pair<int, int>>& edges,
                      const std::vector<std::size_t>& edge_lines, std::size_t joint_count,
                      std::vector<std::int32_t>& parents) {
  std::vector<std::int32_t> bone_ending_at(joint_count, -1);
  for (std::size_t b = 0; b < edges.size(); ++b) {
    std::int32_t& slot = bone_ending_at[static_cast<std::size_t>(edges[b].second)];
    if (slot >= 0) {
      return parseError(at(source, edge_lines[b]) + "joint " + std::to_string(edges[b].second + 1) +
                        " already ends bone " + std::to_string(slot) + " (line " +
                        std::to_string(edge_lines[static_cast<std::size_t>(slot)]) +
                        "), so the parent of a bone starting there is ambiguous");
    }
    slot = static_cast<std::int32_t>(b);
  }
  parents.resize(edges.size());
  for (std::size_t b = 0; b < edges.size(); ++b) parents[b] = bone_ending_at[static_cast<std::size_t>(edges[b].first)];
  for (std::size_t b = 0; b < edges.size(); ++b) {
    std::int32_t p = parents[b];
    for (std::size_t steps = 0; p >= 0; ++steps, p = parents[static_cast<std::size_t>(p)]) {
      if (steps > edges.size())
        return parseError(at(source, edge_lines[b]) + "bone " + std::to_string(b) + " is on a cycle");
    }
  }
  return okStatus();
}

}  // namespace

Result<Skeleton> readTgf(const std::filesystem::path& path) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string text, readTextFile(path));
  return parseTgf(text, path.string());
}

Result<Skeleton> parseTgf(const std::string& text, const std::string& source) {
  std::vector<Vec3> joints;
  std::vector<std::pair<int, int>> edges;  // 0-based joints
  std::vector<std::size_t> edge_lines;
  int section = 0;  // 0: joints, 1: edges, 2: after the closing '#' (libigl's optional extras: ignored)
  LineReader reader(text);
  std::string_view line;
  while (section < 2 && reader.next(line)) {
    std::string_view rest = line;
    const std::string_view first = nextToken(rest);
    if (first.empty()) continue;
    if (first.front() == '#') {
      ++section;
      continue;
    }
    const std::string where = at(source, reader.number());
    if (section == 0) {
      std::size_t index = 0;
      if (!parseInt(first, index) || index != joints.size() + 1) {
        return parseError(where + "expected joint number " + std::to_string(joints.size() + 1) + ", found '" +
                          std::string(first) + "'");
      }
      Vec3 p;
      for (int k = 0; k < 3; ++k) {
        if (!parseDouble(nextToken(rest), p[k])) return parseError(where + "joint needs 3 finite coordinates");
      }
      joints.push_back(p);  // libigl allows further columns; they carry nothing we use
    } else {
      int ends[2] = {0, 0};
      std::string_view tokens[2] = {first, nextToken(rest)};
      for (int k = 0; k < 2; ++k) {
        if (!parseInt(tokens[k], ends[k]) || ends[k] < 1 || static_cast<std::size_t>(ends[k]) > joints.size()) {
          return parseError(where + "bone end '" + std::string(tokens[k]) + "' is not a joint number in 1.." +
                            std::to_string(joints.size()));
        }
      }
      if (ends[0] == ends[1]) return parseError(where + "bone starts and ends at joint " + std::to_string(ends[0]));
      edges.emplace_back(ends[0] - 1, ends[1] - 1);
      edge_lines.push_back(reader.number());
    }
  }
  if (edges.empty()) return parseError(source + ": no bones (edge lines after the first '#')");

  Skeleton skeleton;
  ODESKIN_TRY(resolveParents(source, edges, edge_lines, joints.size(), skeleton.parents));
  for (std::size_t b = 0; b < edges.size(); ++b) {
    skeleton.names.push_back("bone" + std::to_string(b));
    skeleton.heads.push_back(joints[static_cast<std::size_t>(edges[b].first)]);
    skeleton.tails.push_back(joints[static_cast<std::size_t>(edges[b].second)]);
  }
  return skeleton;
}

Result<DenseMatrix> readDmat(const std::filesystem::path& path) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string text, readTextFile(path));
  return parseDmat(text, path.string());
}

Result<DenseMatrix> parseDmat(const std::string& text, const std::string& source) {
  LineReader reader(text);
  std::string_view line;
  DenseMatrix m;
  bool have_header = false;
  std::size_t count = 0;
  std::vector<double> column_major;
  while (reader.next(line)) {
    for (std::string_view token = nextToken(line); !token.empty(); token = nextToken(line)) {
      auto where = [&] { return at(source, reader.number()); };  // built only on the error paths
      if (!have_header) {
        const std::string_view rows = nextToken(line);
        if (!parseInt(token, m.cols) || !parseInt(rows, m.rows)) {
          return parseError(where() + "header must be 'cols rows', found '" + std::string(token) + " " +
                            std::string(rows) + "'");
        }
        // libigl writes "0 0" before a binary payload; only the ASCII form is read here.
        if (m.rows == 0 || m.cols == 0) return parseError(where() + "empty matrix (or a binary DMAT, not supported)");
        if (m.rows > std::numeric_limits<std::size_t>::max() / m.cols) return parseError(where() + "size overflows");
        count = m.rows * m.cols;
        // Never trust the header for the allocation: each value takes at least two bytes.
        column_major.reserve(std::min(count, text.size() / 2));
        if (!nextToken(line).empty()) return parseError(where() + "header has more than 2 numbers");
        have_header = true;
        break;
      }
      double value = 0.0;
      if (!parseDouble(token, value))
        return parseError(where() + "'" + std::string(token) + "' is not a finite number");
      if (column_major.size() == count) {
        return parseError(where() + "more than the " + std::to_string(count) + " values the header announces");
      }
      column_major.push_back(value);
    }
  }
  if (!have_header) return parseError(source + ": empty file, no 'cols rows' header");
  if (column_major.size() != count) {
    return parseError(source + ": header says " + std::to_string(m.cols) + " columns x " +
                      std::to_string(m.rows) + " rows = " + std::to_string(count) + " values, found " +
                      std::to_string(column_major.size()));
  }
  m.values.resize(count);
  for (std::size_t i = 0; i < count; ++i) m.values[(i % m.rows) * m.cols + i / m.rows] = column_major[i];
  return m;
}

// How far a row of weights may stray from a partition of unity: its sum from 1, and each weight
// below 0. Solvers such as libigl's bounded biharmonic weights leave entries like -1e-9 where a
// bone has no say; within the tolerance they are read as zeros.
constexpr double kWeightTolerance = 1e-6;

Result<Influences> readWeightsDmat(const std::filesystem::path& path, std::size_t vertex_count,
                                   std::size_t bone_count) {
  ODESKIN_ASSIGN_OR_RETURN(DenseMatrix w, readDmat(path));
  if (w.rows != vertex_count || w.cols != bone_count) {
    return invalidArgument(path.string() + ": weights are " + std::to_string(w.rows) + " x " + std::to_string(w.cols) +
                           ", expected " + std::to_string(vertex_count) + " vertices x " + std::to_string(bone_count) +
                           " bones");
  }
  for (std::size_t v = 0; v < w.rows; ++v) {
    double sum = 0.0;
    for (std::size_t b = 0; b < w.cols; ++b) {
      double& weight = w.values[v * w.cols + b];
      if (weight < -kWeightTolerance) {
        return invalidArgument(path.string() + ": vertex " + std::to_string(v) + " has weight " +
                               messageNumber(weight) + " < 0 for bone " + std::to_string(b));
      }
      sum += weight;
      weight = std::max(weight, 0.0);
    }
    if (std::abs(sum - 1.0) > kWeightTolerance) {
      return invalidArgument(path.string() + ": weights of vertex " + std::to_string(v) + " sum to " +
                             messageNumber(sum) + ", not 1");
    }
  }
  return influencesFromDense(w.values, vertex_count, static_cast<std::uint32_t>(bone_count));
}

Result<std::vector<RigidTransform>> readTmat(const std::filesystem::path& path, std::size_t bone_count) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string text, readTextFile(path));
  return parseTmat(text, path.string(), bone_count);
}

Result<std::vector<RigidTransform>> parseTmat(const std::string& text, const std::string& source, std::size_t bone_count) {
  if (bone_count == 0) return invalidArgument(source + ": asked for 0 bones");
  std::vector<Eigen::Vector3d> rows;  // one per numeric line
  std::vector<std::size_t> row_lines;
  LineReader reader(text);
  std::string_view line;
  while (reader.next(line)) {
    std::string_view rest = line;
    std::string_view token = nextToken(rest);
    if (token.empty()) continue;
    Eigen::Vector3d row;
    for (int k = 0; k < 3; ++k, token = nextToken(rest)) {
      if (!parseDouble(token, row[k])) {
        return parseError(at(source, reader.number()) + "expected 3 finite numbers, found '" + std::string(line) + "'");
      }
    }
    if (!token.empty()) return parseError(at(source, reader.number()) + "more than 3 numbers on a line");
    rows.push_back(row);
    row_lines.push_back(reader.number());
  }
  if (rows.size() != 4 * bone_count) {
    return invalidArgument(source + ": " + std::to_string(rows.size()) + " lines of 3 numbers, expected 4 x " +
                           std::to_string(bone_count) + " bones = " + std::to_string(4 * bone_count));
  }
  std::vector<RigidTransform> transforms(bone_count);
  for (std::size_t b = 0; b < bone_count; ++b) {
    Eigen::Matrix3d r;
    for (int c = 0; c < 3; ++c) r.col(c) = rows[4 * b + static_cast<std::size_t>(c)];
    // The files print ~6 digits, so R is orthonormal only to ~1e-6: take the nearest rotation
    // (polar factor U V^T), and refuse anything farther than print rounding could explain.
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Matrix3d nearest = svd.matrixU() * svd.matrixV().transpose();
    const double off = (r - nearest).cwiseAbs().maxCoeff();
    const std::string where = at(source, row_lines[4 * b]) + "bone " + std::to_string(b);
    if (nearest.determinant() < 0.0)
      return invalidArgument(where + " has determinant < 0: a reflection, not a rotation");
    if (!(off <= 1e-4)) {
      return invalidArgument(where + " is not a rotation within 1e-4 (an entry is off by " + messageNumber(off) + ")");
    }
    glm::dmat3 rotation;
    for (int c = 0; c < 3; ++c) rotation[c] = toGlm(nearest.col(c));
    transforms[b].rotation = glm::normalize(glm::quat_cast(rotation));
    transforms[b].translation = toGlm(rows[4 * b + 3]);
  }
  return transforms;
}

Result<std::vector<glm::dquat>> readPoseJson(const std::filesystem::path& path, std::size_t bone_count) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string text, readTextFile(path));
  return parsePoseJson(text, path.string(), bone_count);
}

Result<std::vector<glm::dquat>> parsePoseJson(const std::string& text, const std::string& source, std::size_t bone_count) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {  // nlohmann reports syntax errors only by throwing
    const std::size_t byte = std::min<std::size_t>(e.byte, text.size());
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(byte), '\n'));
    return parseError(at(source, line) + "invalid JSON (" + e.what() + ")");
  } catch (const nlohmann::json::exception& e) {
    return parseError(source + ": invalid JSON (" + e.what() + ")");
  }
  if (!doc.is_object()) return parseError(source + ": the top level is not a JSON object");
  if (const std::string twice = duplicateJsonKey(text); !twice.empty()) return parseError(source + ": " + twice);
  std::vector<glm::dquat> rotations(bone_count, glm::dquat(1.0, 0.0, 0.0, 0.0));
  // "dQ-1" and "dQ-01" name the same bone; JSON allows both keys, and one would silently win.
  std::vector<std::string> key_of_bone(bone_count);
  for (const auto& [key, value] : doc.items()) {
    if (key.rfind("dQ-", 0) != 0) continue;  // Camera, threshold: viewer state
    const std::string where = source + ": \"" + key + "\"";
    std::size_t b = 0;
    if (!parseInt(std::string_view(key).substr(3), b)) return parseError(where + " does not name a bone number");
    if (b >= bone_count) {
      return parseError(where + " names bone " + std::to_string(b) + " but the skeleton has " +
                        std::to_string(bone_count) + " bones");
    }
    if (!key_of_bone[b].empty()) {
      return parseError(where + " names bone " + std::to_string(b) + ", as \"" + key_of_bone[b] + "\" does");
    }
    key_of_bone[b] = key;
    if (!value.is_array() || value.size() != 4) return parseError(where + " must be an array [x, y, z, w]");
    double q[4];
    for (std::size_t k = 0; k < 4; ++k) {
      if (!value[k].is_number() || !std::isfinite(value[k].get<double>())) {
        return parseError(where + " component " + std::to_string(k) + " is not a finite number");
      }
      q[k] = value[k].get<double>();
    }
    const glm::dquat rotation(q[3], q[0], q[1], q[2]);  // file order x y z w; glm's constructor takes w first
    const double norm = glm::length(rotation);
    if (std::abs(norm - 1.0) > 1e-4) {
      return parseError(where + " has length " + messageNumber(norm) + ", not a unit quaternion");
    }
    rotations[b] = rotation / norm;
  }
  return rotations;
}

std::vector<RigidTransform> forwardKinematics(const Skeleton& skeleton, const std::vector<glm::dquat>& relative) {
  const std::size_t bones = skeleton.boneCount();
  auto parentOf = [&](std::size_t b) -> std::int64_t {
    const std::int64_t p = b < skeleton.parents.size() ? skeleton.parents[b] : -1;
    return p >= 0 && static_cast<std::size_t>(p) < bones ? p : -1;
  };
  std::vector<RigidTransform> out(bones);
  enum : char { kPending, kOnChain, kDone };
  std::vector<char> state(bones, kPending);
  std::vector<std::size_t> chain;
  for (std::size_t start = 0; start < bones; ++start) {
    // Walk up to a finished ancestor or a root, then fill the chain top down: parents may come in
    // any order, and long chains need no recursion depth.
    chain.clear();
    for (std::int64_t b = static_cast<std::int64_t>(start); b >= 0 && state[static_cast<std::size_t>(b)] == kPending;
         b = parentOf(static_cast<std::size_t>(b))) {
      state[static_cast<std::size_t>(b)] = kOnChain;
      chain.push_back(static_cast<std::size_t>(b));
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const std::size_t b = *it;
      const glm::dquat q = b < relative.size() ? relative[b] : glm::dquat(1.0, 0.0, 0.0, 0.0);
      const Vec3& c = skeleton.heads[b];
      const std::int64_t p = parentOf(b);
      // A parent still on the chain means a cycle (validateRig rejects those): break it here.
      if (p >= 0 && state[static_cast<std::size_t>(p)] == kDone) {
        const RigidTransform& parent = out[static_cast<std::size_t>(p)];
        out[b].rotation = parent.rotation * q;
        out[b].translation = parent.translation + parent.rotation * c - out[b].rotation * c;
      } else {
        out[b].rotation = q;
        out[b].translation = c - q * c;
      }
      state[b] = kDone;
    }
  }
  return out;
}

}  // namespace odeskin

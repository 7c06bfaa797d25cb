// SPDX-License-Identifier: MIT
#include "gltf_skin.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "../core/number_text.hpp"
#include "gltf_accessor.hpp"

namespace odeskin::gltf {
namespace {

constexpr std::array kMatrixFormats{kFloat};
// Welded copies of a vertex must bind to the same joints; 1e-4 lets through 16-bit quantisation
// (1/65535) and float round-off, and still catches a vertex bound to another joint.
constexpr double kWeldedWeightTolerance = 1e-4;
// A weight sum this far from 1 is the file's, not the rounding of 8-bit weights (two steps of 1/255).
constexpr double kWeightSumTolerance = 1e-2;

using Row = std::vector<std::pair<std::uint32_t, double>>;  // (joint, weight), sorted by joint

// Normalised influences of render vertex r (see topologyInfluences).
Result<Row> renderRow(const MeshData& mesh, std::size_t r, std::uint32_t bone_count) {
  const std::size_t width = 4 * mesh.influence_sets;
  Row row;
  double sum = 0.0;
  for (std::size_t k = 0; k < width; ++k) {
    const std::uint32_t joint = mesh.joints[r * width + k];
    const double w = mesh.weights[r * width + k];
    if (joint >= bone_count) {
      return parseError("render vertex " + std::to_string(r) + ": JOINTS_" + std::to_string(k / 4) + " names joint " +
                        std::to_string(joint) + ", the skin has " + std::to_string(bone_count) + " joints");
    }
    if (w < 0.0) {
      return parseError("render vertex " + std::to_string(r) + ": WEIGHTS_" + std::to_string(k / 4) +
                        " has a negative weight " + messageNumber(w));
    }
    if (w == 0.0) continue;
    sum += w;
    auto it = std::lower_bound(row.begin(), row.end(), joint, [](const auto& e, std::uint32_t j) { return e.first < j; });
    if (it != row.end() && it->first == joint) {
      it->second += w;
    } else {
      row.insert(it, {joint, w});
    }
  }
  if (!(sum > 0.0)) return parseError("render vertex " + std::to_string(r) + ": its skin weights sum to 0");
  for (auto& e : row) e.second /= sum;
  return row;
}

// Largest per-joint difference between two sorted rows.
double rowDifference(const Row& a, const Row& b) {
  double worst = 0.0;
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i].first < b[j].first)) {
      worst = std::max(worst, a[i++].second);
    } else if (i == a.size() || b[j].first < a[i].first) {
      worst = std::max(worst, b[j++].second);
    } else {
      worst = std::max(worst, std::abs(a[i++].second - b[j++].second));
    }
  }
  return worst;
}

}  // namespace

Result<SkinData> readSkin(const tinygltf::Model& model, int skin_index, std::span<const int> parents,
                          DecodeBudget& budget) {
  const tinygltf::Skin& skin = model.skins[static_cast<std::size_t>(skin_index)];
  const std::string where = "skin " + std::to_string(skin_index);
  const std::size_t bones = skin.joints.size();
  if (bones == 0) return parseError(where + " has no joints");
  SkinData out;
  out.joint_nodes = skin.joints;
  std::vector<int> joint_of_node(model.nodes.size(), -1);
  for (std::size_t j = 0; j < bones; ++j) {
    const int node = skin.joints[j];
    if (node < 0 || node >= static_cast<int>(model.nodes.size())) {
      return parseError(where + ": joint " + std::to_string(j) + " is node " + std::to_string(node) + ", which does not exist");
    }
    if (joint_of_node[static_cast<std::size_t>(node)] >= 0) {
      return parseError(where + ": node " + std::to_string(node) + " is listed as a joint twice");
    }
    joint_of_node[static_cast<std::size_t>(node)] = static_cast<int>(j);
  }

  out.inverse_bind.assign(bones, glm::dmat4(1.0));
  if (skin.inverseBindMatrices >= 0) {
    ODESKIN_ASSIGN_OR_RETURN(AccessorData ibm, readAccessor(model, skin.inverseBindMatrices,
                                                            {where + " inverseBindMatrices", TINYGLTF_TYPE_MAT4, kMatrixFormats},
                                                            budget));
    if (ibm.count < bones) {
      return parseError(where + ": " + std::to_string(ibm.count) + " inverse bind matrices for " +
                        std::to_string(bones) + " joints");
    }
    for (std::size_t j = 0; j < bones; ++j) {
      glm::dmat4& m = out.inverse_bind[j];
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) m[c][r] = ibm.at(j, 4 * static_cast<std::size_t>(c) + static_cast<std::size_t>(r));
      }
      const bool affine = std::abs(m[0][3]) < 1e-6 && std::abs(m[1][3]) < 1e-6 && std::abs(m[2][3]) < 1e-6 &&
                          std::abs(m[3][3] - 1.0) < 1e-6;
      // Relative to the columns' lengths (Hadamard's bound), since a quantized mesh's IBMs carry its
      // grid step, 1e-5 or less, in every column.
      const double columns = glm::length(glm::dvec3(m[0])) * glm::length(glm::dvec3(m[1])) * glm::length(glm::dvec3(m[2]));
      if (!affine || !(std::abs(glm::determinant(glm::dmat3(m))) > 1e-12 * columns)) {
        return parseError(where + ": inverse bind matrix " + std::to_string(j) +
                          " is not an invertible affine matrix (last row must be 0 0 0 1)");
      }
    }
  }

  Skeleton& s = out.skeleton;
  s.names.resize(bones);
  s.parents.assign(bones, -1);
  for (std::size_t j = 0; j < bones; ++j) {
    const int node = skin.joints[j];
    const std::string& name = model.nodes[static_cast<std::size_t>(node)].name;
    s.names[j] = name.empty() ? "joint" + std::to_string(j) : name;
    for (int p = parents[static_cast<std::size_t>(node)]; p >= 0; p = parents[static_cast<std::size_t>(p)]) {
      if (joint_of_node[static_cast<std::size_t>(p)] >= 0) {
        s.parents[j] = joint_of_node[static_cast<std::size_t>(p)];
        break;
      }
    }
  }
  placeJoints(out);
  return out;
}

void placeJoints(SkinData& skin) {
  Skeleton& s = skin.skeleton;
  const std::size_t bones = skin.inverse_bind.size();
  s.heads.resize(bones);
  for (std::size_t j = 0; j < bones; ++j) s.heads[j] = Vec3(glm::inverse(skin.inverse_bind[j])[3]);
  s.tails = s.heads;
  for (std::size_t j = bones; j-- > 0;) {  // backwards, so the first child in bone order wins
    if (s.parents[j] >= 0) s.tails[static_cast<std::size_t>(s.parents[j])] = s.heads[j];
  }
}

Result<Influences> topologyInfluences(const MeshData& mesh, const Welded& welded, std::uint32_t bone_count,
                                      std::string* warning) {
  const std::size_t topology = welded.positions.size();
  std::vector<Row> rows(topology);
  for (std::size_t t = 0; t < topology; ++t) {
    ODESKIN_ASSIGN_OR_RETURN(rows[t], renderRow(mesh, welded.first_render[t], bone_count));
  }
  // glTF asks weights to sum to 1; renderers differ on sums that do not (three.js scales them,
  // others skin as stored), so the ones odeskin scales to 1 are counted aloud.
  const std::size_t width = 4 * mesh.influence_sets;
  std::size_t off = 0, first_off = 0;
  double first_sum = 1.0;
  for (std::size_t r = 0; r < welded.topology_of_render.size(); ++r) {
    double sum = 0.0;
    for (std::size_t k = 0; k < width; ++k) sum += std::max(mesh.weights[r * width + k], 0.0);
    if (std::abs(sum - 1.0) > kWeightSumTolerance) {
      if (off++ == 0) first_off = r, first_sum = sum;
    }
  }
  if (warning != nullptr && off > 0) {
    *warning = "the skin weights of " + std::to_string(off) + " render vertices do not sum to 1 (vertex " +
               std::to_string(first_off) + ": " + messageNumber(first_sum) + "); they are scaled to sum to 1";
  }
  for (std::size_t r = 0; r < welded.topology_of_render.size(); ++r) {
    const std::uint32_t t = welded.topology_of_render[r];
    if (welded.first_render[t] == r) continue;
    ODESKIN_ASSIGN_OR_RETURN(Row row, renderRow(mesh, r, bone_count));
    const double d = rowDifference(rows[t], row);
    if (d > kWeldedWeightTolerance) {
      return parseError("topology vertex " + std::to_string(t) + ": render vertices " +
                        std::to_string(welded.first_render[t]) + " and " + std::to_string(r) +
                        " share its position but their skin weights differ by " + messageNumber(d));
    }
  }
  Influences out;
  out.offsets.reserve(topology + 1);
  for (const Row& row : rows) {
    for (const auto& [joint, w] : row) {
      out.bones.push_back(joint);
      out.weights.push_back(w);
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.bones.size()));
  }
  return out;
}

}  // namespace odeskin::gltf

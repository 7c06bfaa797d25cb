// SPDX-License-Identifier: MIT
#include "fourier_deform_fast_job.hpp"
#include "../core/parallel.hpp"
#include "../core/thread_count.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <tbb/blocked_range.h>
#include <tbb/task_arena.h>

namespace odeskin {
namespace {

// 4096 vertices per task: large enough that scheduling is noise next to the series (N = 9 costs
// ~80 flops a curve), small enough to balance 1e3-vertex meshes over a few threads.
constexpr std::size_t kGrain = 4096;
constexpr float kTwoPi = 6.28318530717958647692f;

glm::vec3 xyz(const gpu::Float4& f) { return {f.x, f.y, f.z}; }
glm::vec4 vec(const gpu::Float4& f) { return {f.x, f.y, f.z, f.w}; }

// Entry m of a curve's coefficients folded with its mode's time basis, A_m = gamma d_m + psi rdot_m:
// what shaders/fold_series.comp writes for the shaders' series (and foldCurve of the CPU kernel).
glm::vec3 folded(const gpu::Float4* coef, const gpu::Float4* rate, const gpu::ModeBasis& b, std::size_t m) {
  return rate ? b.gamma * xyz(coef[m]) + b.psi * xyz(rate[m]) : b.gamma * xyz(coef[m]);
}

// Same order of operations as curveSeries() in shaders/deform_vertex.glsl on fold_series.comp's
// folded coefficients.
glm::vec3 curveSeries(const PackedDeformData& d, const gpu::DeformPushConstants& pc,
                      std::span<const gpu::ModeBasis> basis, std::uint32_t curve, float v, float c1, float s1) {
  const std::uint32_t m_count = 2 * pc.modes + 2;
  const std::size_t base = (static_cast<std::size_t>(pc.segment) * pc.curve_count + curve) * m_count;
  const std::size_t basis_base = static_cast<std::size_t>(d.curve_materials[curve]) * (pc.modes + 1);
  const gpu::Float4* coef = d.coefficients.data() + base;
  const gpu::Float4* rate = pc.use_rates ? d.rates.data() + base : nullptr;
  const gpu::ModeBasis& b0 = basis[basis_base];
  glm::vec3 sum = folded(coef, rate, b0, 0) + v * folded(coef, rate, b0, m_count - 1);
  float cn = c1;
  float sn = s1;
  for (std::uint32_t n = 1; n <= pc.modes; ++n) {
    const gpu::ModeBasis& bn = basis[basis_base + n];
    sum += cn * folded(coef, rate, bn, 2 * n - 1) + sn * folded(coef, rate, bn, 2 * std::size_t{n});
    const float c_next = cn * c1 - sn * s1;
    sn = sn * c1 + cn * s1;
    cn = c_next;
  }
  return sum;
}

// Vertex i's entries [begin, end) in d.influences. Fixed slot counts are template arguments so the
// 4- and 8-influence loops unroll.
template <std::uint32_t kSlots>
std::pair<std::size_t, std::size_t> influenceRow(const PackedDeformData& d, std::size_t i) {
  if constexpr (kSlots == 0) {
    return {d.influence_offsets[i], d.influence_offsets[i + 1]};
  } else {
    return {i * kSlots, i * kSlots + kSlots};
  }
}

template <std::uint32_t kSlots>
glm::vec3 skinPoint(const PackedDeformData& d, std::span<const gpu::BoneMatrix> bones, std::size_t i,
                    const glm::vec3& p) {
  const auto [begin, end] = influenceRow<kSlots>(d, i);
  const glm::vec4 h(p, 1.0f);
  glm::vec3 out(0.0f);
  for (std::size_t k = begin; k < end; ++k) {
    const gpu::Influence inf = d.influences[k];
    const gpu::BoneMatrix& m = bones[inf.bone];
    out += inf.weight * glm::vec3(glm::dot(vec(m.row0), h), glm::dot(vec(m.row1), h), glm::dot(vec(m.row2), h));
  }
  return out;
}

// Kavan et al. 2008, Algorithm 1, in the order of operations of skinPointDq() in
// shaders/skinning.glsl: pivot = the first largest weight, bones on the pivot's side, blend,
// divide by |real|, then x -> R x + t from the unit dual quaternion. A degenerate blend (see
// kMinDualQuaternionBlendNorm) takes the LBS path.
template <std::uint32_t kSlots>
glm::vec3 skinPointDq(const PackedDeformData& d, std::span<const gpu::BoneMatrix> bones,
                      std::span<const gpu::DualQuat> dual_quats, std::size_t i, const glm::vec3& p) {
  const auto [begin, end] = influenceRow<kSlots>(d, i);
  if (begin == end) return skinPoint<kSlots>(d, bones, i, p);
  std::size_t pivot = begin;
  for (std::size_t k = begin + 1; k < end; ++k) {
    if (d.influences[k].weight > d.influences[pivot].weight) pivot = k;
  }
  const glm::vec4 pivot_real = vec(dual_quats[d.influences[pivot].bone].real);
  glm::vec4 real(0.0f);
  glm::vec4 dual(0.0f);
  for (std::size_t k = begin; k < end; ++k) {
    const gpu::Influence inf = d.influences[k];
    const gpu::DualQuat& q = dual_quats[inf.bone];
    const glm::vec4 q_real = vec(q.real);
    const float w = glm::dot(q_real, pivot_real) < 0.0f ? -inf.weight : inf.weight;
    real += w * q_real;
    dual += w * vec(q.dual);
  }
  const float norm = glm::length(real);
  if (!(norm > static_cast<float>(ODESKIN_DQS_MIN_BLEND_NORM))) return skinPoint<kSlots>(d, bones, i, p);
  const float inv_norm = 1.0f / norm;  // one division instead of eight
  const glm::vec4 r = real * inv_norm;
  const glm::vec4 e = dual * inv_norm;
  const glm::vec3 rv(r.x, r.y, r.z);
  const glm::vec3 ev(e.x, e.y, e.z);
  const glm::vec3 t = 2.0f * (r.w * ev - e.w * rv + glm::cross(rv, ev));
  const float xx = r.x * r.x, yy = r.y * r.y, zz = r.z * r.z;
  const float xy = r.x * r.y, xz = r.x * r.z, yz = r.y * r.z;
  const float wx = r.w * r.x, wy = r.w * r.y, wz = r.w * r.z;
  const glm::vec3 c0(1.0f - 2.0f * (yy + zz), 2.0f * (xy + wz), 2.0f * (xz - wy));
  const glm::vec3 c1(2.0f * (xy - wz), 1.0f - 2.0f * (xx + zz), 2.0f * (yz + wx));
  const glm::vec3 c2(2.0f * (xz + wy), 2.0f * (yz - wx), 1.0f - 2.0f * (xx + yy));
  return c0 * p.x + c1 * p.y + c2 * p.z + t;
}

// The vertex's skinning in the mode of `dual_quats`: empty = LBS.
template <std::uint32_t kSlots>
glm::vec3 skin(const PackedDeformData& d, std::span<const gpu::BoneMatrix> bones,
               std::span<const gpu::DualQuat> dual_quats, std::size_t i, const glm::vec3& p) {
  return dual_quats.empty() ? skinPoint<kSlots>(d, bones, i, p) : skinPointDq<kSlots>(d, bones, dual_quats, i, p);
}

template <std::uint32_t kSlots>
void deformRange(const FourierDeformFastJob& job, const gpu::DeformPushConstants& pc,
                 std::span<const gpu::DualQuat> dual_quats, std::size_t begin, std::size_t end) {
  const PackedDeformData& d = *job.data;
  const gpu::SegmentVertex* segment = d.segment_vertices.data() + static_cast<std::size_t>(pc.segment) * pc.vertex_count;
  for (std::size_t i = begin; i < end; ++i) {
    const gpu::VertexBinding vb = d.bindings[i];
    const float angle = kTwoPi * vb.v;
    const float c1 = std::cos(angle);
    const float s1 = std::sin(angle);
    const glm::vec3 series_a = curveSeries(d, pc, job.basis, vb.curve_a, vb.v, c1, s1);
    const glm::vec3 series_b =
        vb.curve_b == vb.curve_a ? series_a : curveSeries(d, pc, job.basis, vb.curve_b, vb.v, c1, s1);
    glm::vec3 residual = (1.0f - vb.w) * series_a + vb.w * series_b;
    const gpu::SegmentVertex sv = segment[i];
    residual += glm::vec3(sv.base_x, sv.base_y, sv.base_z);
    if (sv.remainder_index != gpu::kNoRemainder) {
      residual += job.basis.back().gamma * xyz(d.remainders[pc.remainder_base + sv.remainder_index]);
    }
    const glm::vec3 rest = xyz(d.rest_positions[i]);
    const glm::vec3 p = pc.residual_space == ODESKIN_RESIDUAL_BIND
                            ? skin<kSlots>(d, job.bones, dual_quats, i, rest + residual)
                            : skin<kSlots>(d, job.bones, dual_quats, i, rest) + residual;
    job.out_positions[i] = gpu::Float4{p.x, p.y, p.z, 1.0f};
  }
}

template <std::uint32_t kSlots>
void lbsRange(const LbsFastJob& job, std::span<const gpu::DualQuat> dual_quats, std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    const glm::vec3 p = skin<kSlots>(*job.data, job.bones, dual_quats, i, xyz(job.data->rest_positions[i]));
    job.out_positions[i] = gpu::Float4{p.x, p.y, p.z, 1.0f};
  }
}

// The frame's bones as dual quaternions when `d` skins with them, else empty.
std::vector<gpu::DualQuat> frameDualQuats(const PackedDeformData& d, std::span<const gpu::BoneMatrix> bones) {
  std::vector<gpu::DualQuat> dual_quats;
  if (d.skinning == SkinningMode::kDualQuaternion) {
    dual_quats.resize(bones.size());
    toGpuDualQuaternions(bones, dual_quats);
  }
  return dual_quats;
}

// Runs body(begin, end) over [0, count) on `threads` workers (0 = all). A single thread runs
// inline, so the 1-thread benchmark measures the kernel, not the scheduler.
template <typename Body>
void parallelRange(std::size_t count, unsigned threads, const Body& body) {
  if (threads > 1) threads = usableThreads(threads);
  if (threads == 1 || count <= kGrain) {
    body(std::size_t{0}, count);
    return;
  }
  auto loop = [&] {
    parallelFor(tbb::blocked_range<std::size_t>(0, count, kGrain),
                [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
  };
  if (threads == 0) {
    loop();
  } else {
    tbb::task_arena arena(static_cast<int>(threads));
    arenaExecute(arena, loop);
  }
}

Status checkLayout(const PackedDeformData& d, const char* job) {
  const std::uint32_t layout = d.influence_layout;
  if (layout != ODESKIN_INFLUENCES_SPARSE && layout != 4 && layout != 8) {
    return invalidArgument(std::string(job) + ": influence_layout " + std::to_string(layout) + " is not 0, 4 or 8");
  }
  if (d.skinning != SkinningMode::kLinear && d.skinning != SkinningMode::kDualQuaternion) {
    return invalidArgument(std::string(job) + ": unknown skinning mode " +
                           std::to_string(static_cast<std::uint32_t>(d.skinning)));
  }
  if (d.rest_positions.size() != d.vertex_count) return invalidArgument(std::string(job) + ": rest_positions size");
  if (layout == ODESKIN_INFLUENCES_SPARSE) {
    if (d.influence_offsets.size() != static_cast<std::size_t>(d.vertex_count) + 1 ||
        d.influences.size() != d.influence_offsets.back()) {
      return invalidArgument(std::string(job) + ": sparse influence rows do not match vertex_count");
    }
  } else if (d.influences.size() != static_cast<std::size_t>(d.vertex_count) * layout) {
    return invalidArgument(std::string(job) + ": influences size is not vertex_count x slots");
  }
  return okStatus();
}

}  // namespace

Status FourierDeformFastJob::validate() const {
  if (data == nullptr) return invalidArgument("fourier deform fast: data is null");
  const PackedDeformData& d = *data;
  ODESKIN_TRY(checkLayout(d, "fourier deform fast"));
  if (segment >= d.segment_count) {
    return invalidArgument("fourier deform fast: segment " + std::to_string(segment) + " of " +
                           std::to_string(d.segment_count));
  }
  const std::size_t m_count = d.coefficientsPerCurve();
  if (d.bindings.size() != d.vertex_count ||
      d.segment_vertices.size() != static_cast<std::size_t>(d.segment_count) * d.vertex_count ||
      d.curve_materials.size() != d.curve_count ||
      d.coefficients.size() != static_cast<std::size_t>(d.segment_count) * d.curve_count * m_count ||
      (!d.rates.empty() && d.rates.size() != d.coefficients.size()) ||
      d.remainder_base.size() != d.segment_count) {
    return invalidArgument("fourier deform fast: packed data sizes disagree with its counts");
  }
  if (bones.size() != d.bone_count) {
    return invalidArgument("fourier deform fast: bones has " + std::to_string(bones.size()) + " entries, expected " +
                           std::to_string(d.bone_count));
  }
  if (basis.size() != ODESKIN_BASIS_ENTRIES(std::size_t{d.material_count}, std::size_t{d.modes})) {
    return invalidArgument("fourier deform fast: basis has " + std::to_string(basis.size()) +
                           " entries, expected material_count x (N+1) + 1 = " +
                           std::to_string(ODESKIN_BASIS_ENTRIES(std::size_t{d.material_count}, std::size_t{d.modes})));
  }
  if (out_positions.size() != d.vertex_count) {
    return invalidArgument("fourier deform fast: out_positions has " + std::to_string(out_positions.size()) +
                           " entries, expected " + std::to_string(d.vertex_count));
  }
  return okStatus();
}

Status FourierDeformFastJob::run() const {
  ODESKIN_TRY(validate());
  const gpu::DeformPushConstants pc = deformPushConstants(*data, segment);
  const std::vector<gpu::DualQuat> dual_quats = frameDualQuats(*data, bones);
  parallelRange(data->vertex_count, threads, [&](std::size_t begin, std::size_t end) {
    switch (data->influence_layout) {
      case 4: deformRange<4>(*this, pc, dual_quats, begin, end); break;
      case 8: deformRange<8>(*this, pc, dual_quats, begin, end); break;
      default: deformRange<0>(*this, pc, dual_quats, begin, end); break;
    }
  });
  return okStatus();
}

Status LbsFastJob::validate() const {
  if (data == nullptr) return invalidArgument("lbs fast: data is null");
  ODESKIN_TRY(checkLayout(*data, "lbs fast"));
  if (bones.size() != data->bone_count) {
    return invalidArgument("lbs fast: bones has " + std::to_string(bones.size()) + " entries, expected " +
                           std::to_string(data->bone_count));
  }
  if (out_positions.size() != data->vertex_count) {
    return invalidArgument("lbs fast: out_positions has " + std::to_string(out_positions.size()) +
                           " entries, expected " + std::to_string(data->vertex_count));
  }
  return okStatus();
}

Status LbsFastJob::run() const {
  ODESKIN_TRY(validate());
  const std::vector<gpu::DualQuat> dual_quats = frameDualQuats(*data, bones);
  parallelRange(data->vertex_count, threads, [&](std::size_t begin, std::size_t end) {
    switch (data->influence_layout) {
      case 4: lbsRange<4>(*this, dual_quats, begin, end); break;
      case 8: lbsRange<8>(*this, dual_quats, begin, end); break;
      default: lbsRange<0>(*this, dual_quats, begin, end); break;
    }
  });
  return okStatus();
}

}  // namespace odeskin

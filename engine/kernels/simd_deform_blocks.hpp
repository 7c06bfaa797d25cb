// SPDX-License-Identifier: MIT
// The block loops of CpuDeformKernel (thesis Eq 6.30 corrected, MATH.md 5.6; PIPELINE.md 3), written
// once with GCC/Clang vector extensions and compiled once per instruction set:
// cpu_deform_kernel_simd.cpp includes this file inside a namespace and a target region, with
// ODESKIN_SIMD_LANES = 16 (AVX-512), 8 (AVX2 + FMA) or 4 (SSE2, NEON, any target), the widest
// vector. A block's last lanes run at that width, or on AVX-512 at half of it where they fit, so a
// pair whose vertex count is not a multiple of 16 wastes less than 8 lanes. No include guard
// on purpose, and no #include: the including file provides <cstring>, <cstdint>, <utility> and
// simd_deform_layout.hpp.
//
// Per block of kBlockLanes vertices sharing the curve pair (a, b), in float:
//   A_cm = gamma_n(m) d_cm + psi_n(m) rdot_cm           (folded once per curve, not per vertex)
//   S_c  = A_c0 + v A_c,2N+1 + sum_n cos(2 pi n v) A_c,2n-1 + sin(2 pi n v) A_c,2n
//   D    = S_a + w (S_b - S_a),   r = D + r^s + gamma_rem eps
//   bind: out = skin(X + r);  posed: out = skin(X) + r
// The harmonics come from the lane's precomputed cos/sin(2 pi v) by the Chebyshev recurrence
//   cos((n+1) t) = 2 cos t cos(n t) - cos((n-1) t),  and the same for sin,
// one FMA per harmonic and function where the angle-addition recurrence of
// fourier_deform_fast_job.cpp and the shader takes two (a quarter of the series' arithmetic at two
// curves). Its rounding error grows like n^2 ulps instead of n; at N = 17 that is ~2e-5 of the
// harmonic's own coefficient, which is far below the float tolerance because fitted
// coefficients decay with n (the tests and the benchmark's verification measure it). Where the
// registers allow (AVX-512's 32, or one curve), cosine and sine terms go to separate accumulators
// so the FMA chains of one coordinate run in parallel; two curves in 16 registers chain them.

static_assert(kBlockLanes % ODESKIN_SIMD_LANES == 0);
inline constexpr std::uint32_t kMaxLanes = ODESKIN_SIMD_LANES;
// The width of a block's last lanes when they fit in it: half a vector on AVX-512. Narrower
// targets already skip a block's empty vectors, and a 4-lane tail measured slower than it saved.
inline constexpr std::uint32_t kTailLanes = kMaxLanes == 16 ? 8 : kMaxLanes;

template <std::uint32_t kL>
struct Vec {
  typedef float V __attribute__((vector_size(kL * sizeof(float))));
  typedef std::int32_t VI __attribute__((vector_size(kL * sizeof(std::int32_t))));
};
template <std::uint32_t kL>
using Vf = typename Vec<kL>::V;
template <std::uint32_t kL>
using Vi = typename Vec<kL>::VI;

template <std::uint32_t kL>
struct P3 {
  Vf<kL> x, y, z;
};

template <std::uint32_t kL>
[[gnu::always_inline]] inline Vf<kL> load(const float* p) {
  Vf<kL> v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// s - 0 == s for every float (unlike 0 + s for s = -0), so the compiler folds this to a broadcast,
// or to an embedded-broadcast memory operand of an FMA on AVX-512.
template <std::uint32_t kL>
[[gnu::always_inline]] inline Vf<kL> splat(float s) {
  return s - Vf<kL>{};
}

// Folds curve `curve`'s coefficients of frame `f` with its material's time basis: out[3m + k] =
// gamma_n(m) d_cm,k + psi_n(m) rdot_cm,k, the order of fourier_deform_fast_job's products. Harmonics
// above the curve's last non-zero one are written as zero, so a two-curve block can run both
// series to the larger of the two counts. The floats are taken in runs that share one basis entry
// (the constant, each harmonic's cos and sin, the trend), without a branch per float: at 1,000
// vertices of the cat a frame folds 72 curves for 102 blocks, and a branch per float made the
// folds a third of the frame.
inline void foldCurve(const Layout& layout, const Frame& f, std::uint32_t curve, float* out) {
  const std::uint32_t m_count = layout.coefficientsPerCurve();
  const std::size_t base = (static_cast<std::size_t>(f.segment) * layout.curve_count + curve) * m_count * 3;
  const float* d = layout.coefficients.data() + base;
  const float* r = layout.has_rates ? layout.rates.data() + base : nullptr;
  const gpu::ModeBasis* basis = f.basis + static_cast<std::size_t>(layout.curve_materials[curve]) * (layout.modes + 1);
  const std::uint32_t used = layout.curve_modes[static_cast<std::size_t>(f.segment) * layout.curve_count + curve];
  // Floats [first, first + count) with basis entry b.
  auto fold = [&](std::uint32_t first, std::uint32_t count, gpu::ModeBasis b) {
    if (r != nullptr) {
      for (std::uint32_t e = first; e < first + count; ++e) out[e] = b.gamma * d[e] + b.psi * r[e];
    } else {
      for (std::uint32_t e = first; e < first + count; ++e) out[e] = b.gamma * d[e];
    }
  };
  fold(0, 3, basis[0]);  // m = 0: the constant
  for (std::uint32_t n = 1; n <= used; ++n) fold(6 * n - 3, 6, basis[n]);  // m = 2n - 1, 2n
  const std::uint32_t trend = 3 * (m_count - 1);
  for (std::uint32_t e = 6 * used + 3; e < trend; ++e) out[e] = 0.0f;
  fold(trend, 3, basis[0]);  // m = 2N + 1: the open curve's trend
}

// The folded coefficients of the last two curves a worker used. Blocks come sorted by pair, so
// runs like (a, a), (a, a+1), (a+1, a+1) fold each curve once per worker and frame.
struct FoldCache {
  alignas(64) float coefficients[2][kMaxCurveFloats];
  std::uint32_t curve[2] = {kPaddingLane, kPaddingLane};
  std::uint32_t last = 0;

  // The slot holding `curve`, folding it into the slot other than `keep` (-1: the least recent).
  std::uint32_t slot(const Layout& layout, const Frame& f, std::uint32_t c, int keep) {
    for (std::uint32_t s = 0; s < 2; ++s) {
      if (curve[s] == c) return last = s;
    }
    const std::uint32_t s = keep >= 0 ? 1u - static_cast<std::uint32_t>(keep) : 1u - last;
    foldCurve(layout, f, c, coefficients[s]);
    curve[s] = c;
    return last = s;
  }
};

// `trend`: either curve has a non-zero open-curve trend (closed curves have none).
template <std::uint32_t kL, bool kTwoCurves>
[[gnu::always_inline]] inline P3<kL> series(const float* lanes, const float* a, const float* b,
                                            std::uint32_t modes_used, std::uint32_t m_count, bool trend) {
  using V = Vf<kL>;
  const V c1 = load<kL>(lanes + rowOffset(kCos));
  const V s1 = load<kL>(lanes + rowOffset(kSin));
  V ax = splat<kL>(a[0]), ay = splat<kL>(a[1]), az = splat<kL>(a[2]);
  V ax_sin{}, ay_sin{}, az_sin{};
  V bx{}, by{}, bz{}, bx_sin{}, by_sin{}, bz_sin{};
  if constexpr (kTwoCurves) {
    bx = splat<kL>(b[0]);
    by = splat<kL>(b[1]);
    bz = splat<kL>(b[2]);
  }
  if (trend) {
    const V v = load<kL>(lanes + rowOffset(kV));
    const float* a_trend = a + 3 * static_cast<std::size_t>(m_count - 1);
    ax = v * splat<kL>(a_trend[0]) + ax;
    ay = v * splat<kL>(a_trend[1]) + ay;
    az = v * splat<kL>(a_trend[2]) + az;
    if constexpr (kTwoCurves) {
      const float* b_trend = b + 3 * static_cast<std::size_t>(m_count - 1);
      bx = v * splat<kL>(b_trend[0]) + bx;
      by = v * splat<kL>(b_trend[1]) + by;
      bz = v * splat<kL>(b_trend[2]) + bz;
    }
  }
  const V two_c1 = c1 + c1;
  V c_prev = splat<kL>(1.0f);
  V s_prev{};
  V cn = c1;
  V sn = s1;
  constexpr bool kSplit = !kTwoCurves || kMaxLanes == 16;
  for (std::uint32_t n = 1; n <= modes_used; ++n) {
    const float* an = a + 3 * (2 * static_cast<std::size_t>(n) - 1);  // cos xyz, then sin xyz
    if constexpr (kSplit) {
      ax = cn * splat<kL>(an[0]) + ax;
      ay = cn * splat<kL>(an[1]) + ay;
      az = cn * splat<kL>(an[2]) + az;
      ax_sin = sn * splat<kL>(an[3]) + ax_sin;
      ay_sin = sn * splat<kL>(an[4]) + ay_sin;
      az_sin = sn * splat<kL>(an[5]) + az_sin;
    } else {
      ax = sn * splat<kL>(an[3]) + (cn * splat<kL>(an[0]) + ax);
      ay = sn * splat<kL>(an[4]) + (cn * splat<kL>(an[1]) + ay);
      az = sn * splat<kL>(an[5]) + (cn * splat<kL>(an[2]) + az);
    }
    if constexpr (kTwoCurves) {
      const float* bn = b + 3 * (2 * static_cast<std::size_t>(n) - 1);
      if constexpr (kSplit) {
        bx = cn * splat<kL>(bn[0]) + bx;
        by = cn * splat<kL>(bn[1]) + by;
        bz = cn * splat<kL>(bn[2]) + bz;
        bx_sin = sn * splat<kL>(bn[3]) + bx_sin;
        by_sin = sn * splat<kL>(bn[4]) + by_sin;
        bz_sin = sn * splat<kL>(bn[5]) + bz_sin;
      } else {
        bx = sn * splat<kL>(bn[3]) + (cn * splat<kL>(bn[0]) + bx);
        by = sn * splat<kL>(bn[4]) + (cn * splat<kL>(bn[1]) + by);
        bz = sn * splat<kL>(bn[5]) + (cn * splat<kL>(bn[2]) + bz);
      }
    }
    const V c_next = two_c1 * cn - c_prev;
    const V s_next = two_c1 * sn - s_prev;
    c_prev = cn;
    s_prev = sn;
    cn = c_next;
    sn = s_next;
  }
  P3<kL> s{ax + ax_sin, ay + ay_sin, az + az_sin};
  if constexpr (kTwoCurves) {
    const V w = load<kL>(lanes + rowOffset(kW));
    s.x = w * ((bx + bx_sin) - s.x) + s.x;
    s.y = w * ((by + by_sin) - s.y) + s.y;
    s.z = w * ((bz + bz_sin) - s.z) + s.z;
  }
  return s;
}

// Linear blend skinning of the sub-block's points: sum over the block's union bones of w_u (M_u p).
// `offset`: the sub-block's first lane in the block.
template <std::uint32_t kL>
[[gnu::always_inline]] inline P3<kL> skinLinear(const Layout& layout, const Frame& f, const Block& block,
                                                std::uint32_t offset, const P3<kL>& p) {
  using V = Vf<kL>;
  P3<kL> o{V{}, V{}, V{}};
  for (std::uint32_t u = 0; u < block.union_count; ++u) {
    const std::uint32_t e = block.union_begin + u;
    const gpu::BoneMatrix& m = f.bones[layout.union_bones[e]];
    const V w = load<kL>(layout.union_weights.data() + static_cast<std::size_t>(e) * kBlockLanes + offset);
    o.x = w * (splat<kL>(m.row0.w) + p.x * splat<kL>(m.row0.x) + p.y * splat<kL>(m.row0.y) + p.z * splat<kL>(m.row0.z)) + o.x;
    o.y = w * (splat<kL>(m.row1.w) + p.x * splat<kL>(m.row1.x) + p.y * splat<kL>(m.row1.y) + p.z * splat<kL>(m.row1.z)) + o.y;
    o.z = w * (splat<kL>(m.row2.w) + p.x * splat<kL>(m.row2.x) + p.y * splat<kL>(m.row2.y) + p.z * splat<kL>(m.row2.z)) + o.z;
  }
  return o;
}

// Kavan et al. 2008, Algorithm 1, as skinPointDq in fourier_deform_fast_job.cpp: bones on the
// pivot's side of the real parts, blend, and x -> R x + t of the blend divided by |real|. R and t
// are quadratic in the blend, so dividing by |real|^2 once replaces the square root. A blend with
// |real| <= ODESKIN_DQS_MIN_BLEND_NORM (or NaN) takes the LBS result instead.
template <std::uint32_t kL>
[[gnu::always_inline]] inline P3<kL> skinDualQuaternion(const Layout& layout, const Frame& f, const Block& block,
                                                        std::size_t lane0, std::uint32_t offset, const P3<kL>& p) {
  using V = Vf<kL>;
  using VI = Vi<kL>;
  VI pivot;
  std::memcpy(&pivot, layout.pivots.data() + lane0, sizeof pivot);
  V px{}, py{}, pz{}, pw{};
  for (std::uint32_t u = 0; u < block.union_count; ++u) {
    const gpu::Float4& q = f.dual_quats[layout.union_bones[block.union_begin + u]].real;
    const VI is_pivot = pivot == (static_cast<std::int32_t>(u) - VI{});
    px = is_pivot ? splat<kL>(q.x) : px;
    py = is_pivot ? splat<kL>(q.y) : py;
    pz = is_pivot ? splat<kL>(q.z) : pz;
    pw = is_pivot ? splat<kL>(q.w) : pw;
  }
  V rx{}, ry{}, rz{}, rw{}, dx{}, dy{}, dz{}, dw{};
  for (std::uint32_t u = 0; u < block.union_count; ++u) {
    const std::uint32_t e = block.union_begin + u;
    const gpu::DualQuat& q = f.dual_quats[layout.union_bones[e]];
    V w = load<kL>(layout.union_weights.data() + static_cast<std::size_t>(e) * kBlockLanes + offset);
    const V dot = splat<kL>(q.real.x) * px + splat<kL>(q.real.y) * py + splat<kL>(q.real.z) * pz + splat<kL>(q.real.w) * pw;
    w = dot < 0.0f - V{} ? -w : w;
    rx = w * splat<kL>(q.real.x) + rx;
    ry = w * splat<kL>(q.real.y) + ry;
    rz = w * splat<kL>(q.real.z) + rz;
    rw = w * splat<kL>(q.real.w) + rw;
    dx = w * splat<kL>(q.dual.x) + dx;
    dy = w * splat<kL>(q.dual.y) + dy;
    dz = w * splat<kL>(q.dual.z) + dz;
    dw = w * splat<kL>(q.dual.w) + dw;
  }
  const V norm2 = rx * rx + ry * ry + rz * rz + rw * rw;
  constexpr float kMinNorm = static_cast<float>(ODESKIN_DQS_MIN_BLEND_NORM);
  const VI ok = norm2 > splat<kL>(kMinNorm * kMinNorm);
  const V s = splat<kL>(2.0f) / norm2;
  const V xx = rx * rx, yy = ry * ry, zz = rz * rz;
  const V xy = rx * ry, xz = rx * rz, yz = ry * rz;
  const V wx = rw * rx, wy = rw * ry, wz = rw * rz;
  // t = 2 (r_w e_v - e_w r_v + r_v x e_v) of the normalised blend.
  const V tx = s * (rw * dx - dw * rx + (ry * dz - rz * dy));
  const V ty = s * (rw * dy - dw * ry + (rz * dx - rx * dz));
  const V tz = s * (rw * dz - dw * rz + (rx * dy - ry * dx));
  const V one = splat<kL>(1.0f);
  P3<kL> o;
  o.x = (one - s * (yy + zz)) * p.x + s * (xy - wz) * p.y + s * (xz + wy) * p.z + tx;
  o.y = s * (xy + wz) * p.x + (one - s * (xx + zz)) * p.y + s * (yz - wx) * p.z + ty;
  o.z = s * (xz - wy) * p.x + s * (yz + wx) * p.y + (one - s * (xx + yy)) * p.z + tz;
  bool all_ok = true;
  for (std::uint32_t l = 0; l < kL; ++l) all_ok = all_ok && ok[l] != 0;
  if (!all_ok) {
    const P3<kL> lbs = skinLinear<kL>(layout, f, block, offset, p);
    o.x = ok ? o.x : lbs.x;
    o.y = ok ? o.y : lbs.y;
    o.z = ok ? o.z : lbs.z;
  }
  return o;
}

template <std::uint32_t kL, bool kDualQuaternion>
[[gnu::always_inline]] inline P3<kL> skin(const Layout& layout, const Frame& f, const Block& block, std::size_t lane0,
                                          std::uint32_t offset, const P3<kL>& p) {
  if constexpr (kDualQuaternion) {
    return skinDualQuaternion<kL>(layout, f, block, lane0, offset, p);
  } else {
    return skinLinear<kL>(layout, f, block, offset, p);
  }
}

// 4x4 transposes within each 128-bit group of lanes (SSE's unpcklps / unpckhps and movlhps /
// movhlps, per group): unpack interleaves two vectors' pairs, half joins their low or high halves.
constexpr int unpackIndex(int i, int high, int lanes) { return (i % 2 ? lanes : 0) + 4 * (i / 4) + (i % 4) / 2 + 2 * high; }
constexpr int halfIndex(int i, int high, int lanes) { return ((i % 4) / 2 ? lanes : 0) + 4 * (i / 4) + i % 2 + 2 * high; }

template <int kHigh, std::uint32_t kL, int... I>
[[gnu::always_inline]] inline Vf<kL> unpack(Vf<kL> a, Vf<kL> b, std::integer_sequence<int, I...>) {
  return __builtin_shufflevector(a, b, unpackIndex(I, kHigh, static_cast<int>(kL))...);
}
template <int kHigh, std::uint32_t kL, int... I>
[[gnu::always_inline]] inline Vf<kL> half(Vf<kL> a, Vf<kL> b, std::integer_sequence<int, I...>) {
  return __builtin_shufflevector(a, b, halfIndex(I, kHigh, static_cast<int>(kL))...);
}

template <int kQuad, std::uint32_t kL>
[[gnu::always_inline]] inline void storeQuad(Vf<kL> q, gpu::Float4* out) {
  const Vf<4> quad = __builtin_shufflevector(q, q, 4 * kQuad, 4 * kQuad + 1, 4 * kQuad + 2, 4 * kQuad + 3);
  std::memcpy(out, &quad, sizeof quad);
}

// Lane l = 4k + j of a sub-block is quadruple k of vector j; one 16-byte store per vertex.
template <std::uint32_t kL, int... L>
[[gnu::always_inline]] inline void storeQuads(const Vf<kL> (&q)[4], gpu::Float4* out, const std::uint32_t* perm,
                                              std::integer_sequence<int, L...>) {
  (storeQuad<L / 4, kL>(q[L % 4], out + perm[L]), ...);
}

// Writes the sub-block's `valid` lanes to their mesh vertices as (x, y, z, 1): transposed in
// registers to four vectors of (x, y, z, 1) quadruples, then one 16-byte store per vertex.
template <std::uint32_t kL>
[[gnu::always_inline]] inline void store(const Layout& layout, const Frame& f, std::size_t lane0,
                                         std::uint32_t valid, const P3<kL>& p) {
  using V = Vf<kL>;
  constexpr auto kIdx = std::make_integer_sequence<int, static_cast<int>(kL)>{};
  const V one = splat<kL>(1.0f);
  const V xy_low = unpack<0, kL>(p.x, p.y, kIdx), xy_high = unpack<1, kL>(p.x, p.y, kIdx);
  const V z1_low = unpack<0, kL>(p.z, one, kIdx), z1_high = unpack<1, kL>(p.z, one, kIdx);
  const V q[4] = {half<0, kL>(xy_low, z1_low, kIdx), half<1, kL>(xy_low, z1_low, kIdx),
                  half<0, kL>(xy_high, z1_high, kIdx), half<1, kL>(xy_high, z1_high, kIdx)};
  const std::uint32_t* perm = layout.perm.data() + lane0;
  if (valid == kL) {
    storeQuads<kL>(q, f.out_positions, perm, kIdx);
    return;
  }
  alignas(64) float quads[4][kL];
  std::memcpy(quads, q, sizeof quads);
  for (std::uint32_t l = 0; l < valid; ++l) {
    std::memcpy(f.out_positions + perm[l], &quads[l % 4][4 * (l / 4)], sizeof(gpu::Float4));
  }
}

// Runs sub.run<kL>(offset, valid) over the block's lanes: full-width vectors, and the last
// lanes at the tail width when they fit in it.
template <typename Sub>
[[gnu::always_inline]] inline void forEachSubBlock(const Block& block, const Sub& sub) {
  for (std::uint32_t offset = 0; offset < kBlockLanes; offset += kMaxLanes) {  // a constant trip count
    if (offset >= block.lanes) return;
    const std::uint32_t left = block.lanes - offset;
    if constexpr (kTailLanes < kMaxLanes) {
      if (left <= kTailLanes) {
        sub.template run<kTailLanes>(offset, left);
        return;
      }
    }
    sub.template run<kMaxLanes>(offset, left < kMaxLanes ? left : kMaxLanes);
  }
}

template <bool kTwoCurves, bool kDualQuaternion, bool kBindSpace>
struct DeformSub {
  const Layout& layout;
  const Frame& f;
  const Block& block;
  std::size_t b;
  const float* a;
  const float* c;
  std::uint32_t modes_used;
  bool trend;
  bool has_remainder;
  float remainder_weight;

  template <std::uint32_t kL>
  [[gnu::always_inline]] inline void run(std::uint32_t offset, std::uint32_t valid) const {
    using V = Vf<kL>;
    const std::size_t segment_block = static_cast<std::size_t>(f.segment) * layout.blockCount() + b;
    const std::size_t lane0 = b * kBlockLanes + offset;
    const float* lanes = layout.lane_rows.data() + b * kLaneRows * kBlockLanes + offset;
    const float* seg = layout.segment_rows.data() + segment_block * kSegmentRows * kBlockLanes + offset;
    P3<kL> r = series<kL, kTwoCurves>(lanes, a, c, modes_used, layout.coefficientsPerCurve(), trend);
    r.x += load<kL>(seg + rowOffset(kBaseX));
    r.y += load<kL>(seg + rowOffset(kBaseY));
    r.z += load<kL>(seg + rowOffset(kBaseZ));
    if (has_remainder) {
      const V g = splat<kL>(remainder_weight);
      r.x = g * load<kL>(seg + rowOffset(kRemX)) + r.x;
      r.y = g * load<kL>(seg + rowOffset(kRemY)) + r.y;
      r.z = g * load<kL>(seg + rowOffset(kRemZ)) + r.z;
    }
    const P3<kL> rest{load<kL>(lanes + rowOffset(kRestX)), load<kL>(lanes + rowOffset(kRestY)),
                      load<kL>(lanes + rowOffset(kRestZ))};
    P3<kL> out;
    if constexpr (kBindSpace) {
      out = skin<kL, kDualQuaternion>(layout, f, block, lane0, offset,
                                      P3<kL>{rest.x + r.x, rest.y + r.y, rest.z + r.z});
    } else {
      out = skin<kL, kDualQuaternion>(layout, f, block, lane0, offset, rest);
      out.x += r.x;
      out.y += r.y;
      out.z += r.z;
    }
    store<kL>(layout, f, lane0, valid, out);
  }
};

template <bool kTwoCurves, bool kDualQuaternion, bool kBindSpace>
[[gnu::always_inline]] inline void deformBlock(const Layout& layout, const Frame& f, std::size_t b, const float* a,
                                               const float* c, std::uint32_t modes_used, bool trend,
                                               float remainder_weight) {
  const Block& block = layout.blocks[b];
  const bool has_remainder =
      layout.has_remainder[static_cast<std::size_t>(f.segment) * layout.blockCount() + b] != 0;
  forEachSubBlock(block, DeformSub<kTwoCurves, kDualQuaternion, kBindSpace>{
                             layout, f, block, b, a, c, modes_used, trend, has_remainder, remainder_weight});
}

template <bool kDualQuaternion, bool kBindSpace>
void deformRangeOf(const Frame& f, std::size_t begin, std::size_t end) {
  const Layout& layout = *f.layout;
  const float remainder_weight = f.basis[static_cast<std::size_t>(layout.material_count) * (layout.modes + 1)].gamma;
  const std::uint32_t* curve_modes = layout.curve_modes.data() + static_cast<std::size_t>(f.segment) * layout.curve_count;
  const std::uint8_t* curve_trends = layout.curve_trends.data() + static_cast<std::size_t>(f.segment) * layout.curve_count;
  FoldCache cache;
  for (std::size_t b = begin; b < end; ++b) {
    const Block& block = layout.blocks[b];
    const std::uint32_t slot_a = cache.slot(layout, f, block.curve_a, -1);
    const float* a = cache.coefficients[slot_a];
    if (block.curve_b == block.curve_a) {
      deformBlock<false, kDualQuaternion, kBindSpace>(layout, f, b, a, a, curve_modes[block.curve_a],
                                                      curve_trends[block.curve_a] != 0, remainder_weight);
    } else {
      const float* c = cache.coefficients[cache.slot(layout, f, block.curve_b, static_cast<int>(slot_a))];
      const std::uint32_t used = curve_modes[block.curve_a] > curve_modes[block.curve_b] ? curve_modes[block.curve_a]
                                                                                        : curve_modes[block.curve_b];
      const bool trend = curve_trends[block.curve_a] != 0 || curve_trends[block.curve_b] != 0;
      deformBlock<true, kDualQuaternion, kBindSpace>(layout, f, b, a, c, used, trend, remainder_weight);
    }
  }
}

inline void deformRange(const Frame& f, std::size_t begin, std::size_t end) {
  const bool dq = f.layout->skinning == SkinningMode::kDualQuaternion;
  const bool bind = f.layout->residual_space == ResidualSpace::kBind;
  if (dq) {
    bind ? deformRangeOf<true, true>(f, begin, end) : deformRangeOf<true, false>(f, begin, end);
  } else {
    bind ? deformRangeOf<false, true>(f, begin, end) : deformRangeOf<false, false>(f, begin, end);
  }
}

template <bool kDualQuaternion>
struct SkinSub {
  const Layout& layout;
  const Frame& f;
  const Block& block;
  std::size_t b;

  template <std::uint32_t kL>
  [[gnu::always_inline]] inline void run(std::uint32_t offset, std::uint32_t valid) const {
    const std::size_t lane0 = b * kBlockLanes + offset;
    const float* lanes = layout.lane_rows.data() + b * kLaneRows * kBlockLanes + offset;
    const P3<kL> rest{load<kL>(lanes + rowOffset(kRestX)), load<kL>(lanes + rowOffset(kRestY)),
                      load<kL>(lanes + rowOffset(kRestZ))};
    store<kL>(layout, f, lane0, valid, skin<kL, kDualQuaternion>(layout, f, block, lane0, offset, rest));
  }
};

template <bool kDualQuaternion>
void skinRangeOf(const Frame& f, std::size_t begin, std::size_t end) {
  const Layout& layout = *f.layout;
  for (std::size_t b = begin; b < end; ++b) {
    forEachSubBlock(layout.blocks[b], SkinSub<kDualQuaternion>{layout, f, layout.blocks[b], b});
  }
}

inline void skinRange(const Frame& f, std::size_t begin, std::size_t end) {
  if (f.layout->skinning == SkinningMode::kDualQuaternion) {
    skinRangeOf<true>(f, begin, end);
  } else {
    skinRangeOf<false>(f, begin, end);
  }
}

inline BlockFunctions blockFunctions() { return BlockFunctions{&deformRange, &skinRange}; }

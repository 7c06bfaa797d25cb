// SPDX-License-Identifier: MIT
// simd_deform_blocks.hpp compiled once per instruction set, each copy in its own namespace (so no
// two copies can be merged by the linker) and, on x86-64, inside a target region, so the default
// build stays baseline x86-64 while CpuDeformKernel picks AVX2 or AVX-512 at run time. Only the
// functions defined inside a region get its instructions; the library functions they call (memcpy)
// are builtins, and nothing from the standard library is instantiated in a region (the blocks use
// std::integer_sequence, a type, only).
#include <cstdint>
#include <cstring>
#include <utility>

#include "simd_deform_layout.hpp"

namespace odeskin::simd_deform {

namespace generic {
namespace {
#define ODESKIN_SIMD_LANES 4
#include "simd_deform_blocks.hpp"
#undef ODESKIN_SIMD_LANES
}  // namespace
}  // namespace generic

BlockFunctions genericBlockFunctions() { return generic::blockFunctions(); }

#if ODESKIN_SIMD_X86

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,fma,bmi,bmi2,f16c,lzcnt,popcnt"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2,fma,bmi,bmi2,f16c,lzcnt,popcnt")
#endif
namespace avx2 {
namespace {
#define ODESKIN_SIMD_LANES 8
#include "simd_deform_blocks.hpp"
#undef ODESKIN_SIMD_LANES
}  // namespace
}  // namespace avx2
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

// x86-64-v4's AVX-512 subsets (F, CD, BW, DQ, VL).
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx512f,avx512cd,avx512bw,avx512dq,avx512vl,avx2,fma,bmi,bmi2,f16c,lzcnt,popcnt"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx512f,avx512cd,avx512bw,avx512dq,avx512vl,avx2,fma,bmi,bmi2,f16c,lzcnt,popcnt")
#endif
namespace avx512 {
namespace {
#define ODESKIN_SIMD_LANES 16
#include "simd_deform_blocks.hpp"
#undef ODESKIN_SIMD_LANES
}  // namespace
}  // namespace avx512
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

BlockFunctions avx2BlockFunctions() { return avx2::blockFunctions(); }
BlockFunctions avx512BlockFunctions() { return avx512::blockFunctions(); }

#endif  // ODESKIN_SIMD_X86

}  // namespace odeskin::simd_deform

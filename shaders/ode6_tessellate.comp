// SPDX-License-Identifier: MIT
// C2 surface patches of a network on the GPU (thesis ch. 4, Eqs 4.2 and 4.8; MATH.md 3):
//   S(u, v) = g1(u) c1(v) + g2(u) c2(v) + g3(u) c3(v) + g4(u) c4(v) + g5(u) c5(v) + g6(u) c6(v).
// Mirrors the CPU reference tessellation (engine/surfaces/tessellation.hpp, tessellation_cache.cpp)
// and its cardinal functions (engine/surfaces/ode6_cardinal.cpp) in float:
//  pass ODESKIN_TESSELLATE_PASS_CARDINALS (specialization constant kPass) evaluates g_1..g_6 at every
//    u sample of every cardinal set from the well-conditioned even/odd block bases of MATH.md 3.3-3.4 (power series, deflated and
//    overflow-free scaled hyperbolic/trigonometric functions, MATH.md 1.4), never from the thesis's
//    closed forms (Eqs 4.20-4.22), which cancel catastrophically in float (MATH.md 1.6);
//  pass ODESKIN_TESSELLATE_PASS_POSITIONS forms every vertex of the welded grid from its owning
//    patch's table row and the six boundary samples of its column, in the CPU's order of terms.
// Distances to the nearer end of [0, 1] come from integer sample indices, so thin boundary layers
// (exp(-p d), p up to 1e6) keep their relative accuracy in float.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "../engine/surfaces/tessellation_layout.h"

layout(local_size_x = ODESKIN_TESSELLATE_WORKGROUP_SIZE) in;
layout(constant_id = ODESKIN_TESSELLATE_PASS_CONSTANT_ID) const uint kPass = ODESKIN_TESSELLATE_PASS_CARDINALS;

layout(std430, set = 0, binding = ODESKIN_TESSELLATE_BINDING_CARDINALS) readonly buffer Cardinals { Ode6GpuCardinal cardinals[]; };
layout(std430, set = 0, binding = ODESKIN_TESSELLATE_BINDING_PATCH_CARDINALS) readonly buffer PatchCardinals { uint patch_cardinals[]; };
layout(std430, set = 0, binding = ODESKIN_TESSELLATE_BINDING_BOUNDARY_SAMPLES) readonly buffer BoundarySamples { vec4 boundary_samples[]; };
layout(std430, set = 0, binding = ODESKIN_TESSELLATE_BINDING_TABLE) buffer Table { float cardinal_table[]; };
layout(std430, set = 0, binding = ODESKIN_TESSELLATE_BINDING_OUT_POSITIONS) writeonly buffer OutPositions { vec4 out_positions[]; };

layout(push_constant) uniform Push { TessellatePushConstants pc; };

// sinh(y)/y; the series below |y| = 1, where exp(y) - exp(-y) would cancel in float.
float sinhc(float y) {
  if (abs(y) < 1.0) {
    float y2 = y * y;
    return 1.0 + y2 / 6.0 * (1.0 + y2 / 20.0 * (1.0 + y2 / 42.0 * (1.0 + y2 / 72.0 * (1.0 + y2 / 110.0))));
  }
  return (exp(y) - exp(-y)) / (2.0 * y);
}

// sin(z)/z likewise.
float sinc(float z) {
  if (abs(z) < 1.0) {
    float z2 = z * z;
    return 1.0 - z2 / 6.0 * (1.0 - z2 / 20.0 * (1.0 - z2 / 42.0 * (1.0 - z2 / 72.0 * (1.0 - z2 / 110.0))));
  }
  return sin(z) / z;
}

// -expm1(-y) = 1 - exp(-y) for y >= 0, without cancellation for small y.
float oneMinusExp(float y) {
  if (y < 0.5) {
    float e = 1.0;
    for (int k = 9; k >= 1; --k) e = 1.0 - y / float(k + 1) * e;
    return y * e;
  }
  return 1.0 - exp(-y);
}

// phis(w) = sum_k w^k / (2k+3)!, |w| < 1 (MATH.md 1.4).
float phis(float w) {
  float sum = 0.0;
  float term = 1.0 / 6.0;
  for (int k = 0; k < 8; ++k) {
    sum += term;
    term *= w / float((2 * k + 4) * (2 * k + 5));
  }
  return sum;
}

// Ch, Sh, Ct, St (MATH.md 1.3) at (x, t), divided by N(x) = cosh(sqrt(x)/2) for x > 0. `d` is
// 1/2 - |t|, the distance to the nearer end, given separately for its precision.
struct Scaled {
  float ch;
  float sh;
  float ct;
  float st;
};

Scaled scaledFunctions(float x, float t, float d) {
  Scaled s;
  float t2 = t * t;
  float a = abs(t);
  if (x > 0.0) {
    float p = sqrt(x);
    float den = 1.0 + exp(-p);
    float inv_n = 2.0 * exp(-0.5 * p) / den;
    float grow = exp(-p * d);
    s.ch = grow * (1.0 + exp(-2.0 * p * a)) / den;
    if (p * a < 1e-3) {
      s.sh = t * sinhc(p * a) * inv_n;
    } else {
      s.sh = sign(t) * grow * oneMinusExp(2.0 * p * a) / (den * p);
    }
    if (x * t2 >= 1.0) {
      s.ct = (s.ch - inv_n) / x;
      s.st = (s.sh - t * inv_n) / x;
    } else {
      float h = sinhc(0.5 * p * a);
      s.ct = 0.5 * t2 * h * h * inv_n;
      s.st = t * t2 * phis(x * t2) * inv_n;
    }
  } else if (x < 0.0) {
    float q = sqrt(-x);
    s.ch = cos(q * t);
    s.sh = t * sinc(q * t);
    if (-x * t2 >= 1.0) {
      s.ct = (s.ch - 1.0) / x;
      s.st = (s.sh - t) / x;
    } else {
      float h = sinc(0.5 * q * t);
      s.ct = 0.5 * t2 * h * h;
      s.st = t * t2 * phis(x * t2);
    }
  } else {
    s.ch = 1.0;
    s.sh = t;
    s.ct = 0.5 * t2;
    s.st = t * t2 / 6.0;
  }
  return s;
}

// Y_k(t) = sum_n a_n t^n / n! with a_k = 1 among a_0..a_5 and a_(n+6) = -b a_(n+4) - c a_(n+2).
float seriesY(int k, float t, float b, float c) {
  float a[6];
  for (int i = 0; i < 6; ++i) a[i] = i == k ? 1.0 : 0.0;
  float sum = 0.0;
  float term = 1.0;  // t^n / n!
  for (int n = 0; n < ODESKIN_ODE6_SERIES_TERMS; ++n) {
    float an;
    if (n < 6) {
      an = a[n];
    } else {
      an = -b * a[(n - 2) % 6] - c * a[(n - 4) % 6];
      a[n % 6] = an;
    }
    sum += an * term;
    term *= t / float(n + 1);
  }
  return sum;
}

// g_1..g_6 of cardinal set `set` at sample i of n (u = i / (n - 1)).
void cardinalValues(uint set, uint i, uint n, out float g[6]) {
  Ode6GpuCardinal card = cardinals[set];
  float t = (float(2u * i) - float(n - 1u)) / float(2u * (n - 1u));
  float d = float(min(i, n - 1u - i)) / float(n - 1u);
  float e[3];
  float o[3];
  e[0] = 1.0;
  o[0] = t;
  if (card.branch == ODESKIN_ODE6_SERIES) {
    e[1] = seriesY(2, t, card.b, card.c);
    e[2] = seriesY(4, t, card.b, card.c);
    o[1] = seriesY(3, t, card.b, card.c);
    o[2] = seriesY(5, t, card.b, card.c);
  } else {
    Scaled s1 = scaledFunctions(card.x1, t, d);
    Scaled s2 = scaledFunctions(card.x2, t, d);
    if (card.branch == ODESKIN_ODE6_REAL) {
      e[1] = s1.ct;
      e[2] = s2.ct;
      o[1] = s1.st;
      o[2] = s2.st;
    } else {
      e[1] = s1.ch * s2.ch;
      e[2] = s1.sh * s2.sh;
      o[1] = s1.sh * s2.ch;
      o[2] = s1.ch * s2.sh;
    }
  }
  float E[3];
  float O[3];
  for (int k = 0; k < 3; ++k) {
    E[k] = e[0] * card.even[k] + e[1] * card.even[3 + k] + e[2] * card.even[6 + k];
    O[k] = o[0] * card.odd[k] + o[1] * card.odd[3 + k] + o[2] * card.odd[6 + k];
  }
  // MATH.md 3.3.
  g[0] = 0.5 * (E[0] - O[0]);
  g[1] = 0.5 * (O[1] - E[1]);
  g[2] = 0.5 * (E[2] - O[2]);
  g[3] = 0.5 * (E[0] + O[0]);
  g[4] = 0.5 * (E[1] + O[1]);
  g[5] = 0.5 * (E[2] + O[2]);
}

void main() {
  uint item = pc.first_item + gl_GlobalInvocationID.x;
  if (item >= pc.item_count) return;
  if (kPass == ODESKIN_TESSELLATE_PASS_CARDINALS) {
    float g[6];
    cardinalValues(item / pc.u_samples, item % pc.u_samples, pc.u_samples, g);
    for (uint k = 0u; k < 6u; ++k) cardinal_table[6u * item + k] = g[k];
    return;
  }
  // Owner patch of grid vertex (gi, gj), as TessellationGrid::rowOwner / columnOwner.
  uint gi = item / pc.grid_columns;
  uint gj = item % pc.grid_columns;
  uint row = min(gi / (pc.u_samples - 1u), pc.rows - 1u);
  uint ui = gi - row * (pc.u_samples - 1u);
  uint column = min(gj / (pc.v_samples - 1u), pc.columns - 1u);
  uint set = patch_cardinals[row * pc.columns + column];
  uint base = 6u * (set * pc.u_samples + ui);
  uint lower = 3u * row * pc.grid_columns + gj;
  uint upper = 3u * ((row + 1u) % pc.boundary_count) * pc.grid_columns + gj;
  vec3 s = cardinal_table[base] * boundary_samples[lower].xyz;
  s += cardinal_table[base + 1u] * boundary_samples[lower + pc.grid_columns].xyz;
  s += cardinal_table[base + 2u] * boundary_samples[lower + 2u * pc.grid_columns].xyz;
  s += cardinal_table[base + 3u] * boundary_samples[upper].xyz;
  s += cardinal_table[base + 4u] * boundary_samples[upper + pc.grid_columns].xyz;
  s += cardinal_table[base + 5u] * boundary_samples[upper + 2u * pc.grid_columns].xyz;
  out_positions[item] = vec4(s, 1.0);
}

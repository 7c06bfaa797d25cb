// SPDX-License-Identifier: MIT
// Timings of the C2 surface patches (issue 7, points 3 and 4), verified before they are timed:
//  1. One patch at 100 x 100 and 1000 x 1000 samples, the CPU double-precision reference against the
//     compute shader (shaders/ode6_tessellate.comp), next to the thesis's 0.063 s for 100 x 100
//     (sec. 4.6). GPU results must match the CPU within 1e-5 of the box first.
//  2. Interactive editing: a 10 x 10 network (100 patches); after one change (a row's shape, a
//     boundary tangent, one patch's shape) NetworkTessellation::update() re-evaluates only the
//     patches the change affects. Each edit's mesh is checked bitwise against a full rebuild.
// Median of repeated runs; wall clock on this machine (shared CPU cores; the GPU may be lavapipe,
// a CPU implementation of Vulkan, which the summary says).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "engine/surfaces/tessellation.hpp"
#include "engine/surfaces/tessellation_cache.hpp"
#include "host/device.hpp"
#include "host/surface_tessellator.hpp"
#include "engine/offline/residual_fit.hpp"
#include "samples/main_guard.hpp"

namespace odeskin {
namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// A wavy open sheet of rows x columns patches; boundary derivatives by coefficients and by control
// curves (after), all rows (1, 3, 1), the thesis's Fig 4.1/4.3 shape.
NetworkDescription sheet(std::uint32_t rows, std::uint32_t columns, ContinuityPolicy continuity) {
  NetworkDescription d;
  d.columns = columns;
  d.continuity = continuity;
  const std::uint32_t points = 4 * columns + 1;
  auto curve = [&](double xi) {
    std::vector<Vec3> p;
    for (std::uint32_t k = 0; k < points; ++k) {
      const double s = static_cast<double>(k) / (points - 1);
      p.emplace_back(columns * s, xi, 0.3 * std::sin(6.0 * s + xi) * std::cos(0.7 * xi));
    }
    return p;
  };
  auto add = [&](std::vector<Vec3> p) {
    std::string name = "c";  // appended, not "c" + ...: GCC 12's -Wrestrict misfires on that
    name += std::to_string(d.curve_names.size());
    d.curve_names.push_back(name);
    d.curve_points.push_back(std::move(p));
    d.curve_closed.push_back(false);
    return static_cast<std::uint32_t>(d.curve_names.size() - 1);
  };
  for (std::uint32_t b = 0; b <= rows; ++b) {
    NetworkBoundary x;
    x.position = add(curve(b));
    if (b % 2 == 1 && b < rows) {
      x.source = DerivativeSource::kControlCurves;
      x.side = ControlSide::kAfter;
      x.u_lower = 0.25;
      x.u_upper = 0.5;
      x.control_lower = add(curve(b + 0.25));
      x.control_upper = add(curve(b + 0.5));
    } else {
      x.w_first = 0.05;
      x.w_second = 0.0;
    }
    d.boundaries.push_back(x);
  }
  d.shapes.assign(std::size_t{rows} * columns, Ode6Shape{1.0, 3.0, 1.0});
  return d;
}

bool sameMesh(const SurfaceMesh& a, const SurfaceMesh& b) {
  return a.positions.size() == b.positions.size() &&
         std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(Vec3)) == 0;
}

int onePatch(const vk::Device* device, int repeats) {
  Result<Network> network = Network::build(sheet(1, 1, ContinuityPolicy::kRefuse));
  if (!network.ok()) return std::fprintf(stderr, "%s\n", network.status().toString().c_str()), 1;
  std::printf("\n## One patch, (rho, eta, lambda) = (1, 3, 1)\n\n");
  std::printf("| samples | CPU mesh (double) | CPU re-evaluation | GPU dispatch + wait | GPU timestamps | GPU read back | parity |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (std::uint32_t n : {100u, 1000u}) {
    const TessellationResolution r{n, n};
    std::vector<double> cpu;
    Result<SurfaceMesh> reference = tessellateNetwork(*network, r);
    for (int i = 0; i < repeats; ++i) {
      const auto start = Clock::now();
      Result<SurfaceMesh> mesh = tessellateNetwork(*network, r);
      cpu.push_back(seconds(start));
      if (!mesh.ok()) return 1;
    }
    // The same work as the GPU's two passes: the cardinal table and the vertices, into existing memory.
    std::vector<double> cpu_update;
    Result<NetworkTessellation> cache = NetworkTessellation::create(*network, r);
    if (!cache.ok()) return 1;
    for (int i = 0; i < repeats; ++i) {
      if (!cache->setRowShape(0, {1.0, 3.0 + 0.01 * (i % 2), 1.0}).ok()) return 1;
      const auto start = Clock::now();
      cache->update();
      cpu_update.push_back(seconds(start));
    }
    std::string gpu_wall = "-", gpu_time = "-", gpu_read = "-", parity = "no device";
    if (device) {
      Result<SurfaceTessellator> gpu = SurfaceTessellator::create(*device, *network, r);
      if (!gpu.ok()) return std::fprintf(stderr, "%s\n", gpu.status().toString().c_str()), 1;
      std::vector<gpu::Float4> out(gpu->grid().vertexCount());
      // Verify, then time.
      if (!gpu->run().ok() || !gpu->readPositions(out).ok()) return 1;
      double worst = 0.0;
      for (std::size_t i = 0; i < out.size(); ++i) {
        worst = std::max(worst, glm::length(Vec3(out[i].x, out[i].y, out[i].z) - reference->positions[i]));
      }
      worst /= longestBoxSide(reference->positions);
      if (worst > 1e-5) return std::fprintf(stderr, "GPU parity %.3g exceeds 1e-5\n", worst), 1;
      std::vector<double> wall, stamps, read;
      for (int i = 0; i < repeats; ++i) {
        auto start = Clock::now();
        if (!gpu->run().ok()) return 1;
        wall.push_back(seconds(start));
        stamps.push_back(gpu->lastGpuSeconds());
        start = Clock::now();
        if (!gpu->readPositions(out).ok()) return 1;
        read.push_back(seconds(start));
      }
      char text[64];
      std::snprintf(text, sizeof text, "%.2f ms", 1e3 * median(wall));
      gpu_wall = text;
      std::snprintf(text, sizeof text, "%.2f ms", 1e3 * median(stamps));
      gpu_time = text;
      std::snprintf(text, sizeof text, "%.2f ms", 1e3 * median(read));
      gpu_read = text;
      std::snprintf(text, sizeof text, "%.1e", worst);
      parity = text;
    }
    std::printf("| %u x %u | %.2f ms | %.2f ms | %s | %s | %s | %s |\n", n, n, 1e3 * median(cpu), 1e3 * median(cpu_update),
                gpu_wall.c_str(), gpu_time.c_str(), gpu_read.c_str(), parity.c_str());
  }
  std::printf("\nThesis (sec. 4.6): 0.063 s for 100 x 100. CPU mesh: tessellateNetwork (cardinal table, boundary\n"
              "samples, vertices and quads, allocated). CPU re-evaluation: the table and vertices again after a\n"
              "shape change, one thread for one patch (the GPU's work). GPU: both passes in one submission.\n");
  return 0;
}

struct Edit {
  const char* what;
  std::function<Status(NetworkTessellation&, int)> apply;
  ContinuityPolicy policy;
};

int hundredPatches(int repeats, std::uint32_t samples) {
  std::printf("\n## Editing a 10 x 10 network (100 patches), %u x %u samples per patch\n\n", samples, samples);
  const TessellationResolution r{samples, samples};
  const std::vector<Edit> edits = {
      {"eta of row 4 (a chain of 10 v-adjacent patches)",
       [](NetworkTessellation& t, int i) { return t.setRowShape(4, {1.0, 3.0 + 0.01 * (i % 7 + 1), 1.0}); },
       ContinuityPolicy::kRefuse},
      {"tangent coefficient of boundary 4 (rows 3 and 4)",
       [](NetworkTessellation& t, int i) {
         NetworkBoundary b = t.network().description().boundaries[4];
         b.w_first = 0.05 + 0.01 * (i % 7 + 1);
         return t.setBoundary(4, b);
       },
       ContinuityPolicy::kRefuse},
      {"control-curve position of boundary 5 (rows 4 and 5)",
       [](NetworkTessellation& t, int i) {
         NetworkBoundary b = t.network().description().boundaries[5];
         b.u_upper = 0.5 + 0.01 * (i % 7 + 1);
         return t.setBoundary(5, b);
       },
       ContinuityPolicy::kRefuse},
      {"eta of patch (4, 4) alone (network with \"continuity\": \"warn\")",
       [](NetworkTessellation& t, int i) { return t.setPatchShape(4, 4, {1.0, 3.0 + 0.01 * (i % 7 + 1), 1.0}); },
       ContinuityPolicy::kWarn},
  };
  Result<Network> base = Network::build(sheet(10, 10, ContinuityPolicy::kRefuse));
  if (!base.ok()) return 1;
  std::vector<double> full;
  for (int i = 0; i < repeats; ++i) {
    const auto start = Clock::now();
    Result<SurfaceMesh> mesh = tessellateNetwork(*base, r);
    full.push_back(seconds(start));
    if (!mesh.ok()) return 1;
  }
  std::printf("full tessellation of all 100 patches: %.2f ms (%zu vertices)\n\n", 1e3 * median(full),
              tessellateNetwork(*base, r)->positions.size());
  std::printf("| one change | patches re-evaluated | update() | equals a rebuild |\n|---|---|---|---|\n");
  for (const Edit& edit : edits) {
    Result<Network> network = Network::build(sheet(10, 10, edit.policy));
    Result<NetworkTessellation> t = NetworkTessellation::create(std::move(network).value(), r);
    if (!t.ok()) return 1;
    std::vector<double> times;
    std::uint32_t patches = 0;
    bool same = true;
    for (int i = 0; i < repeats; ++i) {
      if (Status s = edit.apply(*t, i); !s.ok()) return std::fprintf(stderr, "%s\n", s.toString().c_str()), 1;
      const auto start = Clock::now();
      patches = t->update();
      times.push_back(seconds(start));
      if (i < 3) same = same && sameMesh(t->mesh(), *tessellateNetwork(t->network(), r));
    }
    if (!same) return std::fprintf(stderr, "%s: the edited mesh differs from a rebuild\n", edit.what), 1;
    std::printf("| %s | %u | %.2f ms | bitwise |\n", edit.what, patches, 1e3 * median(times));
  }
  return 0;
}

}  // namespace
}  // namespace odeskin

static int run(int argc, char** argv) {
  bool quick = false;
  CLI::App app("odeskin_surface_tessellation_bench: C2 patch tessellation, CPU against Vulkan (docs/surfaces.md)");
  app.add_flag("--quick", quick, "Median of 3 runs instead of 21");
  CLI11_PARSE(app, argc, argv);
  const int repeats = quick ? 3 : 21;
  std::printf("# odeskin C2 surface patches: tessellation timings (%s build)\n\n", ODESKIN_BUILD_TYPE);
  std::printf("CPU: %u hardware threads; median of %d runs.\n", std::thread::hardware_concurrency(), repeats);
  odeskin::Result<odeskin::vk::Gpu> gpu = odeskin::vk::Gpu::open("auto", false);
  if (gpu.ok()) {
    const VkPhysicalDeviceType type = gpu->device.properties().deviceType;
    std::printf("GPU: %s (%s%s)\n", gpu->device.name(), odeskin::vk::deviceTypeName(type),
                type == VK_PHYSICAL_DEVICE_TYPE_CPU ? ": lavapipe, Vulkan run on the same CPU cores" : "");
  } else {
    std::printf("GPU: none (%s)\n", gpu.status().toString().c_str());
  }
  if (int rc = odeskin::onePatch(gpu.ok() ? &gpu->device : nullptr, repeats); rc != 0) return rc;
  for (std::uint32_t samples : {33u, 100u}) {
    if (int rc = odeskin::hundredPatches(repeats, samples); rc != 0) return rc;
  }
  return 0;
}

int main(int argc, char** argv) { return odeskin::runGuarded("odeskin_surface_tessellation_bench", run, argc, argv); }

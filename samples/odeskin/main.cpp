// SPDX-License-Identifier: MIT
// The odeskin command line. Exit status: 0 success; 1 bad input or runtime failure, with one line
// "odeskin: error: ..." on stderr; 2 usage error.
#include <cstdio>
#include <iostream>
#include <map>

#include <CLI/CLI.hpp>

#include "demo.hpp"
#include "host/device_info.hpp"

namespace {

constexpr double kDemoEndTolerance = 1e-5;  // frame 0 / last frame vs start.obj / end.obj, of the box

int fail(const odeskin::Status& status) {
  std::cerr << "odeskin: error: " << status.message() << "\n";
  return 1;
}

int runDemoCommand(const odeskin::DemoOptions& options) {
  odeskin::Result<odeskin::DemoResult> result = odeskin::runDemo(options, std::cout);
  if (!result.ok()) return fail(result.status());
  const odeskin::DemoResult& r = *result;
  std::printf("frames: %zu written to %s\n", r.frames.size(), options.output_dir.string().c_str());
  std::printf("per-frame time: %.3f ms wall", 1e3 * r.mean_frame_seconds);
  if (r.mean_gpu_seconds > 0.0) std::printf(", %.3f ms GPU (timestamp queries)", 1e3 * r.mean_gpu_seconds);
  std::printf("\ncheck: frame 0 vs start.obj %.2e, last frame vs end.obj %.2e (of the box, limit %.0e)\n",
              r.first_frame_error, r.last_frame_error, kDemoEndTolerance);
  if (r.first_frame_error > kDemoEndTolerance || r.last_frame_error > kDemoEndTolerance) {
    return fail(odeskin::internalError("the played frames do not reproduce the example poses"));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"odeskin: analytic physics-based skin deformation (Bian 2018) on CPU and Vulkan compute"};
  app.require_subcommand(1);
  std::string device = "auto";
  app.add_option("--device", device, "Vulkan device: auto, an index or a name substring (env ODESKIN_DEVICE)");

  CLI::App* info = app.add_subcommand("info", "List Vulkan devices and the limits that matter");

  odeskin::DemoOptions demo;
  std::string backend = "auto";
  std::string residual = "bind";
  CLI::App* demo_cmd = app.add_subcommand("demo", "Fit the procedural arm's two poses and play the in-betweens");
  demo_cmd->add_option("-o,--output", demo.output_dir, "Output folder for start.obj, end.obj, frame_NNNN.obj");
  demo_cmd->add_option("--frames", demo.frames, "Frames from t = 0 to t = 1")->check(CLI::Range(2, 100000));
  demo_cmd->add_option("--backend", backend, "cpu, vulkan or auto")->check(CLI::IsMember({"auto", "cpu", "vulkan"}));
  demo_cmd->add_option("--modes", demo.modes, "Fourier modes N per curve")->check(CLI::Range(1, 15));
  demo_cmd->add_option("--material", demo.material, "skin (dynamic) or static")->check(CLI::IsMember({"skin", "static"}));
  demo_cmd->add_option("--residual", residual, "bind (rotation-aware) or posed (the thesis's)")
      ->check(CLI::IsMember({"bind", "posed"}));
  demo_cmd->add_option("--threads", demo.threads, "CPU threads (0 = all)");
  demo_cmd->add_flag("--validation", demo.validation, "Enable the Khronos validation layer; fail on any message");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }

  if (info->parsed()) {
    odeskin::Status status = odeskin::vk::printDeviceInfo(std::cout, device);
    return status.ok() ? 0 : fail(status);
  }
  if (demo_cmd->parsed()) {
    static const std::map<std::string, odeskin::Backend> kBackends{
        {"auto", odeskin::Backend::kAuto}, {"cpu", odeskin::Backend::kCpu}, {"vulkan", odeskin::Backend::kVulkan}};
    demo.backend = kBackends.at(backend);
    demo.device = device;
    demo.residual_space = residual == "posed" ? odeskin::ResidualSpace::kPosed : odeskin::ResidualSpace::kBind;
    return runDemoCommand(demo);
  }
  return 2;
}

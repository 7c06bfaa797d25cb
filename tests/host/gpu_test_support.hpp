// SPDX-License-Identifier: MIT
// Fixture for GPU tests: validation layer on whenever installed, any warning or error it reports
// fails the test (checked after the device and instance are destroyed, so teardown counts too);
// GTEST_SKIP without a Vulkan device unless ODESKIN_REQUIRE_GPU=1 (CI), which turns that into a failure.
#pragma once

#include <array>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "host/device.hpp"
#include "host/instance.hpp"

namespace odeskin::testing {

// Lavapipe gaps met by these tests, one entry per missing feature (kompute keeps such a list). None
// so far: lavapipe runs every test here.
inline constexpr std::array<const char*, 0> kLavapipeGaps{};

inline bool gpuRequired() {
  const char* value = std::getenv("ODESKIN_REQUIRE_GPU");
  return value != nullptr && std::strcmp(value, "1") == 0;
}

class GpuTest : public ::testing::Test {
 protected:
  // Whether the instance asks for the validation layer (the environment's ODESKIN_VALIDATION=1
  // turns it on regardless).
  virtual bool wantsValidation() const { return vk::Instance::validationLayerInstalled(); }

  void SetUp() override {
    vk::InstanceOptions options;
    options.validation = wantsValidation();
    options.debug_log = &log_;
    Result<vk::Instance> instance = vk::Instance::create(options);
    if (!instance.ok()) return noDevice(instance.status());
    instance_.emplace(std::move(instance).value());
    Result<vk::Device> device = vk::Device::create(*instance_, "auto");
    if (!device.ok()) return noDevice(device.status());
    device_.emplace(std::move(device).value());
  }

  void TearDown() override {
    // Without a device the loader's own complaints ("Found no drivers!") were already reported by
    // noDevice(); they are not validation failures.
    if (!device_) return;
    device_.reset();
    instance_.reset();
    for (const std::string& message : log_.messages()) ADD_FAILURE() << "Vulkan validation: " << message;
  }

  vk::Instance& instance() { return *instance_; }
  vk::Device& device() { return *device_; }

  vk::DebugLog log_;  // outlives the instance, so messages from its destruction are seen
  std::optional<vk::Instance> instance_;
  std::optional<vk::Device> device_;

 private:
  void noDevice(const Status& status) {
    std::string loader;
    for (const std::string& message : log_.messages()) loader += "\n  loader: " + message;
    if (gpuRequired()) {
      FAIL() << "ODESKIN_REQUIRE_GPU=1 but no Vulkan device: " << status.toString() << loader;
    } else {
      GTEST_SKIP() << "no Vulkan device: " << status.toString();
    }
  }
};

}  // namespace odeskin::testing

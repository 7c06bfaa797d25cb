// SPDX-License-Identifier: MIT
// The CPU reference of the renderer's colours (render_shading.h, also compiled into the shaders):
// the heat colour map runs from blue to red with the hue falling monotonically, and lighting
// never clips, so a lit heat colour keeps its hue.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "engine/visual/render_shading.hpp"
#include "render_colour.hpp"

namespace odeskin::visual {
namespace {

using shader::heatColour;
using shader::shadeColour;
using shader::shadeIntensity;

TEST(RenderShading, HeatHueFallsMonotonicallyFromBlueToRed) {
  double previous = hueDegrees(heatColour(0.0f));
  EXPECT_NEAR(previous, 227.0, 2.0);
  for (int i = 1; i <= 1000; ++i) {
    const double hue = hueDegrees(heatColour(static_cast<float>(i) / 1000.0f));
    EXPECT_LT(hue, previous + 1e-9) << "s = " << i / 1000.0;
    previous = hue;
  }
  EXPECT_NEAR(previous, 2.0, 2.0);
  // Outside [0, 1] the map clamps.
  EXPECT_EQ(heatColour(-3.0f), heatColour(0.0f));
  EXPECT_EQ(heatColour(7.0f), heatColour(1.0f));
  // The stops are hit exactly.
  EXPECT_EQ(heatColour(0.5f), glm::vec3(0.40f, 0.80f, 0.36f));
}

TEST(RenderShading, LightingStaysBelowOneAndAboveAmbient) {
  std::mt19937 rng(3);
  std::normal_distribution<float> g;
  float brightest = 0.0f;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 n = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    const float intensity = shadeIntensity(n);
    EXPECT_LE(intensity, 1.0f);
    EXPECT_GE(intensity, ODESKIN_AMBIENT * 0.6f - 1e-6f);
    brightest = std::max(brightest, intensity);
  }
  EXPECT_GT(brightest, 0.85f);  // the key light really lights
  // A lit heat colour is the heat colour scaled: same hue.
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.4f, 0.8f));
  for (float s : {0.1f, 0.45f, 0.8f}) {
    EXPECT_NEAR(hueDegrees(shadeColour(n, heatColour(s))), hueDegrees(heatColour(s)), 1e-3);
  }
}

TEST(RenderShading, FacesTowardTheKeyLightAreBrighter) {
  const glm::vec3 key = glm::normalize(glm::vec3(ODESKIN_KEY_LIGHT_X, ODESKIN_KEY_LIGHT_Y, ODESKIN_KEY_LIGHT_Z));
  EXPECT_GT(shadeIntensity(key), shadeIntensity(glm::vec3(0, 0, 1)));
  EXPECT_GT(shadeIntensity(glm::vec3(0, 0, 1)), shadeIntensity(glm::vec3(0, 0, -1)));
  EXPECT_EQ(shader::surfaceColour(ODESKIN_SHADE_BASE, glm::vec3(0.2f), 5.0f, 1.0f), glm::vec3(0.2f));
  EXPECT_EQ(shader::surfaceColour(ODESKIN_SHADE_HEAT, glm::vec3(0.2f), 0.25f, 0.5f), heatColour(0.5f));
}

}  // namespace
}  // namespace odeskin::visual

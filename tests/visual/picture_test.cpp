// SPDX-License-Identifier: MIT
// Putting pictures together on the CPU: compositing over the background, resizing, contact sheets,
// labels, the colour bar against the colour map, the layout of panels, and PNG files that decode
// back to the same pixels and are never left half-written.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC  // private to this test: no clash with tinygltf's copy
#include <stb/stb_image.h>

#include "engine/visual/colour_bar.hpp"
#include "engine/visual/compose.hpp"
#include "engine/visual/picture_layout.hpp"
#include "engine/visual/png_writer.hpp"
#include "engine/visual/render_shading.hpp"
#include "engine/visual/text.hpp"
#include "render_colour.hpp"
#include "engine/temp_dir_test.hpp"

namespace odeskin::visual {
namespace {

constexpr Rgba8 kWhite{255, 255, 255, 255};
constexpr Rgba8 kInk{10, 20, 30, 255};

std::size_t countColour(const Image& image, Rgba8 colour) {
  return static_cast<std::size_t>(std::count(image.pixels.begin(), image.pixels.end(), colour));
}

TEST(Compose, OverBackgroundTreatsPixelsAsPremultiplied) {
  Image src(3, 1);
  src.at(0, 0) = {0, 0, 0, 0};          // nothing drawn
  src.at(1, 0) = {200, 100, 50, 255};   // fully covered
  src.at(2, 0) = {100, 50, 25, 128};    // half covered: already scaled by coverage
  const Image out = overBackground(src, {40, 80, 120, 255});
  EXPECT_EQ(out.at(0, 0), (Rgba8{40, 80, 120, 255}));
  EXPECT_EQ(out.at(1, 0), (Rgba8{200, 100, 50, 255}));
  EXPECT_EQ(out.at(2, 0), (Rgba8{120, 90, 85, 255}));  // 100 + 127/255 * 40 = 119.9 ...
}

TEST(Compose, BlitClipsAndResizeAverages) {
  Image dst(4, 4, kWhite);
  Image src(3, 3, kInk);
  blit(dst, src, 2, -1);  // only the 2 x 2 overlap lands
  EXPECT_EQ(countColour(dst, kInk), 4u);
  EXPECT_EQ(dst.at(3, 0), kInk);
  EXPECT_EQ(dst.at(1, 0), kWhite);

  Image checker(4, 2);
  for (std::uint32_t y = 0; y < 2; ++y) {
    for (std::uint32_t x = 0; x < 4; ++x) checker.at(x, y) = (x + y) % 2 ? Rgba8{200, 0, 0, 255} : Rgba8{0, 0, 100, 255};
  }
  const Image half = resize(checker, 2, 1);
  EXPECT_EQ(half.at(0, 0), (Rgba8{100, 0, 50, 255}));
  EXPECT_EQ(half.at(1, 0), (Rgba8{100, 0, 50, 255}));
  const Image big = resize(checker, 8, 4);  // enlarging picks the nearest source pixel
  EXPECT_EQ(big.at(0, 0), checker.at(0, 0));
  EXPECT_EQ(big.at(7, 3), checker.at(3, 1));
}

TEST(Compose, ContactSheetTilesFramesInBalancedRows) {
  EXPECT_EQ(balancedColumns(8, 6), 4u);
  EXPECT_EQ(balancedColumns(9, 6), 5u);
  EXPECT_EQ(balancedColumns(3, 6), 3u);
  std::vector<Image> frames;
  for (std::uint8_t i = 0; i < 5; ++i) frames.emplace_back(40, 20, Rgba8{static_cast<std::uint8_t>(40 * i), 0, 0, 255});
  const Image sheet = contactSheet(frames, 3, 20, 2, kWhite);
  EXPECT_EQ(sheet.width, 2u + 3 * (20 + 2));
  EXPECT_EQ(sheet.height, 2u + 2 * (10 + 2));
  EXPECT_EQ(sheet.at(2, 2), frames[0].pixels[0]);
  EXPECT_EQ(sheet.at(2 + 22, 2), frames[1].pixels[0]);
  EXPECT_EQ(sheet.at(2, 2 + 12), frames[3].pixels[0]);
  EXPECT_EQ(sheet.at(sheet.width - 3, sheet.height - 3), kWhite);  // the sixth cell is empty
  const std::vector<std::string> captions{"a", "b", "c", "d", "e"};
  EXPECT_GT(contactSheet(frames, 3, 20, 2, kWhite, captions).height, sheet.height);
}

TEST(Text, DrawsInsideItsBoxAndDistinguishesCharacters) {
  for (const std::string text : {"0", "0.25", "1e-05", "error", "% of box"}) {
    Image image(200, 40, kWhite);
    const TextSize size = textSize(text, 2);
    drawText(image, 10, 10, text, kInk, 2);
    std::size_t inked = 0;
    for (std::uint32_t y = 0; y < image.height; ++y) {
      for (std::uint32_t x = 0; x < image.width; ++x) {
        if (image.at(x, y) != kInk) continue;
        ++inked;
        EXPECT_GE(x, 10u) << text;
        EXPECT_LT(x, 10u + size.width) << text;
        EXPECT_GE(y, 10u) << text;
        EXPECT_LT(y, 10u + size.height + 6u) << text;  // descenders (e.g. 'g') reach below
      }
    }
    EXPECT_GT(inked, 8u * text.size()) << text;
  }
  Image a(60, 30, kWhite);
  Image b(60, 30, kWhite);
  drawText(a, 2, 2, "1", kInk, 2);
  drawText(b, 2, 2, "7", kInk, 2);
  EXPECT_NE(a.pixels, b.pixels);
}

TEST(ColourBar, TicksAreRound) {
  EXPECT_EQ(niceTicks(10.0, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(niceTicks(14.6, 5), (std::vector<double>{0, 5, 10}));
  EXPECT_EQ(niceTicks(1.0, 4), (std::vector<double>{0, 0.25, 0.5, 0.75, 1.0}));
  EXPECT_TRUE(niceTicks(0.0, 5).empty());
  EXPECT_TRUE(niceTicks(std::nan(""), 5).empty());
  EXPECT_EQ(tickLabel(0.25, 0.25), "0.25");
  EXPECT_EQ(tickLabel(10.0, 5.0), "10");
  EXPECT_EQ(tickLabel(0.0, 5.0), "0");
  EXPECT_EQ(tickLabel(2e-5, 1e-5), "2e-05");
}

TEST(ColourBar, RowsFollowTheColourMapFromBottomToTop) {
  Image image(200, 300, kWhite);
  ColourBarStyle style;
  const std::int64_t top = 60;
  const std::int64_t bottom = 260;
  drawColourBar(image, 10, top, bottom, 0.04, style);
  const std::uint32_t x = static_cast<std::uint32_t>(10 + 2 * style.text_scale + style.bar_width / 2);
  for (std::int64_t r = top; r < bottom; ++r) {
    const float s = static_cast<float>((double(bottom - r) - 0.5) / double(bottom - top));
    EXPECT_EQ(image.at(x, static_cast<std::uint32_t>(r)), toRgba8(shader::heatColour(s))) << "row " << r;
  }
  // Blue at the bottom, red at the top, labels drawn in ink beside it.
  EXPECT_GT(hueDegrees(image.at(x, bottom - 1)), 200.0);
  EXPECT_LT(hueDegrees(image.at(x, top)), 10.0);
  EXPECT_GT(countColour(image, style.ink), 200u);
  EXPECT_LE(colourBarWidth(0.04, style), 200);
}

TEST(PictureLayout, FillsTheRequestedSize) {
  PictureSpec spec;
  spec.width = 1000;
  spec.height = 300;
  spec.panels = 3;
  spec.label_lines = 2;
  spec.heat_max = 0.05;
  Result<PictureLayout> layout = layoutPicture(spec);
  ASSERT_TRUE(layout.ok()) << layout.status().toString();
  EXPECT_EQ(layout->width, 1000u);
  EXPECT_EQ(layout->height, 300u);
  ASSERT_EQ(layout->panel_left.size(), 3u);
  EXPECT_LE(layout->panel_left.back() + layout->panel_width, layout->bar_left);
  EXPECT_LT(layout->panel_height, 300u);  // room for the labels
  EXPECT_LT(layout->bar_top, layout->bar_bottom);

  std::vector<Image> panels(3, Image(layout->panel_width, layout->panel_height, Rgba8{0, 0, 0, 0}));
  panels[1] = Image(layout->panel_width, layout->panel_height, Rgba8{200, 10, 10, 255});
  const std::vector<std::vector<std::string>> labels{{"a"}, {"b", "c"}, {}};
  const Image picture = composePicture(*layout, panels, labels, kWhite, kInk);
  EXPECT_EQ(picture.width, 1000u);
  EXPECT_EQ(picture.height, 300u);
  EXPECT_EQ(picture.at(static_cast<std::uint32_t>(layout->panel_left[1] + 5), 5), (Rgba8{200, 10, 10, 255}));
  EXPECT_EQ(picture.at(static_cast<std::uint32_t>(layout->panel_left[0] + 5), 5), kWhite);

  spec.width = 0;  // 720 per panel plus the bar
  spec.heat_max.reset();
  EXPECT_EQ(layoutPicture(spec)->width, 3u * 720u);
  spec.width = 40;  // 13 pixels a panel
  Result<PictureLayout> small = layoutPicture(spec);
  EXPECT_EQ(small.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(small.status().message().find("at least 16 x 16"), std::string::npos) << small.status().message();
  // A picture wider than a PNG may be is refused here, before any panel is drawn.
  spec.width = 0;
  spec.panels = 300;
  Result<PictureLayout> wide = layoutPicture(spec);
  EXPECT_EQ(wide.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(wide.status().message(), "picture: 300 panel(s) make it 216000 x 300 pixels, over the 32768 a side a PNG may "
                                     "have here; give a smaller size or fewer panels");
  spec.panels = 45;  // 32,400 pixels: fits
  EXPECT_TRUE(layoutPicture(spec).ok());
}

class Png : public testing::TempDirTest {
 protected:
  Png() : TempDirTest("odeskin_png_test_") {}
};

TEST_F(Png, DecodesToTheSamePixels) {
  Image image(37, 23);
  for (std::uint32_t y = 0; y < image.height; ++y) {
    for (std::uint32_t x = 0; x < image.width; ++x) {
      image.at(x, y) = {static_cast<std::uint8_t>(7 * x), static_cast<std::uint8_t>(11 * y),
                        static_cast<std::uint8_t>(x * y), static_cast<std::uint8_t>(255 - x)};
    }
  }
  const std::filesystem::path path = dir_ / "p.png";
  ASSERT_TRUE(writePng(path, image).ok());
  int w = 0, h = 0, channels = 0;
  unsigned char* decoded = stbi_load(path.string().c_str(), &w, &h, &channels, 4);
  ASSERT_NE(decoded, nullptr);
  EXPECT_EQ(w, 37);
  EXPECT_EQ(h, 23);
  EXPECT_EQ(std::memcmp(decoded, image.pixels.data(), image.pixels.size() * 4), 0);
  stbi_image_free(decoded);
  // Only the picture is left in the folder: the temporary was renamed into place.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir_), std::filesystem::directory_iterator{}), 1);
}

TEST_F(Png, FailuresNameThePathAndLeaveNothing) {
  EXPECT_EQ(encodePng(Image{}).status().code(), StatusCode::kInvalidArgument);
  const Status missing = writePng(dir_ / "no" / "such" / "folder" / "p.png", Image(2, 2));
  EXPECT_EQ(missing.code(), StatusCode::kIoError);
  EXPECT_NE(missing.message().find("p.png"), std::string::npos) << missing.message();
  const Status empty = writePng(dir_ / "e.png", Image{});
  EXPECT_EQ(empty.code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

}  // namespace
}  // namespace odeskin::visual

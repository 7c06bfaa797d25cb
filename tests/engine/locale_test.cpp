// SPDX-License-Identifier: MIT
// Files odeskin writes do not follow the C locale: an application embedding the engine may set a
// German LC_NUMERIC, under which snprintf("%.9g") wrote OBJ vertices as "v 1,5 -2,25 0", which no
// reader (odeskin's included) takes. The locale is compiled from Debian's `locales` sources into a
// scratch folder (scripts/install-deps.sh installs the package), so the test needs no system locale.
#include <clocale>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/number_text.hpp"
#include "engine/io/libigl_writer.hpp"
#include "engine/io/obj_io.hpp"
#include "engine/io/obj_reader.hpp"
#include "scratch_dir.hpp"  // tests/

namespace odeskin {
namespace {

namespace fs = std::filesystem;

std::string contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

class GermanNumbers : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = odeskin::testing::scratchDir("locale");
    fs::create_directories(dir_ / "locales");
    const std::string command =
        "localedef -i de_DE -f UTF-8 '" + (dir_ / "locales" / "de_DE.UTF-8").string() + "' > /dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0)
        << "localedef could not build de_DE.UTF-8: Debian's `locales` package (scripts/install-deps.sh) is missing";
    // The process's environment and locale change while no other thread of the test runs.
    ::setenv("LOCPATH", (dir_ / "locales").c_str(), 1);            // NOLINT(concurrency-mt-unsafe)
    ASSERT_NE(std::setlocale(LC_ALL, "de_DE.UTF-8"), nullptr);  // NOLINT(concurrency-mt-unsafe)
    char probe[16];
    std::snprintf(probe, sizeof probe, "%.1f", 1.5);
    ASSERT_STREQ(probe, "1,5");  // the locale is in force: printf would write commas
  }
  void TearDown() override {
    std::setlocale(LC_ALL, "C");  // NOLINT(concurrency-mt-unsafe)
    ::unsetenv("LOCPATH");        // NOLINT(concurrency-mt-unsafe)
    fs::remove_all(dir_);
  }
  fs::path dir_;
};

TEST_F(GermanNumbers, WrittenFilesKeepTheirPoints) {
  const std::vector<Vec3> positions{{1.5, -2.25, 0.0}, {1e-7, 3.0, 0.125}, {0.0, 1.0, 2.5}};
  FaceList faces;
  faces.indices = {0, 1, 2};
  faces.face_offsets = {0, 3};
  ASSERT_TRUE(writeObj(dir_ / "t.obj", positions, faces).ok());
  const std::string obj = contents(dir_ / "t.obj");
  EXPECT_NE(obj.find("v 1.5 -2.25 0\nv 1e-07 3 0.125\n"), std::string::npos) << obj;
  Result<ObjMesh> read = readObj(dir_ / "t.obj");
  ASSERT_TRUE(read.ok()) << read.status().toString();
  EXPECT_EQ(read->positions, positions);

  const std::vector<double> weights{0.5, 0.25, 1.0 / 3.0, 1.0};
  ASSERT_TRUE(writeDmat(dir_ / "w.dmat", 2, 2, weights).ok());
  const std::string dmat = contents(dir_ / "w.dmat");
  EXPECT_NE(dmat.find("0.5"), std::string::npos) << dmat;
  EXPECT_NE(dmat.find("0.33333333333333331"), std::string::npos) << dmat;
  EXPECT_EQ(dmat.find(','), std::string::npos) << dmat;

  EXPECT_EQ(messageNumber(0.5), "0.5");
  EXPECT_EQ(numberText(2.75), "2.75");
  EXPECT_EQ(scientific(1.234e-4), "1.23e-04");
  EXPECT_EQ(finiteNumberIn("1.5"), 1.5);  // not 1 with ",5" expected, as strtod would read it here
}

TEST(FiniteNumberIn, ReadsWhatAnOptionsValueSpells) {
  EXPECT_EQ(finiteNumberIn("2.5e-6"), 2.5e-6);
  EXPECT_EQ(finiteNumberIn("-3"), -3.0);
  EXPECT_EQ(finiteNumberIn("+3"), 3.0);
  EXPECT_EQ(finiteNumberIn(".5"), 0.5);
  EXPECT_EQ(finiteNumberIn("1e-320"), 1e-320);  // a denormal is a number; std::stod threw out_of_range
  EXPECT_EQ(finiteNumberIn("4.9e-324"), 4.9e-324);
  for (const char* bad : {"", "+", "+-1", "++1", " 3", "3 ", "0x10", "inf", "-inf", "nan", "1e400", "1e-400", "1,5",
                          "1.5.2", "e5", "3x"}) {
    EXPECT_EQ(finiteNumberIn(bad), std::nullopt) << "'" << bad << "'";
  }
  EXPECT_EQ(finiteNumbersIn("1,3,0.5", 3), (std::vector<double>{1.0, 3.0, 0.5}));
  for (const char* bad : {"1,3", "1,3,0.5,2", "1,,3", "1,3,", ",1,3", "1,3,x", ""}) {
    EXPECT_EQ(finiteNumbersIn(bad, 3), std::nullopt) << "'" << bad << "'";
  }
}

}  // namespace
}  // namespace odeskin

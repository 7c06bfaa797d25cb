// SPDX-License-Identifier: MIT
// libFuzzer target: the libigl .dmat dense-matrix reader (engine/io/libigl_io.hpp) on arbitrary
// bytes; a header announcing more values than the file can hold must not allocate them.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/io/libigl_io.hpp"
#include "fuzz_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace odeskin;
  const std::string source = "fuzz.dmat";
  const Result<DenseMatrix> m = parseDmat(fuzz::text(data, size), source);
  if (!fuzz::accepted(m, source)) return 0;
  fuzz::require(m->rows > 0 && m->cols > 0, "accepted an empty matrix");
  fuzz::require(m->values.size() == m->rows * m->cols, "value count is not rows x cols");
  for (double v : m->values) fuzz::require(std::isfinite(v), "accepted a non-finite value");
  return 0;
}

// SPDX-License-Identifier: MIT
// libFuzzer target: the patch-network JSON reader (engine/surfaces/network_json.hpp) on arbitrary
// bytes, then what `odeskin surface` does with an accepted description: Network::build and a
// coarse CPU tessellation (3 x 3 samples per patch) of networks up to 2^16 patches: larger ones
// are bounded by kMaxTessellationVertices (1.5 GiB of positions), not by the fuzzer's 2 GiB.
// parseNetworkDescription's messages
// name the field (readNetworkDescription adds the path), so here a refusal need only be a
// kParseError.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/surfaces/network_json.hpp"
#include "engine/surfaces/tessellation.hpp"
#include "fuzz_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace odeskin;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Result<NetworkDescription> description = parseNetworkDescription(text);
  if (!description.ok()) {
    fuzz::require(description.status().code() == StatusCode::kParseError,
                  "a refused network file is not a kParseError: " + description.status().toString());
    return 0;
  }
  // What it reads it writes back unchanged (network_json.hpp).
  const Result<NetworkDescription> again = parseNetworkDescription(networkJson(*description));
  fuzz::require(again.ok(), "networkJson output does not parse: " + again.status().toString());
  fuzz::require(networkJson(*again) == networkJson(*description), "networkJson(parse(networkJson(d))) differs");

  std::vector<std::string> warnings;
  Result<Network> network = Network::build(std::move(description).value(), &warnings);
  if (!network.ok()) {
    fuzz::require(network.status().code() != StatusCode::kInternal, "internal error: " + network.status().toString());
    return 0;
  }
  if (std::uint64_t{network->rows()} * network->columns() > (std::uint64_t{1} << 16)) return 0;
  const Result<SurfaceMesh> mesh = tessellateNetwork(*network, TessellationResolution{3, 3});
  if (!mesh.ok()) {
    fuzz::require(mesh.status().code() != StatusCode::kInternal, "internal error: " + mesh.status().toString());
    return 0;
  }
  for (std::uint32_t v : mesh->faces.indices) fuzz::require(v < mesh->positions.size(), "face index out of range");
  return 0;
}

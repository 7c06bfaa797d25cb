// SPDX-License-Identifier: MIT
// A mesh of ../shared/data (ODESKIN_DATA_DIR, set for every test), read or the test stops.
#pragma once

#include <stdexcept>
#include <string>

#include "engine/io/obj_reader.hpp"

namespace odeskin::testing {

// `name` relative to the data folder, e.g. "cylinder/cylinder.obj".
inline ObjMesh dataMesh(const std::string& name) {
  Result<ObjMesh> mesh = readObj(std::string(ODESKIN_DATA_DIR) + "/" + name);
  if (!mesh.ok()) throw std::runtime_error(mesh.status().toString());
  return std::move(mesh).value();
}

}  // namespace odeskin::testing

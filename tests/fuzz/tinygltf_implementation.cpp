// SPDX-License-Identifier: MIT
// The fuzz build's tinygltf (cmake/OdeskinTinyGltf.cmake): Debian's tiny_gltf.h compiled with the
// fuzzers' instrumentation, in place of the prebuilt libtinygltf. Only this file defines
// TINYGLTF_IMPLEMENTATION, and only the fuzz build compiles it.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>

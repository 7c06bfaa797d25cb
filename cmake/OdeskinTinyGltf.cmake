# Which tinygltf odeskin links: ODESKIN_TINYGLTF names the target. Normally Debian's prebuilt
# libtinygltf (TinyGLTF::TinyGLTF; nothing here defines TINYGLTF_IMPLEMENTATION). The fuzz build
# instead compiles the implementation from Debian's own tiny_gltf.h (the same 2.7.0 the library was
# built from) with the fuzzers' coverage and sanitizer flags, and links that in place of the
# library: tinygltf's JSON-to-model code is where a hostile glTF arrives first, and uninstrumented
# it was neither guided by coverage nor checked by AddressSanitizer (docs/reliability.md).
if(ODESKIN_BUILD_FUZZERS)
  find_path(ODESKIN_STB_IMAGE_DIR stb_image.h PATH_SUFFIXES stb REQUIRED
            DOC "stb single-file libraries (Debian libstb-dev: /usr/include/stb)")
  find_library(ODESKIN_STB_LIBRARY stb REQUIRED DOC "Debian libstb: stb_image's implementation, as libtinygltf links it")
  add_library(odeskin_tinygltf_instrumented STATIC ${PROJECT_SOURCE_DIR}/tests/fuzz/tinygltf_implementation.cpp)
  target_include_directories(odeskin_tinygltf_instrumented SYSTEM PRIVATE ${ODESKIN_STB_IMAGE_DIR})
  target_link_libraries(odeskin_tinygltf_instrumented PUBLIC nlohmann_json::nlohmann_json ${ODESKIN_STB_LIBRARY})
  target_compile_options(odeskin_tinygltf_instrumented PRIVATE -w)  # upstream code: not ours to warn about
  set(ODESKIN_TINYGLTF odeskin_tinygltf_instrumented)
else()
  set(ODESKIN_TINYGLTF TinyGLTF::TinyGLTF)
endif()

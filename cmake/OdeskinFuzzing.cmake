# libFuzzer build (tests/fuzz, scripts/fuzz.sh; docs/reliability.md, "Fuzzing"): clang only. Every
# library the fuzz targets link is compiled with coverage instrumentation, AddressSanitizer and
# UBSan, and undefined behaviour aborts (a finding, not a log line); libstdc++'s assertions turn an
# out-of-range operator[] into a finding too. Only the fuzz targets link libFuzzer's main.
if(ODESKIN_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "ODESKIN_BUILD_FUZZERS needs clang's libFuzzer: configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer -D_GLIBCXX_ASSERTIONS)
  add_link_options(-fsanitize=address,undefined)
endif()

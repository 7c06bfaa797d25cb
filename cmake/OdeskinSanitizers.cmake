# ODESKIN_SANITIZE builds every odeskin target (libraries, tests, programs) with the named sanitizers:
#   address,undefined  AddressSanitizer + LeakSanitizer + UndefinedBehaviorSanitizer (CI's full build)
#   thread             ThreadSanitizer (scripts/tsan.sh: the engine's threaded CPU paths)
# The flags are set directory-wide here, before any add_subdirectory, because a sanitizer must see
# every translation unit of a program: an uninstrumented library hides its own bugs and, for TSan,
# reports false races on memory it touches. -g1 adds just the line tables the reports need.
set(ODESKIN_SANITIZE "" CACHE STRING
    "Sanitizers for every odeskin target: empty, address,undefined or thread")
set_property(CACHE ODESKIN_SANITIZE PROPERTY STRINGS "" "address,undefined" "thread")

if(ODESKIN_SANITIZE)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    message(FATAL_ERROR "ODESKIN_SANITIZE needs GCC or Clang, not ${CMAKE_CXX_COMPILER_ID}")
  endif()
  string(REPLACE "," ";" odeskin_sanitizers "${ODESKIN_SANITIZE}")
  foreach(s IN LISTS odeskin_sanitizers)
    if(NOT s MATCHES "^(address|undefined|thread)$")
      message(FATAL_ERROR "ODESKIN_SANITIZE: unknown sanitizer '${s}' (address, undefined or thread)")
    endif()
  endforeach()
  if("thread" IN_LIST odeskin_sanitizers AND "address" IN_LIST odeskin_sanitizers)
    message(FATAL_ERROR "ODESKIN_SANITIZE: thread and address cannot be combined in one build")
  endif()

  set(odeskin_sanitize_flags -fsanitize=${ODESKIN_SANITIZE} -fno-omit-frame-pointer -g1)
  if("undefined" IN_LIST odeskin_sanitizers)
    # A UB finding aborts the test that hit it instead of printing a line and carrying on.
    list(APPEND odeskin_sanitize_flags -fno-sanitize-recover=undefined)
  endif()
  if("address" IN_LIST odeskin_sanitizers OR "undefined" IN_LIST odeskin_sanitizers)
    # GCC 12 compiles ASan + UBSan at -O3 for 2.2 to 4 times the CPU time of a plain -O3 build, at
    # -O1 for 1.6 to 1.9 times (docs/reliability.md, "Sanitizers"), and CI builds everything this way on
    # two cores, so these builds optimise at -O1 (it comes after the build type's -O3 and wins).
    list(APPEND odeskin_sanitize_flags -O1)
  endif()
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # The sanitizers' checks defeat GCC's flow analysis: -Wmaybe-uninitialized then fires on
    # OpenMesh's and Eigen's deliberately uninitialised vector types (GCC's manual warns of these
    # false positives under -fsanitize), and ODESKIN_WERROR would turn them into errors.
    list(APPEND odeskin_sanitize_flags -Wno-maybe-uninitialized)
  endif()
  add_compile_options(${odeskin_sanitize_flags})
  add_link_options(-fsanitize=${ODESKIN_SANITIZE})
  message(STATUS "odeskin: sanitizers ${ODESKIN_SANITIZE}")
endif()

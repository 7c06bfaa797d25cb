# SPDX-License-Identifier: MIT
# `cmake --install BUILD --prefix P` puts the odeskin program, the libraries, their headers and a
# CMake package under P, so a project outside this build can use odeskin without its sources:
#   find_package(odeskin 0.1 REQUIRED)                      # CMAKE_PREFIX_PATH=P
#   target_link_libraries(game PRIVATE odeskin::runtime)    # and odeskin::engine, odeskin::vulkan_runtime
# the names add_subdirectory gives (docs/runtime.md, "Building odeskin into an engine").
# `find_package(odeskin COMPONENTS vulkan_runtime)` fails on a package built without the host.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(ODESKIN_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/odeskin")

# Every library the three entry points link, public or not: static libraries carry their private
# dependencies along as link-only entries, so those must be in the package too.
set(odeskin_installed_libraries
  odeskin_warnings odeskin_core odeskin_kernels odeskin_offline odeskin_mesh odeskin_rig odeskin_io odeskin_gltf
  odeskin_curves odeskin_curve_rig odeskin_pipeline odeskin_export odeskin_baselines odeskin_evaluation
  odeskin_visual odeskin_surfaces odeskin_engine odeskin_runtime)
if(ODESKIN_BUILD_HOST)
  list(APPEND odeskin_installed_libraries odeskin_host odeskin_host_runtime)
  # The generated SPIR-V headers' targets (link-only, nothing to install but the name).
  foreach(library odeskin_host odeskin_host_runtime)
    get_target_property(links ${library} LINK_LIBRARIES)
    foreach(link IN LISTS links)
      if(link MATCHES "^odeskin_shader_")
        list(APPEND odeskin_installed_libraries ${link})
      endif()
    endforeach()
  endforeach()
  list(REMOVE_DUPLICATES odeskin_installed_libraries)
endif()
foreach(library IN LISTS odeskin_installed_libraries)
  string(REGEX REPLACE "^odeskin_" "" name "${library}")
  set_target_properties(${library} PROPERTIES EXPORT_NAME ${name})
endforeach()
if(ODESKIN_BUILD_HOST)
  set_target_properties(odeskin_host_runtime PROPERTIES EXPORT_NAME vulkan_runtime)
endif()

install(TARGETS ${odeskin_installed_libraries} EXPORT odeskinTargets
        ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
        INCLUDES DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/odeskin")
# Headers keep their paths (#include "engine/runtime/cpu_runtime.hpp"), under include/odeskin.
install(DIRECTORY engine DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/odeskin"
        FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")
if(ODESKIN_BUILD_HOST)
  install(DIRECTORY host DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/odeskin"
          FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")
endif()
if(ODESKIN_BUILD_HOST AND ODESKIN_BUILD_PROGRAMS)
  install(TARGETS odeskin RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
endif()

install(EXPORT odeskinTargets NAMESPACE odeskin:: DESTINATION "${ODESKIN_INSTALL_CMAKEDIR}")
# What the package's config must find again: the imported targets the libraries name.
get_target_property(odeskin_visual_links odeskin_visual LINK_LIBRARIES)
set(ODESKIN_PACKAGE_ZLIB OFF)
if("ZLIB::ZLIB" IN_LIST odeskin_visual_links)
  set(ODESKIN_PACKAGE_ZLIB ON)
endif()
configure_package_config_file(cmake/odeskinConfig.cmake.in "${PROJECT_BINARY_DIR}/odeskinConfig.cmake"
                              INSTALL_DESTINATION "${ODESKIN_INSTALL_CMAKEDIR}")
# 0.x: a minor release may break the API, so only the same minor version is compatible.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/odeskinConfigVersion.cmake" COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/odeskinConfig.cmake" "${PROJECT_BINARY_DIR}/odeskinConfigVersion.cmake"
        DESTINATION "${ODESKIN_INSTALL_CMAKEDIR}")

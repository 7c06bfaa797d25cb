# odeskin_glsl_shader(TARGET name SOURCE stem.comp SYMBOL c_name [STEM out_stem] [DEFINES NAME...]
#                     [DEPENDS headers...])
#
# Compiles a GLSL compute shader to SPIR-V at build time (never into the source tree), checks the
# result with spirv-val, and wraps it as an INTERFACE target whose include directory holds
# shaders/<stem>.spv.h: `const uint32_t c_name[]`, embedded in whatever links the target. A variant
# of a source (DEFINES, each passed as -DNAME) names its own STEM so both headers can coexist.
function(odeskin_glsl_shader)
  cmake_parse_arguments(ARG "" "TARGET;SOURCE;SYMBOL;STEM" "DEPENDS;DEFINES" ${ARGN})
  get_filename_component(source "${ARG_SOURCE}" ABSOLUTE)
  get_filename_component(stem "${ARG_SOURCE}" NAME_WE)
  if(ARG_STEM)
    set(stem "${ARG_STEM}")
  endif()
  set(defines)
  foreach(define IN LISTS ARG_DEFINES)
    list(APPEND defines "-D${define}")
  endforeach()
  set(out_dir "${PROJECT_BINARY_DIR}/generated/shaders")
  set(header "${out_dir}/${stem}.spv.h")
  set(spv "${out_dir}/${stem}.spv")
  set(validate_cmd)
  if(ODESKIN_SPIRV_VAL)
    set(validate_cmd COMMAND "${ODESKIN_SPIRV_VAL}" --target-env vulkan1.1 "${spv}")
  endif()
  add_custom_command(
    OUTPUT "${header}" "${spv}"
    COMMAND "${CMAKE_COMMAND}" -E make_directory "${out_dir}"
    COMMAND "${Vulkan_GLSLANG_VALIDATOR_EXECUTABLE}" -V --target-env vulkan1.1
            -I${PROJECT_SOURCE_DIR}/engine/core ${defines} -o "${spv}" "${source}"
    ${validate_cmd}
    COMMAND "${Vulkan_GLSLANG_VALIDATOR_EXECUTABLE}" -V --target-env vulkan1.1
            -I${PROJECT_SOURCE_DIR}/engine/core ${defines} --vn ${ARG_SYMBOL} -o "${header}" "${source}"
    DEPENDS "${source}" ${ARG_DEPENDS}
    COMMENT "GLSL -> SPIR-V ${ARG_TARGET}"
    VERBATIM)
  add_custom_target(${ARG_TARGET}_spirv DEPENDS "${header}")
  add_library(${ARG_TARGET} INTERFACE)
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_spirv)
  target_include_directories(${ARG_TARGET} INTERFACE "$<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated>")
endfunction()

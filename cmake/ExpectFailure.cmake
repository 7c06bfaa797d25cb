# cmake -DCOMMAND="prog;arg;..." -DEXPECT_CODE=N -DEXPECT_REGEX=re -P ExpectFailure.cmake
# Passes when the command exits with exactly EXPECT_CODE (so a crash or signal never passes) and its
# stderr matches EXPECT_REGEX.
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT "${code}" STREQUAL "${EXPECT_CODE}")
  message(FATAL_ERROR "expected exit code ${EXPECT_CODE}, got '${code}'\nstdout: ${out}\nstderr: ${err}")
endif()
if(NOT err MATCHES "${EXPECT_REGEX}")
  message(FATAL_ERROR "stderr does not match '${EXPECT_REGEX}':\n${err}")
endif()

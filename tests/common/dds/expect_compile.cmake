# Builds one target of the build tree and checks the compiler's verdict:
#   cmake -DBUILD_DIR=<dir> -DTARGET=<target> -DEXPECT=pass|fail [-DMATCH=<regex>] -P expect_compile.cmake
# EXPECT=fail passes only when the build fails with an error whose text matches MATCH (the
# mismatched type), so an unrelated failure does not count as the rejection being tested.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${TARGET}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(EXPECT STREQUAL "pass")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${TARGET} should compile but does not:\n${out}")
  endif()
  message(STATUS "${TARGET} compiles, as it must")
elseif(EXPECT STREQUAL "fail")
  if(rc EQUAL 0)
    message(FATAL_ERROR "${TARGET} compiles, but the mismatched pairing must be rejected")
  endif()
  if(NOT out MATCHES "error" OR NOT out MATCHES "${MATCH}")
    message(FATAL_ERROR "${TARGET} fails, but not with an error matching '${MATCH}':\n${out}")
  endif()
  message(STATUS "${TARGET} is rejected by the compiler, as it must be")
else()
  message(FATAL_ERROR "EXPECT must be pass or fail, got '${EXPECT}'")
endif()

# Runs PROGRAM with ARGS (|-separated) and checks its exit status and output.
#   -DPROGRAM=...  -DARGS=a|b|c  -DEXPECT_EXIT=N
#   -DEXPECT_OUTPUT=text   (optional) text that must appear in stdout+stderr
#   -DCOMPARE=a.png|b.png  (optional, with -DIMGCMP=...) images that must match after the run
string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND "${PROGRAM}" ${args} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err
                TIMEOUT 100)
message("${out}${err}")
if(NOT "${status}" STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "expected exit status ${EXPECT_EXIT}, got ${status}")
endif()
if(DEFINED EXPECT_OUTPUT)
  string(FIND "${out}${err}" "${EXPECT_OUTPUT}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the output does not contain: ${EXPECT_OUTPUT}")
  endif()
endif()
if(DEFINED COMPARE)
  string(REPLACE "|" ";" images "${COMPARE}")
  execute_process(COMMAND "${IMGCMP}" ${images} RESULT_VARIABLE cmp_status OUTPUT_VARIABLE cmp_out ERROR_VARIABLE cmp_out)
  message("${cmp_out}")
  if(NOT cmp_status EQUAL 0)
    message(FATAL_ERROR "the two renders differ")
  endif()
endif()

# cmake -DPROGRAM=exe [-DARGS=a|b|c] -DEXPECT_EXIT=N -DEXPECT_OUTPUT=text [-DEXPECT_NO_PASS=1] -P this-file
#
# Runs a program built from untouched exercise stubs and checks that it
# fails *politely*: it exits with status EXPECT_EXIT (not a signal, not a
# hang), says EXPECT_OUTPUT, and, for a test executable with EXPECT_NO_PASS,
# no test case passed (a public test that passes on a stub tests nothing).
string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND "${PROGRAM}" ${args}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
set(all "${out}${err}")
if(NOT rc STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "${PROGRAM} ended with '${rc}', expected exit status ${EXPECT_EXIT}:\n${all}")
endif()
string(FIND "${all}" "${EXPECT_OUTPUT}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${PROGRAM} did not say '${EXPECT_OUTPUT}':\n${all}")
endif()
if(EXPECT_NO_PASS)
  if(NOT all MATCHES "test cases: *[0-9]+ \\| *0 passed")
    message(FATAL_ERROR "${PROGRAM}: some test case passed against a stub, so it does not test the exercise:\n${all}")
  endif()
endif()
message(STATUS "${PROGRAM} failed politely (exit ${rc}, said '${EXPECT_OUTPUT}')")

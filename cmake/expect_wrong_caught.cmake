# cmake -DPROGRAM=hidden-tests-linked-with-a-bug -DEXPECT_FILE=expect_fail.txt [-DSTATUS_FILE=patch-status.txt] -P this-file
#
# A realistic wrong implementation must lose points on exactly the right
# tests: every test case named in EXPECT_FILE must fail when run on its own,
# and every other hidden test case must pass (so a fixture that drifted into
# a second bug, or a bug that the list undersells, is noticed). That the
# reference solution passes them all is checked by chNN.hidden.*.
if(DEFINED STATUS_FILE)
  if(NOT EXISTS "${STATUS_FILE}")
    message(FATAL_ERROR "${STATUS_FILE} is missing: the fixture's patch was never applied")
  endif()
  file(READ "${STATUS_FILE}" status)
  if(NOT status STREQUAL "ok\n")
    message(FATAL_ERROR "${status}")
  endif()
endif()
if(NOT EXISTS "${PROGRAM}")
  message(FATAL_ERROR "${PROGRAM} was not built: nothing was checked")
endif()
file(STRINGS "${EXPECT_FILE}" lines)
set(count 0)
foreach(line IN LISTS lines)
  string(REGEX REPLACE "#.*$" "" name "${line}")
  string(STRIP "${name}" name)
  if(name STREQUAL "")
    continue()
  endif()
  math(EXPR count "${count} + 1")
  # doctest treats ',' in a filter as a separator: escape it.
  string(REPLACE "," "\\," filter "${name}")
  execute_process(COMMAND "${PROGRAM}" "--test-case=${filter}" "--no-version"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
  if(out MATCHES "test cases: *0 \\|")
    message(FATAL_ERROR "${EXPECT_FILE}: no hidden test case is called '${name}'")
  endif()
  if(NOT out MATCHES "test cases: *[0-9]+ \\|" AND rc MATCHES "^[0-9]+$")
    message(FATAL_ERROR "${PROGRAM} printed no doctest summary (exit ${rc}): nothing was checked\n${out}${err}")
  endif()
  if(rc EQUAL 0)
    message(FATAL_ERROR "the bug in ${EXPECT_FILE} went unnoticed: hidden test '${name}' passed\n${out}${err}")
  endif()
  message(STATUS "caught by '${name}' (exit ${rc})")
  list(APPEND expected "${filter}")
endforeach()
if(count EQUAL 0)
  message(FATAL_ERROR "${EXPECT_FILE} names no test case")
endif()

# Everything else must pass: the bug is the fixture's only difference.
list(JOIN expected "," excluded)
execute_process(COMMAND "${PROGRAM}" "--test-case-exclude=${excluded}" "--no-version"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "hidden tests that ${EXPECT_FILE} does not name failed too: either the fixture holds "
                      "more than its bug, or expect_fail.txt must list them\n${out}${err}")
endif()
message(STATUS "every other hidden test case passes")

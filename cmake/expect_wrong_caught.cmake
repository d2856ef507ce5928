# cmake -DPROGRAM=hidden-tests-linked-with-a-bug -DEXPECT_FILE=expect_fail.txt -P this-file
#
# A realistic wrong implementation must lose points on the right tests:
# every test case named in EXPECT_FILE must fail when run on its own.
# (That the reference solution passes them all is checked by chNN.hidden.*.)
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
  if(rc EQUAL 0)
    message(FATAL_ERROR "the bug in ${EXPECT_FILE} went unnoticed: hidden test '${name}' passed\n${out}${err}")
  endif()
  message(STATUS "caught by '${name}' (exit ${rc})")
endforeach()
if(count EQUAL 0)
  message(FATAL_ERROR "${EXPECT_FILE} names no test case")
endif()

# cmake -DSOURCE_ROOT=repo -DWORK=scratch-dir -P this-file
#
# Checks the fixture machinery itself (ctest fixtures.drift_is_caught): a
# patch applies to the solution it was made against, and the same patch is
# refused once that solution has changed under it, so a fixture can never
# drift into testing something else without a failing test saying so.
set(fixture "${SOURCE_ROOT}/tests/fixtures/wrong/ch01/far-root/bug.patch")
set(file "solutions/01-unit-sphere/unit_sphere.cpp")
set(apply "${CMAKE_CURRENT_LIST_DIR}/apply_fixture_patch.cmake")
file(REMOVE_RECURSE "${WORK}")

# 1. Against the current solution: it applies.
execute_process(COMMAND ${CMAKE_COMMAND} -DPATCH=${fixture} -DSOURCE_ROOT=${SOURCE_ROOT} -DOUT=${WORK}/fresh
                        -DFILES=${file} -DSTATUS=${WORK}/fresh.status -P ${apply})
file(READ "${WORK}/fresh.status" status)
if(NOT status STREQUAL "ok\n")
  message(FATAL_ERROR "the ch01 far-root fixture does not apply to the current solution:\n${status}")
endif()
file(READ "${WORK}/fresh/${file}" patched)
file(READ "${SOURCE_ROOT}/${file}" original)
if(patched STREQUAL original)
  message(FATAL_ERROR "applying the far-root patch changed nothing")
endif()

# 2. Against a solution that moved on (every line of it edited): refused,
# and the copy left behind is the unpatched solution (so it still compiles).
string(REGEX REPLACE "\n" " // edited\n" drifted "${original}")
file(WRITE "${WORK}/drifted-root/${file}" "${drifted}")
execute_process(COMMAND ${CMAKE_COMMAND} -DPATCH=${fixture} -DSOURCE_ROOT=${WORK}/drifted-root -DOUT=${WORK}/drifted
                        -DFILES=${file} -DSTATUS=${WORK}/drifted.status -P ${apply})
file(READ "${WORK}/drifted.status" status)
if(status STREQUAL "ok\n" OR NOT status MATCHES "no longer applies")
  message(FATAL_ERROR "a patch against a changed solution was not refused:\n${status}")
endif()
file(READ "${WORK}/drifted/${file}" left)
if(NOT left STREQUAL drifted)
  message(FATAL_ERROR "after a refused patch the fixture's copy is not the plain solution")
endif()
message(STATUS "a drifted fixture is refused with: ${status}")

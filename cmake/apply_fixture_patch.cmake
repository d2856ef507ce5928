# cmake -DPATCH=bug.patch -DSOURCE_ROOT=repo -DOUT=dir -DFILES="solutions/NN-name/f.cpp;..." -DSTATUS=file -P this-file
#
# Makes the source of a wrong-implementation fixture: copies the solution's
# exercise files into OUT (same relative paths) and applies the fixture's
# bug.patch to them with GNU patch, with no fuzz: a patch whose context no
# longer matches the solution exactly has drifted, and the fixture must be
# looked at again rather than silently test something else.
#
# The build never fails here: when the patch does not apply, OUT keeps the
# unpatched solution (so everything still compiles) and STATUS says why; the
# fixture's test (expect_wrong_caught.cmake) reads STATUS and fails with that
# message. One drifted fixture must not stop everybody's build.
find_program(RT_PATCH_PROGRAM patch)
foreach(f IN LISTS FILES)
  get_filename_component(dir "${OUT}/${f}" DIRECTORY)
  file(MAKE_DIRECTORY "${dir}")
  file(COPY_FILE "${SOURCE_ROOT}/${f}" "${OUT}/${f}")
endforeach()
if(NOT RT_PATCH_PROGRAM)
  file(WRITE "${STATUS}" "GNU patch is not installed (apt-get install patch): ${PATCH} was not applied\n")
  return()
endif()
execute_process(COMMAND "${RT_PATCH_PROGRAM}" --batch --forward --fuzz=0 --no-backup-if-mismatch -r - -p1
                        -d "${OUT}" -i "${PATCH}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  file(WRITE "${STATUS}" "ok\n")
else()
  foreach(f IN LISTS FILES)  # back to the plain solution, so it compiles
    file(COPY_FILE "${SOURCE_ROOT}/${f}" "${OUT}/${f}")
  endforeach()
  file(WRITE "${STATUS}" "${PATCH} no longer applies to the solution (it has drifted: make the bug again "
                         "against the current solution and rewrite the patch):\n${out}${err}")
endif()

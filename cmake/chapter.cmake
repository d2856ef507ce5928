# rt_chapter(): everything one chapter builds, in one place.
#
#   rt_chapter(01
#     TITLE     "unit sphere"
#     EXERCISES unit_sphere.cpp   # the files a student edits (same names in solutions/NN-name/)
#     PROGRAM   main.cpp          # renders the chapter's scene
#     DEPENDS   01 02)            # earlier chapters whose exercises this one calls
#   NOISY_PICTURE                 # optional: the picture is a Monte Carlo estimate, so the grader's
#                                 # imgcmp compares it by statistics (--statistical, common/image_compare.hpp)
#
# makes, for chapter NN in chapters/NN-name/:
#   chNN_student     library of the student's exercise files (stubs until filled in)
#   chNN_solution    library of solutions/NN-name/ (when that folder exists)
#   chNN_exercises   whichever of the two this build selects (RT_SIDE, RT_STUDENT_CHAPTERS)
#   chNN             the chapter's program, linked with chNN_exercises
#   chNN_public_tests, chNN_hidden_tests   doctest executables from tests/public and tests/hidden
#   chNN_public_objects, chNN_hidden_objects, chNN_program_objects   their sources and the program's
#                    main.cpp, each compiled once (rt_chapter_objects())
# and registers ctest tests labelled chNN (ctest -L ch01 runs chapter 01 only):
#   chNN.public.*, chNN.hidden.*   one ctest test per doctest test case
#   chNN.render                    renders the scene and compares it with chapters/NN-name/reference.png
#   chNN.stub.*                    (solution builds only) the untouched stubs compile, link and fail politely
#   chNN.wrong.BUG                 (normal solution builds only, not the sanitizer build) each realistic wrong implementation kept in
#                                  tests/fixtures/wrong/chNN/BUG/ fails the hidden tests it names
#
# A wrong-implementation fixture is a folder tests/fixtures/wrong/chNN/BUG/ holding
#   - bug.patch: the bug and nothing else, as a unified diff against the
#     chapter's solution files (`diff -u` or `git diff` form, paths
#     a/solutions/NN-name/FILE and b/solutions/NN-name/FILE; text before the
#     first `---` line describes the bug). It is applied at build time
#     (cmake/apply_fixture_patch.cmake), with no fuzz, to a copy of the
#     current solution, so a fixture cannot drift away from it unnoticed.
#   - expect_fail.txt: one hidden test-case name per line (doctest wildcards
#     allowed, '#' starts a comment) that the bug must fail; every other
#     hidden test case must pass (cmake/expect_wrong_caught.cmake).

option(RT_DISCOVER_TESTS "register one ctest test per doctest case (runs each test executable once at build time)" ON)
set(RT_STUB_CHECK_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/expect_polite_failure.cmake")
include(doctest)  # doctest_discover_tests, shipped by doctest-dev
include("${CMAKE_CURRENT_LIST_DIR}/judge.cmake")  # rt_chapter_judge(): the autograder's judges and runner

function(rt_chapter_side number out_side)
  set(side "${RT_SIDE}")
  if(number IN_LIST RT_STUDENT_CHAPTERS OR "all" IN_LIST RT_STUDENT_CHAPTERS)
    set(side student)
  endif()
  set(${out_side} "${side}" PARENT_SCOPE)
endfunction()

# The OBJECT library of one solution file, e.g. ch08_solution_slab_test_cpp.
function(rt_solution_file_objects id file out_target)
  string(MAKE_C_IDENTIFIER "${id}_solution_${file}" target)
  set(${out_target} ${target} PARENT_SCOPE)
endfunction()

# Links the hidden tests of chapter `id` against a wrong implementation and
# checks that the hidden tests catch it.
function(rt_wrong_fixtures id chapter_dir solution_dir exercises dependency_solution_libs)
  # Whether the hidden tests catch a mistake is a property of the tests' logic,
  # the same in every build, so only the normal build makes and runs the
  # fixtures. The sanitizer build checks the course's own code (solutions,
  # tests, tools); the deliberately wrong copies were more than half of its
  # build steps (351 of 566 with twelve chapters), and a fixture that only
  # stops under a memory bound (a build that never stops splitting) cannot run
  # there at all: AddressSanitizer maps terabytes of shadow memory, so RLIMIT_AS
  # cannot bound it (tests/support/memory_bound.hpp).
  if(RT_SANITIZE)
    return()
  endif()
  file(GLOB fixture_dirs LIST_DIRECTORIES true CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/tests/fixtures/wrong/${id}/*")
  if(NOT fixture_dirs OR NOT TARGET ${id}_hidden_objects)
    return()
  endif()
  file(RELATIVE_PATH solution_rel "${PROJECT_SOURCE_DIR}" "${solution_dir}")
  foreach(dir IN LISTS fixture_dirs)
    if(NOT IS_DIRECTORY "${dir}")
      continue()
    endif()
    get_filename_component(bug "${dir}" NAME)
    set(problem "")
    if(NOT EXISTS "${dir}/expect_fail.txt")
      set(problem "needs expect_fail.txt (the hidden tests it must fail)")
    elseif(NOT EXISTS "${dir}/bug.patch")
      set(problem "needs bug.patch (the bug, as a diff against ${solution_rel})")
    endif()
    if(problem)
      # Not fatal, so one unfinished fixture does not stop everybody's build;
      # the fixture's own test fails and says why.
      message(WARNING "${dir}: a wrong-implementation fixture ${problem}")
      add_test(NAME ${id}.wrong.${bug} COMMAND ${CMAKE_COMMAND} -E echo "${dir} ${problem}")
      set_tests_properties(${id}.wrong.${bug} PROPERTIES LABELS "${id};wrong" WILL_FAIL TRUE)
      continue()
    endif()
    # The patched copies live in the build folder; the exercise files the
    # patch does not touch are the solution's objects, as they are.
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${dir}/bug.patch")
    file(STRINGS "${dir}/bug.patch" patched_lines REGEX "^\\+\\+\\+ b/")
    set(out "${PROJECT_BINARY_DIR}/wrong_src/${id}/${bug}")
    set(sources "")
    set(patched "")
    set(patched_outputs "")
    foreach(f IN LISTS exercises)
      set(rel "${solution_rel}/${f}")
      string(REGEX MATCH "\\+\\+\\+ b/${rel}([\t ;]|$)" touched "${patched_lines}")
      if(touched)
        list(APPEND patched "${rel}")
        list(APPEND patched_outputs "${out}/${rel}")
        list(APPEND sources "${out}/${rel}")
      else()
        rt_solution_file_objects(${id} "${f}" objects)
        list(APPEND sources $<TARGET_OBJECTS:${objects}>)
      endif()
    endforeach()
    set(status "${out}/patch-status.txt")
    if(NOT patched)
      set(problem "bug.patch touches none of this chapter's exercise files (${exercises})")
      message(WARNING "${dir}: ${problem}")
      add_test(NAME ${id}.wrong.${bug} COMMAND ${CMAKE_COMMAND} -E echo "${dir}: ${problem}")
      set_tests_properties(${id}.wrong.${bug} PROPERTIES LABELS "${id};wrong" WILL_FAIL TRUE)
      continue()
    endif()
    set(solution_inputs "")
    foreach(rel IN LISTS patched)
      list(APPEND solution_inputs "${PROJECT_SOURCE_DIR}/${rel}")
    endforeach()
    add_custom_command(OUTPUT ${patched_outputs} "${status}"
                       COMMAND ${CMAKE_COMMAND} -DPATCH=${dir}/bug.patch -DSOURCE_ROOT=${PROJECT_SOURCE_DIR}
                               -DOUT=${out} "-DFILES=${patched}" -DSTATUS=${status}
                               -P "${PROJECT_SOURCE_DIR}/cmake/apply_fixture_patch.cmake"
                       DEPENDS "${dir}/bug.patch" ${solution_inputs} "${PROJECT_SOURCE_DIR}/cmake/apply_fixture_patch.cmake"
                       COMMENT "Applying the wrong-implementation fixture ${id}/${bug}"
                       VERBATIM)
    set(target ${id}_wrong_${bug})
    string(MAKE_C_IDENTIFIER "${target}" target)
    add_executable(${target} ${sources})
    target_include_directories(${target} PRIVATE "${PROJECT_SOURCE_DIR}/chapters" "${chapter_dir}" "${solution_dir}")
    target_link_libraries(${target} PRIVATE $<TARGET_OBJECTS:${id}_hidden_objects> rt_test_support rt_common
                                            ${dependency_solution_libs})
    set_target_properties(${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/wrong")
    add_test(NAME ${id}.wrong.${bug}
             COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:${target}> -DEXPECT_FILE=${dir}/expect_fail.txt
                     -DSTATUS_FILE=${status} -P "${PROJECT_SOURCE_DIR}/cmake/expect_wrong_caught.cmake")
    set_tests_properties(${id}.wrong.${bug} PROPERTIES LABELS "${id};wrong" TIMEOUT 120)
  endforeach()
endfunction()

# Writes build/<dir>/rt_chapters/chNN.json: what the tools (the autograder,
# the kit exporter) need to know about a chapter, so they grow with the
# chapters without being edited. Paths to executables are the build's own.
function(rt_json_list out)
  set(items "")
  foreach(item IN LISTS ARGN)
    list(APPEND items "\"${item}\"")
  endforeach()
  list(JOIN items ", " joined)
  set(${out} "[${joined}]" PARENT_SCOPE)
endfunction()

function(rt_chapter_description id number folder title chapter_dir side exercises depends noisy)
  rt_json_list(exercises_json ${exercises})
  rt_json_list(depends_json ${depends})
  set(targets "")
  foreach(kind public hidden)
    if(TARGET ${id}_${kind}_tests)
      string(APPEND targets "  \"${kind}_tests\": \"$<TARGET_FILE:${id}_${kind}_tests>\",\n")
    endif()
  endforeach()
  set(solution_program "")
  if(TARGET ${id}_solution_program)
    set(solution_program "  \"solution_program\": \"$<TARGET_FILE:${id}_solution_program>\",\n")
  endif()
  set(reference "")
  if(EXISTS "${chapter_dir}/reference.png")
    set(reference "${chapter_dir}/reference.png")
  endif()
  file(GENERATE OUTPUT "${PROJECT_BINARY_DIR}/rt_chapters/${id}.json" CONTENT
"{
  \"id\": \"${id}\",
  \"number\": \"${number}\",
  \"folder\": \"${folder}\",
  \"title\": \"${title}\",
  \"chapter_dir\": \"${chapter_dir}\",
  \"side\": \"${side}\",
  \"exercises\": ${exercises_json},
  \"depends\": ${depends_json},
${targets}  \"program\": \"$<TARGET_FILE:${id}>\",
${solution_program}  \"student_library\": \"$<TARGET_FILE:${id}_student>\",
  \"reference\": \"${reference}\",
  \"noisy_picture\": ${noisy}
}
")
endfunction()

# A chapter's test sources (and its program's main.cpp) are compiled once,
# into an OBJECT library, and put into every executable that runs them (as
# $<TARGET_OBJECTS:...>, which carries no library along): the tests, the
# untouched stubs' tests, the judges, the wrong-implementation fixtures. They
# all compile the same sources with the same headers and flags; which code
# answers the exercise functions (solution, stub, the judge's forwarding
# stub, a patched copy), and which main(), is decided when each one links.
# `support` is the library whose headers and flags they compile with
# (rt_test_support for tests, rt_common for a program).
function(rt_chapter_objects id target support)
  add_library(${target} OBJECT ${ARGN})
  target_include_directories(${target} PRIVATE "$<TARGET_PROPERTY:${id}_student,INTERFACE_INCLUDE_DIRECTORIES>")
  target_link_libraries(${target} PRIVATE ${support})
endfunction()

function(rt_chapter number)
  cmake_parse_arguments(PARSE_ARGV 1 CH "NOISY_PICTURE" "TITLE;PROGRAM" "EXERCISES;DEPENDS")
  get_filename_component(folder "${CMAKE_CURRENT_SOURCE_DIR}" NAME)
  set(id "ch${number}")
  string(REGEX REPLACE "^[0-9][0-9]-" "" short_name "${folder}")
  set(chapter_dir "${CMAKE_CURRENT_SOURCE_DIR}")
  set(solution_dir "${PROJECT_SOURCE_DIR}/solutions/${folder}")
  rt_chapter_side(${number} side)
  if(side STREQUAL "solutions" AND NOT EXISTS "${solution_dir}")
    message(FATAL_ERROR "${id}: RT_SIDE=solutions but ${solution_dir} does not exist "
                        "(a student kit has no solutions: configure with -DRT_SIDE=student)")
  endif()

  # Earlier chapters this one links: the side the build selects, or always
  # the solutions when grading (so one mistake is charged once).
  set(dependency_libs "")
  foreach(dep IN LISTS CH_DEPENDS)
    if(RT_DEPENDENCIES_FROM_SOLUTIONS AND TARGET ch${dep}_solution)
      list(APPEND dependency_libs ch${dep}_solution)
    else()
      list(APPEND dependency_libs ch${dep}_exercises)
    endif()
  endforeach()

  # The two sides share the chapter's exercise header (one header per exercise: the contract both implement).
  set(student_sources "")
  foreach(f IN LISTS CH_EXERCISES)
    list(APPEND student_sources "${chapter_dir}/${f}")
  endforeach()
  # Chapter headers are included with their chapter's folder,
  # "02-sphere/sphere.hpp", so two chapters' headers can never be mistaken
  # for one another: users of a chapter see only chapters/ (PUBLIC). The
  # chapter's own exercise files may still write "sphere.hpp" for their own
  # header (PRIVATE), which is what a student's file does wherever the
  # grader compiles it.
  add_library(${id}_student STATIC ${student_sources})
  target_include_directories(${id}_student PUBLIC "${PROJECT_SOURCE_DIR}/chapters" PRIVATE "${chapter_dir}")
  target_link_libraries(${id}_student PUBLIC rt_common ${dependency_libs})

  if(EXISTS "${solution_dir}")
    # One OBJECT library per solution file: a wrong-implementation fixture
    # patches one file and links the others' objects as they are.
    set(solution_objects "")
    foreach(f IN LISTS CH_EXERCISES)
      rt_solution_file_objects(${id} "${f}" objects)
      add_library(${objects} OBJECT "${solution_dir}/${f}")
      target_include_directories(${objects} PRIVATE "${PROJECT_SOURCE_DIR}/chapters" "${chapter_dir}")
      target_link_libraries(${objects} PRIVATE rt_common ${dependency_libs})
      list(APPEND solution_objects $<TARGET_OBJECTS:${objects}>)
    endforeach()
    add_library(${id}_solution STATIC ${solution_objects})
    target_include_directories(${id}_solution PUBLIC "${PROJECT_SOURCE_DIR}/chapters")
    target_link_libraries(${id}_solution PUBLIC rt_common ${dependency_libs})
  endif()

  add_library(${id}_exercises INTERFACE)
  if(side STREQUAL "student")
    target_link_libraries(${id}_exercises INTERFACE ${id}_student)
  else()
    target_link_libraries(${id}_exercises INTERFACE ${id}_solution)
  endif()
  set_property(GLOBAL APPEND PROPERTY RT_CHAPTERS ${id})

  # The chapter's program.
  rt_chapter_objects(${id} ${id}_program_objects rt_common "${chapter_dir}/${CH_PROGRAM}")
  add_executable(${id} $<TARGET_OBJECTS:${id}_program_objects>)
  target_link_libraries(${id} PRIVATE ${id}_exercises)
  set_target_properties(${id} PROPERTIES OUTPUT_NAME "${id}-${short_name}" RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/bin")
  # The same program on the solutions: the autograder draws its reference picture with it, from a view it
  # chooses at grading time (tools/grader/README.md, "Picture"). Built only when asked for (the grader's tree
  # builds it; its earlier chapters are the solutions there, RT_DEPENDENCIES_FROM_SOLUTIONS).
  if(TARGET ${id}_solution)
    add_executable(${id}_solution_program EXCLUDE_FROM_ALL $<TARGET_OBJECTS:${id}_program_objects>)
    target_link_libraries(${id}_solution_program PRIVATE ${id}_solution)
    set_target_properties(${id}_solution_program PROPERTIES OUTPUT_NAME "${id}-${short_name}"
                          RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/bin/solution")
  endif()

  # Tests: every tests/<kind>/chNN_*.cpp file of the chapter.
  foreach(kind public hidden)
    file(GLOB test_sources CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/tests/${kind}/${id}_*.cpp")
    if(NOT test_sources)
      continue()
    endif()
    rt_chapter_objects(${id} ${id}_${kind}_objects rt_test_support ${test_sources})
    rt_test_file_options(${id}_${kind}_objects)
    add_executable(${id}_${kind}_tests $<TARGET_OBJECTS:${id}_${kind}_objects>)
    target_link_libraries(${id}_${kind}_tests PRIVATE ${id}_exercises rt_test_support)
    set_target_properties(${id}_${kind}_tests PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/tests")
    # Discovery runs the freshly linked executable at build time. The
    # autograder's tree links a student's code into it, and must never run
    # that code outside its sandbox: it configures with RT_DISCOVER_TESTS=OFF.
    if(RT_DISCOVER_TESTS)
      doctest_discover_tests(${id}_${kind}_tests TEST_PREFIX "${id}.${kind}."
                             PROPERTIES TIMEOUT 60 LABELS "${id}-${kind}")
    endif()
  endforeach()

  # The picture: render the scene and compare it with the reference render.
  if(EXISTS "${chapter_dir}/reference.png")
    add_test(NAME ${id}.render
             COMMAND ${id} --out "${PROJECT_BINARY_DIR}/render/${id}.png" --compare "${chapter_dir}/reference.png")
    set_tests_properties(${id}.render PROPERTIES LABELS "${id};render" TIMEOUT 120)
  endif()

  rt_chapter_judge(${id} "${chapter_dir}" "${CH_DEPENDS}" "${dependency_libs}")

  if(CH_NOISY_PICTURE)
    set(noisy true)
  else()
    set(noisy false)
  endif()
  rt_chapter_description(${id} "${number}" "${folder}" "${CH_TITLE}" "${chapter_dir}" "${side}"
                         "${CH_EXERCISES}" "${CH_DEPENDS}" ${noisy})

  # On a solution build, check the untouched student side as well: it must
  # compile, link, and fail with "not implemented yet", never crash or hang.
  if(side STREQUAL "solutions" AND TARGET ${id}_public_tests)
    add_executable(${id}_public_tests_stub $<TARGET_OBJECTS:${id}_public_objects>)
    target_link_libraries(${id}_public_tests_stub PRIVATE ${id}_student rt_test_support)
    set_target_properties(${id}_public_tests_stub PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/stub")
    add_executable(${id}_stub $<TARGET_OBJECTS:${id}_program_objects>)
    target_link_libraries(${id}_stub PRIVATE ${id}_student)
    set_target_properties(${id}_stub PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/stub")

    add_test(NAME ${id}.stub.tests_fail_politely
             COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:${id}_public_tests_stub> -DEXPECT_EXIT=1
                     -DEXPECT_OUTPUT=not\ implemented\ yet -DEXPECT_NO_PASS=1 -P "${RT_STUB_CHECK_SCRIPT}")
    add_test(NAME ${id}.stub.program_fails_politely
             COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:${id}_stub> -DEXPECT_EXIT=3
                     -DEXPECT_OUTPUT=not\ implemented\ yet -DARGS=--out|${PROJECT_BINARY_DIR}/stub/${id}.png
                     -P "${RT_STUB_CHECK_SCRIPT}")
    set_tests_properties(${id}.stub.tests_fail_politely ${id}.stub.program_fails_politely
                         PROPERTIES LABELS "${id};stub" TIMEOUT 120)

    set(dependency_solution_libs "")
    foreach(dep IN LISTS CH_DEPENDS)
      list(APPEND dependency_solution_libs ch${dep}_solution)
    endforeach()
    rt_wrong_fixtures(${id} "${chapter_dir}" "${solution_dir}" "${CH_EXERCISES}" "${dependency_solution_libs}")
  endif()
endfunction()

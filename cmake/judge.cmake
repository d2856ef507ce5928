# rt_chapter_judge(): the chapter's judges and runner, for the autograder (tests/support/rpc/README.md
# follows one call through them; tools/grader/README.md, "Who decides pass or fail", says why).
# Called by rt_chapter() for every chapter that has an RPC table
# tests/support/rpc/chNN.cpp; it makes
#   chNN_runner          the chapter's exercise code (chNN_exercises: the student's in the grader's tree)
#                        and nothing else: it answers calls on a socket
#   chNN_public_judge    the public tests, with a forwarding stub for each exercise function instead of
#   chNN_hidden_judge    any student code; the earlier chapters it calls come from dependency_libs
# and writes rt_judges/chNN.json (their paths) for the grader.
#
# Adding a chapter: write tests/support/rpc/chNN.cpp (one RT_RPC_FUNCTION line and one forwarding stub
# per exercise function; a new struct in its arguments needs a fields() overload, see exact_bits.hpp; an
# object callback goes through RT_RPC_FORWARD_SERVED; tests/support/rpc/README.md, "Adding a chapter").
# Off by default in the sanitizer build and in a student's build (the kit): the grader configures its
# own tree with RT_JUDGE=ON, and there the judges would only compile the tests once more.
if(RT_SANITIZE OR RT_SIDE STREQUAL "student")
  option(RT_JUDGE "build each chapter's judges and runner (the autograder's)" OFF)
else()
  option(RT_JUDGE "build each chapter's judges and runner (the autograder's)" ON)
endif()

set(RT_RPC_DIR "${PROJECT_SOURCE_DIR}/tests/support/rpc")

if(RT_JUDGE)
  add_library(rt_rpc STATIC "${RT_RPC_DIR}/messages.cpp")
  target_include_directories(rt_rpc PUBLIC "${PROJECT_SOURCE_DIR}/tests/support")
  target_link_libraries(rt_rpc PUBLIC rt_common)
  add_library(rt_rpc_judge STATIC "${RT_RPC_DIR}/judge_side.cpp")
  target_link_libraries(rt_rpc_judge PUBLIC rt_rpc)
  # The mains, compiled once for every chapter: the judges' (doctest's implementation, the slowest file
  # of a judge), one for the public judges and one for the hidden ones, and the runners'.
  # EXCLUDE_FROM_ALL: built only for a judge that links them (a kit has no hidden judge).
  foreach(kind public hidden)
    add_library(rt_judge_main_${kind} OBJECT EXCLUDE_FROM_ALL "${RT_RPC_DIR}/judge_main.cpp")
    target_link_libraries(rt_judge_main_${kind} PRIVATE rt_rpc_judge doctest::doctest)
    # doctest's own machinery (options, reporters) is not what a test run spends its time on; unoptimised it
    # compiles in less than half the time (the tests themselves stay optimised).
    target_compile_options(rt_judge_main_${kind} PRIVATE -O0)
  endforeach()
  target_compile_definitions(rt_judge_main_public PRIVATE RT_JUDGE_PUBLIC)
  add_library(rt_rpc_runner_main OBJECT EXCLUDE_FROM_ALL "${RT_RPC_DIR}/runner_main.cpp")
  target_link_libraries(rt_rpc_runner_main PRIVATE rt_rpc)
endif()

function(rt_chapter_judge id chapter_dir depends dependency_libs)
  set(table "${RT_RPC_DIR}/${id}.cpp")
  if(NOT RT_JUDGE OR NOT EXISTS "${table}")
    return()
  endif()
  # The table, compiled once for each side.
  add_library(${id}_runner_table OBJECT "${table}")
  target_compile_definitions(${id}_runner_table PRIVATE RT_RPC_RUNNER RT_RPC_CHAPTER="${id}")
  target_include_directories(${id}_runner_table PRIVATE "$<TARGET_PROPERTY:${id}_student,INTERFACE_INCLUDE_DIRECTORIES>")
  target_link_libraries(${id}_runner_table PRIVATE rt_rpc)
  add_library(${id}_judge_table OBJECT "${table}")
  target_compile_definitions(${id}_judge_table PRIVATE RT_RPC_JUDGE RT_RPC_CHAPTER="${id}")
  target_include_directories(${id}_judge_table PRIVATE "$<TARGET_PROPERTY:${id}_student,INTERFACE_INCLUDE_DIRECTORIES>")
  target_link_libraries(${id}_judge_table PRIVATE rt_rpc)

  # Earlier chapters the tests call: the solutions' code when this build links them (in the judge, like
  # the tests themselves: instructor code), otherwise forwarded to the runner like the chapter's own
  # functions (a student kit: the judge then holds no student code either).
  set(runner_tables ${id}_runner_table)
  set(judge_dependencies "")
  foreach(dep IN LISTS depends)
    rt_chapter_side(${dep} dep_side)
    if(TARGET ch${dep}_solution AND ("ch${dep}_solution" IN_LIST dependency_libs OR dep_side STREQUAL "solutions"))
      list(APPEND judge_dependencies ch${dep}_solution)
    elseif(TARGET ch${dep}_judge_table)
      list(APPEND judge_dependencies ch${dep}_judge_table)
      list(APPEND runner_tables ch${dep}_runner_table)
    else()
      list(APPEND judge_dependencies ch${dep}_exercises)
    endif()
  endforeach()

  add_executable(${id}_runner)
  target_link_libraries(${id}_runner PRIVATE rt_rpc_runner_main ${runner_tables} ${id}_exercises rt_rpc)
  set_target_properties(${id}_runner PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/judge")

  set(json "  \"runner\": \"$<TARGET_FILE:${id}_runner>\"")
  foreach(kind public hidden)
    file(GLOB test_sources CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/tests/${kind}/${id}_*.cpp")
    if(NOT test_sources)
      continue()
    endif()
    set(target ${id}_${kind}_judge)
    add_executable(${target} $<TARGET_OBJECTS:${id}_${kind}_objects>)  # compiled once, shared with the tests
    target_include_directories(${target} PRIVATE "$<TARGET_PROPERTY:${id}_student,INTERFACE_INCLUDE_DIRECTORIES>")
    target_link_libraries(${target} PRIVATE rt_judge_main_${kind} ${id}_judge_table ${judge_dependencies} rt_rpc_judge
                                            doctest::doctest rt_common)
    set_target_properties(${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/judge")
    string(APPEND json ",\n  \"${kind}_judge\": \"$<TARGET_FILE:${target}>\"")
    # With the solutions on the runner's side, every test passes through the judge as it does directly:
    # the table forwards every function the tests call, and every value crosses unchanged.
    string(SUBSTRING "${id}" 2 2 number)
    rt_chapter_side(${number} side)
    if(side STREQUAL "solutions")
      add_test(NAME ${id}.judge.${kind} COMMAND ${target} --no-version)
      set_tests_properties(${id}.judge.${kind} PROPERTIES LABELS "${id};judge" TIMEOUT 300
                           ENVIRONMENT "RT_RUNNER=$<TARGET_FILE:${id}_runner>")
    endif()
  endforeach()
  file(GENERATE OUTPUT "${PROJECT_BINARY_DIR}/rt_judges/${id}.json" CONTENT "{\n${json}\n}\n")
endfunction()

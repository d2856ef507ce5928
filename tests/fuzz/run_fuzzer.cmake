# Builds the scene-file fuzzer with clang (libFuzzer, AddressSanitizer,
# UndefinedBehaviorSanitizer) and runs it for a bounded time on the corpus
# kept in tests/fuzz/corpus. New inputs go to a work folder in the build
# tree, so a test run never changes the repository; a crash leaves its input
# in WORK_DIR (crash-*, timeout-*, oom-*) and fails the test.
#   -DCLANGXX=clang++ -DSOURCE_DIR=<repo> -DWORK_DIR=<build dir> -DSECONDS=20
set(fuzzer "${WORK_DIR}/scene_fuzzer")
set(sources "${SOURCE_DIR}/tests/fuzz/scene_fuzz.cpp" "${SOURCE_DIR}/common/scene_file.cpp"
            "${SOURCE_DIR}/common/spd.cpp" "${SOURCE_DIR}/common/obj_mesh.cpp"
            "${SOURCE_DIR}/common/instances.cpp" "${SOURCE_DIR}/common/render.cpp"
            "${SOURCE_DIR}/common/big_array.cpp")
set(rebuild FALSE)
foreach(f IN LISTS sources ITEMS "${SOURCE_DIR}/common/scene_file.hpp" "${SOURCE_DIR}/common/scene.hpp"
                                 "${SOURCE_DIR}/common/camera.hpp" "${SOURCE_DIR}/common/shapes.hpp"
                                 "${SOURCE_DIR}/common/spd.hpp" "${SOURCE_DIR}/common/obj_mesh.hpp"
                                 "${SOURCE_DIR}/common/render.hpp")
  if(NOT EXISTS "${fuzzer}" OR "${f}" IS_NEWER_THAN "${fuzzer}")
    set(rebuild TRUE)
  endif()
endforeach()
if(rebuild)
  message("building ${fuzzer} with ${CLANGXX}")
  execute_process(COMMAND "${CLANGXX}" -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined
                          -fno-sanitize-recover=undefined -DTINYOBJLOADER_USE_DOUBLE -I "${SOURCE_DIR}" ${sources}
                          -ltinyobjloader_double -o "${fuzzer}"
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT status EQUAL 0)
    if(out MATCHES "clang_rt\\.fuzzer|fsanitize=fuzzer")
      message("scenes.fuzz skipped: this clang has no libFuzzer runtime (Debian: apt-get install libclang-rt-14-dev)\n${out}")
      return()
    endif()
    message(FATAL_ERROR "building the fuzzer failed:\n${out}")
  endif()
endif()
file(MAKE_DIRECTORY "${WORK_DIR}/corpus")
execute_process(COMMAND "${fuzzer}" -dict=${SOURCE_DIR}/tests/fuzz/scene.dict -max_total_time=${SECONDS}
                        -timeout=5 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix=${WORK_DIR}/
                        "${WORK_DIR}/corpus" "${SOURCE_DIR}/tests/fuzz/corpus"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
string(REGEX MATCH "stat::number_of_executed_units: *[0-9]+" runs "${out}")
message("${runs}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the fuzzer found an input that crashes the scene reader "
                      "(saved in ${WORK_DIR}, see crash-*/timeout-*/oom-*):\n${out}")
endif()

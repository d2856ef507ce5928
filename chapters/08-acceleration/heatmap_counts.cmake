# heatmap_counts.cmake — ch08's --heatmap counts what the traversal did:
#   one sphere around the camera: every primary ray starts inside the only
#     box (the root, a leaf), so each pixel opens 1 box and asks 1 object;
#   one sphere behind the camera: no ray enters its box, 0 and 0;
#   brute force asks every object for every pixel: 1 here, and 11 for the
#     sphereflake at level 1 (10 spheres and the ground plane), where the
#     tree asks fewer.
# Run by ctest: cmake -DPROGRAM=... -DOUT=dir [-DRT_RENDER=1] -P heatmap_counts.cmake
# (with RT_RENDER, PROGRAM is rt-render, which takes the scene file as its
# argument and counts on its general path: the one-sphere cases only).
file(MAKE_DIRECTORY "${OUT}")
function(run_heatmap name expected)
  execute_process(COMMAND "${PROGRAM}" ${ARGN} --heatmap --width 24 --height 16 -o "${OUT}/${name}.png"
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: the program failed (${rc}):\n${out}${err}")
  endif()
  if(NOT EXISTS "${OUT}/${name}-heatmap.png")
    message(FATAL_ERROR "${name}: no ${OUT}/${name}-heatmap.png written:\n${out}")
  endif()
  foreach(line IN LISTS expected)
    string(FIND "${out}" "${line}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "${name}: expected the line\n  ${line}\nin the output:\n${out}")
    endif()
  endforeach()
  message(STATUS "${name}: counts as expected")
endfunction()

foreach(where around behind)
  if(where STREQUAL "around")
    set(center "[0, 0, 0]")
  else()
    set(center "[0, 0, 20]")
  endif()
  file(WRITE "${OUT}/one-sphere-${where}.json" "{
  \"camera\": {\"eye\": [0, 0, 0], \"look_at\": [0, 0, -1], \"fov\": 60, \"width\": 24, \"height\": 16},
  \"background\": [0.2, 0.2, 0.2],
  \"materials\": [{\"diffuse\": [0.9, 0.1, 0.1]}],
  \"spheres\": [{\"center\": ${center}, \"radius\": 5}]
}
")
endforeach()
if(RT_RENDER)
  set(scene_option "")
else()
  set(scene_option "--scene")
endif()
run_heatmap(one-sphere-around
  "tree: boxes opened: min 1, mean 1.00, max 1 per pixel;tree: objects asked: min 1, mean 1.00, max 1 per pixel;brute force: objects asked: min 1, mean 1.00, max 1 per pixel"
  ${scene_option} "${OUT}/one-sphere-around.json")
run_heatmap(one-sphere-behind
  "tree: boxes opened: min 0, mean 0.00, max 0 per pixel;tree: objects asked: min 0, mean 0.00, max 0 per pixel;brute force: objects asked: min 1, mean 1.00, max 1 per pixel"
  ${scene_option} "${OUT}/one-sphere-behind.json")
if(RT_RENDER)
  return()
endif()
run_heatmap(level-1 "brute force: objects asked: min 11, mean 11.00, max 11 per pixel" --level 1)
# The tree asks at least the ground plane (outside the tree) and fewer than all 11 somewhere.
execute_process(COMMAND "${PROGRAM}" --level 1 --heatmap --width 24 --height 16 -o "${OUT}/level-1.png"
                OUTPUT_VARIABLE out)
string(REGEX MATCH "tree: objects asked: min ([0-9]+), mean [0-9.]+, max ([0-9]+)" _ "${out}")
if(NOT CMAKE_MATCH_1 OR CMAKE_MATCH_1 LESS 1 OR NOT CMAKE_MATCH_1 LESS 11)
  message(FATAL_ERROR "level-1: the tree's fewest objects asked per pixel should be 1 to 10:\n${out}")
endif()

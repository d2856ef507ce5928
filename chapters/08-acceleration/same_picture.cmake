# cmake -DTREE=ch08-program -DBRUTE=ch06-program -DPRECISION=float|double -DSCENE=file.json -DOUT=dir -P this-file
#
# Draws one scene file with chapter 08's program (through the BVH) and with
# chapter 06's (chapter 03's loop over every object), and checks that the two
# PNG files are identical: the same object and the same t for every ray gives
# the same bytes.
file(MAKE_DIRECTORY "${OUT}")
foreach(which TREE BRUTE)
  execute_process(COMMAND "${${which}}" --scene "${SCENE}" --precision ${PRECISION} --width 160 --height 160
                          --out "${OUT}/${which}-${PRECISION}.png"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${${which}} failed (exit ${rc}):\n${out}${err}")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${OUT}/TREE-${PRECISION}.png" "${OUT}/BRUTE-${PRECISION}.png"
                RESULT_VARIABLE differ)
if(differ)
  message(FATAL_ERROR "the picture drawn through the tree differs from brute force's "
                      "(${OUT}/TREE-${PRECISION}.png, ${OUT}/BRUTE-${PRECISION}.png)")
endif()
message(STATUS "${PRECISION}: the tree's picture is brute force's, byte for byte")

# Every third-party library comes from a Debian package; none is downloaded
# or copied into this repository. A missing one stops configuration with the
# name of the package to install (tools/setup installs them all).

function(rt_require_package found what package)
  if(NOT ${found})
    message(FATAL_ERROR "${what} was not found. Install the Debian package '${package}' "
                        "(sudo apt-get install ${package}), or run tools/setup which installs everything.")
  endif()
endfunction()

find_package(glm CONFIG QUIET)
rt_require_package(glm_FOUND "GLM (the vector math library)" libglm-dev)

find_package(doctest CONFIG QUIET)
rt_require_package(doctest_FOUND "doctest (the unit-test framework)" doctest-dev)

find_package(CLI11 CONFIG QUIET)
rt_require_package(CLI11_FOUND "CLI11 (command-line parsing)" libcli11-dev)

find_path(STB_INCLUDE_DIR stb/stb_image_write.h)
find_library(STB_LIBRARY NAMES stb)
if(STB_INCLUDE_DIR AND STB_LIBRARY)
  set(STB_FOUND TRUE)
endif()
rt_require_package(STB_FOUND "stb_image and stb_image_write" libstb-dev)
add_library(rt_stb INTERFACE)
target_include_directories(rt_stb SYSTEM INTERFACE "${STB_INCLUDE_DIR}")
target_link_libraries(rt_stb INTERFACE "${STB_LIBRARY}")

# GLM's own target name differs between versions.
if(TARGET glm::glm)
  set(RT_GLM_TARGET glm::glm)
else()
  set(RT_GLM_TARGET glm)
endif()

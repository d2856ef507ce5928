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

# stb and MPFR ship no CMake package, but Debian gives both a pkg-config
# file: that is how they are found (pkg-config itself is Debian's pkgconf).
find_package(PkgConfig QUIET)
rt_require_package(PKG_CONFIG_FOUND "pkg-config (finds stb and MPFR)" pkgconf)

pkg_check_modules(STB QUIET IMPORTED_TARGET stb)
rt_require_package(STB_FOUND "stb_image and stb_image_write" libstb-dev)
add_library(rt_stb INTERFACE)
target_link_libraries(rt_stb INTERFACE PkgConfig::STB)

# MPFR is needed only by the formulation study and the numerics tests
# (tools/study/CMakeLists.txt requires it there): PkgConfig::MPFR when found.
pkg_check_modules(MPFR QUIET IMPORTED_TARGET mpfr)

# GLM's own target name differs between versions.
if(TARGET glm::glm)
  set(RT_GLM_TARGET glm::glm)
else()
  set(RT_GLM_TARGET glm)
endif()

# OBJ meshes (common/obj_mesh.hpp), read in double precision.
find_package(tinyobjloader CONFIG QUIET)
rt_require_package(tinyobjloader_FOUND "tinyobjloader (Wavefront OBJ meshes)" libtinyobjloader-dev)

# Fails when a file of render/ includes a sim/ header other than the plain data and geometry it
cmake_minimum_required(VERSION 3.25)
# may read: the snapshot, the scene description (with the settings of its fields), the mesh and
# the primitive tessellations, the view descriptions and the assert macro. World, haptic loop, Bullet glue: never.
# Run by ctest: cmake -DRENDER_DIR=<repo>/render -P check_includes.cmake
set(allowed
  "sim/snapshot.hpp" "sim/scene_desc.hpp" "sim/settings.hpp" "sim/patch_settings.hpp" "sim/mesh.hpp"
  "sim/primitives.hpp" "sim/assert.hpp" "sim/view_desc.hpp")
file(GLOB sources "${RENDER_DIR}/*.hpp" "${RENDER_DIR}/*.cpp")
set(bad "")
foreach(source IN LISTS sources)
  file(STRINGS "${source}" includes REGEX "^#include \"sim/")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" header "${line}")
    if(NOT header IN_LIST allowed)
      list(APPEND bad "${source}: ${header}")
    endif()
  endforeach()
endforeach()
if(bad)
  list(JOIN bad "\n  " text)
  message(FATAL_ERROR "render/ may include only ${allowed} from sim/; found:\n  ${text}")
endif()
list(LENGTH sources count)
message(STATUS "render/: ${count} files include only snapshot and description headers of sim/")

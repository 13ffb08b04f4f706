# godfinger as a library, used as an outside project would use it:
#   cmake -DSOURCE_DIR=<source> -DBINARY_DIR=<build> -DWORK=<scratch folder> -P embed_test.cmake
# 1. `cmake --install` the build into a temporary prefix; examples/embed (its own CMakeLists.txt)
#    configured with CMAKE_PREFIX_PATH at that prefix finds godfinger::sim, builds and runs: the
#    pinch is held with god-fingers and swings once they are god-objects.
# 2. The same program compiled from the installed pkg-config file (static libraries).
# 3. A physics-only configuration (no scene, render, app, tests or benchmarks) succeeds with the
#    packages it must not need made unfindable.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(prefix "${WORK}/prefix")

function(run label)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE failed OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(failed)
    message(FATAL_ERROR "${label} failed (${failed}):\n${out}\n${err}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

# The program's report: held while god-fingers (tilt under 2 degrees at 3.5 s, lifted), swinging
# after (tilt over 2 degrees at 5 s).
function(check_embed label text)
  foreach(needed "switched to god-objects" "t = 3.50 s" "t = 5.00 s")
    string(FIND "${text}" "${needed}" at)
    if(at LESS 0)
      message(FATAL_ERROR "${label}: no '${needed}' in its output:\n${text}")
    endif()
  endforeach()
  string(REGEX MATCH "t = 3\\.50 s[^\n]*height ([0-9.]+) m, tilt +([0-9.]+) deg" held "${text}")
  set(height "${CMAKE_MATCH_1}")
  set(tilt_held "${CMAKE_MATCH_2}")
  string(REGEX MATCH "t = 5\\.00 s[^\n]*tilt +([0-9.]+) deg" late "${text}")
  set(tilt_late "${CMAKE_MATCH_1}")
  if(height LESS 0.09 OR tilt_held GREATER 2.0 OR NOT tilt_late GREATER 2.0)
    message(FATAL_ERROR "${label}: expected the cylinder lifted (> 0.09 m) and held (< 2 deg) at 3.5 s, swinging "
                        "(> 2 deg) at 5 s; got ${height} m, ${tilt_held} deg, ${tilt_late} deg:\n${text}")
  endif()
endfunction()

run("install" "${CMAKE_COMMAND}" --install "${BINARY_DIR}" --prefix "${prefix}")
foreach(installed lib/libgodfinger_sim.a lib/cmake/godfinger/godfingerConfig.cmake lib/pkgconfig/godfinger-sim.pc
        include/godfinger/sim/world/world.hpp include/godfinger/sim/math.hpp share/godfinger/scenes/fig8-pinch-oscillation.toml)
  if(NOT EXISTS "${prefix}/${installed}")
    message(FATAL_ERROR "not installed: ${installed}")
  endif()
endforeach()
# The internal headers (sim/CMakeLists.txt GF_SIM_INTERNAL_HEADERS: Bullet's types) stay behind.
foreach(internal contact/patch_friction.hpp world/world_impl.hpp world/body_factory.hpp)
  if(EXISTS "${prefix}/include/godfinger/sim/${internal}")
    message(FATAL_ERROR "an internal header was installed: sim/${internal}")
  endif()
endforeach()

run("configure the example" "${CMAKE_COMMAND}" -S "${SOURCE_DIR}/examples/embed" -B "${WORK}/embed-build" -G Ninja
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}")
run("build the example" "${CMAKE_COMMAND}" --build "${WORK}/embed-build")
run("run the example" "${WORK}/embed-build/embed")
check_embed("examples/embed (CMake package)" "${output}")

set(ENV{PKG_CONFIG_PATH} "${prefix}/lib/pkgconfig")
run("pkg-config" pkg-config --static --cflags --libs godfinger-sim)
string(STRIP "${output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run("compile with pkg-config" c++ -std=c++20 -O1 "${SOURCE_DIR}/examples/embed/main.cpp" -o "${WORK}/embed-pc" ${flags})
run("run the pkg-config build" "${WORK}/embed-pc")
check_embed("examples/embed (pkg-config)" "${output}")

run("physics-only configure" "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK}/physics-only" -G Ninja
    -DGF_BUILD_SCENE=OFF -DGF_BUILD_RENDER=OFF -DGF_BUILD_APP=OFF -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_CLI11=ON -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_tomlplusplus=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON)
message(STATUS "installed, built and ran examples/embed (CMake package and pkg-config); physics-only configure ok")

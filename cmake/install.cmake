# `cmake --install BUILD --prefix P` installs, for each library built:
#   P/lib/libgodfinger_{sim,scene,render}.a        godfinger::sim, ::scene, ::render
#   P/include/godfinger/{sim,app/scene,render}/**/*.hpp  the public headers (not sim/'s internal ones)
#   P/lib/cmake/godfinger/                         find_package(godfinger [COMPONENTS ...])
#   P/lib/pkgconfig/godfinger-{sim,scene,render}.pc
#   P/share/godfinger/                             bundled scenes, studies, meshes, hard cases
# and, with GF_BUILD_APP, P/bin/godfinger and, for device authors, P/share/doc/godfinger/
# device-protocol.md and P/share/doc/godfinger/examples/device-udp/client.py. Each library has an export set of its own, so an
# application asking for sim alone needs only sim's dependencies.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
set(GF_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/godfinger)
set(GF_INCLUDE_DIR ${CMAKE_INSTALL_INCLUDEDIR}/godfinger)

# Public headers: a user includes them as "sim/world/world.hpp" with P/include/godfinger on the path.
# sim/'s families keep their folders (sim/world/world.hpp); its internal headers stay behind.
file(GLOB_RECURSE GF_SIM_HEADERS RELATIVE ${PROJECT_SOURCE_DIR}/sim ${PROJECT_SOURCE_DIR}/sim/*.hpp)
list(REMOVE_ITEM GF_SIM_HEADERS ${GF_SIM_INTERNAL_HEADERS})
foreach(header IN LISTS GF_SIM_HEADERS)
  cmake_path(GET header PARENT_PATH folder)
  install(FILES ${PROJECT_SOURCE_DIR}/sim/${header} DESTINATION ${GF_INCLUDE_DIR}/sim/${folder} COMPONENT dev)
endforeach()
set(GF_INSTALLED_COMPONENTS sim)
install(TARGETS gf_sim EXPORT godfinger-sim ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
install(EXPORT godfinger-sim NAMESPACE godfinger:: FILE godfinger-sim-targets.cmake DESTINATION ${GF_CMAKE_DIR}
        COMPONENT dev)
if(GF_BUILD_SCENE)
  list(APPEND GF_INSTALLED_COMPONENTS scene)
  # The scene library's public headers (not its internal sections.hpp and toml_reader.hpp).
  set(GF_SCENE_HEADERS input_error scene_file session_desc expect_desc data_folder schema)
  list(TRANSFORM GF_SCENE_HEADERS PREPEND ${PROJECT_SOURCE_DIR}/app/scene/)
  list(TRANSFORM GF_SCENE_HEADERS APPEND .hpp)
  install(FILES ${GF_SCENE_HEADERS} DESTINATION ${GF_INCLUDE_DIR}/app/scene COMPONENT dev)
  # The view descriptions the scene reader fills (header-only; installed with render/ too).
  install(FILES ${PROJECT_SOURCE_DIR}/render/view/view_desc.hpp DESTINATION ${GF_INCLUDE_DIR}/render/view COMPONENT dev)
  install(TARGETS gf_scene EXPORT godfinger-scene ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
  install(EXPORT godfinger-scene NAMESPACE godfinger:: FILE godfinger-scene-targets.cmake DESTINATION ${GF_CMAKE_DIR}
          COMPONENT dev)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/assets/ DESTINATION ${CMAKE_INSTALL_DATADIR}/godfinger)
endif()
if(GF_BUILD_RENDER)
  list(APPEND GF_INSTALLED_COMPONENTS render)
  file(GLOB_RECURSE GF_RENDER_HEADERS RELATIVE ${PROJECT_SOURCE_DIR}/render ${PROJECT_SOURCE_DIR}/render/*.hpp)
  list(REMOVE_ITEM GF_RENDER_HEADERS gl/gl.hpp gl/shaders.hpp)  # GL declarations and shader sources
  foreach(header IN LISTS GF_RENDER_HEADERS)
    cmake_path(GET header PARENT_PATH folder)
    install(FILES ${PROJECT_SOURCE_DIR}/render/${header} DESTINATION ${GF_INCLUDE_DIR}/render/${folder} COMPONENT dev)
  endforeach()
  install(TARGETS gf_render EXPORT godfinger-render ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
  install(EXPORT godfinger-render NAMESPACE godfinger:: FILE godfinger-render-targets.cmake DESTINATION ${GF_CMAKE_DIR}
          COMPONENT dev)
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/godfingerConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/godfingerConfig.cmake INSTALL_DESTINATION ${GF_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/godfingerConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/godfingerConfig.cmake ${PROJECT_BINARY_DIR}/godfingerConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/godfingerDependencies.cmake DESTINATION ${GF_CMAKE_DIR} COMPONENT dev)

# pkg-config: static libraries, so `pkg-config --static --libs godfinger-sim` lists what they link.
# The files find the prefix from where they are (relocatable).
file(RELATIVE_PATH GF_PC_TO_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
foreach(component IN LISTS GF_INSTALLED_COMPONENTS)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/godfinger-${component}.pc.in
                 ${PROJECT_BINARY_DIR}/pkgconfig/godfinger-${component}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/pkgconfig/godfinger-${component}.pc
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)
endforeach()

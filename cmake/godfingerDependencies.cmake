# The Debian packages each godfinger library needs, found for the components listed in
# godfinger_FIND_COMPONENTS (sim, scene, render). Included by the top-level CMakeLists.txt and by
# an installed package's godfingerConfig.cmake, so an application finds what the static
# libraries link. Every dependency is REQUIRED: a missing one stops with its package's name.
find_package(PkgConfig REQUIRED)
# sim: Bullet in double precision (the walk, the coupling and the solver run in double), Eigen
# (the public math types), assimp (mesh files).
pkg_check_modules(BULLET REQUIRED IMPORTED_TARGET bullet-float64)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(assimp REQUIRED)
if(NOT GF_GIMPACT_UTILS)
  find_library(GF_GIMPACT_UTILS NAMES GIMPACTUtils-float64 REQUIRED)
endif()
if(NOT GF_HACD)
  find_library(GF_HACD NAMES HACD-float64 REQUIRED)
endif()
if("scene" IN_LIST godfinger_FIND_COMPONENTS)
  find_package(tomlplusplus REQUIRED)
  find_package(nlohmann_json REQUIRED)
endif()
if("render" IN_LIST godfinger_FIND_COMPONENTS)
  # OSMesa exports the whole GL API: linking it (and not libGL) resolves every gl* call.
  pkg_check_modules(OSMESA REQUIRED IMPORTED_TARGET osmesa)
  # PNG frames are deflated by libdeflate (zlib streams, level 1 for frames).
  pkg_check_modules(DEFLATE REQUIRED IMPORTED_TARGET libdeflate)
  # A held sequence's frames are deflated band by band by zlib (flushed parts of one stream).
  pkg_check_modules(ZLIB REQUIRED IMPORTED_TARGET zlib)
  pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
  # The browser view's frames are JPEGs encoded by libjpeg-turbo.
  pkg_check_modules(TURBOJPEG REQUIRED IMPORTED_TARGET libturbojpeg)
endif()

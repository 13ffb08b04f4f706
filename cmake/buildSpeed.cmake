# How the build spends less time: unity builds of the glue, ccache when it is installed.
# docs/testing.md ("Build time") has the measurements behind each choice.
#
# Unity builds (GF_UNITY_BUILD, on by default): the files of one folder of app/ and of tests/
# compile as one translation unit, so CLI11, nlohmann_json, GoogleTest and the app headers are
# parsed and their templates instantiated once per folder instead of once per file; app/ was two
# thirds of a release build's compile time for that reason. sim/ and render/ stay one unit per
# file: their time is their own code generation, and an edit there recompiles one file.
option(GF_UNITY_BUILD "Compile each folder of app/ and tests/ as one translation unit (unity build)" ON)

# gf_unity_by_folder(TARGET [BATCH n]): TARGET's .cpp files compile as one unit per folder, at most
# n files a unit (default: the whole folder). A file that must stay alone sets
# SKIP_UNITY_BUILD_INCLUSION itself.
function(gf_unity_by_folder target)
  if(NOT GF_UNITY_BUILD)
    return()
  endif()
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "BATCH" "")
  get_target_property(sources ${target} SOURCES)
  get_target_property(source_dir ${target} SOURCE_DIR)
  foreach(source IN LISTS sources)
    if(NOT source MATCHES "\\.cpp$")
      continue()
    endif()
    cmake_path(ABSOLUTE_PATH source BASE_DIRECTORY ${source_dir} OUTPUT_VARIABLE path)
    cmake_path(GET path PARENT_PATH folder)
    cmake_path(GET folder FILENAME group)
    # Batches of at most BATCH files within a folder: group, group_2, ...
    if(arg_BATCH)
      string(MAKE_C_IDENTIFIER "${group}" key)
      if(NOT DEFINED count_${key})
        set(count_${key} 0)
      endif()
      math(EXPR batch "${count_${key}} / ${arg_BATCH}")
      math(EXPR count_${key} "${count_${key}} + 1")
      if(batch GREATER 0)
        string(APPEND group "_${batch}")
      endif()
    endif()
    set_property(SOURCE ${path} TARGET_DIRECTORY ${target} PROPERTY UNITY_GROUP "${target}_${group}")
  endforeach()
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_MODE GROUP)
endfunction()

# ccache, where installed (scripts/test installs it): a rebuild of the same sources with the same
# flags in any clone on this machine takes the objects from the cache. Paths under the source tree
# are hashed relative to it and the working directory is not hashed, so two clones share entries.
option(GF_CCACHE "Compile through ccache when it is installed" ON)
if(GF_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(GF_CCACHE_PROGRAM ccache)
  if(GF_CCACHE_PROGRAM)
    set(CMAKE_CXX_COMPILER_LAUNCHER env CCACHE_BASEDIR=${PROJECT_SOURCE_DIR} CCACHE_NOHASHDIR=1
        CCACHE_SLOPPINESS=include_file_ctime,include_file_mtime,pch_defines,time_macros ${GF_CCACHE_PROGRAM})
  endif()
endif()

# Precompiled headers (GF_PCH): the Eigen, Bullet and standard headers nearly every file of sim/
# and render/ includes, parsed once per library instead of once per file.
option(GF_PCH "Precompile the Eigen, Bullet and standard headers of gf_sim and gf_render" ON)

# gf_precompile(TARGET HEADER...): TARGET's files compile against one precompiled HEADER list.
function(gf_precompile target)
  if(GF_PCH)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()

# ctest `package_consumer`: checks the two ways an application consumes the library, with the tiny
# project in tests/package/consumer/ (which links only DEME::deme):
#   1. `cmake --install` of the already-built library into a temporary prefix, then
#      find_package(DEME REQUIRED) with CMAKE_PREFIX_PATH pointing there;
#   2. add_subdirectory(<source tree> deme-build) with the subproject's tests/demos/bench off.
# Each consumer is configured, built (Release, -j2) and run; any failure fails the test.
#
#   cmake -DDEME_BUILD_DIR=<outer build> -DDEME_SOURCE_DIR=<repo> -DWORK_DIR=<scratch dir>
#         [-DDEME_GENERATOR=<generator>] [-DDEME_MAKE_PROGRAM=<make/ninja>]
#         [-DDEME_CXX_COMPILER=<c++>] [-DDEME_CONFIG=<config>] -P package_test.cmake
cmake_minimum_required(VERSION 3.20)

foreach(var DEME_BUILD_DIR DEME_SOURCE_DIR WORK_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "package_test.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT DEME_CONFIG)
  set(DEME_CONFIG Release)
endif()

set(consumer_src ${DEME_SOURCE_DIR}/tests/package/consumer)
set(prefix ${WORK_DIR}/prefix)

# A clean scratch area each run.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# Builds started from inside `make test` must not join the outer make's job server.
unset(ENV{MAKEFLAGS})
unset(ENV{MFLAGS})
unset(ENV{MAKELEVEL})
# Nothing but the temporary prefix may satisfy find_package(DEME).
unset(ENV{DEME_DIR})
unset(ENV{DEME_ROOT})
unset(ENV{CMAKE_PREFIX_PATH})

# Generator, make program and compiler of the outer build.
set(gen_args)
if(DEME_GENERATOR)
  list(APPEND gen_args -G ${DEME_GENERATOR})
endif()
if(DEME_MAKE_PROGRAM)
  list(APPEND gen_args -DCMAKE_MAKE_PROGRAM=${DEME_MAKE_PROGRAM})
endif()
if(DEME_CXX_COMPILER)
  list(APPEND gen_args -DCMAKE_CXX_COMPILER=${DEME_CXX_COMPILER})
endif()

string(TIMESTAMP t_start "%s")

# run(<label> <log name> COMMAND...): runs a command, keeps its output in WORK_DIR/<log name>.log,
# prints it and stops the test if the command fails.
function(run label log)
  string(TIMESTAMP t0 "%s")
  execute_process(COMMAND ${ARGN}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  string(TIMESTAMP t1 "%s")
  math(EXPR dt "${t1} - ${t0}")
  file(WRITE ${WORK_DIR}/${log}.log "${out}")
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message("${out}")
    message(FATAL_ERROR "package_consumer: ${label} failed (${rc}) after ${dt} s\n  command: ${cmd}\n  log: ${WORK_DIR}/${log}.log")
  endif()
  message(STATUS "${label}: ok (${dt} s)")
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

# find_app(<var> <build dir>): the consumer executable (single- or multi-config layout).
function(find_app var dir)
  foreach(candidate ${dir}/app ${dir}/Release/app)
    if(EXISTS ${candidate} AND NOT IS_DIRECTORY ${candidate})
      set(${var} ${candidate} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  message(FATAL_ERROR "package_consumer: no app executable in ${dir}")
endfunction()

# ---- 1. installed package + find_package(DEME)
run("install into ${prefix}" install
  ${CMAKE_COMMAND} --install ${DEME_BUILD_DIR} --prefix ${prefix} --config ${DEME_CONFIG})

# The installed package: the umbrella header, the config files, and no absolute path into the
# source or build tree in the exported targets (the package must be relocatable).
if(NOT EXISTS ${prefix}/include/deme/deme.h)
  message(FATAL_ERROR "package_consumer: include/deme/deme.h not installed")
endif()
file(GLOB_RECURSE config_files ${prefix}/*/DEMEConfig.cmake)
file(GLOB_RECURSE version_files ${prefix}/*/DEMEConfigVersion.cmake)
file(GLOB_RECURSE target_files ${prefix}/*/DEMETargets*.cmake)
if(NOT config_files OR NOT version_files OR NOT target_files)
  message(FATAL_ERROR "package_consumer: DEMEConfig.cmake, DEMEConfigVersion.cmake or DEMETargets*.cmake not installed")
endif()
foreach(f ${config_files} ${target_files})
  file(READ ${f} text)
  foreach(dir ${DEME_SOURCE_DIR} ${DEME_BUILD_DIR})
    string(FIND "${text}" "${dir}/" pos)
    if(NOT pos EQUAL -1)
      message(FATAL_ERROR "package_consumer: ${f} refers to ${dir}; the installed package is not relocatable")
    endif()
  endforeach()
endforeach()

set(find_build ${WORK_DIR}/find_package)
run("configure consumer (find_package)" find_configure
  ${CMAKE_COMMAND} -S ${consumer_src} -B ${find_build} ${gen_args}
  -DCMAKE_BUILD_TYPE=Release
  -DCMAKE_PREFIX_PATH=${prefix}
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
  -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
# find_package must have found the temporary prefix, not some other DEME.
file(STRINGS ${find_build}/CMakeCache.txt deme_dir_line REGEX "^DEME_DIR:")
string(REGEX REPLACE "^DEME_DIR:[A-Z]+=" "" deme_dir "${deme_dir_line}")
file(REAL_PATH "${prefix}" real_prefix)
if(NOT deme_dir)
  message(FATAL_ERROR "package_consumer: DEME_DIR not set by find_package")
endif()
file(REAL_PATH "${deme_dir}" real_deme_dir)
string(FIND "${real_deme_dir}" "${real_prefix}/" pos)
if(NOT pos EQUAL 0)
  message(FATAL_ERROR "package_consumer: find_package(DEME) used ${deme_dir}, not the package installed in ${prefix}")
endif()
run("build consumer (find_package)" find_build
  ${CMAKE_COMMAND} --build ${find_build} --config Release -j 2)
find_app(find_app ${find_build})
run("run consumer (find_package)" find_run ${find_app})
message(STATUS "${run_output}")

# ---- 2. add_subdirectory(<source tree>)
set(sub_build ${WORK_DIR}/add_subdirectory)
run("configure consumer (add_subdirectory)" sub_configure
  ${CMAKE_COMMAND} -S ${consumer_src} -B ${sub_build} ${gen_args}
  -DCMAKE_BUILD_TYPE=Release
  -DDEME_SOURCE_DIR=${DEME_SOURCE_DIR}
  -DDEME_BUILD_TESTS=OFF -DDEME_BUILD_DEMOS=OFF -DDEME_BUILD_BENCH=OFF
  -DDEME_NATIVE_ARCH=OFF)
run("build consumer (add_subdirectory)" sub_build
  ${CMAKE_COMMAND} --build ${sub_build} --config Release -j 2)
find_app(sub_app ${sub_build})
run("run consumer (add_subdirectory)" sub_run ${sub_app})
message(STATUS "${run_output}")

string(TIMESTAMP t_end "%s")
math(EXPR total "${t_end} - ${t_start}")
message(STATUS "package_consumer: both ways passed (${total} s)")

# The install-and-consume test, run by ctest as `cmake -P` with:
#   BUILD_DIR     the build folder of the running ctest (its libraries are what gets installed)
#   SOURCE_DIR    the repository (the example and the scene)
#   WORK_DIR      a scratch folder, emptied first: WORK_DIR/prefix and WORK_DIR/example
#   CXX_COMPILER  BUILD_TYPE  the build's compiler and build type, which the consumer reuses (a
#                 sanitizer build's libraries need the same compiler's runtimes)
# Steps: `cmake --install BUILD_DIR --prefix WORK_DIR/prefix`; the prefix holds graspcd::core,
# graspcd::io, graspcd::mujoco and bin/graspcd, and no CGAL library; the standalone project
# examples/nonconvex_contacts is configured against the prefix alone (CMAKE_PREFIX_PATH) with
# find_package(graspcd 0.4), which accepts this build's later 0.x (SameMajorVersion), built, and
# run on mjcf/example1.xml: its fingers fall onto the cup, so graspcd must serve calls and hand
# contacts to MuJoCo. A missing scene must be one line on stderr and exit code 2.
cmake_minimum_required(VERSION 3.25)
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR CXX_COMPILER BUILD_TYPE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_consume.cmake: -D${var}=... is required")
  endif()
endforeach()

function(run_checked what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()

set(prefix "${WORK_DIR}/prefix")
set(example "${WORK_DIR}/example")
file(REMOVE_RECURSE "${WORK_DIR}")

# 1. Install the build into a fresh prefix.
run_checked("cmake --install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")

# 2. What was installed: the three libraries, the executable, the headers, the package; no CGAL,
# no study, no grasp experiment, nothing named "bridge" (the 0.1 include path include/graspcd/bridge,
# removed in 0.3, and the 0.2 namespace's alias header, removed in 0.5). (The library folder is
# GNUInstallDirs' CMAKE_INSTALL_LIBDIR: lib, or lib/<multiarch> for a /usr prefix.)
file(GLOB_RECURSE config_file "${prefix}/graspcdConfig.cmake")
if(NOT config_file)
  message(FATAL_ERROR "no graspcdConfig.cmake under ${prefix}")
endif()
get_filename_component(package_dir "${config_file}" DIRECTORY)
get_filename_component(libdir "${package_dir}/../.." ABSOLUTE)
foreach(f ${libdir}/libgraspcd_core.a ${libdir}/libgraspcd_io.a ${libdir}/libgraspcd_mujoco.a
          ${package_dir}/graspcdConfigVersion.cmake ${package_dir}/graspcdTargets.cmake
          ${prefix}/bin/graspcd
          ${prefix}/include/graspcd/core/obb_tree.h ${prefix}/include/graspcd/io/mesh_io.h
          ${prefix}/include/graspcd/mujoco/registry.h
          ${prefix}/include/graspcd/mujoco/nonconvex_contacts.h)
  if(NOT EXISTS "${f}")
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
file(GLOB_RECURSE installed RELATIVE "${prefix}" "${prefix}/*")
foreach(f ${installed})
  if(f MATCHES "exact|study|grasp/|graspcd_grasp|fcl|bridge")
    message(FATAL_ERROR "installed but must not be: ${f}")
  endif()
endforeach()
file(GLOB target_files "${package_dir}/*.cmake")
foreach(f ${target_files})
  file(READ "${f}" text)
  if(text MATCHES "CGAL|graspcd_exact|nlohmann")
    message(FATAL_ERROR "${f} refers to ${CMAKE_MATCH_0}")
  endif()
endforeach()

# 3. Configure and build the example against the prefix only.
run_checked("configuring the example" ${CMAKE_COMMAND}
  -S "${SOURCE_DIR}/examples/nonconvex_contacts" -B "${example}"
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=${BUILD_TYPE}
  -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
file(STRINGS "${example}/CMakeCache.txt" graspcd_dir REGEX "^graspcd_DIR:")
if(NOT graspcd_dir STREQUAL "graspcd_DIR:PATH=${package_dir}")
  message(FATAL_ERROR "the example found graspcd elsewhere: ${graspcd_dir}")
endif()
run_checked("building the example" ${CMAKE_COMMAND} --build "${example}")
# The example's second program reads a mesh with graspcd::io and builds its tree (graspcd::core).
if(NOT EXISTS "${example}/mesh_tree")
  message(FATAL_ERROR "the example's mesh_tree program was not built")
endif()
run_checked("the mesh_tree program" "${example}/mesh_tree" "${SOURCE_DIR}/mjcf/meshes/cup.obj")
if(NOT run_out MATCHES "faces [1-9][0-9]* boxes [1-9][0-9]*")
  message(FATAL_ERROR "mesh_tree printed no face and box count:\n${run_out}")
endif()
# The installed executable runs from the prefix.
run_checked("the installed graspcd" "${prefix}/bin/graspcd" --version)
if(NOT run_out MATCHES "^graspcd ")
  message(FATAL_ERROR "the installed graspcd --version printed:\n${run_out}")
endif()

# 4. Run it on a shipped scene: served calls and graspcd's contacts must both occur.
set(exe "${example}/nonconvex_contacts")
run_checked("the example on example1.xml" "${exe}" "${SOURCE_DIR}/mjcf/example1.xml" 1000)
message(STATUS "example output:\n${run_out}")
if(NOT run_out MATCHES "summary steps 1000 method sat served_pairs ([0-9]+) served_calls ([0-9]+) graspcd_contacts ([0-9]+) max_ncon ([0-9]+)")
  message(FATAL_ERROR "no summary line in the example's output")
endif()
set(pairs ${CMAKE_MATCH_1})
set(calls ${CMAKE_MATCH_2})
set(served ${CMAKE_MATCH_3})
set(max_ncon ${CMAKE_MATCH_4})
if(pairs EQUAL 0 OR calls EQUAL 0 OR served EQUAL 0 OR max_ncon EQUAL 0)
  message(FATAL_ERROR "expected served pairs, served calls and graspcd contacts: pairs ${pairs}, "
                      "calls ${calls}, contacts ${served}, max_ncon ${max_ncon}")
endif()

# 5. Bad input: one line on stderr, exit code 2.
execute_process(COMMAND "${exe}" "${WORK_DIR}/no-such-scene.xml" RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCHALL "\n" newlines "${err}")
list(LENGTH newlines lines)
if(NOT rc EQUAL 2 OR NOT lines EQUAL 1 OR NOT err MATCHES "no-such-scene.xml")
  message(FATAL_ERROR "a missing scene: expected one line naming it and exit 2, got ${rc}:\n${err}")
endif()
message(STATUS "install and consume: ${pairs} served pairs, ${calls} served calls, ${served} contacts")

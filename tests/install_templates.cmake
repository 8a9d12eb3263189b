# The installed executable finds its template scenes in its own prefix, not in the checkout, run by
# ctest as `cmake -P` with:
#   BUILD_DIR   the build folder of the running ctest (what gets installed)
#   SOURCE_DIR  the repository, whose mjcf/ the installed executable must not name
#   MODELS_DIR  the real models the build was configured with (GRASPCD_MODELS_DIR)
#   WORK_DIR    a scratch folder, emptied first
# Steps: `cmake --install BUILD_DIR --prefix WORK_DIR/prefix`, then the prefix is moved to
# WORK_DIR/moved, so that the path it was installed to no longer exists. The executable must hold
# no reference to SOURCE_DIR/mjcf; from the moved prefix, `grasp --object --hand project` must run
# to a verdict on a template that its scene's header says came from the moved
# share/graspcd/mjcf; `--hand robotiq` with GRASPCD_MODELS_DIR set to an empty folder must be one
# line naming that folder and exit 2; and, when MODELS_DIR holds the Robotiq hand, `--hand robotiq`
# must run to a verdict with the models folder the build recorded, and with GRASPCD_MODELS_DIR
# naming a link to it.
cmake_minimum_required(VERSION 3.25)
foreach(var BUILD_DIR SOURCE_DIR MODELS_DIR WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_templates.cmake: -D${var}=... is required")
  endif()
endforeach()

# Runs a command; `what` names it in a failure. Leaves run_out, run_err and run_rc.
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(run_out "${out}" PARENT_SCOPE)
  set(run_err "${err}" PARENT_SCOPE)
  set(run_rc "${rc}" PARENT_SCOPE)
endfunction()

# A grasp's JSON document: exit 0 and a verdict (gripped and held, true or false).
function(expect_verdict what)
  if(NOT run_rc EQUAL 0)
    message(FATAL_ERROR "${what}: exit ${run_rc}:\n${run_out}\n${run_err}")
  endif()
  foreach(key gripped held)
    string(JSON type ERROR_VARIABLE error TYPE "${run_out}" ${key})
    if(error OR NOT type STREQUAL "BOOLEAN")
      message(FATAL_ERROR "${what}: no verdict '${key}' in the JSON (${error}):\n${run_out}")
    endif()
    string(JSON value GET "${run_out}" ${key})
    message(STATUS "${what}: ${key} ${value}")
  endforeach()
endfunction()

set(prefix "${WORK_DIR}/prefix")
set(moved "${WORK_DIR}/moved")
file(REMOVE_RECURSE "${WORK_DIR}")

# 1. Install, then move the prefix away from where it was installed.
run("cmake --install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
if(NOT run_rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${run_rc}):\n${run_out}\n${run_err}")
endif()
file(RENAME "${prefix}" "${moved}")
set(exe "${moved}/bin/graspcd")
set(mjcf "${moved}/share/graspcd/mjcf")
foreach(f example1.xml example1.pairs.json meshes/cup.obj real_robotiq_mug.xml
          real_robotiq_mug.pairs.json real_shadow_glass.xml real_shadow_glass.pairs.json)
  if(NOT EXISTS "${mjcf}/${f}")
    message(FATAL_ERROR "not installed: share/graspcd/mjcf/${f}")
  endif()
endforeach()

# 2. No reference to the checkout's templates in the executable (as `strings` would list them).
file(STRINGS "${exe}" mjcf_strings REGEX "mjcf")
foreach(s ${mjcf_strings})
  string(FIND "${s}" "${SOURCE_DIR}/mjcf" at)
  if(at GREATER_EQUAL 0)
    message(FATAL_ERROR "the installed graspcd names the checkout's templates: ${s}")
  endif()
endforeach()

# 3. The project hand from the moved prefix, its scene kept: the template came from there.
run("grasp --hand project" "${exe}" grasp --object "${mjcf}/meshes/cup.obj" --hand project --fit
    --json --write-scene "${WORK_DIR}/project")
expect_verdict("grasp --object cup.obj --hand project")
file(READ "${WORK_DIR}/project/cup.xml" scene)
file(REAL_PATH "${mjcf}/example1.xml" template)
string(FIND "${scene}" "from the template ${template} " at)
if(at LESS 0)
  message(FATAL_ERROR "the scene does not come from ${template}:\n${scene}")
endif()

# 4. No models where GRASPCD_MODELS_DIR says: one line naming the folder, exit 2.
file(MAKE_DIRECTORY "${WORK_DIR}/no-models")
run("grasp --hand robotiq without models" ${CMAKE_COMMAND} -E env
    "GRASPCD_MODELS_DIR=${WORK_DIR}/no-models" "${exe}" grasp --object "${mjcf}/meshes/cup.obj"
    --hand robotiq --fit --json)
string(CONCAT line "graspcd: the Robotiq hand's models are not found at ${WORK_DIR}/no-models: "
       "set GRASPCD_MODELS_DIR to the folder that holds hands/robotiq_2f85/2f85.xml\n")
if(NOT run_rc EQUAL 2 OR NOT run_err STREQUAL line OR NOT run_out STREQUAL "")
  message(FATAL_ERROR "robotiq without models: expected exit 2 and\n${line}got ${run_rc}:\n"
                      "${run_out}\n${run_err}")
endif()

# 5. The Robotiq hand with the models folder the build recorded: a 3 x 3 x 6 cm block (in mm)
# standing between the pads.
if(EXISTS "${MODELS_DIR}/hands/robotiq_2f85/2f85.xml")
  file(WRITE "${WORK_DIR}/block.obj"
       "v -30 -15 -15\nv 30 -15 -15\nv -30 15 -15\nv 30 15 -15\n"
       "v -30 -15 15\nv 30 -15 15\nv -30 15 15\nv 30 15 15\n"
       "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\n"
       "f 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n")
  run("grasp --hand robotiq" ${CMAKE_COMMAND} -E env --unset=GRASPCD_MODELS_DIR "${exe}" grasp
      --object "${WORK_DIR}/block.obj" --scale 0.001 --up x --hand robotiq --json)
  expect_verdict("grasp --object block.obj --hand robotiq")
  # And with the environment naming the models elsewhere (a link to them).
  file(CREATE_LINK "${MODELS_DIR}" "${WORK_DIR}/models-link" SYMBOLIC)
  run("grasp --hand robotiq, GRASPCD_MODELS_DIR" ${CMAKE_COMMAND} -E env
      "GRASPCD_MODELS_DIR=${WORK_DIR}/models-link" "${exe}" grasp --object "${WORK_DIR}/block.obj"
      --scale 0.001 --up x --hand robotiq --json)
  expect_verdict("grasp --object block.obj --hand robotiq, GRASPCD_MODELS_DIR")
else()
  message(STATUS "the Robotiq hand is not in ${MODELS_DIR}: --hand robotiq not run")
endif()
message(STATUS "install_templates: the installed graspcd ran from ${moved}")

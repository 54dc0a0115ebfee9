# cmake -P script behind the ctest install.find_package_consumer (see
# CMakeLists.txt here). Inputs: BUILD_DIR (a built mddual), EXAMPLE_DIR
# (examples/cpp_planning), CFG (the config it plans), WORK_DIR (scratch),
# CXX_COMPILER, LAUNCHER and CXX_FLAGS (the build's compiler, launcher and
# warning flags, for the example),
# HAVE_PLANNING (whether the build has the scene and planning components).
#   1. cmake --install into WORK_DIR/prefix;
#   2. the example against the install (CMAKE_PREFIX_PATH only), built and run;
#   3. the same against the build tree (mddual_DIR = BUILD_DIR);
#   4. the config's messages: an unknown component, a component whose
#      dependency is missing (CMAKE_DISABLE_FIND_PACKAGE_ompl), an optional
#      component that is missing (configure succeeds). Without the planning
#      layer, a request for it must say that this mddual lacks it.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
set(common_args -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(LAUNCHER)
  list(APPEND common_args -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()

# run(<label> COMMAND...): runs it, stops with its output when it fails; the
# output is left in run_out.
function(run label)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${label} failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()

# expect_configure(<label> <expected: PASS or a text the error must contain> <components> <optional> [args...])
# configures a one-line project: find_package(mddual REQUIRED COMPONENTS ... OPTIONAL_COMPONENTS ...).
set(find_dir ${WORK_DIR}/find_check)
file(WRITE ${find_dir}/CMakeLists.txt [=[
cmake_minimum_required(VERSION 3.16)
project(mddual_find_check LANGUAGES CXX)
find_package(mddual REQUIRED COMPONENTS ${COMPONENTS} OPTIONAL_COMPONENTS ${OPTIONAL})
message(STATUS "find_check: planning found: ${mddual_planning_FOUND}")
if(TARGET mddual::planning)
  message(STATUS "find_check: target mddual::planning exists")
endif()
]=])
function(expect_configure label expected components optional)
  set(bdir ${WORK_DIR}/find_check_${label})
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${find_dir} -B ${bdir} -DCMAKE_PREFIX_PATH=${prefix}
                          ${common_args} "-DCOMPONENTS=${components}" "-DOPTIONAL=${optional}" ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX REPLACE "[ \t\r\n]+" " " all "${out} ${err}")  # CMake wraps long messages
  if(expected STREQUAL "PASS")
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "find check '${label}': configure failed, expected success\n${out}\n${err}")
    endif()
  else()
    if(rc EQUAL 0)
      message(FATAL_ERROR "find check '${label}': configure succeeded, expected an error with '${expected}'\n${out}")
    endif()
    string(FIND "${all}" "${expected}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "find check '${label}': the error does not say '${expected}':\n${err}")
    endif()
  endif()
  set(check_out "${all}" PARENT_SCOPE)
  message(STATUS "find check '${label}': ok")
endfunction()

# 1. Install.
run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

if(NOT HAVE_PLANNING)
  expect_configure(core_only PASS "core" "")
  expect_configure(no_planning "component 'planning' is not in this mddual" "core;planning" "")
  return()
endif()

# 2 and 3. The example against the install and against the build tree.
foreach(kind install build_tree)
  set(bdir ${WORK_DIR}/example_${kind})
  if(kind STREQUAL "install")
    set(where -DCMAKE_PREFIX_PATH=${prefix})
    set(expected_dir ${prefix}/)
  else()
    set(where -Dmddual_DIR=${BUILD_DIR})
    set(expected_dir ${BUILD_DIR})
  endif()
  run("configure example (${kind})" ${CMAKE_COMMAND} -S ${EXAMPLE_DIR} -B ${bdir} ${where} ${common_args}
      "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}")
  # The package really came from where it should (not another install).
  file(STRINGS ${bdir}/CMakeCache.txt found_dir REGEX "^mddual_DIR:")
  string(FIND "${found_dir}" "${expected_dir}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "example (${kind}): mddual found at '${found_dir}', expected under '${expected_dir}'")
  endif()
  run("build example (${kind})" ${CMAKE_COMMAND} --build ${bdir})
  # The example seeds OMPL and RRT-Connect stops at its first solution; a
  # time limit of 300 s (not the example's default 5 s) is only a safety net,
  # so a slow or loaded machine gives the same verdict.
  run("run example (${kind})" ${bdir}/plan_with_mddual ${CFG} 300)
  message(STATUS "example (${kind}):\n${run_out}")
  foreach(needed "verified: valid" "clearance ahead" "ok")
    string(FIND "${run_out}" "${needed}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "example (${kind}): the output lacks '${needed}':\n${run_out}")
    endif()
  endforeach()
endforeach()

# 4. The package config's messages.
expect_configure(all PASS "core;scene;planning" "")
expect_configure(unknown "unknown component 'nosuch'" "core;nosuch" "")
expect_configure(missing_dependency "component 'planning' needs the package 'ompl'" "planning" ""
                 -DCMAKE_DISABLE_FIND_PACKAGE_ompl=ON)
expect_configure(optional_missing PASS "core" "planning" -DCMAKE_DISABLE_FIND_PACKAGE_ompl=ON)
string(FIND "${check_out}" "find_check: planning found: FALSE" at)
if(at EQUAL -1)
  message(FATAL_ERROR "find check 'optional_missing': mddual_planning_FOUND is not FALSE:\n${check_out}")
endif()
string(FIND "${check_out}" "target mddual::planning exists" at)
if(NOT at EQUAL -1)
  message(FATAL_ERROR "find check 'optional_missing': mddual::planning exists although ompl is missing")
endif()

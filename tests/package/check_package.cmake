# SPDX-License-Identifier: MIT
# Configures, builds and installs the solver folder on its own (no Box2D, GoogleTest or Google
# Benchmark anywhere), then configures, builds and runs a consumer project, compiled as C++17,
# that finds it with find_package(chain), and again with nothing but the first releases'
# find_package(chainbench). Run by ctest (script mode).
foreach(var SOLVER_DIR CONSUMER_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_package.cmake needs -D${var}=...")
  endif()
endforeach()
# What is checked is the packaging, not the code's speed: -O1 keeps these builds short.
set(quick_release "-O1 -DNDEBUG")
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()
run(${CMAKE_COMMAND} -S "${SOLVER_DIR}" -B "${WORK_DIR}/solver" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=${quick_release}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/solver")
run(${CMAKE_COMMAND} --install "${WORK_DIR}/solver" --prefix "${prefix}")
file(GLOB version_file "${prefix}/lib*/cmake/chain/chainConfigVersion.cmake")
file(READ "${version_file}" version_text)
file(STRINGS "${SOLVER_DIR}/CMakeLists.txt" version_line REGEX "set\\(CHAINBENCH_SOLVER_VERSION")
string(REGEX MATCH "[0-9]+\\.[0-9]+\\.[0-9]+" solver_version "${version_line}")
if(NOT version_text MATCHES "PACKAGE_VERSION \"${solver_version}\"")
  message(FATAL_ERROR "the installed package is not version ${solver_version}:\n${version_text}")
endif()
foreach(old_names OFF ON)
  set(names new)
  if(old_names)
    set(names old)
  endif()
  run(${CMAKE_COMMAND} -S "${CONSUMER_DIR}" -B "${WORK_DIR}/build-${names}" -G "${GENERATOR}"
      -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=${quick_release}"
      "-DCMAKE_PREFIX_PATH=${prefix}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" -DOLD_NAMES=${old_names})
  run(${CMAKE_COMMAND} --build "${WORK_DIR}/build-${names}")
  run("${WORK_DIR}/build-${names}/consumer")
endforeach()
file(GLOB library "${prefix}/lib*/libchain.a")
if(NOT library)
  message(FATAL_ERROR "the installed library is not libchain.a")
endif()
message(STATUS "solver ${solver_version} installed alone; the C++17 consumer built and ran")

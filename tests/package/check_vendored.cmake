# SPDX-License-Identifier: MIT
# Copies the solver folder into a C++17 game project that has no VERSION, builds and runs it; then
# checks that the vendored solver installs nothing by default, and that when asked to install it
# stamps its own version on the package, not the game's. Run by ctest (script mode).
foreach(var SOLVER_DIR GAME_DIR GAME_SOURCE WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_vendored.cmake needs -D${var}=...")
  endif()
endforeach()
# What is checked is the packaging, not the code's speed: -O1 keeps these builds short.
set(quick_release "-O1 -DNDEBUG")
file(REMOVE_RECURSE "${WORK_DIR}")
set(game "${WORK_DIR}/game")
file(COPY "${GAME_DIR}/" DESTINATION "${game}")
file(COPY "${GAME_SOURCE}" DESTINATION "${game}")
file(COPY "${SOLVER_DIR}/" DESTINATION "${game}/third_party/chain")
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()

run(${CMAKE_COMMAND} -S "${game}" -B "${WORK_DIR}/build" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=${quick_release}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
run("${WORK_DIR}/build/game")
run(${CMAKE_COMMAND} --install "${WORK_DIR}/build" --prefix "${WORK_DIR}/prefix")
if(EXISTS "${WORK_DIR}/prefix/include/chain")
  message(FATAL_ERROR "a vendored solver installed its headers without being asked")
endif()

# A game with a version of its own that asks for the solver's install rules: the package version
# file (written at configure time) must carry the solver's version.
run(${CMAKE_COMMAND} -S "${game}" -B "${WORK_DIR}/versioned" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=${quick_release}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" -DGAME_VERSION=7.3.1
    -DCHAINBENCH_SOLVER_INSTALL=ON)
set(version_file "${WORK_DIR}/versioned/third_party/chain/chainConfigVersion.cmake")
if(NOT EXISTS "${version_file}")
  message(FATAL_ERROR "CHAINBENCH_SOLVER_INSTALL=ON set up no package")
endif()
file(READ "${version_file}" version_text)
file(STRINGS "${SOLVER_DIR}/CMakeLists.txt" version_line REGEX "set\\(CHAINBENCH_SOLVER_VERSION")
string(REGEX MATCH "[0-9]+\\.[0-9]+\\.[0-9]+" solver_version "${version_line}")
if(NOT version_text MATCHES "PACKAGE_VERSION \"${solver_version}\"")
  message(FATAL_ERROR "the solver package is not version ${solver_version}:\n${version_text}")
endif()
message(STATUS "vendored into a C++17 game without a VERSION: built, ran, installed nothing")

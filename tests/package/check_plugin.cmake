# SPDX-License-Identifier: MIT
# "Bring your own resolver", as docs/plugins.md gives it: install chainbench into a scratch
# prefix and the plugin header's package alone (bench/include/) into another; build the example
# plugin out of tree against the header alone, where no package or library the harness is built
# with can be found (find_package(chainbench_plugin) -> chainbench::engine_plugin); and run the
# installed chainbench and chainbench_bench with it beside the built-in engines. Run by ctest
# (script mode).
foreach(var BUILD_DIR HEADER_DIR PLUGIN_DIR WORK_DIR GENERATOR MAKE_PROGRAM CXX_COMPILER PROBE BENCH)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_plugin.cmake needs -D${var}=...")
  endif()
endforeach()
# What is checked is the packaging, not the code's speed: -O1 keeps these builds short.
set(quick_release "-O1 -DNDEBUG")
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
set(header_prefix "${WORK_DIR}/header_prefix")
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
set(programs chainbench)
if(BENCH)
  list(APPEND programs chainbench_bench)
endif()
foreach(file include/chainbench/engine_plugin.h share/cmake/chainbench_plugin/chainbench_pluginConfig.cmake)
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "the install holds no ${file}")
  endif()
endforeach()
foreach(program IN LISTS programs)
  if(NOT EXISTS "${prefix}/bin/${program}")
    message(FATAL_ERROR "the install holds no bin/${program}")
  endif()
endforeach()

# The header's package on its own: no compiler, nothing found, nothing built.
run(${CMAKE_COMMAND} -S "${HEADER_DIR}" -B "${WORK_DIR}/header" -G "${GENERATOR}")
run(${CMAKE_COMMAND} --install "${WORK_DIR}/header" --prefix "${header_prefix}")
file(GLOB_RECURSE header_files RELATIVE "${header_prefix}" "${header_prefix}/*")
list(SORT header_files)
set(expected include/chainbench/engine_plugin.h
    share/cmake/chainbench_plugin/chainbench_pluginConfig.cmake
    share/cmake/chainbench_plugin/chainbench_pluginConfigVersion.cmake
    share/cmake/chainbench_plugin/chainbench_pluginTargets.cmake)
if(NOT header_files STREQUAL expected)
  message(FATAL_ERROR "the header's package installs ${header_files}, not ${expected}")
endif()
# Neither copy of its config asks for another package, nor links its target to anything.
foreach(dir "${prefix}" "${header_prefix}")
  file(GLOB config_files "${dir}/share/cmake/chainbench_plugin/*.cmake")
  foreach(file IN LISTS config_files)
    file(READ "${file}" text)
    # A call of either, of any package (a comment's "find_package()" aside), or a link.
    if(text MATCHES "(find_dependency|find_package)\\([ \t\n]*[A-Za-z_]|INTERFACE_LINK_LIBRARIES")
      message(FATAL_ERROR "${file} asks for more than the header (${CMAKE_MATCH_0})")
    endif()
  endforeach()
endforeach()

# A plugin's author's machine: only the header's package can be found (no system prefix, no
# environment, no package registry), which the probe checks after project(). The build tool is
# named, since PATH is not searched.
set(only_the_prefix "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}" -DCMAKE_FIND_USE_CMAKE_SYSTEM_PATH=OFF
    -DCMAKE_FIND_USE_SYSTEM_ENVIRONMENT_PATH=OFF -DCMAKE_FIND_USE_CMAKE_ENVIRONMENT_PATH=OFF
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF
    "-DCMAKE_PROJECT_INCLUDE=${PROBE}")
run(${CMAKE_COMMAND} -S "${PLUGIN_DIR}" -B "${WORK_DIR}/relaxation" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=${quick_release}"
    "-DCMAKE_PREFIX_PATH=${header_prefix}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" ${only_the_prefix})
if(NOT last_output MATCHES "no package or library of the harness is findable here")
  message(FATAL_ERROR "the probe of what is findable did not run:\n${last_output}")
endif()
run(${CMAKE_COMMAND} --build "${WORK_DIR}/relaxation")
set(plugin "${WORK_DIR}/relaxation/librelaxation.so")
if(NOT EXISTS "${plugin}")
  message(FATAL_ERROR "building the example plugin out of tree made no ${plugin}")
endif()
# docs/plugins.md's way, against the whole install: it finds the same package there.
run(${CMAKE_COMMAND} -S "${PLUGIN_DIR}" -B "${WORK_DIR}/relaxation_full" -G "${GENERATOR}"
    "-DCMAKE_PREFIX_PATH=${prefix}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" ${only_the_prefix})

run("${prefix}/bin/chainbench" run --scene pyramid --set base=6 --steps 60
    --engines "chain,box2d,chipmunk,plugin:path=${plugin},iterations=8")
if(NOT last_output MATCHES "plugin:path=librelaxation.so,iterations=8")
  message(FATAL_ERROR "the run's table has no row for the plugin:\n${last_output}")
endif()
if(BENCH)
  # docs/plugins.md's benchmark command, the plugin's benchmark of its smallest family only.
  run("${prefix}/bin/chainbench_bench" "--chainbench_engines=chain,plugin:path=${plugin}"
      "--benchmark_filter=^stack/plugin")
  if(NOT last_output MATCHES "stack/plugin:path=librelaxation.so/0/[^\n]* bodies=16")
    message(FATAL_ERROR "the installed chainbench_bench timed no plugin:\n${last_output}")
  endif()
endif()
message(STATUS "the example plugin built against the header alone and ran in the installed "
               "${programs}")

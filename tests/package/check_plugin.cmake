# "Bring your own resolver", as README gives it: install chainbench into a scratch prefix, build
# the example plugin out of tree against it (find_package(chainbench) -> chainbench::engine_plugin),
# and run the installed command with the plugin beside the built-in engines. Run by ctest (script
# mode).
foreach(var BUILD_DIR PLUGIN_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_plugin.cmake needs -D${var}=...")
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
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
if(NOT EXISTS "${prefix}/include/chainbench/engine_plugin.h")
  message(FATAL_ERROR "the install holds no include/chainbench/engine_plugin.h")
endif()
run(${CMAKE_COMMAND} -S "${PLUGIN_DIR}" -B "${WORK_DIR}/relaxation" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=${quick_release}" "-DCMAKE_PREFIX_PATH=${prefix}"
    "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/relaxation")
set(plugin "${WORK_DIR}/relaxation/librelaxation.so")
if(NOT EXISTS "${plugin}")
  message(FATAL_ERROR "building the example plugin out of tree made no ${plugin}")
endif()
run("${prefix}/bin/chainbench" run --scene pyramid --set base=6 --steps 60
    --engines "chain,box2d,chipmunk,plugin:path=${plugin},iterations=8")
if(NOT last_output MATCHES "plugin:path=librelaxation.so,iterations=8")
  message(FATAL_ERROR "the run's table has no row for the plugin:\n${last_output}")
endif()
message(STATUS "the example plugin built against ${prefix} and ran beside the built-in engines")

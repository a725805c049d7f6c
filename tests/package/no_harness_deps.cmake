# SPDX-License-Identifier: MIT
# Included after project() of a plugin's build (CMAKE_PROJECT_INCLUDE) by check_plugin.cmake:
# fails unless every package and library the harness is built with is out of reach, so that a
# plugin that configures and builds beside it is shown to need none of them.
foreach(package box2d GTest benchmark CLI11 nlohmann_json)
  find_package(${package} CONFIG QUIET)
  if(${package}_FOUND)
    message(FATAL_ERROR "${package} is findable (${${package}_DIR}): this build cannot show that "
                        "the plugin needs none of the harness' packages")
  endif()
endforeach()
find_library(chainbench_probe_chipmunk chipmunk)
find_path(chainbench_probe_box2d box2d/box2d.h)
foreach(probe chainbench_probe_chipmunk chainbench_probe_box2d)
  if(${probe})
    message(FATAL_ERROR "${${probe}} is findable: this build cannot show that the plugin needs "
                        "none of the harness' libraries")
  endif()
endforeach()
message(STATUS "no package or library of the harness is findable here")

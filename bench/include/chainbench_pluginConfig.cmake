# SPDX-License-Identifier: MIT
# chainbench::engine_plugin: the plugin header and nothing else; this package asks for no other.
include("${CMAKE_CURRENT_LIST_DIR}/chainbench_pluginTargets.cmake")

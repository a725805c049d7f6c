// SPDX-License-Identifier: MIT
// The replay page's template, style and script (the files beside this header), compiled into
// the chainbench command by CMake (embed.cmake), so that writing a page needs no other file.
#pragma once

#include <string>

namespace chainbench::replay_assets {

// page.html, with the slots {{TITLE}}, {{GENERATOR}}, {{STYLE}}, {{DATA}} and {{SCRIPT}}.
std::string page();
// replay.css.
std::string style();
// Every file of js/, in the order bench/CMakeLists.txt lists them, joined.
std::string script();

}  // namespace chainbench::replay_assets

// SPDX-License-Identifier: MIT
// The one way a number is written where it must be exact: messages (a value and the bound it
// broke), spec labels, parameter lists, traces. A rounded value could look equal to its bound
// ("must be in [1e-6, 1] s, got 1" for 1.0000001), so every digit the double needs is written,
// and no more.
#pragma once

#include <string>

namespace chainbench {

// The text that reads back as exactly v: a whole number below 1e15 in magnitude in full
// ("2147483648", "1000000"), any other the shortest round-trip text ("0.1", "1.0000001",
// "1e+300"); "nan", "inf" and "-inf" for the others. -0 is written "-0".
std::string exact_number(double v);
// The same, appended to `out` (no allocation beyond out's growth: for traces).
void append_exact_number(std::string& out, double v);

}  // namespace chainbench

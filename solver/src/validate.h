// SPDX-License-Identifier: MIT
// Input checks shared by validate() and the World functions that take numbers.
#pragma once

#include <string>

namespace chain::detail {

// "%g" of v.
std::string number(double v);
// Empty if v is finite and within [lo, hi]; else "<field> must be <what>, got v".
std::string check_range(const char* field, double v, double lo, double hi, const char* what);

}  // namespace chain::detail

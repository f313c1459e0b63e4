#pragma once
// Numbers as people write them in messages: whole numbers without decimals (2147483647, 650),
// others to six significant digits (0.05, 1.2345, 1e-05), never "650.000000" or "2.14748e+09".
#include <cmath>
#include <cstdio>
#include <string>

namespace activetouch {

inline std::string numberText(double v) {
    char buf[40];
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15)
        std::snprintf(buf, sizeof buf, "%.0f", v);
    else
        std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

}  // namespace activetouch

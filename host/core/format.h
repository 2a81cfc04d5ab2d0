// Numbers in messages and labels, written the short way people read them ("0.1", "1e+06", "20").
#pragma once

#include <cstdio>
#include <string>

namespace vkray {

inline std::string shortNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

}  // namespace vkray

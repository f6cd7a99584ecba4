// Benchmarks' shared printf-style formatting into a std::string (report tables).
#pragma once

#include <cstdarg>
#include <cstdio>
#include <string>

namespace ltbench {

// Formats like printf; output longer than 511 characters is cut.
inline std::string format(const char* fmt, ...) {
    char buf[512];
    va_list args;
    va_start(args, fmt);
    std::vsnprintf(buf, sizeof(buf), fmt, args);
    va_end(args);
    return buf;
}

}  // namespace ltbench

// Private to the baker: small text helpers for error messages.
#pragma once

#include <charconv>
#include <string>

namespace lt {

// Shortest decimal text that reads back as `f` (locale-independent).
inline std::string formatFloat(float f) {
    char buf[32];
    auto res = std::to_chars(buf, buf + sizeof buf, f);
    return std::string(buf, res.ptr);
}

} // namespace lt

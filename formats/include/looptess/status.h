// looptess/status.h -- the result of every operation on untrusted data or a device.
#pragma once

#include <string>
#include <utility>

namespace lt {

// Result of an operation on untrusted data. Falsy on failure; `message` names the
// file, the object and what is wrong. The code's values are stable (the tools exit
// with them).
struct Status {
    // A fixed underlying type: every int is a valid value, so a Status read from
    // anywhere (a union, a cast exit code) is never undefined behaviour to load.
    enum Code : int { Ok = 0, Usage = 1, BadInput = 2, Unsupported = 3, WriteFailed = 4, Internal = 5 };
    Code code = Ok;
    std::string message;
    explicit operator bool() const { return code == Ok; }
    static Status ok() { return {}; }
    static Status error(Code c, std::string m) { return {c, std::move(m)}; }
};

// The code's name as spelled above ("Ok", "BadInput", ...); "Unknown" for any other
// value. A static string, never null.
const char* toString(Status::Code code);

}  // namespace lt

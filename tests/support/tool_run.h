// Test helper: runs one of the project's command-line tools and captures its output.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace lt::test {

struct RunResult {
    int exitCode = -1;  // -1 when the process did not exit normally
    std::string out, err;
};

// Runs `exe` with `args` (each quoted for the shell); stdout and stderr go through
// files in `scratch`, which are removed afterwards.
RunResult runTool(const std::string& exe, const std::vector<std::string>& args, const std::filesystem::path& scratch);

// A folder of this test process's own, `prefix` and the process id under the
// temporary directory: created on first use, removed with its files when the
// process exits (one per prefix).
std::filesystem::path processTempDir(const std::string& prefix);

// The whole file as text ("" when it cannot be read).
std::string readText(const std::filesystem::path& path);

// The finding ids of loopcheck's text output ("ASSET: error N1: ..." lines), sorted,
// each once: {"N1"} when N1 is its only error.
std::vector<std::string> loopcheckErrorIds(const std::string& out);

// Whether `haystack` holds `needle` (messages in assertions).
inline bool contains(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

}  // namespace lt::test

// Test helper: see tool_run.h.
#include "tool_run.h"

#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace lt::test {
namespace {

std::string quote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// The folders of processTempDir, removed at exit.
struct TempDirs {
    std::map<std::string, std::filesystem::path> byPrefix;
    ~TempDirs() {
        for (const auto& [prefix, path] : byPrefix) {
            std::error_code ec;
            std::filesystem::remove_all(path, ec);
        }
    }
};

}  // namespace

std::filesystem::path processTempDir(const std::string& prefix) {
    static TempDirs dirs;
    auto [it, added] = dirs.byPrefix.emplace(prefix, std::filesystem::path());
    if (added) {
        it->second = std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(getpid()));
        std::filesystem::create_directories(it->second);
    }
    return it->second;
}

std::vector<std::string> loopcheckErrorIds(const std::string& out) {
    std::set<std::string> ids;
    std::istringstream lines(out);
    std::string line;
    const std::string tag = ": error ";
    while (std::getline(lines, line)) {
        const size_t at = line.find(tag);
        if (at == std::string::npos) continue;
        const size_t start = at + tag.size(), end = line.find(':', start);
        if (end != std::string::npos) ids.insert(line.substr(start, end - start));
    }
    return {ids.begin(), ids.end()};
}

std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

RunResult runTool(const std::string& exe, const std::vector<std::string>& args, const std::filesystem::path& scratch) {
    const std::filesystem::path out = scratch / "stdout.txt", err = scratch / "stderr.txt";
    std::string cmd = quote(exe);
    for (const std::string& a : args) cmd += " " + quote(a);
    const int status = std::system((cmd + " >" + quote(out.string()) + " 2>" + quote(err.string())).c_str());
    RunResult r;
    r.exitCode = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readText(out);
    r.err = readText(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
}

}  // namespace lt::test

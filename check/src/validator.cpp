// The Khronos glTF-Validator through node (looptess/tools/check.h, runKhronosValidator).
#include "looptess/tools/check.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace lt {
namespace {

// Runs `argv` (searched on PATH) and collects its stdout and stderr. Returns the
// exit status (-1: it could not start or did not exit normally; `error` says why).
int runProcess(const std::vector<std::string>& args, std::string& out, std::string& err, std::string& error) {
    int outPipe[2], errPipe[2];
    if (pipe2(outPipe, O_CLOEXEC) != 0) return error = std::strerror(errno), -1;
    if (pipe2(errPipe, O_CLOEXEC) != 0) {
        close(outPipe[0]), close(outPipe[1]);
        return error = std::strerror(errno), -1;
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, outPipe[1], 1);
    posix_spawn_file_actions_adddup2(&actions, errPipe[1], 2);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(outPipe[1]);
    close(errPipe[1]);
    if (rc != 0) {
        close(outPipe[0]), close(errPipe[0]);
        error = args[0] + ": " + std::strerror(rc);
        return -1;
    }
    pollfd fds[2] = {{outPipe[0], POLLIN, 0}, {errPipe[0], POLLIN, 0}};
    std::string* sinks[2] = {&out, &err};
    int open = 2;
    char buffer[65536];
    while (open > 0) {
        if (poll(fds, 2, -1) < 0) {
            if (errno == EINTR) continue;
            break;
        }
        for (int k = 0; k < 2; ++k) {
            if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            const ssize_t n = read(fds[k].fd, buffer, sizeof buffer);
            if (n > 0)
                sinks[k]->append(buffer, size_t(n));
            else if (n == 0 || errno != EINTR)
                close(fds[k].fd), fds[k].fd = -1, --open;
        }
    }
    for (auto& f : fds)
        if (f.fd >= 0) close(f.fd);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    if (!WIFEXITED(status)) return error = args[0] + " did not exit normally", -1;
    return WEXITSTATUS(status);
}

std::string firstLine(const std::string& text) {
    const size_t end = text.find('\n');
    return text.substr(0, end == std::string::npos ? text.size() : end);
}

// Reads the validator's JSON report from its stdout into `r` (may throw on a report
// whose fields have unexpected types; the caller catches).
void readReport(const std::string& out, const std::string& err, ValidatorResult& r) {
    const nlohmann::json report = nlohmann::json::parse(out, nullptr, false);
    if (report.is_discarded() || !report.is_object() || !report.contains("issues") || !report["issues"].is_object())
        return void(r.detail = "the validator printed no report" + (err.empty() ? "" : ": " + firstLine(err)));
    const nlohmann::json& issues = report["issues"];
    auto count = [&](const char* key) {
        const auto it = issues.find(key);
        return it != issues.end() && it->is_number_unsigned() ? it->get<uint64_t>() : uint64_t(0);
    };
    r.state = ValidatorResult::Ran;
    r.errors = count("numErrors");
    r.warnings = count("numWarnings");
    r.infos = count("numInfos");
    r.hints = count("numHints");
    static const char* kSeverity[] = {"error", "warning", "info", "hint"};
    // The first 20, most severe first (errors, then warnings, ...), in report order.
    if (auto it = issues.find("messages"); it != issues.end() && it->is_array())
        for (int severity = 0; severity < 4; ++severity)
            for (const nlohmann::json& m : *it) {
                if (r.messages.size() >= 20) break;
                if (!m.is_object() || m.value("severity", 0) != severity) continue;
                r.messages.push_back(std::string(kSeverity[severity]) + " " + m.value("code", "") + " " +
                                     m.value("pointer", "") + ": " + m.value("message", ""));
            }
}

}  // namespace

ValidatorResult runKhronosValidator(const std::string& file, const std::string& script) {
    ValidatorResult r;
    r.state = ValidatorResult::Unavailable;
    std::error_code ec;
    if (!std::filesystem::exists(script, ec)) return r.detail = "no validator script at " + script, r;
    std::string out, err, error;
    const int code = runProcess({"node", script, file}, out, err, error);
    if (code < 0) return r.detail = error, r;
    if (code == 127) return r.detail = "node: not found", r;
    if (code != 0 && code != 1) {
        r.detail =
            "node " + script + " exited with " + std::to_string(code) + (err.empty() ? "" : ": " + firstLine(err));
        return r;
    }
    try {
        readReport(out, err, r);
    } catch (const std::exception& e) {  // a report of unexpected types: never thrown out
        r = ValidatorResult{};
        r.state = ValidatorResult::Unavailable;
        r.detail = std::string("unreadable validator report: ") + e.what();
    }
    return r;
}

}  // namespace lt

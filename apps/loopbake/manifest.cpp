// loopbake --manifest: reading and checking the manifest (see batch.h).
#include "batch.h"

#include "looptess/tools/file_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <map>

namespace lt::batch {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr size_t kMaxManifestBytes = size_t(64) << 20;

// Options a job may not set: they belong to the batch, not to one bake.
const char* const kBatchOnly[] = {"o", "json", "manifest", "threads", "v", "verbose", "h", "help", "version"};
// Options whose value is a path, resolved against the manifest's folder like input
// and output.
const char* const kPathOptions[] = {"depfile", "displacement", "edits"};

bool validKey(const std::string& k) {
    if (k.empty() || k[0] == '-') return false;
    return std::all_of(k.begin(), k.end(),
                       [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-'; });
}

template <size_t N>
bool listed(const char* const (&list)[N], const std::string& k) {
    return std::find_if(std::begin(list), std::end(list), [&](const char* s) { return k == s; }) != std::end(list);
}

// A readable, bounded rendering of a JSON value for messages.
std::string shown(const Json& v) {
    std::string s = v.dump(-1, ' ', false, Json::error_handler_t::replace);
    return s.size() > 60 ? s.substr(0, 57) + "..." : s;
}

class Reader {
public:
    Reader(const std::string& path) : path_(path) {
        const fs::path dir = fs::path(path).parent_path();
        dir_ = dir.empty() ? fs::path(".") : dir;
    }

    Status read(std::vector<Job>& jobs) {
        std::vector<uint8_t> bytes;
        if (Status st = readFile(path_, bytes, kMaxManifestBytes); !st) return st;
        Json doc = Json::parse(bytes.begin(), bytes.end(), nullptr, false);
        if (doc.is_discarded()) return fail("", "is not valid JSON");
        if (!doc.is_object()) return fail("", "the top level must be an object with a \"jobs\" array");
        for (auto it = doc.begin(); it != doc.end(); ++it)
            if (it.key() != "jobs") return fail(it.key(), "unknown key (the top level has only \"jobs\")");
        auto list = doc.find("jobs");
        if (list == doc.end() || !list->is_array()) return fail("jobs", "missing or not an array");
        jobs.clear();
        for (size_t i = 0; i < list->size(); ++i) {
            Job job;
            job.index = i;
            if (Status st = readJob((*list)[i], job); !st) return st;
            jobs.push_back(std::move(job));
        }
        return checkOutputs(jobs);
    }

private:
    Status fail(const std::string& at, const std::string& what) const {
        return Status::error(Status::BadInput, path_ + ": " + (at.empty() ? "" : at + ": ") + what);
    }

    // `p` relative to the manifest's folder, unless absolute.
    std::string resolve(const std::string& p) const {
        return fs::path(p).is_absolute() ? p : (dir_ / p).lexically_normal().string();
    }

    Status readJob(const Json& j, Job& job) {
        const std::string at = "jobs[" + std::to_string(job.index) + "]";
        if (!j.is_object()) return fail(at, "must be an object with \"input\" and \"output\"");
        for (const char* key : {"input", "output"}) {
            auto v = j.find(key);
            if (v == j.end() || !v->is_string() || v->get_ref<const std::string&>().empty())
                return fail(at + "." + key, "missing, or not a non-empty string");
            (std::string(key) == "input" ? job.input : job.output) = resolve(v->get<std::string>());
        }
        for (auto it = j.begin(); it != j.end(); ++it) {
            const std::string& key = it.key();
            const Json& v = it.value();
            if (key == "input" || key == "output") continue;
            const std::string where = at + "." + key;
            if (!validKey(key))
                return fail(where, "not an option name (lower-case letters, digits and '-', without the leading '--')");
            if (listed(kBatchOnly, key)) return fail(where, "a batch-wide option; give it on the command line");
            if (v.is_boolean()) {
                if (v.get<bool>()) job.options.push_back("--" + key);
            } else if (v.is_string()) {
                const std::string& s = v.get_ref<const std::string&>();
                job.options.push_back("--" + key + "=" + (listed(kPathOptions, key) ? resolve(s) : s));
            } else if (v.is_number()) {
                job.options.push_back("--" + key + "=" + v.dump());
            } else {
                return fail(where, "must be a number, string or boolean, not " + shown(v));
            }
        }
        return Status::ok();
    }

    // Two jobs writing one file (an output or a depfile) would race; a job
    // overwriting another's input would make the results depend on the order of jobs.
    // (Within a job, loopbake's own check: parseArgs.)
    Status checkOutputs(const std::vector<Job>& jobs) const {
        std::map<std::string, size_t> outputs, inputs;
        for (const Job& job : jobs) inputs.emplace(lt::fileKey(job.input), job.index);
        for (const Job& job : jobs) {
            std::vector<std::pair<std::string, std::string>> written = {{"output", job.output}};
            for (const std::string& o : job.options)
                if (o.rfind("--depfile=", 0) == 0) written.push_back({"depfile", o.substr(10)});
            for (const auto& [what, path] : written) {
                const std::string at = "jobs[" + std::to_string(job.index) + "]." + what;
                const std::string k = lt::fileKey(path);
                auto [it, added] = outputs.emplace(k, job.index);
                if (!added && it->second != job.index)
                    return fail(at, "\"" + path + "\" is also written by jobs[" + std::to_string(it->second) + "]");
                auto in = inputs.find(k);
                if (in != inputs.end() && in->second != job.index)
                    return fail(at, "\"" + path + "\" is the input of jobs[" + std::to_string(in->second) + "]");
            }
        }
        return Status::ok();
    }

    std::string path_;
    fs::path dir_;
};

}  // namespace

Status readManifest(const std::string& path, std::vector<Job>& jobs) {
    try {
        return Reader(path).read(jobs);
    } catch (const std::exception& e) {  // bad_alloc, filesystem errors
        return Status::error(Status::Internal, path + ": " + e.what());
    }
}

}  // namespace lt::batch

// loopbake --manifest: the job loop, threads and the batch report (see batch.h).
#include "batch.h"

#include "limits_cli.h"
#include "looptess/tools/file_io.h"
#include "looptess/version.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <new>
#include <thread>

namespace lt::batch {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

// Calls the bake callback; an exception escaping it fails that job only.
Status bakeOne(const Callbacks& callbacks, const Job& job, JobResult& result) {
    try {
        return callbacks.bake(job, result);
    } catch (const std::bad_alloc&) {
        return Status::error(Status::Internal, job.input + ": out of memory");
    } catch (const std::exception& e) {
        return Status::error(Status::Internal, job.input + ": internal error: " + e.what());
    }
}

void printJob(const Job& job, const JobResult& r, size_t total, bool verbose) {
    if (!r.status) std::fprintf(stderr, "loopbake: error: %s\n", r.status.message.c_str());
    if (!verbose) return;
    if (r.status)
        std::fprintf(stderr,
                     "loopbake: [%zu/%zu] ok %s -> %s: %u faces, %llu bytes, %.3f s, memory estimated %.1f MiB\n",
                     job.index + 1, total, job.input.c_str(), job.output.c_str(), r.faces,
                     static_cast<unsigned long long>(r.outputBytes), r.seconds,
                     double(r.memory.estimatedBytes) / double(1 << 20));
    else
        std::fprintf(stderr, "loopbake: [%zu/%zu] failed (exit %d) %s, %.3f s\n", job.index + 1, total,
                     int(r.status.code), job.input.c_str(), r.seconds);
}

// Byte-stable for the same manifest and settings, whatever the thread count: jobs in
// manifest order, timings and the process's peak memory only with -v.
std::string reportJson(const Options& options, const std::vector<Job>& jobs, const std::vector<JobResult>& results,
                       double seconds) {
    Json j;
    j["tool"] = "loopbake";
    j["version"] = LOOPTESS_VERSION_STRING;
    j["manifest"] = options.manifest;
    size_t failed = 0;
    j["jobs"] = Json::array();
    for (size_t i = 0; i < jobs.size(); ++i) {
        const JobResult& r = results[i];
        failed += !r.status;
        Json job = {{"index", i},
                    {"input", jobs[i].input},
                    {"output", jobs[i].output},
                    {"options", jobs[i].options},
                    {"status", r.status ? "ok" : "failed"},
                    {"exitCode", int(r.status.code)},
                    {"message", r.status.message},
                    {"bytes", r.outputBytes}};
        if (options.verbose) job["seconds"] = r.seconds;
        if (!r.report.empty()) {
            Json report = Json::parse(r.report, nullptr, false);
            if (!report.is_discarded()) job["report"] = std::move(report);
        }
        j["jobs"].push_back(std::move(job));
    }
    j["summary"] = {{"jobs", jobs.size()}, {"succeeded", jobs.size() - failed}, {"failed", failed}};
    if (options.verbose)
        j["timing"] = {{"seconds", seconds}, {"threads", options.threads}, {"peakRssBytes", cli::peakRssBytes()}};
    return j.dump(2) + "\n";
}

}  // namespace

int run(const Options& options, const Callbacks& callbacks) {
    const auto start = Clock::now();
    std::vector<Job> jobs;
    Status st = readManifest(options.manifest, jobs);
    for (size_t i = 0; st && i < jobs.size(); ++i) {
        st = callbacks.check(jobs[i]);
        if (!st)
            st = Status::error(Status::BadInput, options.manifest + ": jobs[" + std::to_string(i) + "] (" +
                                                     jobs[i].input + "): " + st.message);
    }
    if (!st) {
        std::fprintf(stderr, "loopbake: error: %s\n", st.message.c_str());
        return int(Status::BadInput);
    }

    std::vector<JobResult> results(jobs.size());
    std::atomic<size_t> next{0};
    std::mutex printing;
    auto worker = [&] {
        for (size_t i; (i = next++) < jobs.size();) {
            const auto t0 = Clock::now();
            JobResult& r = results[i];
            r.status = bakeOne(callbacks, jobs[i], r);
            r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
            std::lock_guard<std::mutex> lock(printing);
            printJob(jobs[i], r, jobs.size(), options.verbose);
        }
    };
    const unsigned threads =
        unsigned(std::min<size_t>(std::max(1u, options.threads), std::max<size_t>(1, jobs.size())));
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();

    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    int code = 0;
    size_t failed = 0;
    for (const JobResult& r : results) {
        if (!r.status && code == 0) code = int(r.status.code);
        failed += !r.status;
    }
    if (options.verbose)
        std::fprintf(stderr,
                     "loopbake: %zu of %zu jobs succeeded, %zu failed; %.3f s on %u thread%s, "
                     "peak resident %.1f MiB (getrusage)\n",
                     jobs.size() - failed, jobs.size(), failed, seconds, threads, threads == 1 ? "" : "s",
                     double(cli::peakRssBytes()) / double(1 << 20));
    if (!options.report.empty()) {
        const std::string json = reportJson(options, jobs, results, seconds);
        st = writeFileAtomic(options.report, reinterpret_cast<const uint8_t*>(json.data()), json.size());
        if (!st) {
            std::fprintf(stderr, "loopbake: error: %s\n", st.message.c_str());
            if (code == 0) code = int(Status::WriteFailed);
        }
    }
    return code;
}

}  // namespace lt::batch

// loopbake --manifest: many bakes in one process (part of the loopbake tool).
//
// A manifest is a JSON file listing jobs; paths are relative to the manifest's folder:
//
//   {"jobs": [
//     {"input": "hero.obj", "output": "out/hero.glb", "max-depth": 5, "crease-angle": 40},
//     {"input": "duck.glb", "output": "out/duck.glb", "strict": true, "max-faces": 20000}
//   ]}
//
// Every key other than "input" and "output" is a loopbake option without its leading
// "--": a number or string is its value ("--max-depth=5"), true adds a flag
// ("--strict"), false leaves it out. A job's options come after the command line's,
// so they override it for that job. Options that would change the batch itself
// (-o, --json, --manifest, --threads, -v, --help, --version) are refused, as are two
// jobs with the same output, or an output that is another job's input.
//
// readManifest checks the whole manifest first (nothing is baked when it is
// malformed); run() then bakes every job, on `threads` threads, continuing past
// failed jobs. Each output is written atomically by the bake callback, so a failed
// job leaves no file. The report lists the jobs in manifest order whatever the
// thread count, and each output depends only on its own job: the bytes are the same
// with any number of threads.
#pragma once

#include "looptess/tools/baker.h"

#include <functional>
#include <string>
#include <vector>

namespace lt::batch {

struct Job {
    size_t index = 0;                  // position in the manifest
    std::string input, output;         // resolved against the manifest's folder
    std::vector<std::string> options;  // "--name=value" or "--name", in manifest order
};

// Reads and checks `path`. Errors (BadInput) name the manifest and the job:
//   "list.json: jobs[3].max-depth: must be a number, string or boolean".
Status readManifest(const std::string& path, std::vector<Job>& jobs);

// What the bake callback reports about one job.
struct JobResult {
    Status status;
    uint64_t outputBytes = 0;
    uint32_t faces = 0, vertices = 0;  // of the control mesh, when it was read
    MemoryStats memory;
    std::string report;  // the job's own --json report (JSON text), or ""
    double seconds = 0;  // filled by run()
};

struct Options {
    std::string manifest;
    std::string report;    // --json; empty: none
    unsigned threads = 1;  // >= 1
    bool verbose = false;  // -v: a line per job, timings in the report
};

// `check` validates a job's options without baking (called for every job before any
// bake); `bake` bakes one job and must be safe to call from several threads at once.
struct Callbacks {
    std::function<Status(const Job&)> check;
    std::function<Status(const Job&, JobResult&)> bake;
};

// Runs the manifest and writes the report. Returns the exit code: 0 when every job
// succeeded; otherwise the exit code of the first failed job in manifest order (2
// bad input, 3 unsupported, 4 write failed, 5 internal); 2 when the manifest itself
// is unreadable or malformed (nothing is baked); 4 when the report cannot be written.
int run(const Options& options, const Callbacks& callbacks);

}  // namespace lt::batch

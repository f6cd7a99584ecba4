// looptess/tools/file_io.h -- the file helpers the command-line tools share. The
// libraries themselves do no I/O; only the tools' thin mains call these.
#pragma once

#include "looptess/asset.h"

#include <string>
#include <vector>

namespace lt {

// Reads a whole file. Fails with BadInput naming the path when it cannot be read
// or is larger than `maxBytes`.
Status readFile(const std::string& path, std::vector<uint8_t>& bytes, size_t maxBytes = size_t(1) << 31);

// Writes `bytes` to `path` atomically: to a temporary file beside it, then renamed
// over `path`. On failure nothing is left behind (no partial or temporary file).
Status writeFileAtomic(const std::string& path, const uint8_t* data, size_t size);

// The same text for every path naming one file: absolute, normalized, links
// resolved where the file exists (lexically normalized where that fails).
std::string fileKey(const std::string& path);

// A file a tool reads or writes, by the option that names it ("--json") or by its
// role ("the input"), for checkDistinctFiles.
struct NamedFile {
    std::string name, path;  // path empty: not given
    bool written = false;
};

// Usage error when a written file of `files` and another of them name one file (the
// same path however written, or one file through a link): a report or depfile would
// overwrite the input it is about, or the output. The first such pair in order,
// e.g. "--json 'a.obj' is also the input". Files that are only read may coincide.
Status checkDistinctFiles(const std::vector<NamedFile>& files);

// Whether `path` names a USD layer (.usd, .usda, .usdc, .usdz, any case): the tools
// take it to the USD reader, or refuse it clearly when built without one.
bool isUsdPath(const std::string& path);

}  // namespace lt

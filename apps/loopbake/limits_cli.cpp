// loopbake's resource-limit options and memory report (see limits_cli.h).
#include "limits_cli.h"

#include <sys/resource.h>
#include <sys/stat.h>

#include <algorithm>
#include <charconv>
#include <cstdio>

namespace lt::cli {
namespace {

constexpr uint64_t kMiB = uint64_t(1) << 20;

// One option: its name, the field it sets, its range, and the unit its value is in.
struct LimitOption {
    const char* name;
    uint64_t lo, hi;
    uint64_t scale;  // value * scale is stored (MiB for --max-memory-mb)
    const char* help;
};

// Ranges: counts stay far below 2^32 indices and OpenSubdiv's int indices after
// refinement; OpenSubdiv stores valences in 16 bits; a GLB's length field is 32 bits.
const LimitOption kOptions[] = {
    {"--max-input-bytes", 1, uint64_t(1) << 40, 1, "size of the input file in bytes"},
    {"--max-faces", 1, uint64_t(1) << 28, 1,
     "triangles of one mesh after triangulation (a glTF mesh once, however many nodes draw it)"},
    {"--max-vertices", 1, uint64_t(1) << 28, 1, "control vertices"},
    {"--max-valence", 3, 65535, 1, "edges at one vertex"},
    {"--max-output-bytes", 1, (uint64_t(1) << 32) - 1, 1, "size of the written GLB in bytes"},
    {"--max-memory-mb", 1, uint64_t(1) << 24, kMiB, "the bake's estimated memory in MiB, checked before refining"},
};

uint64_t current(const Limits& l, const std::string& name) {
    if (name == "--max-input-bytes") return l.maxInputBytes;
    if (name == "--max-faces") return l.maxFaces;
    if (name == "--max-vertices") return l.maxVertices;
    if (name == "--max-valence") return l.maxValence;
    if (name == "--max-output-bytes") return l.maxOutputBytes;
    return l.maxMemoryBytes / kMiB;
}

void store(Limits& l, const std::string& name, uint64_t v) {
    if (name == "--max-input-bytes")
        l.maxInputBytes = v;
    else if (name == "--max-faces")
        l.maxFaces = uint32_t(v);
    else if (name == "--max-vertices")
        l.maxVertices = uint32_t(v);
    else if (name == "--max-valence")
        l.maxValence = uint32_t(v);
    else if (name == "--max-output-bytes")
        l.maxOutputBytes = v;
    else
        l.maxMemoryBytes = v;
}

}  // namespace

std::string limitsUsage() {
    const Limits defaults;
    std::string text = "resource limits (exceeding one is bad input, exit 2):\n";
    for (const LimitOption& o : kOptions) {
        std::string line = std::string("  ") + o.name + " N";
        line.resize(std::max<size_t>(line.size() + 2, 24), ' ');
        text += line + o.help + " (default " + std::to_string(current(defaults, o.name)) + ")\n";
    }
    return text;
}

bool isLimitOption(const std::string& opt) {
    for (const LimitOption& o : kOptions)
        if (opt == o.name) return true;
    return false;
}

bool applyLimitOption(const std::string& opt, const std::string& value, Limits& limits, Status& st) {
    for (const LimitOption& o : kOptions) {
        if (opt != o.name) continue;
        uint64_t v = 0;
        const char* end = value.data() + value.size();
        auto res = std::from_chars(value.data(), end, v);
        if (res.ec != std::errc() || res.ptr != end || v < o.lo || v > o.hi) {
            st = Status::error(Status::Usage, opt + " must be an integer from " + std::to_string(o.lo) + " to " +
                                                  std::to_string(o.hi) + ", not '" + value + "'");
        } else {
            store(limits, opt, v * o.scale);
            st = Status::ok();
        }
        return true;
    }
    return false;
}

Status checkInputFile(const std::string& path, const Limits& limits) {
    struct stat s;
    if (stat(path.c_str(), &s) != 0 || !S_ISREG(s.st_mode)) return Status::ok();
    return checkInputBytes(uint64_t(s.st_size), limits, path);
}

uint64_t peakRssBytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
    return uint64_t(usage.ru_maxrss) * 1024;  // Linux: kilobytes
}

void printMemory(const MemoryStats& m, const Limits& limits) {
    std::fprintf(stderr,
                 "memory: bake estimated %.1f MiB (limit %.0f MiB; %llu refined faces estimated, %llu made); "
                 "peak resident %.1f MiB (getrusage)\n",
                 double(m.estimatedBytes) / kMiB, double(limits.maxMemoryBytes) / kMiB,
                 static_cast<unsigned long long>(m.estimatedRefinedFaces),
                 static_cast<unsigned long long>(m.refinedFaces), double(peakRssBytes()) / kMiB);
}

nlohmann::ordered_json limitsJson(const Limits& l) {
    return {{"maxInputBytes", l.maxInputBytes},   {"maxFaces", l.maxFaces},
            {"maxVertices", l.maxVertices},       {"maxValence", l.maxValence},
            {"maxOutputBytes", l.maxOutputBytes}, {"maxMemoryBytes", l.maxMemoryBytes}};
}

nlohmann::ordered_json memoryJson(const MemoryStats& m, bool verbose) {
    nlohmann::ordered_json j = {{"estimatedBytes", m.estimatedBytes},
                                {"estimatedRefinedFaces", m.estimatedRefinedFaces},
                                {"estimatedOutputBytes", m.estimatedOutputBytes},
                                {"refinedFaces", m.refinedFaces}};
    if (verbose) j["peakRssBytes"] = peakRssBytes();  // the whole process, so far
    return j;
}

}  // namespace lt::cli

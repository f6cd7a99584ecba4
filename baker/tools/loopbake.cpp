// loopbake -- bakes Loop subdivision tables from a triangle control mesh (.obj,
// .gltf, .glb) into a GLB with the EXT_mesh_loop_subdivision extension.
//
//   loopbake IN -o OUT.glb [--max-depth D] [--crease-angle DEG] [--strict] [-v]
//            [--edits EDITS.json]
//            [--displacement MAP.png --scale S [--bias B] [--displacement-resolution R]]
//            [--json REPORT.json] [--help] [--version]
//            [--max-faces N] [--max-vertices N] [--max-valence N] [--max-input-bytes N]
//            [--max-output-bytes N] [--max-memory-mb N]      (limits_cli.h; exit 2 past one)
//   loopbake --manifest LIST.json [--json REPORT.json] [--threads N] [options]
//            (batch.h: the manifest format; exit 0, or the first failed job's code)
//
// Exit codes (the same numbers as lt::Status::Code):
//   0  success
//   1  usage error (bad command line)
//   2  bad input (unreadable file, parse error, mesh rejected by checks or by the baker)
//   3  unsupported (input format or feature looptess does not handle)
//   4  write failed (output or report could not be written)
//   5  internal error
//
// Outputs are written to `OUT.tmp-<pid>` and renamed into place, so OUT is never
// left partial; the temporary is removed on failure (lt::writeFileAtomic).
#include "looptess/baker.h"
#include "looptess/file_io.h"

#include "batch.h"
#include "limits_cli.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <optional>
#include <thread>
#include <string>
#include <vector>

namespace {

using lt::Status;
using Clock = std::chrono::steady_clock;

const char* const kUsage =
    "usage: loopbake IN -o OUT.glb [options]\n"
    "       loopbake --manifest LIST.json [--json REPORT.json] [--threads N] [options]\n"
    "\n"
    "Bakes Loop subdivision tables from a triangle control mesh (.obj, .gltf or .glb)\n"
    "into a glTF 2.0 binary using the EXT_mesh_loop_subdivision extension.\n"
    "\n"
    "options:\n"
    "  -o OUT.glb          output file (written atomically; never left partial)\n"
    "  --max-depth D       maximum adaptive refinement depth, 1..8 (default: the\n"
    "                      deepest up to 6 that fits --max-memory-mb and\n"
    "                      --max-output-bytes; a lower one is said on stderr)\n"
    "  --crease-angle DEG  make edges whose face normals differ by more than DEG\n"
    "                      degrees (0..180) infinitely sharp (default: off)\n"
    "  --strict            reject quads and n-gons instead of triangulating them\n"
    "  --edits EDITS.json  hierarchical vertex edits for any input (README \"Hierarchical\n"
    "                      edits\"), after an OBJ's own 't vertexedit' tags\n"
    "  --displacement MAP.png  bake a scalar displacement map (8- or 16-bit grayscale\n"
    "                      PNG, read through the mesh's UVs) into the asset; needs --scale\n"
    "  --scale S           displacement = S * map + B in object units (map 0..1)\n"
    "  --bias B            (default 0)\n"
    "  --displacement-resolution R  samples per face edge, a power of two 1..64\n"
    "                      (default: about one sample per texel of the map, at most 64)\n"
    "  --json REPORT.json  write a machine-readable report (timings only with -v)\n"
    "  -v                  print per-level statistics, table sizes and times to stderr\n"
    "  --help              print this help and exit\n"
    "  --version           print the version and exit\n"
    "  --manifest LIST.json  bake every job of LIST.json in one process (no IN or -o):\n"
    "                      {\"jobs\": [{\"input\": \"a.obj\", \"output\": \"a.glb\", \"max-depth\": 4}]}\n"
    "                      paths relative to LIST.json's folder; other keys are options\n"
    "                      without '--' (true: a flag), overriding the command line's;\n"
    "                      continues past failed jobs; --json reports every job; exit 0\n"
    "                      when all succeed, else the first failed job's exit code\n"
    "  --threads N         bake N manifest jobs at once (default 1; 0: one per core);\n"
    "                      the outputs are the same bytes with any N\n"
    "\n"
    "exit codes:\n"
    "  0 success   1 usage error   2 bad input   3 unsupported\n"
    "  4 write failed   5 internal error\n";

// Every option and its default, in one place.
struct Settings {
    std::string input;
    std::string output;
    std::string report;                  // --json; empty: none
    int maxDepth = 0;                    // --max-depth; 0: automatic (lt::BakeSettings)
    std::optional<float> creaseAngle;    // --crease-angle; unset: off
    bool strict = false;
    std::string edits;                   // --edits EDITS.json; empty: none
    std::string displacement;            // --displacement MAP.png; empty: none
    std::optional<float> scale, bias;    // --scale (required with a map), --bias (default 0)
    std::optional<int> displacementResolution;   // --displacement-resolution; unset: chosen
    bool verbose = false;
    bool help = false;
    bool version = false;
    lt::Limits limits;                   // --max-faces etc. (lt::cli::applyLimitOption)
    std::string manifest;                // --manifest LIST.json; empty: one file
    unsigned threads = 1;                // --threads (manifest jobs at once)
};

Status usage(const std::string& what) { return Status::error(Status::Usage, what); }

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

// Parses a whole-string number in [lo, hi] (locale-independent).
template <typename T>
bool parseNumber(const std::string& text, T lo, T hi, T& out) {
    T value{};
    const char* end = text.data() + text.size();
    auto res = std::from_chars(text.data(), end, value);
    if (res.ec != std::errc() || res.ptr != end || !(value >= lo && value <= hi)) return false;
    out = value;
    return true;
}

Status applyOption(const std::string& opt, const std::string& value, Settings& s) {
    if (Status st; lt::cli::applyLimitOption(opt, value, s.limits, st)) return st;
    if (opt == "--manifest") s.manifest = value;
    else if (opt == "--threads") {
        if (!parseNumber(value, 0u, 256u, s.threads))
            return usage("--threads must be an integer from 0 to 256, not '" + value + "'");
        if (s.threads == 0) s.threads = std::max(1u, std::thread::hardware_concurrency());
    } else if (opt == "-o") s.output = value;
    else if (opt == "--json") s.report = value;
    else if (opt == "--edits") s.edits = value;
    else if (opt == "--max-depth") {
        if (!parseNumber(value, 1, 8, s.maxDepth))
            return usage("--max-depth must be an integer from 1 to 8, not '" + value + "'");
    } else if (opt == "--displacement") {
        s.displacement = value;
    } else if (opt == "--scale" || opt == "--bias") {
        float x = 0;
        if (!parseNumber(value, -std::numeric_limits<float>::max(), std::numeric_limits<float>::max(), x))
            return usage(opt + " must be a finite number, not '" + value + "'");
        (opt == "--scale" ? s.scale : s.bias) = x;
    } else if (opt == "--displacement-resolution") {
        int r = 0;
        if (!parseNumber(value, 1, 64, r) || (r & (r - 1)) != 0)
            return usage("--displacement-resolution must be a power of two from 1 to 64, not '" + value + "'");
        s.displacementResolution = r;
    } else {
        float deg = 0;
        if (!parseNumber(value, 0.0f, 180.0f, deg))
            return usage("--crease-angle must be a number of degrees from 0 to 180, not '" +
                         value + "'");
        s.creaseAngle = deg;
    }
    return Status::ok();
}

Status parseArgs(int argc, char** argv, Settings& s) {
    const char* const withValue[] = {"-o", "--json", "--max-depth", "--crease-angle", "--displacement", "--scale",
                                     "--bias", "--displacement-resolution", "--edits"};
    bool optionsDone = false;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (optionsDone || arg.empty() || arg[0] != '-' || arg == "-") {
            if (!s.input.empty()) return usage("more than one input file ('" + arg + "')");
            s.input = arg;
            continue;
        }
        if (arg == "--") optionsDone = true;
        else if (arg == "--help" || arg == "-h") s.help = true;
        else if (arg == "--version") s.version = true;
        else if (arg == "--strict") s.strict = true;
        else if (arg == "-v" || arg == "--verbose") s.verbose = true;
        else {
            size_t eq = arg.find('=');
            std::string opt = arg.substr(0, eq);
            if (std::find(std::begin(withValue), std::end(withValue), opt) == std::end(withValue) &&
                !lt::cli::isLimitOption(opt) && opt != "--manifest" && opt != "--threads")
                return usage("unknown option '" + arg + "'");
            if (eq == std::string::npos && i + 1 >= argc)
                return usage("option '" + opt + "' needs a value");
            std::string value = eq == std::string::npos ? argv[++i] : arg.substr(eq + 1);
            if (Status st = applyOption(opt, value, s); !st) return st;
        }
    }
    if (s.help || s.version) return Status::ok();
    if (!s.manifest.empty() && (!s.input.empty() || !s.output.empty()))
        return usage("--manifest takes no input file or -o (the manifest lists them)");
    if (!s.manifest.empty()) return Status::ok();   // each job is checked when the manifest is read
    if (s.threads != 1) return usage("--threads needs --manifest");
    if (s.input.empty()) return usage("no input file");
    if (s.output.empty()) return usage("no output file (-o OUT.glb)");
    if (s.displacement.empty() && (s.scale || s.bias || s.displacementResolution))
        return usage("--scale, --bias and --displacement-resolution need --displacement MAP.png");
    if (!s.displacement.empty() && !s.scale) return usage("--displacement needs --scale S (object units)");
    if (lowerExtension(s.output) != ".glb") return usage("output '" + s.output + "' must be a .glb file");
    return Status::ok();
}

Status loadMesh(const Settings& s, lt::InputMesh& mesh) {
    std::string ext = lowerExtension(s.input);
    if (ext != ".obj" && ext != ".gltf" && ext != ".glb")
        return Status::error(Status::Unsupported, s.input + ": unsupported input format '" + ext +
                                                      "' (expected .obj, .gltf or .glb)");
    std::vector<uint8_t> bytes;
    if (Status st = lt::cli::checkInputFile(s.input, s.limits); !st) return st;
    if (Status st = lt::readFile(s.input, bytes, s.limits.maxInputBytes); !st) return st;
    if (ext == ".obj") {
        lt::InputOptions options;
        options.strict = s.strict;
        options.limits = s.limits;
        std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        return lt::parseObj(text, s.input, options, mesh);
    }
    std::string dir = std::filesystem::path(s.input).parent_path().string();
    return lt::parseGltf(bytes.data(), bytes.size(), s.input, dir.empty() ? "." : dir, s.limits, mesh);
}

// --edits: the side-car's edits follow the input's own (baker.h, parseEditsJson).
Status loadEdits(const Settings& s, lt::InputMesh& mesh) {
    std::vector<uint8_t> bytes;
    if (Status st = lt::cli::checkInputFile(s.edits, s.limits); !st) return st;
    if (Status st = lt::readFile(s.edits, bytes, s.limits.maxInputBytes); !st) return st;
    return lt::parseEditsJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                              s.edits, mesh);
}

// checkInput and bake number the edits of the input's tags and of the side-car
// together ("hero.obj: vertex edit 5 (face ...) ..."): name the side-car entry a bad
// edit came from.
void nameEditSource(const Settings& s, size_t tagEdits, Status& st) {
    const std::string key = s.input + ": vertex edit ";
    size_t edit = 0;
    if (s.edits.empty() || st.message.rfind(key, 0) != 0) return;
    const char* first = st.message.data() + key.size();
    if (std::from_chars(first, st.message.data() + st.message.size(), edit).ec != std::errc() || edit < tagEdits)
        return;
    st.message += " (" + s.edits + ": edits[" + std::to_string(edit - tagEdits) + "])";
}

void printWarnings(const std::vector<std::string>& warnings) {
    for (const std::string& w : warnings) std::fprintf(stderr, "loopbake: warning: %s\n", w.c_str());
}

// Everything a run produces besides the output file, for -v and --json.
struct Results {
    lt::InputMesh mesh;
    size_t inputCreases = 0, autoCreases = 0;
    std::vector<std::string> warnings;
    lt::BakeStats stats;
    lt::TableBytes tableBytes;
    std::vector<uint32_t> levelEdits;    // hierarchical edits per level (asset.levels[l].edits)
    lt::GrayImage map;                   // --displacement, decoded (texels dropped after use)
    uint32_t displacementResolution = 0; // 0: no map
    size_t displacementSamples = 0;
    size_t outputBytes = 0;
    double readSeconds = 0, bakeSeconds = 0, writeSeconds = 0;
};

uint32_t levelEdits(const Results& r, size_t level) {
    return level < r.levelEdits.size() ? r.levelEdits[level] : 0;
}

void printVerbose(const Settings& s, const Results& r) {
    const lt::InputMesh& m = r.mesh;
    std::fprintf(stderr,
                 "loopbake: %s: %u vertices, %u faces, %zu creases (%zu by angle), %zu corners, "
                 "%zu holes%s\n",
                 s.input.c_str(), m.vertexCount(), m.faceCount(), m.creases.size(), r.autoCreases,
                 m.corners.size(), m.holes.size(), m.faceUVs.empty() ? "" : ", uvs");
    std::fprintf(stderr, "%5s %10s %10s %10s %10s %10s %10s\n", "level", "vertices", "RPP", "NPP", "IPP", "limit",
                 "edits");
    for (size_t l = 0; l < r.stats.levels.size(); ++l) {
        const lt::LevelStats& ls = r.stats.levels[l];
        std::fprintf(stderr, "%5zu %10u %10u %10u %10u %10u %10u\n", l, ls.vertices, ls.rpp, ls.npp, ls.ipp,
                     ls.limitStencils, levelEdits(r, l));
    }
    const lt::TableBytes& b = r.tableBytes;
    if (r.displacementResolution)
        std::fprintf(stderr, "displacement: %s, %ux%u, %u-bit; resolution %u, %zu samples\n", s.displacement.c_str(),
                     r.map.width, r.map.height, r.map.bitDepth, r.displacementResolution, r.displacementSamples);
    std::fprintf(stderr, "table bytes: control mesh %zu, refinement %zu, masks %zu, patches %zu, "
                         "irregular %zu, limit %zu, displacement %zu, edits %zu, total %zu\n",
                 b.controlMesh, b.refinement, b.masks, b.patches, b.irregular, b.limit, b.displacement, b.edits,
                 b.total());
    std::fprintf(stderr, "time: read %.3f s, bake %.3f s, write %.3f s; output %zu bytes\n",
                 r.readSeconds, r.bakeSeconds, r.writeSeconds, r.outputBytes);
    lt::cli::printMemory(r.stats.memory, s.limits);
}

// Byte-stable for identical inputs and settings: timings only appear with -v.
std::string reportJson(const Settings& s, const Results& r) {
    using Json = nlohmann::ordered_json;
    const lt::InputMesh& m = r.mesh;
    Json j;
    j["tool"] = "loopbake";
    j["version"] = LOOPTESS_VERSION;
    j["input"] = {{"file", s.input}, {"vertices", m.vertexCount()}, {"faces", m.faceCount()},
                  {"creases", r.inputCreases}, {"corners", m.corners.size()},
                  {"holes", m.holes.size()}, {"uvs", !m.faceUVs.empty()}};
    j["settings"] = {{"maxDepth", r.stats.depth},
                     {"depthAutomatic", s.maxDepth == 0},
                     {"depthReason", r.stats.depthReason},
                     {"creaseAngle", s.creaseAngle ? Json(*s.creaseAngle) : Json(nullptr)},
                     {"strict", s.strict}};
    if (r.displacementResolution)
        j["settings"]["displacement"] = {{"file", s.displacement}, {"scale", *s.scale}, {"bias", s.bias.value_or(0.0f)},
                                         {"resolution", r.displacementResolution},
                                         {"mapWidth", r.map.width}, {"mapHeight", r.map.height},
                                         {"mapBitDepth", r.map.bitDepth}, {"samples", r.displacementSamples}};
    j["autoCreases"] = r.autoCreases;
    j["levels"] = Json::array();
    for (size_t l = 0; l < r.stats.levels.size(); ++l) {
        const lt::LevelStats& ls = r.stats.levels[l];
        j["levels"].push_back({{"level", l}, {"vertices", ls.vertices}, {"rpp", ls.rpp},
                               {"npp", ls.npp}, {"ipp", ls.ipp}, {"limitStencils", ls.limitStencils},
                               {"edits", levelEdits(r, l)}});
    }
    const lt::TableBytes& b = r.tableBytes;
    j["tableBytes"] = {{"controlMesh", b.controlMesh}, {"refinement", b.refinement},
                       {"masks", b.masks}, {"patches", b.patches}, {"irregular", b.irregular},
                       {"limit", b.limit}, {"displacement", b.displacement}, {"edits", b.edits},
                       {"total", b.total()}};
    j["output"] = {{"file", s.output}, {"bytes", r.outputBytes}};
    j["warnings"] = r.warnings;
    j["limits"] = lt::cli::limitsJson(s.limits);
    j["memory"] = lt::cli::memoryJson(r.stats.memory, s.verbose);
    if (s.verbose)
        j["timing"] = {{"readSeconds", r.readSeconds}, {"bakeSeconds", r.bakeSeconds},
                       {"writeSeconds", r.writeSeconds}};
    return j.dump(2) + "\n";
}

double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// --displacement: decodes the PNG and resamples it into `asset` (baker.h).
Status addDisplacement(const Settings& s, lt::Asset& asset, Results& r) {
    std::vector<uint8_t> png;
    Status st = lt::readFile(s.displacement, png);
    if (st) st = lt::decodeGrayPng(png.data(), png.size(), s.displacement, r.map);
    if (!st) return st;
    lt::DisplacementSettings ds;
    ds.scale = *s.scale;
    ds.bias = s.bias.value_or(0.0f);
    ds.resolution = uint32_t(s.displacementResolution.value_or(0));
    if (st = lt::bakeDisplacement(r.map, ds, asset, s.input); !st) return st;
    r.map.texels = {};
    r.displacementResolution = asset.displacement.resolution;
    r.displacementSamples = asset.displacement.values.size();
    return Status::ok();
}

// Reads, checks and bakes; the output file is only renamed into place on success.
Status bakeFile(const Settings& s, Results& r) {
    auto t0 = Clock::now();
    if (Status st = loadMesh(s, r.mesh); !st) return st;
    const size_t tagEdits = r.mesh.edits.size();
    if (!s.edits.empty())
        if (Status st = loadEdits(s, r.mesh); !st) return st;
    r.warnings = r.mesh.warnings;
    std::vector<std::string> checkWarnings;
    Status st = lt::checkInput(r.mesh, s.input, checkWarnings);
    nameEditSource(s, tagEdits, st);
    r.warnings.insert(r.warnings.end(), checkWarnings.begin(), checkWarnings.end());
    printWarnings(r.warnings);
    if (!st) return st;
    r.inputCreases = r.mesh.creases.size();
    if (s.creaseAngle) lt::addCreasesByAngle(r.mesh, *s.creaseAngle);
    r.autoCreases = r.mesh.creases.size() - r.inputCreases;
    r.readSeconds = secondsSince(t0);

    t0 = Clock::now();
    lt::Asset asset;
    lt::BakeSettings bakeSettings;
    bakeSettings.maxDepth = s.maxDepth;
    bakeSettings.limits = s.limits;
    bakeSettings.name = s.input;
    st = lt::bake(r.mesh, bakeSettings, asset, &r.stats);
    nameEditSource(s, tagEdits, st);
    if (!st) return st;
    if (r.stats.depthLowered || (s.verbose && s.maxDepth == 0))
        std::fprintf(stderr, "loopbake: %s: %s\n", s.input.c_str(), r.stats.depthReason.c_str());
    for (const lt::Level& level : asset.levels) r.levelEdits.push_back(level.edits.count());
    if (!s.displacement.empty())
        if (st = addDisplacement(s, asset, r); !st) return st;
    std::vector<uint8_t> bytes;
    if (st = lt::writeAssetGlb(asset, bytes, &r.tableBytes); !st) return st;
    r.bakeSeconds = secondsSince(t0);

    t0 = Clock::now();
    if (st = lt::checkOutputBytes(bytes.size(), s.limits, s.output); !st) return st;
    if (st = lt::writeFileAtomic(s.output, bytes.data(), bytes.size()); !st) return st;
    r.outputBytes = bytes.size();
    r.writeSeconds = secondsSince(t0);
    return Status::ok();
}

// --manifest: each job bakes with this command line's settings followed by the job's
// own options, parsed exactly as a command line (batch.h).
Status jobSettings(const Settings& base, const lt::batch::Job& job, Settings& s) {
    s = base;
    s.manifest.clear();
    s.report.clear();
    s.threads = 1;
    std::vector<std::string> args = {"loopbake", "-o", job.output};
    args.insert(args.end(), job.options.begin(), job.options.end());
    args.insert(args.end(), {"--", job.input});
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    return parseArgs(int(argv.size()), argv.data(), s);
}

int runManifest(const Settings& base) {
    lt::batch::Callbacks callbacks;
    callbacks.check = [&](const lt::batch::Job& job) {
        Settings s;
        return jobSettings(base, job, s);
    };
    callbacks.bake = [&](const lt::batch::Job& job, lt::batch::JobResult& out) {
        Settings s;
        Results r;
        Status st = jobSettings(base, job, s);
        if (st) st = bakeFile(s, r);
        out.faces = r.mesh.faceCount();
        out.vertices = r.mesh.vertexCount();
        out.memory = r.stats.memory;
        out.outputBytes = r.outputBytes;
        if (st) out.report = reportJson(s, r);
        return st;
    };
    return lt::batch::run({base.manifest, base.report, base.threads, base.verbose}, callbacks);
}

int run(int argc, char** argv) {
    Settings s;
    if (Status st = parseArgs(argc, argv, s); !st) {
        std::fprintf(stderr, "loopbake: error: %s\nrun 'loopbake --help' for usage\n", st.message.c_str());
        return int(st.code);
    }
    if (s.help) {
        const std::string text = kUsage;   // the limit options go before the exit codes
        const size_t at = std::min(text.find("\nexit codes:"), text.size());
        std::fputs((text.substr(0, at) + "\n" + lt::cli::limitsUsage() + text.substr(at)).c_str(), stdout);
        return 0;
    }
    if (s.version) {
        std::printf("loopbake %s\n", LOOPTESS_VERSION);
        return 0;
    }
    if (!s.manifest.empty()) return runManifest(s);
    Results r;
    Status st = bakeFile(s, r);
    if (st && s.verbose) printVerbose(s, r);
    if (st && !s.report.empty()) {
        std::string json = reportJson(s, r);
        st = lt::writeFileAtomic(s.report, reinterpret_cast<const uint8_t*>(json.data()), json.size());
    }
    if (!st) std::fprintf(stderr, "loopbake: error: %s\n", st.message.c_str());
    return int(st.code);
}

} // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "loopbake: error: out of memory\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "loopbake: error: internal error: %s\n", e.what());
    }
    return int(Status::Internal);
}

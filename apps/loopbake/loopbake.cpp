// loopbake -- bakes Loop subdivision tables from a triangle control mesh (.obj,
// .gltf, .glb) into a GLB with the EXT_mesh_loop_subdivision extension.
//
//   loopbake IN -o OUT.glb [--max-depth D] [--crease-angle DEG] [--hard-edges] [--strict] [-v]
//            [--boundary none|edge|edge-and-corner] [--time T]
//            [--edits EDITS.json] [--mesh NAME|INDEX ...]
//            [--displacement MAP.png --scale S [--bias B] [--displacement-resolution R]]
//            [--compress none|fast|max] [--json REPORT.json] [--depfile OUT.d] [--threads N]
//            [--help] [--version]
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
#include "looptess/tools/baker.h"
#include "looptess/tools/file_io.h"
#include "looptess/version.h"

#include "bake_job.h"
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

using namespace loopbake;

const char* const kUsage =
    "usage: loopbake IN -o OUT.glb [options]\n"
    "       loopbake --manifest LIST.json [--json REPORT.json] [--threads N] [options]\n"
    "\n"
    "Bakes Loop subdivision tables from a triangle control mesh (.obj, .gltf or .glb,\n"
    "or a USD layer: .usd, .usda, .usdc, .usdz) into a glTF 2.0 binary using the\n"
    "EXT_mesh_loop_subdivision extension.\n"
    "\n"
    "options:\n"
    "  -o OUT.glb          output file (written atomically; never left partial)\n"
    "  --max-depth D       maximum adaptive refinement depth, 1..8 (default: the\n"
    "                      deepest up to 6 that fits --max-memory-mb and\n"
    "                      --max-output-bytes; a lower one is said on stderr)\n"
    "  --crease-angle DEG  make edges whose face normals differ by more than DEG\n"
    "                      degrees (0..180) infinitely sharp (default: off)\n"
    "  --hard-edges        glTF: make the edges along which the exporter split the\n"
    "                      vertex normals (its hard edges) infinitely sharp\n"
    "  --boundary none|edge|edge-and-corner  the boundary rule of every mesh baked\n"
    "                      (OpenSubdiv's VTX_BOUNDARY_*): edge keeps the boundary a\n"
    "                      smooth curve, edge-and-corner also keeps vertices of one face\n"
    "                      as corners (USD's default), none leaves faces at the boundary\n"
    "                      undrawn. Default: an OBJ's 't interpolateboundary' tag, else\n"
    "                      edge; overrides the tag (with a warning when they differ)\n"
    "  --strict            accept the mesh only as written: reject quads and n-gons\n"
    "                      instead of triangulating them, and faces with repeated\n"
    "                      vertices, of zero area or repeating another face instead\n"
    "                      of repairing or dropping them (exit 2, naming the first)\n"
    "  --mesh NAME|INDEX   glTF: bake only this mesh (repeatable); the others pass\n"
    "                      through untouched (default: every mesh of triangles);\n"
    "                      USD: a Loop mesh's prim path (/root/body) or glTF index\n"
    "  --time T            USD: read values at time code T (the sample at T, else\n"
    "                      the default value, else the last sample before T, else\n"
    "                      the first; default: the default value, else the first)\n"
    "  --edits EDITS.json  hierarchical vertex edits for any input (README \"Hierarchical\n"
    "                      edits\"), after an OBJ's own 't vertexedit' tags\n"
    "  --displacement MAP.png  bake a scalar displacement map (8- or 16-bit grayscale\n"
    "                      PNG, read through the mesh's UVs) into the asset; needs --scale\n"
    "  --scale S           displacement = S * map + B in object units (map 0..1)\n"
    "  --bias B            (default 0)\n"
    "  --displacement-resolution R  samples per face edge, a power of two 1..64\n"
    "                      (default: about one sample per texel of the map, at most 64)\n"
    "  --compress none|fast|max  how the tables are stored (default fast): one\n"
    "                      Zstandard stream per mesh, level 4 (fast) or 19 (max: smaller,\n"
    "                      slower to bake), or plain accessors (none); the cage never is\n"
    "  --json REPORT.json  write a machine-readable report, also when the bake fails\n"
    "                      (timings only with -v)\n"
    "  --depfile OUT.d     write a Make-syntax depfile: the output depends on the input,\n"
    "                      its buffer and image files, --edits and --displacement\n"
    "                      (Ninja, Make; cmake/LooptessBake.cmake uses it)\n"
    "  -v                  print per-level statistics, table sizes and times to stderr\n"
    "  --help              print this help and exit\n"
    "  --version           print the version and exit\n"
    "  --manifest LIST.json  bake every job of LIST.json in one process (no IN or -o):\n"
    "                      {\"jobs\": [{\"input\": \"a.obj\", \"output\": \"a.glb\", \"max-depth\": 4}]}\n"
    "                      paths relative to LIST.json's folder; other keys are options\n"
    "                      without '--' (true: a flag), overriding the command line's;\n"
    "                      continues past failed jobs; --json reports every job; exit 0\n"
    "                      when all succeed, else the first failed job's exit code\n"
    "  --threads N         threads of the bake (default 0: one per core; 1: serial);\n"
    "                      with --manifest, N jobs at once (default 1; 0: one per\n"
    "                      core), each baking on cores / N threads; the outputs are\n"
    "                      the same bytes with any N\n"
    "\n"
    "exit codes:\n"
    "  0 success   1 usage error   2 bad input   3 unsupported\n"
    "  4 write failed   5 internal error\n";

Status usage(const std::string& what) { return Status::error(Status::Usage, what); }

const char* compressionName(lt::Compression c) {
    return c == lt::Compression::None ? "none" : c == lt::Compression::Fast ? "fast" : "max";
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
    if (opt == "--manifest")
        s.manifest = value;
    else if (opt == "--threads") {
        if (!parseNumber(value, 0u, 256u, s.threads))
            return usage("--threads must be an integer from 0 to 256, not '" + value + "'");
        s.bakeThreads = s.threads;
        if (s.threads == 0) s.threads = std::max(1u, std::thread::hardware_concurrency());
    } else if (opt == "-o")
        s.output = value;
    else if (opt == "--json")
        s.report = value;
    else if (opt == "--edits")
        s.edits = value;
    else if (opt == "--mesh")
        s.meshes.push_back(value);
    else if (opt == "--depfile")
        s.depfile = value;
    else if (opt == "--boundary") {
        lt::BoundaryInterpolation b{};
        if (!lt::parseBoundaryOption(value, b))
            return usage("--boundary must be none, edge or edge-and-corner, not '" + value + "'");
        s.boundary = b;
    } else if (opt == "--compress") {
        if (value == "none")
            s.compression = lt::Compression::None;
        else if (value == "fast")
            s.compression = lt::Compression::Fast;
        else if (value == "max")
            s.compression = lt::Compression::Max;
        else
            return usage("--compress must be none, fast or max, not '" + value + "'");
    } else if (opt == "--max-depth") {
        if (!parseNumber(value, 1, 8, s.maxDepth))
            return usage("--max-depth must be an integer from 1 to 8, not '" + value + "'");
    } else if (opt == "--displacement") {
        s.displacement = value;
    } else if (opt == "--time") {
        double t = 0;
        if (!parseNumber(value, -std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), t))
            return usage("--time must be a finite number (a USD time code), not '" + value + "'");
        s.time = t;
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
            return usage("--crease-angle must be a number of degrees from 0 to 180, not '" + value + "'");
        s.creaseAngle = deg;
    }
    return Status::ok();
}

Status parseArgs(int argc, char** argv, Settings& s) {
    const char* const withValue[] = {"-o",
                                     "--json",
                                     "--max-depth",
                                     "--crease-angle",
                                     "--displacement",
                                     "--scale",
                                     "--bias",
                                     "--displacement-resolution",
                                     "--edits",
                                     "--mesh",
                                     "--depfile",
                                     "--boundary",
                                     "--compress",
                                     "--time"};
    bool optionsDone = false;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (optionsDone || arg.empty() || arg[0] != '-' || arg == "-") {
            if (!s.input.empty()) return usage("more than one input file ('" + arg + "')");
            s.input = arg;
            continue;
        }
        if (arg == "--")
            optionsDone = true;
        else if (arg == "--help" || arg == "-h")
            s.help = true;
        else if (arg == "--version")
            s.version = true;
        else if (arg == "--strict")
            s.strict = true;
        else if (arg == "--hard-edges")
            s.hardEdges = true;
        else if (arg == "-v" || arg == "--verbose")
            s.verbose = true;
        else {
            size_t eq = arg.find('=');
            std::string opt = arg.substr(0, eq);
            if (std::find(std::begin(withValue), std::end(withValue), opt) == std::end(withValue) &&
                !lt::cli::isLimitOption(opt) && opt != "--manifest" && opt != "--threads")
                return usage("unknown option '" + arg + "'");
            if (eq == std::string::npos && i + 1 >= argc) return usage("option '" + opt + "' needs a value");
            std::string value = eq == std::string::npos ? argv[++i] : arg.substr(eq + 1);
            if (Status st = applyOption(opt, value, s); !st) return st;
        }
    }
    if (s.help || s.version) return Status::ok();
    if (!s.manifest.empty() && (!s.input.empty() || !s.output.empty()))
        return usage("--manifest takes no input file or -o (the manifest lists them)");
    if (!s.manifest.empty())  // each job is checked when the manifest is read
        return lt::checkDistinctFiles({{"--manifest", s.manifest, false}, {"--json", s.report, true}});
    if (s.input.empty()) return usage("no input file");
    if (s.output.empty()) return usage("no output file (-o OUT.glb)");
    if (s.displacement.empty() && (s.scale || s.bias || s.displacementResolution))
        return usage("--scale, --bias and --displacement-resolution need --displacement MAP.png");
    if (!s.displacement.empty() && !s.scale) return usage("--displacement needs --scale S (object units)");
    if (lowerExtension(s.output) != ".glb") return usage("output '" + s.output + "' must be a .glb file");
    return lt::checkDistinctFiles({{"the input", s.input, false},
                                   {"--edits", s.edits, false},
                                   {"--displacement", s.displacement, false},
                                   {"-o", s.output, true},
                                   {"--json", s.report, true},
                                   {"--depfile", s.depfile, true}});
}

uint32_t levelEdits(const MeshResult& m, size_t level) { return level < m.levelEdits.size() ? m.levelEdits[level] : 0; }

// The mesh whose bake needed the most memory (what the limits are about).
const MeshResult& largest(const Results& r) {
    return *std::max_element(r.meshes.begin(), r.meshes.end(), [](const MeshResult& a, const MeshResult& b) {
        return a.stats.memory.estimatedBytes < b.stats.memory.estimatedBytes;
    });
}

void printVerbose(const Settings& s, const Results& r) {
    for (const MeshResult& m : r.meshes) {
        std::fprintf(stderr,
                     "loopbake: %s: %u vertices, %u faces, %zu creases (%zu by angle), %zu corners, "
                     "%zu holes%s\n",
                     m.name.c_str(), m.vertices, m.faces, m.creases + m.autoCreases, m.autoCreases, m.corners, m.holes,
                     m.uvs ? ", uvs" : "");
        std::fprintf(stderr, "%5s %10s %10s %10s %10s %10s %10s\n", "level", "vertices", "RPP", "NPP", "IPP", "limit",
                     "edits");
        for (size_t l = 0; l < m.stats.levels.size(); ++l) {
            const lt::LevelStats& ls = m.stats.levels[l];
            std::fprintf(stderr, "%5zu %10u %10u %10u %10u %10u %10u\n", l, ls.vertices, ls.rpp, ls.npp, ls.ipp,
                         ls.limitStencils, levelEdits(m, l));
        }
    }
    if (r.passedThrough) std::fprintf(stderr, "loopbake: %zu meshes passed through (--mesh)\n", r.passedThrough);
    const lt::TableBytes& b = r.tableBytes;
    if (r.displacementResolution)
        std::fprintf(stderr, "displacement: %s, %ux%u, %u-bit; resolution %u, %zu samples\n", s.displacement.c_str(),
                     r.map.width, r.map.height, r.map.bitDepth, r.displacementResolution, r.displacementSamples);
    const lt::TableSizes& e = b.encoded;
    std::fprintf(stderr,
                 "table bytes (raw -> in the file, --compress %s): control mesh %zu -> %zu, refinement "
                 "%zu -> %zu, masks %zu -> %zu, patches %zu -> %zu, irregular %zu -> %zu, limit %zu -> %zu, "
                 "displacement %zu -> %zu, edits %zu -> %zu, total %zu -> %zu\n",
                 compressionName(s.compression), b.controlMesh, e.controlMesh, b.refinement, e.refinement, b.masks,
                 e.masks, b.patches, e.patches, b.irregular, e.irregular, b.limit, e.limit, b.displacement,
                 e.displacement, b.edits, e.edits, b.total(), e.total());
    std::fprintf(stderr, "time: read %.3f s, bake %.3f s, write %.3f s; output %zu bytes\n", r.readSeconds,
                 r.bakeSeconds, r.writeSeconds, r.outputBytes);
    lt::cli::printMemory(largest(r).stats.memory, s.limits);
}

using Json = nlohmann::ordered_json;

Json sizesJson(const lt::TableSizes& b) {
    return {{"controlMesh", b.controlMesh},   {"refinement", b.refinement}, {"masks", b.masks},
            {"patches", b.patches},           {"irregular", b.irregular},   {"limit", b.limit},
            {"displacement", b.displacement}, {"edits", b.edits},           {"total", b.total()}};
}

// CleaningReport's counts (README "Input cleaning").
Json cleaningJson(const lt::CleaningReport& c) {
    return {{"repaired", c.repaired},
            {"droppedDegenerate", c.droppedDegenerate},
            {"droppedZeroArea", c.droppedZeroArea},
            {"droppedDuplicate", c.droppedDuplicate},
            {"droppedCreases", c.droppedCreases},
            {"collapsed", c.collapsed}};
}

Json levelsJson(const std::vector<lt::LevelStats>& levels, const std::vector<uint32_t>& edits) {
    Json j = Json::array();
    for (size_t l = 0; l < levels.size(); ++l) {
        const lt::LevelStats& ls = levels[l];
        j.push_back({{"level", l},
                     {"vertices", ls.vertices},
                     {"rpp", ls.rpp},
                     {"npp", ls.npp},
                     {"ipp", ls.ipp},
                     {"limitStencils", ls.limitStencils},
                     {"edits", l < edits.size() ? edits[l] : 0}});
    }
    return j;
}

// Byte-stable for identical inputs and settings: timings only appear with -v. The
// top-level counts add up every baked mesh; "meshes" has each one's.
std::string reportJson(const Settings& s, const Results& r) {
    MeshResult total;
    std::vector<lt::LevelStats>& levels = total.stats.levels;
    Json meshes = Json::array();
    for (const MeshResult& m : r.meshes) {
        total.vertices += m.vertices;
        total.faces += m.faces;
        total.creases += m.creases;
        total.autoCreases += m.autoCreases;
        total.corners += m.corners;
        total.holes += m.holes;
        total.uvs = total.uvs || m.uvs;
        lt::CleaningReport& c = total.cleaning;
        c.repaired += m.cleaning.repaired, c.droppedDegenerate += m.cleaning.droppedDegenerate;
        c.droppedZeroArea += m.cleaning.droppedZeroArea, c.droppedDuplicate += m.cleaning.droppedDuplicate;
        c.droppedCreases += m.cleaning.droppedCreases, c.collapsed += m.cleaning.collapsed;
        total.stats.depth = std::max(total.stats.depth, m.stats.depth);
        levels.resize(std::max(levels.size(), m.stats.levels.size()));
        total.levelEdits.resize(levels.size());
        for (size_t l = 0; l < m.stats.levels.size(); ++l) {
            const lt::LevelStats& a = m.stats.levels[l];
            lt::LevelStats& t = levels[l];
            t.vertices += a.vertices, t.rpp += a.rpp, t.npp += a.npp, t.ipp += a.ipp;
            t.limitStencils += a.limitStencils;
            total.levelEdits[l] += levelEdits(m, l);
        }
        meshes.push_back({{"mesh", m.mesh < 0 ? Json(nullptr) : Json(m.mesh)},
                          {"name", m.name},
                          {"vertices", m.vertices},
                          {"faces", m.faces},
                          {"cleaning", cleaningJson(m.cleaning)},
                          {"maxDepth", m.stats.depth},
                          {"depthReason", m.stats.depthReason},
                          {"levels", levelsJson(m.stats.levels, m.levelEdits)}});
    }
    Json j;
    j["tool"] = "loopbake";
    j["version"] = LOOPTESS_VERSION_STRING;
    j["status"] = "ok";
    j["exitCode"] = 0;
    j["input"] = {{"file", s.input},          {"vertices", total.vertices},
                  {"faces", total.faces},     {"creases", total.creases},
                  {"corners", total.corners}, {"holes", total.holes},
                  {"uvs", total.uvs},         {"cleaning", cleaningJson(total.cleaning)}};
    j["settings"] = {{"maxDepth", total.stats.depth},
                     {"depthAutomatic", s.maxDepth == 0},
                     {"depthReason", r.meshes.size() == 1 ? r.meshes[0].stats.depthReason : "per mesh (meshes[])"},
                     {"creaseAngle", s.creaseAngle ? Json(*s.creaseAngle) : Json(nullptr)},
                     {"strict", s.strict},
                     {"hardEdges", s.hardEdges},
                     {"boundary", s.boundary ? Json(lt::boundaryOptionName(*s.boundary)) : Json(nullptr)}};
    if (r.displacementResolution)
        j["settings"]["displacement"] = {{"file", s.displacement},        {"scale", *s.scale},
                                         {"bias", s.bias.value_or(0.0f)}, {"resolution", r.displacementResolution},
                                         {"mapWidth", r.map.width},       {"mapHeight", r.map.height},
                                         {"mapBitDepth", r.map.bitDepth}, {"samples", r.displacementSamples}};
    j["autoCreases"] = total.autoCreases;
    j["levels"] = levelsJson(levels, total.levelEdits);
    j["meshes"] = std::move(meshes);
    j["passedThrough"] = r.passedThrough;
    // tableBytes: the tables' own bytes per kind; encodedBytes: what they take in the file.
    j["settings"]["compress"] = compressionName(s.compression);
    j["tableBytes"] = sizesJson(r.tableBytes);
    j["encodedBytes"] = sizesJson(r.tableBytes.encoded);
    j["output"] = {{"file", s.output}, {"bytes", r.outputBytes}};
    j["warnings"] = r.warnings;
    j["limits"] = lt::cli::limitsJson(s.limits);
    j["memory"] = lt::cli::memoryJson(largest(r).stats.memory, s.verbose);
    if (s.verbose)
        j["timing"] = {
            {"readSeconds", r.readSeconds}, {"bakeSeconds", r.bakeSeconds}, {"writeSeconds", r.writeSeconds}};
    return j.dump(2) + "\n";
}

// The report of a bake that failed (exit 2 to 5), so that a build system reading
// --json finds why instead of no file: the status and message, the files, the
// warnings so far.
std::string failureJson(const Settings& s, const Results& r, const Status& st) {
    Json j;
    j["tool"] = "loopbake";
    j["version"] = LOOPTESS_VERSION_STRING;
    j["status"] = "failed";
    j["exitCode"] = int(st.code);
    j["message"] = st.message;
    j["input"] = {{"file", s.input}};
    j["output"] = {{"file", s.output}, {"bytes", 0}};
    j["warnings"] = r.warnings;
    j["limits"] = lt::cli::limitsJson(s.limits);
    return j.dump(2) + "\n";
}

// --manifest: each job bakes with this command line's settings followed by the job's
// own options, parsed exactly as a command line (batch.h).
Status jobSettings(const Settings& base, const lt::batch::Job& job, Settings& s) {
    s = base;
    s.manifest.clear();
    s.report.clear();
    s.threads = 1;
    s.bakeThreads = std::max(1u, std::thread::hardware_concurrency() / base.threads);
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
        for (const MeshResult& m : r.meshes) {
            out.faces += m.faces;
            out.vertices += m.vertices;
        }
        if (!r.meshes.empty()) out.memory = largest(r).stats.memory;
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
        const std::string text = kUsage;  // the limit options go before the exit codes
        const size_t at = std::min(text.find("\nexit codes:"), text.size());
        std::fputs((text.substr(0, at) + "\n" + lt::cli::limitsUsage() + text.substr(at)).c_str(), stdout);
        return 0;
    }
    if (s.version) {
        std::printf("loopbake %s\n", LOOPTESS_VERSION_STRING);
        return 0;
    }
    if (!s.manifest.empty()) return runManifest(s);
    Results r;
    Status st = bakeFile(s, r);
    if (st && s.verbose) printVerbose(s, r);
    if (!s.report.empty()) {
        const std::string json = st ? reportJson(s, r) : failureJson(s, r, st);
        const Status written =
            lt::writeFileAtomic(s.report, reinterpret_cast<const uint8_t*>(json.data()), json.size());
        if (st) st = written;
    }
    if (!st) std::fprintf(stderr, "loopbake: error: %s\n", st.message.c_str());
    return int(st.code);
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "loopbake: error: out of memory\n");
    } catch (const std::exception& e) { std::fprintf(stderr, "loopbake: error: internal error: %s\n", e.what()); }
    return int(Status::Internal);
}

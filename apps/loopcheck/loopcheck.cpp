// loopcheck -- validates a baked EXT_mesh_loop_subdivision asset for CI: structure,
// accuracy against OpenSubdiv, bitwise watertightness, Embree ray tests, the Khronos
// glTF-Validator. The checks live in looptess_check (looptess/tools/check.h); this main
// parses the command line into CheckSettings, reads the files, prints and writes the
// report. Exit codes: kUsage below.
#include "gpu_capture.h"
#include "looptess/tools/check.h"
#include "looptess/tools/file_io.h"
#include "looptess/version.h"
#ifdef LOOPTESS_HAVE_USD
#include "looptess/tools/usd.h"
#endif

#include <algorithm>
#include <charconv>
#include <functional>
#include <memory>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <new>
#include <optional>
#include <string>
#include <vector>

namespace {

using lt::Status;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

const char* const kUsage =
    "usage: loopcheck ASSET.glb [options]\n"
    "\n"
    "Validates a baked EXT_mesh_loop_subdivision asset: the spec's numbered rules and\n"
    "the tables' topology; with --source, the CPU evaluation against OpenSubdiv's limit\n"
    "surface; bitwise watertightness (open edges, T-junctions), vertex normals against\n"
    "their own triangles (N1: none behind, none zero) and, for closed control meshes,\n"
    "Embree rays from interior points (none may escape; hit distances against a finer\n"
    "tessellation) at each tessellation; the Khronos glTF-Validator.\n"
    "\n"
    "options:\n"
    "  --source IN          the mesh the asset was baked from (.obj, .gltf, .glb, .usd,\n"
    "                       .usda, .usdc, .usdz): compare the control meshes and\n"
    "                       check accuracy\n"
    "  --crease-angle DEG   --strict   --hard-edges   --time T\n"
    "  --boundary none|edge|edge-and-corner\n"
    "                       read --source as loopbake did with these options (the\n"
    "                       asset's stored boundary rule must be the one they give)\n"
    "  --edits EDITS.json   the hierarchical edits loopbake --edits added to --source\n"
    "                       (the accuracy reference includes them)\n"
    "  --tess ITEM...       tessellations to check, replacing the default list\n"
    "                       '1 3.3:odd 5 8 screen=8:odd'; ITEM is F[:equal|:odd] (global\n"
    "                       factor F, 1..64) or screen[=F][:equal|:odd] (per-edge screen-\n"
    "                       space factors from a camera framing the model, largest F)\n"
    "  --rays N             rays per tessellation (default 100000; 0: none)\n"
    "  --seed S             seed of every sample and ray (default fixed)\n"
    "  --threads N          threads of the CPU evaluation (default 0: every hardware\n"
    "                       thread); the results are the same for every N\n"
    "  --no-watertight      evaluate with watertight evaluation off (CPU path)\n"
    "  --max-memory-mb N    a tessellation whose checks would take loopcheck past N MiB\n"
    "                       is checked in pieces of base faces, or where that does not\n"
    "                       fit either not run, an error (L1) (default: loopcheck's own\n"
    "                       and 90% of what the machine has available then)\n"
    "  --piece-triangles N  check a tessellation of more than N triangles in pieces of\n"
    "                       base faces of at most N (and a --gpu capture in sessions\n"
    "                       of at most N), whatever the memory\n"
    "  --path P             tessellator (default): the tessellator's domain points;\n"
    "                       patterns: refinement patterns' (each edge factor rounded up\n"
    "                       to a power of two); compute: the same points, captured with\n"
    "                       --gpu through the runtime's compute path\n"
    "  --gpu                also capture through the Vulkan runtime and check that\n"
    "  --validator FILE     the glTF-Validator wrapper script run with node\n"
    "                       (default: apps/loopcheck/validator/validate.js of the source tree)\n"
    "  --no-validator       do not run the glTF-Validator\n"
    "  --strict-validator   fail when the glTF-Validator cannot run (default: warn)\n"
    "  --json REPORT.json   write a machine-readable report\n"
    "                       (formats/loopcheck-report.schema.json)\n"
    "  --junit REPORT.xml   write a JUnit XML report for CI test reporters: a testsuite\n"
    "                       per surface, a testcase per check and tessellation\n"
    "  -q                   print only warnings, errors and the verdict; no progress\n"
    "  -v                   print statistics and timings\n"
    "  --help, --version\n"
    "\n"
    "exit codes:\n"
    "  0 every check passed   1 usage error\n"
    "  2 the asset is invalid or unreadable (structure), or --source unreadable\n"
    "  3 a check failed (source, accuracy, watertightness, rays, validator, GPU)\n"
    "    or was not run for memory (L1)\n"
    "  4 the report could not be written   5 internal error\n";

struct Options {
    std::string asset, source, json, junit;
    std::string validator = LOOPCHECK_VALIDATOR_JS;
    bool runValidator = true, gpu = false, quiet = false, verbose = false, help = false, version = false;
    lt::SourceOptions sourceOptions;
    std::optional<double> time;  // --time: a USD source's time (loopbake --time)
    lt::CheckSettings settings;
};

template <typename T>
bool parseNumber(const std::string& text, T lo, T hi, T& out) {
    T value{};
    const auto res = std::from_chars(text.data(), text.data() + text.size(), value);
    if (res.ec != std::errc() || res.ptr != text.data() + text.size() || !(value >= lo && value <= hi)) return false;
    out = value;
    return true;
}

Status usage(const std::string& what) { return Status::error(Status::Usage, what); }

// --source a USD layer: its Loop meshes as loopbake reads them (looptess/tools/usd.h),
// each under the glTF mesh index loopbake gives it. The check library reads OBJ and
// glTF only: USD input is an optional module (cmake/Usd.cmake).
Status loadUsdSource(const Options& o, lt::SourceMeshes& source) {
#ifdef LOOPTESS_HAVE_USD
    lt::UsdOptions options;
    options.input.strict = o.sourceOptions.strict;
    options.input.cleaning = o.sourceOptions.strict ? lt::InputCleaning::Refuse : lt::InputCleaning::Repair;
    options.input.boundary = o.sourceOptions.boundary;
    options.time = o.time;
    lt::GltfScene scene;
    if (Status st = lt::parseUsdScene(o.source, options, scene); !st) return st;
    source = lt::SourceMeshes{};
    for (lt::GltfScene::Mesh& m : scene.meshes) {
        source.meshes.push_back(std::move(m.mesh));
        source.index.push_back(m.index);
    }
    return Status::ok();
#else
    return Status::error(Status::Unsupported, o.source +
                                                  ": this loopcheck was built without USD input (configure "
                                                  "with pxr-sdf: scripts/setup-debian.sh, cmake/Usd.cmake)");
#endif
}

Status parseArgs(int argc, char** argv, Options& o) {
    bool tessGiven = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&](std::string& out) {
            if (i + 1 >= argc) return false;
            out = argv[++i];
            return true;
        };
        std::string v;
        if (a == "--help" || a == "-h")
            o.help = true;
        else if (a == "--version")
            o.version = true;
        else if (a == "-q")
            o.quiet = true;
        else if (a == "-v" || a == "--verbose")
            o.verbose = true;
        else if (a == "--gpu")
            o.gpu = true;
        else if (a == "--no-watertight")
            o.settings.watertight = false;
        else if (a == "--path") {
            if (!value(v) || (v != "tessellator" && v != "patterns" && v != "compute"))
                return usage("--path takes tessellator, patterns or compute");
            o.settings.path = v == "tessellator" ? lt::DrawPath::Tessellator
                              : v == "patterns"  ? lt::DrawPath::Patterns
                                                 : lt::DrawPath::Compute;
        } else if (a == "--no-validator")
            o.runValidator = false;
        else if (a == "--strict-validator")
            o.settings.strictValidator = true;
        else if (a == "--strict")
            o.sourceOptions.strict = true;
        else if (a == "--hard-edges")
            o.sourceOptions.hardEdges = true;
        else if (a == "--source" || a == "--json" || a == "--junit" || a == "--validator" || a == "--edits") {
            if (!value(v)) return usage("option '" + a + "' needs a value");
            (a == "--source"  ? o.source
             : a == "--json"  ? o.json
             : a == "--junit" ? o.junit
             : a == "--edits" ? o.sourceOptions.edits
                              : o.validator) = v;
        } else if (a == "--boundary") {
            lt::BoundaryInterpolation b{};
            if (!value(v) || !lt::parseBoundaryOption(v, b))
                return usage("--boundary takes none, edge or edge-and-corner");
            o.sourceOptions.boundary = b;
        } else if (a == "--crease-angle") {
            if (!value(v) || !parseNumber(v, 0.0f, 180.0f, o.sourceOptions.creaseAngle))
                return usage("--crease-angle needs a number of degrees from 0 to 180");
        } else if (a == "--time") {
            double t = 0;
            if (!value(v) ||
                !parseNumber(v, -std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), t))
                return usage("--time needs a finite number (a USD time code)");
            o.time = t;
        } else if (a == "--rays") {
            if (!value(v) || !parseNumber<uint64_t>(v, 0, uint64_t(1) << 32, o.settings.rays))
                return usage("--rays needs a count from 0 to 2^32");
        } else if (a == "--max-memory-mb") {
            uint64_t mib = 0;
            if (!value(v) || !parseNumber<uint64_t>(v, 1, uint64_t(1) << 30, mib))
                return usage("--max-memory-mb needs a size in MiB from 1 to 2^30");
            o.settings.maxMemoryBytes = mib << 20;
        } else if (a == "--piece-triangles") {
            if (!value(v) || !parseNumber<uint64_t>(v, 1, UINT64_MAX, o.settings.pieceTriangles))
                return usage("--piece-triangles needs a count of at least 1");
        } else if (a == "--seed") {
            if (!value(v) || !parseNumber<uint64_t>(v, 0, UINT64_MAX, o.settings.seed))
                return usage("--seed needs an unsigned 64-bit integer");
        } else if (a == "--threads") {
            if (!value(v) || !parseNumber<unsigned>(v, 0u, 256u, o.settings.threads))
                return usage("--threads needs a count from 0 to 256");
        } else if (a == "--tess") {
            if (!tessGiven) o.settings.cases.clear(), tessGiven = true;
            // Items follow as separate arguments or comma-separated, up to the first
            // argument that is not one (the asset, or the next option).
            int taken = 0;
            while (i + 1 < argc && argv[i + 1][0] != '-') {
                std::vector<lt::TessCase> items;
                std::string list = argv[i + 1];
                bool all = true;
                for (size_t at = 0; at <= list.size() && all;) {
                    const size_t comma = std::min(list.find(',', at), list.size());
                    lt::TessCase c;
                    all = bool(lt::parseTessCase(list.substr(at, comma - at), c));
                    items.push_back(c);
                    at = comma + 1;
                }
                if (!all) {
                    if (taken > 0) break;  // the asset's name after the items
                    lt::TessCase c;
                    Status st = lt::parseTessCase(list.substr(0, list.find(',')), c);
                    return st ? usage("--tess: bad item in '" + list + "'") : st;
                }
                o.settings.cases.insert(o.settings.cases.end(), items.begin(), items.end());
                ++i, ++taken;
            }
            if (taken == 0) return usage("--tess needs at least one item");
        } else if (a.size() > 1 && a[0] == '-') {
            return usage("unknown option '" + a + "'");
        } else {
            if (!o.asset.empty()) return usage("more than one asset ('" + o.asset + "', '" + a + "')");
            o.asset = a;
        }
    }
    if (o.help || o.version) return Status::ok();
    if (o.asset.empty()) return usage("no asset");
    if (!o.sourceOptions.edits.empty() && o.source.empty()) return usage("--edits needs --source");
    // A report never overwrites what it reports on.
    return lt::checkDistinctFiles({{"the asset", o.asset, false},
                                   {"--source", o.source, false},
                                   {"--edits", o.sourceOptions.edits, false},
                                   {"--json", o.json, true},
                                   {"--junit", o.junit, true}});
}

// --gpu's device, created once for every surface, or why there is none.
struct Gpu {
    std::unique_ptr<lt::GpuCapture> device;
    std::string error;
};

// Runs every check on one surface into `report`; 0, or the exit code of an error
// that ends the run (its message printed).
int checkSurface(const Options& o, const lt::SceneSurface& surface, const lt::SourceMeshes& source, Gpu& gpu,
                 const std::function<void(const std::string&)>& progress, lt::CheckReport& report) {
    const lt::Asset& asset = surface.asset;
    report.controlVertices = asset.controlVertexCount();
    report.baseFaces = asset.faceCount();
    report.maxDepth = asset.maxDepth();
    report.vertices = asset.totalVertexCount();
    lt::SourceOracle oracle;
    oracle.isolation = o.settings.isolation;
    lt::CheckInputs in;
    in.asset = &asset;
    in.assetName = report.assetName;
    in.progress = progress;
    if (!o.source.empty()) {
        const auto t0 = Clock::now();
        report.sourceName = o.source;
        const int64_t mesh = source.index.size() == 1 && source.index[0] < 0 ? -1 : int64_t(surface.mesh);
        if (Status s = lt::sourceMesh(source, mesh, o.source, o.sourceOptions, oracle.mesh); !s) {
            std::fprintf(stderr, "loopcheck: error: --source: %s\n", s.message.c_str());
            return 2;
        }
        report.sourceMismatch = lt::compareControlMesh(oracle.mesh, asset);
        if (report.sourceMismatch.empty()) {
            progress("building OpenSubdiv's limit surface (isolation " + std::to_string(oracle.isolation) + ")");
            if (Status s = oracle.build(); !s) {
                std::fprintf(stderr, "loopcheck: error: --source: %s\n", s.message.c_str());
                return 2;
            }
            in.source = &oracle;
        }
        report.sourceSeconds += since(t0);  // after the file's read (run)
    }
    if (o.gpu) {
        Status loaded = gpu.device ? gpu.device->load(asset) : Status::error(Status::Unsupported, gpu.error);
        if (gpu.device) report.gpuDevice = gpu.device->deviceName();
        in.gpuCapture = [&gpu, loaded](const lt::EvalSettings& eval, lt::Tessellation& soup) {
            return loaded ? gpu.device->capture(eval, soup) : loaded;
        };
        in.gpuCaptureSessions = [&gpu, loaded](const lt::EvalSettings& eval, uint64_t triangles,
                                               const lt::SessionFn& each) {
            return loaded ? gpu.device->capture(eval, triangles, each) : loaded;
        };
    }
    if (Status s = lt::runChecks(in, o.settings, report); !s) {
        std::fprintf(stderr, "loopcheck: internal error: %s\n", s.message.c_str());
        return 5;
    }
    return 0;
}

int run(int argc, char** argv) {
    Options o;
    if (Status st = parseArgs(argc, argv, o); !st) {
        std::fprintf(stderr, "loopcheck: error: %s\nrun 'loopcheck --help' for usage\n", st.message.c_str());
        return 1;
    }
    if (o.help) return std::fputs(kUsage, stdout), 0;
    if (o.version) return std::printf("loopcheck %s\n", LOOPTESS_VERSION_STRING), 0;
    auto progress = [&](const std::string& line) {
        if (!o.quiet) std::fprintf(stderr, "loopcheck: %s\n", line.c_str());
    };

    std::vector<uint8_t> bytes;
    std::vector<lt::SceneSurface> surfaces;
    Status st = lt::readFile(o.asset, bytes);
    const uint64_t assetBytes = bytes.size();
    if (st) st = lt::checkSceneStructure(bytes.data(), bytes.size(), o.asset, surfaces);
    bytes = {};
    std::vector<lt::CheckReport> reports;
    if (!st) {  // one report: the file is invalid
        surfaces.clear();
        lt::CheckReport& report = reports.emplace_back();
        report.assetName = o.asset;
        report.assetBytes = assetBytes;
        report.structureMessage = st.message;
        lt::addFindings(o.settings, report);
    }
    lt::ValidatorResult validator, sourceValidator;  // of the files: the same in every surface's report
    double validatorSeconds = 0;
    if (st && o.runValidator) {
        progress("running the Khronos glTF-Validator");
        const auto t0 = Clock::now();
        validator = lt::runKhronosValidator(o.asset, o.validator);
        const std::string ext = std::filesystem::path(o.source).extension().string();
        if (validator.state == lt::ValidatorResult::Ran && !validator.pass() && (ext == ".gltf" || ext == ".glb"))
            sourceValidator = lt::runKhronosValidator(o.source, o.validator);
        validatorSeconds = since(t0);
    }
    std::vector<std::string> sceneDifferences;  // of the file: in every surface's report
    double sourceSeconds = 0;
    const std::string sourceExt = std::filesystem::path(o.source).extension().string();
    if (st && (sourceExt == ".gltf" || sourceExt == ".glb")) {
        if (Status s = lt::compareScene(o.asset, o.source, sceneDifferences); !s) {
            std::fprintf(stderr, "loopcheck: error: --source: %s\n", s.message.c_str());
            return 2;
        }
    }
    lt::SourceMeshes source;  // read once for every surface
    if (st && !o.source.empty()) {
        progress("reading " + o.source);
        const auto t0 = Clock::now();
        const Status s =
            lt::isUsdPath(o.source) ? loadUsdSource(o, source) : lt::loadSource(o.source, o.sourceOptions, source);
        if (!s) {
            std::fprintf(stderr, "loopcheck: error: --source: %s\n", s.message.c_str());
            return 2;
        }
        sourceSeconds = since(t0);
    }
    Gpu gpu;
    if (o.gpu && !surfaces.empty()) {
        progress("creating a headless Vulkan device");
        if (Status s = lt::GpuCapture::create(gpu.device); !s) gpu.error = s.message;
    }
    for (const lt::SceneSurface& surface : surfaces) {
        lt::CheckReport& report = reports.emplace_back();
        report.sceneDifferences = sceneDifferences;
        report.assetName = lt::surfaceName(o.asset, surfaces, surface);
        report.assetBytes = assetBytes;
        report.structureValid = true;
        report.validator = validator;
        report.sourceValidator = sourceValidator;
        report.validatorSeconds = validatorSeconds;
        report.sourceSeconds = sourceSeconds;
        if (int code = checkSurface(o, surface, source, gpu, progress, report); code != 0) return code;
    }
    std::string text;
    for (const lt::CheckReport& report : reports) text += lt::reportText(report, o.quiet, o.verbose);
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
    int code = 0;
    for (const lt::CheckReport& report : reports) code = std::max(code, lt::exitCode(report));
    if (!o.json.empty()) {
        const std::string json = lt::reportJson(reports, o.settings, o.verbose);
        if (Status s = lt::writeFileAtomic(o.json, reinterpret_cast<const uint8_t*>(json.data()), json.size()); !s) {
            std::fprintf(stderr, "loopcheck: error: %s\n", s.message.c_str());
            return 4;
        }
    }
    if (!o.junit.empty()) {
        const std::string xml = lt::reportJUnit(reports, o.settings);
        if (Status s = lt::writeFileAtomic(o.junit, reinterpret_cast<const uint8_t*>(xml.data()), xml.size()); !s) {
            std::fprintf(stderr, "loopcheck: error: %s\n", s.message.c_str());
            return 4;
        }
    }
    return code;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "loopcheck: error: out of memory\n");
    } catch (const std::exception& e) { std::fprintf(stderr, "loopcheck: internal error: %s\n", e.what()); }
    return 5;
}

// looprender -- evaluates a baked EXT_mesh_loop_subdivision asset and captures the
// tessellated limit surface.
//
//   looprender --cpu ASSET.glb --tess F [--spacing equal|fractional_odd]
//              [--capture OUT.ply] [-v] [--json REPORT.json]
//
// Exit codes: 0 ok, 1 usage, 2 bad input (unreadable or invalid asset),
// 3 unsupported (the Vulkan path is not built yet), 4 write failed, 5 internal.
#include "looptess/file_io.h"
#include "looptess/runtime.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

const char* kUsage =
    "usage: looprender --cpu ASSET.glb [options]\n"
    "\n"
    "Evaluates the exact Loop limit surface of a baked asset (loopbake's output).\n"
    "\n"
    "options:\n"
    "  --cpu               evaluate on the CPU (the Vulkan path is not built yet)\n"
    "  --tess F            global tessellation factor, a real >= 1 (default 1);\n"
    "                      subdivision depth = ceil(log2 F), capped at the asset's\n"
    "  --spacing S         equal (default) or fractional_odd\n"
    "  --capture OUT.ply   write the emitted triangles (unwelded; x y z nx ny nz face u v)\n"
    "  --json REPORT.json  write a machine-readable summary\n"
    "  -v                  print statistics to stderr\n"
    "  --help, --version\n"
    "\n"
    "exit codes: 0 ok, 1 usage, 2 bad input, 3 unsupported, 4 write failed, 5 internal\n";

struct Settings {
    std::string input;
    bool cpu = false;
    float tess = 1.0f;
    lt::Spacing spacing = lt::Spacing::Equal;
    std::string capture;
    std::string json;
    bool verbose = false;
};

int fail(const lt::Status& st) {
    std::fprintf(stderr, "looprender: error: %s\n", st.message.c_str());
    return int(st.code);
}

int usage(const std::string& message) {
    std::fprintf(stderr, "looprender: error: %s\n\n%s", message.c_str(), kUsage);
    return 1;
}

// Parses argv into `s`; returns -1 to go on, or an exit code.
int parseArgs(int argc, char** argv, Settings& s) {
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&](const char* what) -> const char* {
            if (i + 1 >= argc) return nullptr;
            (void)what;
            return argv[++i];
        };
        if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (a == "--version") {
            std::printf("looprender %s\n", LOOPTESS_VERSION);
            return 0;
        } else if (a == "--cpu") {
            s.cpu = true;
        } else if (a == "-v") {
            s.verbose = true;
        } else if (a == "--tess" || a == "--spacing" || a == "--capture" || a == "--json") {
            const char* v = value(a.c_str());
            if (!v) return usage(a + " needs a value");
            if (a == "--tess") {
                char* end = nullptr;
                s.tess = std::strtof(v, &end);
                if (*end || !(s.tess >= 1.0f && s.tess <= 4096.0f)) return usage("--tess takes a number in [1, 4096]");
            } else if (a == "--spacing") {
                std::string sp = v;
                if (sp == "equal") s.spacing = lt::Spacing::Equal;
                else if (sp == "fractional_odd") s.spacing = lt::Spacing::FractionalOdd;
                else return usage("--spacing takes equal or fractional_odd");
            } else if (a == "--capture") {
                s.capture = v;
            } else {
                s.json = v;
            }
        } else if (!a.empty() && a[0] == '-') {
            return usage("unknown option " + a);
        } else if (s.input.empty()) {
            s.input = a;
        } else {
            return usage("more than one input");
        }
    }
    if (s.input.empty()) return usage("no input asset");
    return -1;
}

int run(const Settings& s) {
    if (!s.cpu)
        return fail(lt::Status::error(lt::Status::Unsupported,
                                      "the Vulkan path is not built yet: use --cpu"));
    auto start = std::chrono::steady_clock::now();
    std::vector<uint8_t> bytes;
    lt::Status st = lt::readFile(s.input, bytes);
    lt::Asset asset;
    if (st) st = lt::readAssetGlb(bytes.data(), bytes.size(), s.input, asset);
    if (!st) return fail(st);
    auto loaded = std::chrono::steady_clock::now();

    lt::EvalSettings es;
    es.tessFactor = s.tess;
    es.spacing = s.spacing;
    lt::Tessellation soup;
    lt::evaluateCpu(asset, asset.positions.data(), es, soup);
    auto evaluated = std::chrono::steady_clock::now();
    uint32_t depth = lt::runtimeDepth(asset, s.tess);

    if (!s.capture.empty()) {
        std::vector<uint8_t> ply;
        lt::writePly(soup, ply);
        st = lt::writeFileAtomic(s.capture, ply.data(), ply.size());
        if (!st) return fail(st);
    }
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::printf("%s: %u base faces, depth %u of %u, factor %g: %zu triangles\n", s.input.c_str(),
                asset.faceCount(), depth, asset.maxDepth(), double(s.tess), soup.triangleCount());
    if (s.verbose)
        std::fprintf(stderr, "looprender: load %.2f ms, evaluate %.2f ms\n", ms(start, loaded), ms(loaded, evaluated));
    if (!s.json.empty()) {
        nlohmann::json report = {{"input", s.input},
                                 {"path", "cpu"},
                                 {"tessFactor", s.tess},
                                 {"spacing", s.spacing == lt::Spacing::Equal ? "equal" : "fractional_odd"},
                                 {"depth", depth},
                                 {"maxDepth", asset.maxDepth()},
                                 {"baseFaces", asset.faceCount()},
                                 {"triangles", soup.triangleCount()},
                                 {"vertices", soup.vertexCount()}};
        std::string text = report.dump(2) + "\n";
        st = lt::writeFileAtomic(s.json, reinterpret_cast<const uint8_t*>(text.data()), text.size());
        if (!st) return fail(st);
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Settings settings;
    int code = parseArgs(argc, argv, settings);
    return code >= 0 ? code : run(settings);
}

// loopcheck -- validates baked EXT_mesh_loop_subdivision assets for CI.
//
//   loopcheck ASSET.glb [ASSET.glb ...] [--json REPORT.json] [-q]
//
// Checks the GLB container and every table against the numbered validity rules of
// formats/EXT_mesh_loop_subdivision/README.md (the reader's own checks).
// Accuracy against OpenSubdiv, bitwise watertightness and ray tests are a later
// milestone.
//
// Exit codes: 0 every asset is valid, 1 usage, 2 an asset is invalid or unreadable,
// 3 an asset uses an unsupported extension version, 4 the report cannot be written.
#include "looptess/asset.h"
#include "looptess/file_io.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>
#include <vector>

namespace {

const char* kUsage =
    "usage: loopcheck ASSET.glb [ASSET.glb ...] [--json REPORT.json] [-q]\n"
    "\n"
    "Validates baked EXT_mesh_loop_subdivision assets against the spec's numbered\n"
    "validity rules (structure, counts, index ranges, weights).\n"
    "\n"
    "  --json FILE   write a machine-readable report\n"
    "  -q            print only failures\n"
    "  --help, --version\n"
    "\n"
    "exit codes: 0 all valid, 1 usage, 2 invalid or unreadable asset,\n"
    "            3 unsupported extension version, 4 report not written\n";

struct Settings {
    std::vector<std::string> inputs;
    std::string json;
    bool quiet = false;
};

int parseArgs(int argc, char** argv, Settings& s) {
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (a == "--version") {
            std::printf("loopcheck %s\n", LOOPTESS_VERSION);
            return 0;
        } else if (a == "-q") {
            s.quiet = true;
        } else if (a == "--json") {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "loopcheck: error: --json needs a file\n\n%s", kUsage);
                return 1;
            }
            s.json = argv[++i];
        } else if (!a.empty() && a[0] == '-') {
            std::fprintf(stderr, "loopcheck: error: unknown option %s\n\n%s", a.c_str(), kUsage);
            return 1;
        } else {
            s.inputs.push_back(a);
        }
    }
    if (s.inputs.empty()) {
        std::fprintf(stderr, "loopcheck: error: no input asset\n\n%s", kUsage);
        return 1;
    }
    return -1;
}

int run(const Settings& s) {
    int code = 0;
    nlohmann::json report = nlohmann::json::array();
    for (const std::string& path : s.inputs) {
        std::vector<uint8_t> bytes;
        lt::Asset asset;
        lt::Status st = lt::readFile(path, bytes);
        if (st) st = lt::readAssetGlb(bytes.data(), bytes.size(), path, asset);
        nlohmann::json entry = {{"file", path}, {"valid", bool(st)}};
        if (st) {
            entry["baseFaces"] = asset.faceCount();
            entry["maxDepth"] = asset.maxDepth();
            entry["vertices"] = asset.totalVertexCount();
            if (!s.quiet)
                std::printf("%s: valid (%u base faces, depth %u, %u vertices)\n", path.c_str(), asset.faceCount(),
                            asset.maxDepth(), asset.totalVertexCount());
        } else {
            entry["error"] = st.message;
            std::printf("%s: INVALID: %s\n", path.c_str(), st.message.c_str());
            bool unsupported = st.code == lt::Status::Unsupported;
            if (code != 2) code = unsupported ? 3 : 2;  // an invalid asset outranks an unsupported one
        }
        report.push_back(entry);
    }
    if (!s.json.empty()) {
        std::string text = nlohmann::json{{"tool", "loopcheck"}, {"assets", report}}.dump(2) + "\n";
        lt::Status st = lt::writeFileAtomic(s.json, reinterpret_cast<const uint8_t*>(text.data()), text.size());
        if (!st) {
            std::fprintf(stderr, "loopcheck: error: %s\n", st.message.c_str());
            return 4;
        }
    }
    return code;
}

} // namespace

int main(int argc, char** argv) {
    Settings settings;
    int code = parseArgs(argc, argv, settings);
    return code >= 0 ? code : run(settings);
}

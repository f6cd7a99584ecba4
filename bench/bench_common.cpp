// bench/bench_common.cpp -- bench_common.h.
#include "bench_common.h"

#include "gen_mesh.h"

#include "looptess/tools/file_io.h"
#include "looptess/version.h"

#include <opensubdiv/version.h>

#include <sched.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

#define LT_STR2(x) #x
#define LT_STR(x)  LT_STR2(x)

namespace ltbench {

lt::Status loadMesh(const std::string& corpus, const std::string& name, lt::InputMesh& mesh, std::string* source) {
    std::string from;
    if (TorusParams p; generatedParams(name, p)) {
        mesh = makeTorus(p);
        char seed[32];
        std::snprintf(seed, sizeof(seed), "0x%llx", static_cast<unsigned long long>(p.seed));
        from = "generated: " + (name == "torus" ? "" : name + ", ") + "torus " + std::to_string(p.around) + "x" +
               std::to_string(p.across) + " cells, 1 in " + std::to_string(p.flipOneIn) +
               " diagonals flipped, LCG seed " + seed;
    } else {
        const bool duck = name == "duck";
        from = corpus + (duck ? "/gltf/Duck.glb" : "/meshes/" + name + ".obj");
        std::vector<uint8_t> bytes;
        lt::Status st = lt::readFile(from, bytes);
        if (!st) return st;
        if (duck)
            st = lt::parseGltf(bytes.data(), bytes.size(), from, corpus + "/gltf", mesh);
        else
            st = lt::parseObj(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), from,
                              lt::InputOptions{}, mesh);
        if (!st) return st;
    }
    if (source) *source = from;
    return lt::checkInput(mesh, from);
}

Machine machineInfo(const std::string& buildType) {
    Machine m;
    cpu_set_t set;
    CPU_ZERO(&set);
    m.nproc = sched_getaffinity(0, sizeof(set), &set) == 0 ? CPU_COUNT(&set) : 0;
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) {
            size_t colon = line.find(':');
            m.cpuModel = colon == std::string::npos ? line : line.substr(line.find_first_not_of(' ', colon + 1));
            break;
        }
    if (m.cpuModel.empty()) m.cpuModel = "unknown CPU";
#if defined(__clang__)
    m.compiler = std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
    m.compiler = std::string("gcc ") + __VERSION__;
#else
    m.compiler = "unknown compiler";
#endif
    m.buildType = buildType;
    m.osdVersion = LT_STR(OPENSUBDIV_VERSION);
    m.looptessVersion = LOOPTESS_VERSION_STRING;
    return m;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n == 0 ? 0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

}  // namespace ltbench

// usd_reader.cpp -- lt::parseUsdScene (looptess/tools/usd.h): the layer read in a
// child process first (UsdOptions::isolate), then read here, checked and turned into
// a glTF scene.
#include "looptess/tools/usd.h"

#include "usd_data.h"

#include <algorithm>
#include <cctype>
#include <csignal>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace lt {
namespace {

// Reads the layer in a forked child: Sdf trusts a crate file's offsets and counts,
// and a corrupt one can crash it. OK when the child ran to its end (whatever the
// layer's own errors, which the read here reports again).
Status readIsolated(const std::string& path, const double* time) {
    const pid_t pid = fork();
    if (pid < 0) return Status::ok();  // no child: read in this process only
    if (pid == 0) {
        for (int sig : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) std::signal(sig, SIG_DFL);
        const int null = open("/dev/null", O_WRONLY);
        if (null >= 0) dup2(null, 2);  // Sdf's own diagnostics: the parent reports
        usd::Layer layer;
        usd::readLayer(path, time, layer);
        _exit(0);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return Status::ok();
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return Status::ok();
    return Status::error(
        Status::BadInput,
        path + ": Sdf crashed reading it" +
            (WIFSIGNALED(status) ? " (signal " + std::to_string(WTERMSIG(status)) + ")" : std::string()) +
            ": the file is corrupt");
}

}  // namespace

bool isUsdPath(const std::string& path) {
    const size_t dot = path.rfind('.');
    if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return false;
    std::string ext = path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".usd" || ext == ".usda" || ext == ".usdc" || ext == ".usdz";
}

Status parseUsdScene(const std::string& path, const UsdOptions& options, GltfScene& scene) {
    scene = GltfScene{};
    const double* time = options.time ? &*options.time : nullptr;
    if (options.isolate)
        if (Status st = readIsolated(path, time); !st) return st;
    usd::Layer layer;
    if (Status st = usd::readLayer(path, time, layer); !st) return st;
    scene.warnings = layer.warnings;
    if (layer.meshes.empty())
        return Status::error(Status::BadInput, path + ": no Mesh prim (under Xform and Scope prims) to bake");
    std::vector<usd::Cage> cages(layer.meshes.size());
    for (size_t i = 0; i < layer.meshes.size(); ++i) {
        const usd::MeshData& m = layer.meshes[i];
        const bool loop = m.scheme == "loop";
        InputMesh mesh;
        if (Status st = usd::buildMesh(m, path, options.input, loop, mesh, cages[i], scene.warnings); !st) return st;
        if (!loop) {
            scene.warnings.push_back(path + ": " + m.path + ": subdivisionScheme \"" + m.scheme +
                                     "\" is not loop: written as a plain triangle mesh, not subdivided");
            continue;
        }
        GltfScene::Mesh& sm = scene.meshes.emplace_back();
        sm.index = uint32_t(i);
        sm.name = m.path;
        sm.primitives = {0};
        sm.controlVertex = {cages[i].controlVertex};
        sm.mesh = std::move(mesh);
    }
    usd::buildScene(layer, cages, scene);
    return Status::ok();
}

}  // namespace lt

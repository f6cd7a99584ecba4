// usd_reader.cpp -- lt::parseUsdScene (looptess/tools/usd.h): the layer read in a
// child process (UsdOptions::isolate) and sent back, then checked and turned into a
// glTF scene here.
#include "looptess/tools/usd.h"

#include "usd_data.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <type_traits>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace lt {
namespace {

// The child's result, sent to the parent through a pipe: the Status, then the Layer
// (usd_data.h), each field in declaration order; numbers as their bytes (same
// process image on both ends), strings and vectors as a uint64 count and the data.
class Wire {
public:
    std::string bytes;
    size_t at = 0;
    bool ok = true;

    template <class T>
    void put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    void put(const std::string& s) {
        put(uint64_t(s.size()));
        bytes += s;
    }
    template <class T>
    void put(const std::vector<T>& v) {
        put(uint64_t(v.size()));
        for (const T& x : v) put(x);
    }
    void put(const usd::Primvar& p) {
        put(p.present), put(p.components), put(p.values), put(p.indexed), put(p.indices), put(p.interpolation);
    }
    void put(const usd::MeshData& m) {
        put(m.path), put(m.scheme), put(m.boundary), put(m.orientation);
        put(m.hasPoints), put(m.hasCounts), put(m.hasIndices);
        put(m.points), put(m.counts), put(m.indices), put(m.creaseIndices), put(m.creaseLengths);
        put(m.cornerIndices), put(m.holeIndices), put(m.creaseSharpnesses), put(m.cornerSharpnesses);
        put(m.st), put(m.displayColor);
    }
    void put(const usd::Node& n) { put(n.name), put(n.hasMatrix), put(n.matrix), put(n.mesh), put(n.children); }

    template <class T>
    void get(T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        if (!(ok = ok && bytes.size() - at >= sizeof v)) return;
        std::memcpy(&v, bytes.data() + at, sizeof v);
        at += sizeof v;
    }
    void get(std::string& s) {
        uint64_t n = 0;
        get(n);
        if (!(ok = ok && bytes.size() - at >= n)) return;
        s.assign(bytes, at, size_t(n));
        at += size_t(n);
    }
    template <class T>
    void get(std::vector<T>& v) {
        uint64_t n = 0;
        get(n);
        if (!(ok = ok && n <= bytes.size() - at)) return;  // every element takes a byte at least
        v.resize(size_t(n));
        for (T& x : v) get(x);
    }
    void get(usd::Primvar& p) {
        get(p.present), get(p.components), get(p.values), get(p.indexed), get(p.indices), get(p.interpolation);
    }
    void get(usd::MeshData& m) {
        get(m.path), get(m.scheme), get(m.boundary), get(m.orientation);
        get(m.hasPoints), get(m.hasCounts), get(m.hasIndices);
        get(m.points), get(m.counts), get(m.indices), get(m.creaseIndices), get(m.creaseLengths);
        get(m.cornerIndices), get(m.holeIndices), get(m.creaseSharpnesses), get(m.cornerSharpnesses);
        get(m.st), get(m.displayColor);
    }
    void get(usd::Node& n) { get(n.name), get(n.hasMatrix), get(n.matrix), get(n.mesh), get(n.children); }
};

void putResult(Wire& w, const Status& st, const usd::Layer& layer) {
    w.put(st.code), w.put(st.message);
    w.put(layer.nodes), w.put(layer.roots), w.put(layer.meshes), w.put(layer.zUp), w.put(layer.warnings);
}

bool getResult(Wire& w, Status& st, usd::Layer& layer) {
    w.get(st.code), w.get(st.message);
    w.get(layer.nodes), w.get(layer.roots), w.get(layer.meshes), w.get(layer.zUp), w.get(layer.warnings);
    return w.ok && w.at == w.bytes.size();
}

// Reads the layer in a forked child, which sends what it read back through a pipe:
// Sdf trusts a crate file's offsets and counts, and a corrupt one can crash it, which
// is then this BadInput, not the caller's crash. This process never runs Sdf itself,
// so it holds none of Sdf's threads or locks when it forks (a child forked while
// another thread held one would wait for it forever).
Status readIsolated(const std::string& path, const double* time, usd::Layer& layer) {
    int fds[2];
    if (pipe(fds) != 0) return usd::readLayer(path, time, layer);  // no child: read here
    const pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]), close(fds[1]);
        return usd::readLayer(path, time, layer);
    }
    if (pid == 0) {
        close(fds[0]);
        for (int sig : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) std::signal(sig, SIG_DFL);
        const int null = open("/dev/null", O_WRONLY);
        if (null >= 0) dup2(null, 2);  // Sdf's own diagnostics: its errors come back in the Status
        Wire w;
        const Status st = usd::readLayer(path, time, layer);
        putResult(w, st, layer);
        for (size_t done = 0; done < w.bytes.size();) {
            const ssize_t n = write(fds[1], w.bytes.data() + done, w.bytes.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) _exit(1);
            done += size_t(n);
        }
        _exit(0);
    }
    close(fds[1]);
    Wire w;
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = read(fds[0], buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        w.bytes.append(buffer, size_t(n));
    }
    close(fds[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) break;
    Status st;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && getResult(w, st, layer)) return st;
    layer = usd::Layer{};
    return Status::error(
        Status::BadInput,
        path + ": Sdf crashed reading it" +
            (WIFSIGNALED(status) ? " (signal " + std::to_string(WTERMSIG(status)) + ")" : std::string()) +
            ": the file is corrupt");
}

}  // namespace

Status parseUsdScene(const std::string& path, const UsdOptions& options, GltfScene& scene) {
    scene = GltfScene{};
    const double* time = options.time ? &*options.time : nullptr;
    usd::Layer layer;
    if (Status st = options.isolate ? readIsolated(path, time, layer) : usd::readLayer(path, time, layer); !st)
        return st;
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

// LeakSanitizer's built-in suppressions for every program that links USD input
// (loopbake, loopcheck, the USD tests, fuzz_usd), in every sanitizer run, whatever
// LSAN_OPTIONS says (CTest's test discovery runs test_usd_input without it): the
// wheels' libPxr*.so and their oneTBB (libtbb.so; the pattern also matches Debian's
// libtbb.so.12, third-party either way) keep registries and caches for the
// process's life, some made by static initializers at load (TBB's allocate_memory,
// Sdf_IdRegistryImpl), and LeakSanitizer reports them at exit. Our own code stays
// checked. Without a sanitizer nothing calls it.
extern "C" const char* __lsan_default_suppressions() { return "leak:libPxr\nleak:libtbb.so\n"; }

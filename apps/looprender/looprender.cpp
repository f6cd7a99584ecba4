// looprender -- evaluates a baked EXT_mesh_loop_subdivision asset: on a Vulkan
// device (default; headless, lavapipe in CI) or on the CPU (--cpu), and captures or
// renders the tessellated limit surface.
//
//   looprender ASSET.glb (--tess F | --lod distance|screen [--pixels-per-edge P])
//              [--spacing equal|fractional_odd] [--no-watertight] [--edit-scale X] [--capture OUT.ply]
//              [--mesh OUT.ply]
//              [--png OUT.png --size WxH] [--camera ...] [--frames N] [--json REPORT]
//   looprender SCENE.glb --color material [--time T] --png OUT.png (the whole scene)
//   looprender --cpu ASSET.glb (--tess F | --lod ...) [--capture OUT.ply] [--mesh OUT.ply] [--json REPORT]
//
// This file parses the command line; looprender_cpu.cpp and looprender_gpu.cpp run
// the two paths, looprender_common.cpp holds the outputs and the camera;
// looprender_scene.cpp draws whole scenes (scene.h, scene_render.h).
// Exit codes: 0 ok, 1 usage, 2 bad input (unreadable or invalid asset),
// 3 unsupported (no Vulkan device, tessellation or transform feedback),
// 4 write failed, 5 internal (a Vulkan error, or validation messages with --validation).
#include "looprender_common.h"

#include "looptess/glb.h"
#include "looptess/tools/file_io.h"
#include "looptess/version.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace {

using looprender::Options;

const char* kUsage =
    "usage: looprender ASSET.glb [options]\n"
    "\n"
    "Evaluates the exact Loop limit surface of a baked asset (loopbake's output) on\n"
    "a Vulkan device, or on the CPU with --cpu: its first surface (mesh) where it has\n"
    "several, which --color material draws all of.\n"
    "\n"
    "options:\n"
    "  --cpu               evaluate on the CPU instead of the Vulkan device\n"
    "  --tess F            global tessellation factor, a real in [1, 4096] (default\n"
    "                      1); subdivision depth = ceil(log2 F), capped at the asset's;\n"
    "                      F itself at 2^maxDepth where the finest level has\n"
    "                      irregular patches (watertight; -v, --json say the F used)\n"
    "  --lod MODE          global (default: --tess), distance (one factor from the\n"
    "                      distance of the bounding-box centre to the eye) or screen\n"
    "                      (a factor per patch edge from its projected length); both\n"
    "                      pick the depth from the largest factor, F <= 2^depth\n"
    "  --pixels-per-edge P target on-screen edge length for --lod (default 8)\n"
    "  --spacing S         equal (default) or fractional_odd\n"
    "  --path P            tessellator: the hardware tessellator's points; patterns:\n"
    "                      refinement patterns, each edge factor rounded up to a power\n"
    "                      of two, drawn as instances (no tessellator; --spacing\n"
    "                      unused); compute: the points of patterns, evaluated in\n"
    "                      compute passes and drawn as plain triangles (the fast path\n"
    "                      where graphics stages run on few cores); auto (default):\n"
    "                      with --frames 2 or more, the frames measure every path\n"
    "                      and keep the fastest (from 4 frames on); one frame,\n"
    "                      captures, --mesh, --cpu and scenes take the tessellator\n"
    "                      with --spacing fractional_odd or --lod screen, else\n"
    "                      patterns (-v, --json say which)\n"
    "  --no-watertight     evaluate each patch alone: faster, but shared edges may differ\n"
    "                      in the last bits (default: watertight, bit-identical seams)\n"
    "  --no-displacement   draw the undisplaced limit surface of an asset with a\n"
    "                      displacement map (loopbake --displacement)\n"
    "  --edit-scale X      multiply every hierarchical edit value of the asset by X\n"
    "                      (default 1; 0 leaves add and subtract edits out), on the host\n"
    "                      before the subdivision passes: no re-bake\n"
    "  --capture OUT.ply   write the emitted triangles (unwelded; x y z nx ny nz face u v,\n"
    "                      then s t where the asset has TEXCOORD_0);\n"
    "                      the same file with and without --cpu\n"
    "  --mesh OUT.ply      write the surface as indexed triangles, each pattern point\n"
    "                      once per patch (the pattern path; VulkanSurface::\n"
    "                      recordEvaluate on the device): x y z nx ny nz, then\n"
    "                      tx ty tz tw s t where the asset has TEXCOORD_0; faces as\n"
    "                      uint indices; the same file with and without --cpu;\n"
    "                      shared edges' points have equal bits (weld by value;\n"
    "                      not with --no-watertight)\n"
    "  --png OUT.png       render offscreen, shaded (Vulkan only)\n"
    "  --size WxH          image size (default 512x512)\n"
    "  --color C           shaded (default); levels: a hue per subdivision level,\n"
    "                      non-plain sub-patches paler, irregular patches dark blue;\n"
    "                      texcoords: a checker of TEXCOORD_0, 8x8 squares a unit;\n"
    "                      material: the whole glTF scene, every node whose mesh is\n"
    "                      subdivided with its transform or skin and its material\n"
    "                      (metallic-roughness with base colour, metallic-roughness,\n"
    "                      normal, occlusion and emissive textures), seen from the\n"
    "                      file's first camera (else framing the scene), one light\n"
    "  --time T            with --color material: pose the scene at T seconds of its\n"
    "                      animation (default: the file's rest pose); skins follow\n"
    "  --animation N       which animation --time plays (default 0, the first)\n"
    "  --wireframe         draw triangle edges only\n"
    "  --camera EX,EY,EZ,TX,TY,TZ[,FOV]  eye, target and vertical field of view in\n"
    "                      degrees (default: framing the bounding box, 40 degrees);\n"
    "                      --lod uses it and the image height (--size) with --cpu too\n"
    "  --frames N          render N frames and report their mean GPU times (default 1)\n"
    "  --threads N         threads of the CPU evaluation (--cpu, and the CPU side of\n"
    "                      --capture checks; default 0: every hardware thread); the\n"
    "                      output is the same for every N\n"
    "  --validation        Vulkan validation layers on; any message fails (exit 5)\n"
    "  --device NAME       use the Vulkan device whose name contains NAME\n"
    "  --json REPORT.json  write a machine-readable summary (Vulkan: per-pass GPU times\n"
    "                      from timestamp queries, device memory of the asset)\n"
    "  -v                  print statistics to stderr\n"
    "  --help, --version\n"
    "\n"
    "exit codes: 0 ok, 1 usage, 2 bad input, 3 unsupported, 4 write failed, 5 internal\n";

int usage(const std::string& message) {
    std::fprintf(stderr, "looprender: error: %s\n\n%s", message.c_str(), kUsage);
    return 1;
}

// Comma-separated floats; false unless there are `min`..`max` of them.
bool parseFloats(const char* text, float* out, int min, int max, int& count) {
    std::stringstream in(text);
    std::string item;
    count = 0;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        if (count == max) return false;
        out[count++] = std::strtof(item.c_str(), &end);
        if (item.empty() || *end) return false;
    }
    return count >= min;
}

// Parses one option that takes a value; returns -1 to go on, or an exit code.
int parseValue(const std::string& a, const char* v, Options& s) {
    char* end = nullptr;
    if (a == "--tess") {
        s.tess = std::strtof(v, &end);
        if (*end || !(s.tess >= 1.0f && s.tess <= 4096.0f)) return usage("--tess takes a number in [1, 4096]");
    } else if (a == "--path") {
        std::string p = v;
        if (p != "auto" && p != "tessellator" && p != "patterns" && p != "compute")
            return usage("--path takes auto, tessellator, patterns or compute");
        s.path = p;
    } else if (a == "--spacing") {
        std::string sp = v;
        if (sp == "equal")
            s.spacing = lt::Spacing::Equal;
        else if (sp == "fractional_odd")
            s.spacing = lt::Spacing::FractionalOdd;
        else
            return usage("--spacing takes equal or fractional_odd");
    } else if (a == "--size") {
        unsigned w = 0, h = 0;
        char tail = 0;
        if (std::sscanf(v, "%ux%u%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384)
            return usage("--size takes WxH, each 1..16384");
        s.width = w;
        s.height = h;
    } else if (a == "--camera") {
        float c[7];
        int n = 0;
        if (!parseFloats(v, c, 6, 7, n)) return usage("--camera takes EX,EY,EZ,TX,TY,TZ[,FOV]");
        if (!std::all_of(c, c + 6, [](float x) { return std::isfinite(x); }))
            return usage("--camera: the eye and the target must be finite");
        if (c[0] == c[3] && c[1] == c[4] && c[2] == c[5]) return usage("--camera: the eye is the target");
        s.camera = true;
        for (int k = 0; k < 3; ++k) {
            s.eye[k] = c[k];
            s.target[k] = c[3 + k];
        }
        if (n == 7) s.fovDegrees = c[6];
        if (!(s.fovDegrees > 0.5f && s.fovDegrees < 179.0f))
            return usage("--camera: FOV must be in (0.5, 179) degrees");
    } else if (a == "--lod") {
        std::string m = v;
        if (m == "global")
            s.lod = lt::LodMode::Global;
        else if (m == "distance")
            s.lod = lt::LodMode::Distance;
        else if (m == "screen")
            s.lod = lt::LodMode::Screen;
        else
            return usage("--lod takes global, distance or screen");
    } else if (a == "--pixels-per-edge") {
        s.pixelsPerEdge = std::strtof(v, &end);
        if (*end || !(s.pixelsPerEdge >= 0.01f && s.pixelsPerEdge <= 100000.0f))
            return usage("--pixels-per-edge takes a number in [0.01, 100000]");
    } else if (a == "--edit-scale") {
        s.editScale = std::strtof(v, &end);
        if (*end || !std::isfinite(s.editScale) || std::fabs(s.editScale) > 1e6f)
            return usage("--edit-scale takes a finite number in [-1e6, 1e6]");
    } else if (a == "--frames") {
        long n = std::strtol(v, &end, 10);
        if (*end || n < 1 || n > 100000) return usage("--frames takes an integer in [1, 100000]");
        s.frames = uint32_t(n);
    } else if (a == "--threads") {
        long n = std::strtol(v, &end, 10);
        if (*end || n < 0 || n > 256) return usage("--threads takes an integer in [0, 256]");
        s.threads = uint32_t(n);
    } else if (a == "--capture") {
        s.capture = v;
    } else if (a == "--mesh") {
        s.mesh = v;
    } else if (a == "--png") {
        s.png = v;
    } else if (a == "--color") {
        std::string c = v;
        if (c != "shaded" && c != "levels" && c != "texcoords" && c != "material")
            return usage("--color takes shaded, levels, texcoords or material");
        s.color = c;
    } else if (a == "--animation") {
        long n = std::strtol(v, &end, 10);
        if (*end || n < 0 || n > 1000000) return usage("--animation takes an index >= 0");
        s.animation = int(n);
    } else if (a == "--time") {
        s.time = std::strtof(v, &end);
        if (*end || !std::isfinite(s.time) || s.time < 0 || s.time > 1e6f)
            return usage("--time takes seconds in [0, 1e6]");
    } else if (a == "--device") {
        s.device = v;
    } else if (a == "--json") {
        s.json = v;
    }
    return -1;
}

// Parses argv into `s`; returns -1 to go on, or an exit code.
int parseArgs(int argc, char** argv, Options& s) {
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (a == "--version") {
            std::printf("looprender %s\n", LOOPTESS_VERSION_STRING);
            return 0;
        } else if (a == "--cpu") {
            s.cpu = true;
        } else if (a == "-v") {
            s.verbose = true;
        } else if (a == "--validation") {
            s.validation = true;
        } else if (a == "--wireframe") {
            s.wireframe = true;
        } else if (a == "--no-watertight") {
            s.watertight = false;
        } else if (a == "--no-displacement") {
            s.displace = false;
        } else if (a == "--tess" || a == "--spacing" || a == "--path" || a == "--capture" || a == "--json" ||
                   a == "--png" || a == "--size" || a == "--camera" || a == "--frames" || a == "--device" ||
                   a == "--color" || a == "--lod" || a == "--pixels-per-edge" || a == "--edit-scale" || a == "--time" ||
                   a == "--animation" || a == "--mesh" || a == "--threads") {
            if (i + 1 >= argc) return usage(a + " needs a value");
            int code = parseValue(a, argv[++i], s);
            if (code >= 0) return code;
        } else if (!a.empty() && a[0] == '-') {
            return usage("unknown option " + a);
        } else if (s.input.empty()) {
            s.input = a;
        } else {
            return usage("more than one input");
        }
    }
    if (s.input.empty()) return usage("no input asset");
    if ((s.time >= 0 || s.animation >= 0) && s.color != "material")
        return usage("--time and --animation need --color material");
    if (!s.mesh.empty() && (s.path == "tessellator" || s.spacing != lt::Spacing::Equal))
        return usage(
            "--mesh writes the pattern path's vertices: not with --path tessellator or --spacing fractional_odd");
    if (s.color == "material" &&
        (!s.mesh.empty() || !s.capture.empty() || s.wireframe || s.lod != lt::LodMode::Global || s.editScale != 1))
        return usage(
            "--color material draws with --tess only: no --capture, --mesh, --wireframe, --lod or --edit-scale");
    if (s.cpu && (!s.png.empty() || s.color != "shaded" || s.wireframe))
        return usage("--png, --color and --wireframe need the Vulkan path (drop --cpu)");
    return -1;
}

constexpr const char* kExtension = "EXT_mesh_loop_subdivision";

// The meshes of `bytes` carrying the extension (the file's surfaces), once
// readAssetGlb has read the first: 0 if the JSON cannot be read again.
size_t surfaceCount(const std::vector<uint8_t>& bytes) {
    lt::GlbChunks chunks;
    if (!lt::readGlb(bytes.data(), bytes.size(), "", lt::GlbLayout::Lenient, chunks)) return 0;
    const nlohmann::json doc = nlohmann::json::parse(chunks.json, nullptr, false);
    const auto meshes = doc.is_object() ? doc.find("meshes") : doc.end();
    if (!doc.is_object() || meshes == doc.end() || !meshes->is_array()) return 0;
    size_t n = 0;
    for (const nlohmann::json& mesh : *meshes) {
        const auto ext = mesh.is_object() ? mesh.find("extensions") : mesh.end();
        n += mesh.is_object() && ext != mesh.end() && ext->is_object() && ext->contains(kExtension);
    }
    return n;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    int code = parseArgs(argc, argv, options);
    if (code >= 0) return code;
    std::vector<uint8_t> bytes;
    lt::Status st = lt::readFile(options.input, bytes);
    if (st && options.color == "material") return looprender::runScene(options, bytes);
    lt::Asset asset;
    if (st) st = lt::readAssetGlb(bytes.data(), bytes.size(), options.input, asset);
    if (!st) return looprender::fail(st);
    // Without --color material one surface is drawn: say so where there are more.
    if (const size_t surfaces = surfaceCount(bytes); surfaces > 1)
        std::fprintf(stderr,
                     "looprender: %s has %zu surfaces (meshes with %s); this draws the first, in mesh order "
                     "(--color material draws the whole scene)\n",
                     options.input.c_str(), surfaces, kExtension);
    return options.cpu ? looprender::runCpu(options, asset) : looprender::runGpu(options, asset);
}

// apps/loopbake/bake_job.cpp -- loopbake::bakeFile (bake_job.h).
#include "bake_job.h"

#include "looptess/tools/file_io.h"
#ifdef LOOPTESS_HAVE_USD
#include "looptess/tools/usd.h"
#endif

#include "limits_cli.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>

namespace loopbake {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void printWarnings(const std::vector<std::string>& warnings) {
    for (const std::string& w : warnings) std::fprintf(stderr, "loopbake: warning: %s\n", w.c_str());
}

// How the readers read s.input: --strict refuses polygons and what input cleaning
// would change; --boundary sets every mesh's boundary rule.
lt::InputOptions inputOptions(const Settings& s) {
    lt::InputOptions options;
    options.strict = s.strict;
    options.boundary = s.boundary;
    options.cleaning = s.strict ? lt::InputCleaning::Refuse : lt::InputCleaning::Repair;
    options.limits = s.limits;
    options.hardEdges = s.hardEdges;
    return options;
}

// --edits: the side-car's edits follow the input's own (baker.h, parseEditsJson).
Status loadEdits(const Settings& s, lt::InputMesh& mesh) {
    std::vector<uint8_t> bytes;
    if (Status st = lt::cli::checkInputFile(s.edits, s.limits); !st) return st;
    if (Status st = lt::readFile(s.edits, bytes, s.limits.maxInputBytes); !st) return st;
    return lt::parseEditsJson(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), s.edits,
                              mesh);
}

// checkInput and bake number the edits of the input's tags and of the side-car
// together ("hero.obj: vertex edit 5 (face ...) ..."): name the side-car entry a bad
// edit came from.
void nameEditSource(const Settings& s, const std::string& name, size_t tagEdits, Status& st) {
    const std::string key = name + ": vertex edit ";
    size_t edit = 0;
    if (s.edits.empty() || st.message.rfind(key, 0) != 0) return;
    const char* first = st.message.data() + key.size();
    if (std::from_chars(first, st.message.data() + st.message.size(), edit).ec != std::errc() || edit < tagEdits)
        return;
    st.message += " (" + s.edits + ": edits[" + std::to_string(edit - tagEdits) + "])";
}

// --displacement: decodes the PNG and resamples it into `asset` (baker.h).
Status addDisplacement(const Settings& s, const std::string& name, lt::Asset& asset, Results& r) {
    std::vector<uint8_t> png;
    Status st = lt::readFile(s.displacement, png);
    if (st) st = lt::decodeGrayPng(png.data(), png.size(), s.displacement, r.map);
    if (!st) return st;
    lt::DisplacementSettings ds;
    ds.scale = *s.scale;
    ds.bias = s.bias.value_or(0.0f);
    ds.resolution = uint32_t(s.displacementResolution.value_or(0));
    if (st = lt::bakeDisplacement(r.map, ds, asset, name); !st) return st;
    r.map.texels = {};
    r.displacementResolution = asset.displacement.resolution;
    r.displacementSamples = asset.displacement.values.size();
    return Status::ok();
}

// Checks, creases, bakes one control mesh (with the side-car edits and the map).
Status bakeMesh(const Settings& s, lt::InputMesh& mesh, MeshResult& m, Results& r, lt::Asset& asset) {
    const size_t tagEdits = mesh.edits.size();
    m.cleaning = mesh.cleaning;
    if (!s.edits.empty())
        if (Status st = loadEdits(s, mesh); !st) return st;
    std::vector<std::string> checkWarnings;
    Status st = lt::checkInput(mesh, m.name, checkWarnings);
    nameEditSource(s, m.name, tagEdits, st);
    printWarnings(checkWarnings);
    r.warnings.insert(r.warnings.end(), checkWarnings.begin(), checkWarnings.end());
    if (!st) return st;
    m.creases = mesh.creases.size();
    if (s.creaseAngle) lt::addCreasesByAngle(mesh, *s.creaseAngle);
    m.autoCreases = mesh.creases.size() - m.creases;
    m.vertices = mesh.vertexCount();
    m.faces = mesh.faceCount();
    m.corners = mesh.corners.size();
    m.holes = mesh.holes.size();
    m.uvs = !mesh.faceUVs.empty();
    lt::BakeSettings bakeSettings;
    bakeSettings.maxDepth = s.maxDepth;
    bakeSettings.threads = s.bakeThreads;
    bakeSettings.limits = s.limits;
    bakeSettings.name = m.name;
    st = lt::bake(mesh, bakeSettings, asset, &m.stats);
    nameEditSource(s, m.name, tagEdits, st);
    if (!st) return st;
    if (m.stats.depthLowered || (s.verbose && s.maxDepth == 0))
        std::fprintf(stderr, "loopbake: %s: %s\n", m.name.c_str(), m.stats.depthReason.c_str());
    for (const lt::Level& level : asset.levels) m.levelEdits.push_back(level.edits.count());
    if (std::all_of(m.stats.levels.begin(), m.stats.levels.end(),
                    [](const lt::LevelStats& l) { return l.rpp + l.npp + l.ipp == 0; })) {
        // An empty surface is no error (a scene may keep it), but never what was meant.
        const std::string w = m.name + ": draws no face: each of its " + std::to_string(m.faces) +
                              " faces is a hole or, with boundary interpolation none, touches the boundary";
        printWarnings({w});
        r.warnings.push_back(w);
    }
    if (!s.displacement.empty()) return addDisplacement(s, m.name, asset, r);
    return Status::ok();
}

// Frees `bytes` (the file) once parsed: the text is not needed by the bake, whose
// peak it would add to.
Status bakeObj(const Settings& s, std::vector<uint8_t>& bytes, Results& r, std::vector<uint8_t>& out) {
    const lt::InputOptions options = inputOptions(s);
    lt::InputMesh mesh;
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    Status st = lt::parseObj(text, s.input, options, mesh);
    std::vector<uint8_t>().swap(bytes);
    printWarnings(mesh.warnings);
    r.warnings = mesh.warnings;
    if (!st) return st;
    if (!s.meshes.empty()) return Status::error(Status::Usage, "--mesh needs a glTF input");
    MeshResult& m = r.meshes.emplace_back();
    m.name = s.input;
    lt::Asset asset;
    if (st = bakeMesh(s, mesh, m, r, asset); !st) return st;
    return lt::writeAssetGlb(asset, out, &r.tableBytes, s.compression, s.bakeThreads);
}

// A glTF mesh's name as messages show it: at most 80 bytes (cut on a UTF-8
// character boundary), as the baker quotes any input.
std::string shownName(const std::string& name) {
    if (name.size() <= 80) return name;
    size_t cut = 80;
    while (cut > 0 && (static_cast<unsigned char>(name[cut]) & 0xC0) == 0x80) --cut;
    return name.substr(0, cut) + "...";
}

// Whether --mesh selects glTF mesh `m` (by index or name); every mesh without --mesh.
bool selected(const Settings& s, const lt::GltfScene::Mesh& m) {
    if (s.meshes.empty()) return true;
    for (const std::string& want : s.meshes)
        if (want == m.name || want == std::to_string(m.index)) return true;
    return false;
}

// Bakes every selected mesh of a scene read from glTF or USD (`st`: the reader's
// status) and writes the scene with its surfaces.
Status bakeScene(const Settings& s, lt::GltfScene& scene, Status st, Results& r, std::vector<uint8_t>& out) {
    printWarnings(scene.warnings);
    r.warnings = scene.warnings;
    if (!st) return st;
    r.inputs.insert(r.inputs.end(), scene.files.begin(), scene.files.end());
    for (const std::string& want : s.meshes)
        if (std::none_of(scene.meshes.begin(), scene.meshes.end(), [&](const lt::GltfScene::Mesh& m) {
                return want == m.name || want == std::to_string(m.index);
            }))
            return Status::error(Status::Usage,
                                 s.input + ": --mesh " + want + ": no mesh of triangles has that name or index");
    const size_t count = size_t(std::count_if(scene.meshes.begin(), scene.meshes.end(),
                                              [&](const lt::GltfScene::Mesh& m) { return selected(s, m); }));
    if (count != 1 && (!s.edits.empty() || !s.displacement.empty()))
        return Status::error(Status::Usage, s.input +
                                                ": --edits and --displacement need exactly one mesh to bake, not " +
                                                std::to_string(count) + " (choose one with --mesh NAME|INDEX)");
    std::vector<lt::SceneSurface> surfaces;
    for (lt::GltfScene::Mesh& sm : scene.meshes) {
        if (!selected(s, sm)) {
            ++r.passedThrough;
            continue;
        }
        MeshResult& m = r.meshes.emplace_back();
        m.mesh = sm.index;
        m.name = s.input + ": meshes[" + std::to_string(sm.index) + "]" +
                 (sm.name.empty() ? "" : " (" + shownName(sm.name) + ")");
        lt::SceneSurface& surface = surfaces.emplace_back();
        surface.mesh = sm.index;
        surface.primitives = sm.primitives;
        surface.controlVertex = std::move(sm.controlVertex);
        if (st = bakeMesh(s, sm.mesh, m, r, surface.asset); !st) return st;
        sm.mesh = lt::InputMesh{};  // its memory back before the next mesh
    }
    return lt::writeSceneGlb(scene.document, std::move(scene.bin), surfaces, out, &r.tableBytes, s.compression,
                             s.bakeThreads);
}

Status bakeGltf(const Settings& s, const std::vector<uint8_t>& bytes, Results& r, std::vector<uint8_t>& out) {
    std::string dir = std::filesystem::path(s.input).parent_path().string();
    lt::GltfScene scene;
    Status st =
        lt::parseGltfScene(bytes.data(), bytes.size(), s.input, dir.empty() ? "." : dir, inputOptions(s), scene);
    return bakeScene(s, scene, st, r, out);
}

// USD: read by path (Sdf opens the file itself; usdz is a zip of layers).
Status bakeUsd(const Settings& s, Results& r, std::vector<uint8_t>& out) {
#ifdef LOOPTESS_HAVE_USD
    lt::UsdOptions options;
    options.input = inputOptions(s);
    options.time = s.time;
    lt::GltfScene scene;
    Status st = lt::parseUsdScene(s.input, options, scene);
    return bakeScene(s, scene, st, r, out);
#else
    return Status::error(Status::Unsupported, s.input +
                                                  ": this loopbake was built without USD input (configure with "
                                                  "pxr-sdf: scripts/setup-debian.sh, cmake/Usd.cmake)");
#endif
}

}  // namespace

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

Status bakeFile(const Settings& s, Results& r) {
    auto t0 = Clock::now();
    const std::string ext = lowerExtension(s.input);
    const bool usd = lt::isUsdPath(s.input);
    if (ext != ".obj" && ext != ".gltf" && ext != ".glb" && !usd)
        return Status::error(Status::Unsupported, s.input + ": unsupported input format '" + ext +
                                                      "' (expected .obj, .gltf, .glb, .usd, .usda, .usdc or .usdz)");
    if (s.time && !usd) return Status::error(Status::Usage, "--time needs a USD input");
    if (s.hardEdges && ext != ".gltf" && ext != ".glb")
        return Status::error(Status::Usage,
                             s.input +
                                 ": --hard-edges reads glTF vertex normals; OBJ and USD carry their "
                                 "creases as data ('t crease' tags, creaseIndices) (or use --crease-angle)");
    std::vector<uint8_t> bytes, out;
    r.inputs = {s.input};
    if (Status st = lt::cli::checkInputFile(s.input, s.limits); !st) return st;
    if (!usd)
        if (Status st = lt::readFile(s.input, bytes, s.limits.maxInputBytes); !st) return st;
    r.readSeconds = secondsSince(t0);  // parsing counts as baking

    t0 = Clock::now();
    Status st = usd ? bakeUsd(s, r, out) : ext == ".obj" ? bakeObj(s, bytes, r, out) : bakeGltf(s, bytes, r, out);
    if (!st) return st;
    r.bakeSeconds = secondsSince(t0);

    t0 = Clock::now();
    if (st = lt::checkOutputBytes(out.size(), s.limits, s.output); !st) return st;
    if (st = lt::writeFileAtomic(s.output, out.data(), out.size()); !st) return st;
    r.outputBytes = out.size();
    if (!s.edits.empty()) r.inputs.push_back(s.edits);
    if (!s.displacement.empty()) r.inputs.push_back(s.displacement);
    if (!s.depfile.empty()) {
        const std::string text = depfileText(s.output, r.inputs);
        if (st = lt::writeFileAtomic(s.depfile, reinterpret_cast<const uint8_t*>(text.data()), text.size()); !st)
            return st;
    }
    r.writeSeconds = secondsSince(t0);
    return Status::ok();
}

std::string depfileText(const std::string& output, const std::vector<std::string>& inputs) {
    auto escape = [](const std::string& path) {
        std::string e;
        for (char c : path) {
            if (c == ' ' || c == '#') e += '\\';
            if (c == '$') e += '$';
            e += c;
        }
        return e;
    };
    std::string text = escape(output) + ":";
    for (const std::string& in : inputs) text += " " + escape(in);
    return text + "\n";
}

}  // namespace loopbake

// Running the checks of every tessellation, and their findings (looptess/tools/check.h).
#include "check_internal.h"

#include "random.h"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace lt {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

void say(const CheckContext& ctx, const std::string& line) {
    if (ctx.progress) ctx.progress(line);
}

// " (the reference includes N hierarchical edits down to level K)", or "".
std::string referenceEdits(uint32_t edits, int level) {
    if (edits == 0) return "";
    return " (the reference includes " + std::to_string(edits) + " hierarchical edit" + (edits == 1 ? "" : "s") +
           " down to level " + std::to_string(level) + ")";
}
std::string referenceEdits(const OsdLimitSurface& s) { return referenceEdits(s.editCount(), s.editLevel()); }

}  // namespace

std::string tessCaseName(const TessCase& c) {
    const char* spacing = c.spacing == Spacing::Equal ? "equal" : "fractional_odd";
    return (c.mode == TessMode::Screen ? "screen F<=" : "F=") + number(c.factor) + " " + spacing;
}

Status parseTessCase(const std::string& text, TessCase& out) {
    TessCase c;
    std::string head = text;
    const size_t colon = text.find(':');
    if (colon != std::string::npos) {
        const std::string spacing = text.substr(colon + 1);
        if (spacing == "odd" || spacing == "fractional_odd")
            c.spacing = Spacing::FractionalOdd;
        else if (spacing != "equal")
            return Status::error(Status::Usage, "--tess '" + text + "': spacing must be 'equal' or 'odd'");
        head = text.substr(0, colon);
    }
    std::string value = head;
    c.factor = 8.0f;
    if (head.rfind("screen", 0) == 0) {
        c.mode = TessMode::Screen;
        value = head.size() > 6 && head[6] == '=' ? head.substr(7) : head.size() == 6 ? "" : "?";
    }
    if (!value.empty()) {
        float f = 0;
        const auto res = std::from_chars(value.data(), value.data() + value.size(), f);
        if (res.ec != std::errc() || res.ptr != value.data() + value.size() || !(f >= 1.0f && f <= 64.0f))
            return Status::error(Status::Usage, "--tess '" + text +
                                                    "': expected F[:equal|:odd] or screen[=F][:equal|:odd], "
                                                    "F from 1 to 64");
        c.factor = f;
    }
    out = c;
    return Status::ok();
}

EvalSettings evalSettingsFor(const Asset& asset, const TessCase& c, const CheckSettings& settings) {
    EvalSettings es;
    es.tessFactor = c.mode == TessMode::Global ? c.factor : 1.0f;
    es.spacing = c.spacing;
    es.path = settings.path;
    es.watertight = settings.watertight;
    es.threads = settings.threads;
    es.displace = false;    // runChecks adds the displaced evaluation
    es.attributes = false;  // no check reads texture coordinates, tangents or colours (a third of the soup)
    if (c.mode == TessMode::Global || asset.positions.empty()) return es;
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < asset.positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], asset.positions[i]);
        hi[i % 3] = std::max(hi[i % 3], asset.positions[i]);
    }
    const double dir[3] = {0.3, 0.2, 1.0}, len = std::sqrt(0.09 + 0.04 + 1.0);
    const double radius = 0.5 * boundingBoxDiagonal(asset.positions);
    const double distance = radius / std::sin(0.5 * double(settings.screenFovDegrees) * 3.141592653589793 / 180.0);
    float eye[3];
    for (int k = 0; k < 3; ++k) eye[k] = float(0.5 * (double(lo[k]) + hi[k]) + dir[k] / len * distance);
    es.lod = cameraLod(LodMode::Screen, eye, settings.screenFovDegrees, settings.screenRows, 8.0f);
    // F is proportional to 1 / pixelsPerEdge where [1, 2^maxDepth] does not clamp it.
    const float top = std::ldexp(1.0f, int(asset.maxDepth()));
    for (float probe = 1.0f / 64; probe < 1e6f; probe *= 2) {
        EvalSettings p = es;
        p.lod = cameraLod(LodMode::Screen, eye, settings.screenFovDegrees, settings.screenRows, probe);
        const float f = lodTessFactor(asset, asset.positions.data(), p);
        if (f > 1.0f && f < top) {
            es.lod =
                cameraLod(LodMode::Screen, eye, settings.screenFovDegrees, settings.screenRows, probe * f / c.factor);
            break;
        }
    }
    return es;
}

namespace {

// The reference factor of `asset` (CheckSettings::referenceFactor, or the finest
// the triangle budget allows, at most 2^maxDepth).
float referenceFactorOf(const Asset& asset, const CheckSettings& settings) {
    float f = settings.referenceFactor;
    if (f > 0) return f;
    // Above 2^maxDepth the deepest patches get factors > 1 next to flat IPPs:
    // T-junctions by design (runtime.h), so the reference stays at or below it.
    f = std::min(64.0f, std::ldexp(1.0f, int(std::min(asset.maxDepth(), 6u))));
    while (f > 1 && 2.0 * f * f * asset.faceCount() > double(settings.referenceTriangleBudget)) f /= 2;
    return f;
}

// The ray reference of `asset` at ctx.referenceFactor, equal spacing (`scene`: with its
// ray scene; else only its (u, v) index).
Status buildReference(const CheckContext& ctx, const Asset& asset, bool displace,
                      std::unique_ptr<CheckContext::Reference>& out, bool scene = true) {
    EvalSettings es;
    es.tessFactor = ctx.referenceFactor;
    es.watertight = ctx.settings->watertight;
    es.threads = ctx.settings->threads;
    es.displace = displace;
    es.attributes = false;  // no check reads texture coordinates, tangents or colours
    auto mesh = std::make_shared<WeldedMesh>();
    out = std::make_unique<CheckContext::Reference>();
    {
        Tessellation soup;
        evaluateCpu(asset, asset.positions.data(), es, soup);
        say(ctx, std::string("reference") + (displace ? " (displaced): " : ": ") +
                     std::to_string(soup.triangleCount()) + " triangles, welding" +
                     (scene ? ", building the ray scene" : ""));
        weldMesh(soup, *mesh);
        out->surface.build(soup, mesh);
    }
    return scene ? RayScene::create(mesh, out->scene) : Status::ok();
}

// `asset` as the runtime shows it at depth `depth`: without the edits of deeper levels.
Asset shownAtDepth(const Asset& asset, uint32_t depth) {
    Asset shown = asset;
    for (size_t l = depth + 1; l < shown.levels.size(); ++l) shown.levels[l].edits = VertexEdits{};
    return shown;
}

// The reference for a tessellation of runtime depth `depth`: the asset's own, or,
// when it has edits deeper than that, one of the asset without them (cached): the
// runtime applies a level's edits only when it computes that level.
Status referenceAtDepth(CheckContext& ctx, uint32_t depth, bool displace, const CheckContext::Reference*& out) {
    out = displace ? ctx.displacedReference.get() : ctx.reference.get();
    if (!out || ctx.asset->editDepth() <= depth) return Status::ok();
    auto& slot = ctx.depthReferences[{depth, displace}];
    if (!slot) {
        say(ctx, "reference without the edits below depth " + std::to_string(depth));
        if (Status st = buildReference(ctx, shownAtDepth(*ctx.asset, depth), displace, slot); !st) return st;
    }
    out = slot.get();
    return Status::ok();
}

// The finer surface checkNormals judges again against for a tessellation of factor
// `factor` and runtime depth `depth`, undisplaced: the ray reference where there is
// one, else one made for the normals; null where the reference is not twice as fine.
Status finerSurface(CheckContext& ctx, uint32_t depth, float factor, const SurfaceIndex*& out) {
    out = nullptr;
    if (2 * factor > ctx.referenceFactor) return Status::ok();
    const CheckContext::Reference* reference = nullptr;
    if (Status st = referenceAtDepth(ctx, depth, false, reference); !st) return st;
    if (!reference) {
        auto& slot = ctx.normalReferences[depth];
        if (!slot) {
            say(ctx, "  normals: a finer surface to judge against");
            if (Status st = buildReference(ctx, shownAtDepth(*ctx.asset, depth), false, slot, false); !st) return st;
        }
        reference = slot.get();
    }
    out = &reference->surface;
    return Status::ok();
}

// Whether soup vertex `v` is a base face's corner on a control vertex of the smooth
// rule, where the asset's own control mesh is an oracle (cageOracle): N1's
// confirmation without --source. A vertex whose 1-ring winds twice round it (a fan
// folded over at a pinch) has a limit normal its triangles approach only 0.8 times
// closer a level: at F = 16 all eleven stood 65 to 100 degrees from it.
bool smoothCorner(CheckContext& ctx, const Tessellation& soup, size_t v) {
    const int corner = baseCorner(soup.uv[2 * v], soup.uv[2 * v + 1]);
    if (corner < 0) return false;
    if (!ctx.cageTried) {
        ctx.cageTried = true;
        say(ctx, "  normals: OpenSubdiv's limit of the asset's own control mesh");
        ctx.cage = std::make_unique<SourceOracle>();
        if (!cageOracle(*ctx.asset, *ctx.cage, ctx.smoothVertex)) ctx.cage.reset();
    }
    return ctx.cage && ctx.smoothVertex[ctx.asset->faces[3 * size_t(soup.face[v]) + size_t(corner)]];
}

}  // namespace

Status prepareChecks(const Asset& asset, SourceOracle* source, const CheckSettings& settings, CheckContext& ctx) {
    ctx.asset = &asset;
    ctx.evaluator = std::make_unique<CpuEvaluator>(asset);
    ctx.settings = &settings;
    ctx.topology = analyzeControlMesh(asset);
    ctx.diagonal = boundingBoxDiagonal(asset.positions);
    ctx.source = source;
    ctx.reference.reset();
    ctx.displacedReference.reset();
    ctx.depthReferences.clear();
    ctx.normalReferences.clear();
    ctx.cage.reset();
    ctx.smoothVertex.clear();
    ctx.cageTried = false;
    const float f = referenceFactorOf(asset, settings);
    ctx.referenceFactor = f;
    if (!ctx.topology.closed() || settings.rays == 0) {
        ctx.referenceSkipped = settings.rays == 0 ? "no rays" : "the control mesh is not closed";
        return Status::ok();
    }
    const auto t0 = Clock::now();
    say(ctx, "reference: evaluating F=" + number(f) + " equal");
    for (bool displace : {false, true}) {
        if (displace && !asset.displacement.present()) break;
        const Status st = buildReference(ctx, asset, displace, displace ? ctx.displacedReference : ctx.reference);
        if (!st) return st;
    }
    ctx.referenceSeconds = since(t0);
    return Status::ok();
}

Status checkEvaluation(CheckContext& ctx, const EvalSettings& eval, bool accuracy, uint64_t seed,
                       TessellationChecks& out, Tessellation* keep) {
    out.eval = eval;
    out.path = "cpu";
    out.factor = lodTessFactor(*ctx.asset, ctx.asset->positions.data(), eval);
    out.depth = runtimeDepth(*ctx.asset, out.factor);
    const auto t0 = Clock::now();
    Tessellation local;
    Tessellation& soup = keep ? *keep : local;
    assert(ctx.evaluator && "prepareChecks first");
    ctx.evaluator->evaluate(ctx.asset->positions.data(), eval, soup);
    out.evaluateSeconds = since(t0);
    return checkTessellation(ctx, soup, accuracy, seed, out);
}

Status checkTessellation(CheckContext& ctx, const Tessellation& soup, bool accuracy, uint64_t seed,
                         TessellationChecks& out) {
    const auto t0 = Clock::now();
    const CheckSettings& settings = *ctx.settings;
    out.triangles = soup.triangleCount();
    if (accuracy && ctx.source) {
        SourceOracle* oracle = nullptr;  // the edits the runtime applies at this depth
        if (Status st = ctx.source->atDepth(out.depth, oracle); !st) return st;
        say(ctx, "  accuracy against OpenSubdiv" + referenceEdits(oracle->fine));
        oracle->assetDepth = ctx.asset->maxDepth();
        checkAccuracy(*oracle, soup, out.depth, ctx.diagonal, settings, deriveSeed(seed, 1), out.accuracy);
    }
    out.accuracySeconds = since(t0);
    auto tc = Clock::now();
    say(ctx, "  weld (" + std::to_string(soup.triangleCount()) + " triangles)");
    auto mesh = std::make_shared<WeldedMesh>();
    weldTessellation(soup, ctx.topology, out.weld, mesh.get());
    out.weldSeconds = since(tc);
    tc = Clock::now();
    // A displaced surface is drawn with the normals of the undisplaced one (shade.frag
    // shades it from its triangles, LT_FLAG_FACETED): nothing to compare.
    if (!(out.eval.displace && ctx.asset->displacement.present())) {
        checkNormals(soup, out.normals);
        if (out.normals.against > 0) {  // only where something fails: judge again
            const SurfaceIndex* finer = nullptr;
            if (Status st = finerSurface(ctx, out.depth, out.factor, finer); !st) return st;
            SourceOracle* oracle = nullptr;
            if (ctx.source)  // the GPU's capture too: A1 samples the CPU's only
                if (Status st = ctx.source->atDepth(out.depth, oracle); !st) return st;
            checkNormals(soup, out.normals, finer, [&](size_t v) {
                if (oracle) return normalConfirmed(*oracle, soup, v, out.depth, settings);
                return smoothCorner(ctx, soup, v) && normalConfirmed(*ctx.cage, soup, v, out.depth, settings);
            });
        }
    } else {
        out.normals.skipped = "displaced: its normals are the undisplaced surface's";
    }
    out.normalsSeconds = since(tc);
    tc = Clock::now();
    const ControlTopology& t = ctx.topology;
    if (!t.closed()) {
        out.rays.skipped = t.drawnFaces == 0 ? "the control mesh draws no face"
                           : t.nonManifoldEdges
                               ? "the control mesh has " + std::to_string(t.nonManifoldEdges) + " non-manifold edges"
                               : "the control mesh is open (" + std::to_string(t.boundaryEdges) + " boundary edges)";
    } else {
        say(ctx, "  rays");
        // The displaced surface's distances against the displaced reference, and a
        // depth that does not show every edit against a reference without those.
        const CheckContext::Reference* reference = nullptr;
        const bool displace = out.eval.displace && ctx.asset->displacement.present();
        if (Status st = referenceAtDepth(ctx, out.depth, displace, reference); !st) return st;
        std::string why;
        if (!reference)
            why = ctx.referenceSkipped;
        else if (2 * out.factor > ctx.referenceFactor)
            why = "the reference F=" + number(ctx.referenceFactor) + " is not twice as fine as F=" + number(out.factor);
        if (!why.empty()) reference = nullptr;
        std::unique_ptr<RayScene> scene;
        if (Status st = RayScene::create(mesh, scene); !st) return st;
        double dispSlack = 0;
        const DisplacementMap& map = ctx.asset->displacement;
        if (out.eval.displace && map.present() && !map.values.empty()) {
            auto [lo, hi] = std::minmax_element(map.values.begin(), map.values.end());
            const double dLo = double(map.scale) * (*lo / 65535.0) + map.bias,
                         dHi = double(map.scale) * (*hi / 65535.0) + map.bias;
            dispSlack = std::max(std::fabs(dLo), std::fabs(dHi)) + std::fabs(dHi - dLo);
        }
        // With a reference: the tested mesh by (face, u, v), and a tested triangle's bound
        // from the surface over its (u, v) where larger than its corner normals say,
        // made once when the rays need it (SurfaceIndex).
        RayParameters parameters;
        SurfaceIndex tested;
        std::vector<float> made;
        if (reference) {
            tested.build(soup, mesh);
            made.assign(mesh->triangleCount(), -1.0f);
            parameters = {&tested, &reference->surface, [&](uint32_t i) {
                              if (made[i] < 0) made[i] = float(reference->surface.bound(soup, mesh->soupTriangle[i]));
                              return double(made[i]);
                          }};
        }
        const RayScene* referenceScene = reference ? reference->scene.get() : nullptr;
        if (Status st = castRays(*scene, referenceScene, ctx.diagonal, settings, deriveSeed(seed, 2), out.rays,
                                 dispSlack, reference ? &parameters : nullptr);
            !st)
            return st;
        if (out.rays.ran) out.rays.distanceSkipped = why;
    }
    out.raysSeconds = since(tc);
    out.checkSeconds = since(t0);
    return Status::ok();
}

// Whether case `cpu` would take the process past settings.maxMemoryBytes; then it
// goes into the report unevaluated (L1), for the GPU too.
bool refusedForMemory(CheckContext& ctx, const CheckInputs& in, const EvalSettings& eval, TessellationChecks& cpu,
                      CheckReport& report) {
    size_t vertices = 0, indices = 0;
    ctx.evaluator->count(ctx.asset->positions.data(), eval, vertices, indices);
    cpu.path = "cpu";
    cpu.eval = eval;
    cpu.factor = lodTessFactor(*ctx.asset, ctx.asset->positions.data(), eval);
    cpu.depth = runtimeDepth(*ctx.asset, cpu.factor);
    cpu.triangles = indices ? indices / 3 : vertices / 3;
    cpu.estimatedBytes = checkBytes(vertices, indices, bool(in.gpuCapture));
    const uint64_t limit = ctx.settings->maxMemoryBytes ? ctx.settings->maxMemoryBytes : physicalMemoryBytes();
    const uint64_t resident = residentBytes();
    if (limit == 0 || resident + cpu.estimatedBytes <= limit) return false;
    auto gib = [](uint64_t bytes) {
        char text[32];
        std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1ull << 30));
        return std::string(text);
    };
    cpu.notRun = std::to_string(cpu.triangles) + " triangles need an estimated " + gib(cpu.estimatedBytes) +
                 " beside the " + gib(resident) + " in use, more than the limit of " + gib(limit) +
                 (ctx.settings->maxMemoryBytes ? " (--max-memory-mb)" : " (this machine's memory; --max-memory-mb)") +
                 "; a lower factor checks the same tables";
    say(ctx, "  not run: " + cpu.notRun);
    report.tessellations.push_back(cpu);
    if (in.gpuCapture) {
        TessellationChecks gpu = cpu;
        gpu.path = "gpu";
        report.tessellations.push_back(gpu);
    }
    return true;
}

// One tessellation case: the CPU evaluation, then (--gpu) the GPU capture.
Status runCase(CheckContext& ctx, const CheckInputs& in, const CheckSettings& settings, size_t i, bool displaced,
               CheckReport& report) {
    const size_t n = settings.cases.size();
    const TessCase& c = settings.cases[i];
    const uint64_t seed = deriveSeed(settings.seed, i + 1);
    TessellationChecks cpu;
    cpu.name = tessCaseName(c) + (displaced ? " displaced" : "");
    cpu.tess = c;
    say(ctx, "[" + std::to_string(i + 1) + "/" + std::to_string(n) + "] " + cpu.name + " (cpu)");
    Tessellation soup;
    EvalSettings eval = evalSettingsFor(*in.asset, c, settings);
    eval.displace = displaced;
    if (refusedForMemory(ctx, in, eval, cpu, report)) return Status::ok();
    if (Status st = checkEvaluation(ctx, eval, !displaced, seed, cpu, &soup); !st) return st;
    report.tessellations.push_back(cpu);
    if (!in.gpuCapture) return Status::ok();
    TessellationChecks gpu;
    gpu.name = cpu.name;
    gpu.tess = c;
    gpu.path = "gpu";
    gpu.eval = cpu.eval;
    gpu.factor = cpu.factor;
    gpu.depth = cpu.depth;
    say(ctx, "[" + std::to_string(i + 1) + "/" + std::to_string(n) + "] " + cpu.name + " (gpu)");
    Tessellation captured;
    const auto tg = Clock::now();
    Status st = in.gpuCapture(cpu.eval, captured);
    gpu.evaluateSeconds = since(tg);
    if (!st) {
        gpu.error = st.message;
        report.tessellations.push_back(gpu);
        return Status::ok();
    }
    gpu.compared = true;
    gpu.cpuVertices = soup.vertexCount();
    const size_t common = std::min(soup.vertexCount(), captured.vertexCount());
    for (size_t v = 0; v < common; ++v) {
        const bool pos = std::memcmp(&soup.positions[3 * v], &captured.positions[3 * v], 12) == 0;
        const bool nrm = std::memcmp(&soup.normals[3 * v], &captured.normals[3 * v], 12) == 0;
        const bool param =
            soup.face[v] == captured.face[v] && std::memcmp(&soup.uv[2 * v], &captured.uv[2 * v], 8) == 0;
        gpu.equalPositions += pos;
        gpu.equalNormals += nrm;
        gpu.equalVertices += pos && nrm && param;
    }
    soup = Tessellation{};
    if (st = checkTessellation(ctx, captured, false, seed, gpu); !st) return st;
    report.tessellations.push_back(gpu);
    return Status::ok();
}

Status runChecks(const CheckInputs& in, const CheckSettings& settings, CheckReport& report) {
    const auto t0 = Clock::now();
    CheckContext ctx;
    ctx.progress = in.progress;
    if (Status st = prepareChecks(*in.asset, in.source, settings, ctx); !st) return st;
    report.topology = ctx.topology;
    report.referenceFactor = ctx.referenceFactor;
    report.referenceSkipped = ctx.referenceSkipped;
    report.referenceSeconds = ctx.referenceSeconds;
    report.gpu = bool(in.gpuCapture);
    if (in.source && in.source->fine.built()) {
        report.sourceEdits = in.source->fine.editCount();
        report.sourceEditLevel = in.source->fine.editLevel();
        say(ctx, "limit stencils against OpenSubdiv's refinement");
        if (Status st = checkStencils(*in.asset, in.source->mesh, report.stencils); !st) return st;
        report.stencilsChecked = true;
    }
    const size_t n = settings.cases.size();
    // Every case undisplaced (accuracy against the source applies), then displaced
    // when the asset has a map (the oracle knows only the undisplaced surface).
    for (bool displaced : {false, true}) {
        if (displaced && !in.asset->displacement.present()) break;
        for (size_t i = 0; i < n; ++i)
            if (Status st = runCase(ctx, in, settings, i, displaced, report); !st) return st;
    }
    report.seconds = since(t0);
    addFindings(settings, report);
    return Status::ok();
}

void addTessellationFindings(const CheckSettings& settings, const TessellationChecks& t, std::vector<Finding>& f) {
    auto add = [&](const char* id, const char* severity, const std::string& text) {
        f.push_back({id, severity, text});
    };
    const std::string at = t.name + " (" + t.path + "): ";
    if (!t.notRun.empty()) {
        add("L1", "error", at + "not run: " + t.notRun);
        return;
    }
    if (!t.error.empty()) {
        add("G1", "error", at + "capture failed: " + t.error);
        return;
    }
    if (t.compared && t.equalVertices != t.cpuVertices)
        add("G2", "info",
            at + std::to_string(t.equalVertices) + " of " + std::to_string(t.cpuVertices) +
                " CPU vertices bitwise equal in the GPU capture");
    const AccuracyResult& a = t.accuracy;
    if (a.positionFailures + a.normalFailures + a.noLimit > 0)
        add("A1", "error",
            at + std::to_string(a.positionFailures) + " positions and " + std::to_string(a.normalFailures) +
                " normals of " + std::to_string(a.sampled) + " vertices (all " + std::to_string(a.corners) +
                " at base corners, a sample of the rest) off OpenSubdiv's limit surface" +
                referenceEdits(a.referenceEdits, a.referenceEditLevel) + " (tolerances " +
                number(settings.positionTolerance) + " of the diagonal, 1 - cos " + number(settings.normalTolerance) +
                "); " + std::to_string(a.noLimit) + " on faces without one; first: " + a.firstFailure +
                " (an asset baked with --crease-angle or --hard-edges needs the same option here)");
    const WeldResult& w = t.weld;
    if (w.nonFiniteVertices) add("W5", "error", at + std::to_string(w.nonFiniteVertices) + " vertices are not finite");
    if (w.crackEdges)
        add("W1", "error",
            at + std::to_string(w.crackEdges) + " open edges off the control mesh's boundary (cracks), " +
                std::to_string(w.tJunctions) + " of them T-junctions, after welding " + std::to_string(w.vertices) +
                " vertices by exact bits into " + std::to_string(w.weldedVertices) + "; first: " + w.firstFailure);
    if (w.unexpectedNonManifoldEdges)
        add("W2", "error",
            at + std::to_string(w.unexpectedNonManifoldEdges) +
                " edges used by three or more triangles off the control mesh's non-manifold edges; "
                "first: " +
                w.firstFailure);
    if (w.contactEdges)
        add("W6", "warning",
            at + std::to_string(w.contactEdges) +
                " edges used three or more times where control faces fold back onto each other (a doubled "
                "triangle) or the limit surface folds: the surface touches itself within float resolution");
    if (w.misorientedEdges)
        add("W3", "error",
            at + std::to_string(w.misorientedEdges) +
                " edges used twice in the same direction; first: " + w.firstFailure);
    const NormalResult& nr = t.normals;
    if (!nr.pass())
        add("N1", "error",
            at + std::to_string(nr.against) + " vertex normals point behind their triangle and " +
                std::to_string(nr.zero) + " are zero or not finite, of " + std::to_string(nr.judged) +
                " triangles judged; first: " + nr.firstFailure);
    const RayResult& r = t.rays;
    if (!r.ran) {
        add("R3", "info", at + "rays skipped: " + r.skipped);
        return;
    }
    // A first hit on a front face: the surface overlaps itself (a displacement too
    // large for a thin part, say) or is inside out, so "inside" is ambiguous and
    // an escaped ray need not be a crack.
    const std::string overlap = std::to_string(r.frontHits) + " of " + std::to_string(r.rays) +
                                " rays first hit a front face: the surface overlaps itself or is inside out";
    if (r.escaped)
        add("R1", "error",
            at + std::to_string(r.escaped) + " of " + std::to_string(r.rays) + " rays from interior points escaped" +
                (r.frontHits && w.crackEdges == 0 ? " (no open edge: " + overlap + ", so an origin may be outside)"
                                                  : std::string()));
    else if (r.frontHits)
        add("R5", "info", at + overlap);
    if (r.distanceFailures)
        add("R2", "error",
            at + std::to_string(r.distanceFailures) + " of " + std::to_string(r.compared) +
                " hit distances disagree with the reference beyond the chord bounds (worst " +
                number(r.maxToleranceRatio) + "x the tolerance)");
    if (!r.distanceSkipped.empty()) add("R4", "info", at + "hit distances not compared: " + r.distanceSkipped);
}

void addFindings(const CheckSettings& settings, CheckReport& report) {
    std::vector<Finding>& f = report.findings;
    f.clear();
    auto add = [&](const char* id, const char* severity, const std::string& text) {
        f.push_back({id, severity, text});
    };
    if (!report.structureValid) {
        add("S1", "error", report.structureMessage);
        return;
    }
    if (!report.sourceMismatch.empty())
        add("M1", "error", "--source " + report.sourceName + ": " + report.sourceMismatch);
    for (const std::string& d : report.sceneDifferences)
        add("M2", "error", "--source " + report.sourceName + ": the scene is not the source's: " + d);
    if (report.sourceEdits > 0)
        add("A2", "info",
            "--source " + report.sourceName + ": the accuracy reference includes the source's " +
                std::to_string(report.sourceEdits) + " hierarchical edit" + (report.sourceEdits == 1 ? "" : "s") +
                " down to level " + std::to_string(report.sourceEditLevel) +
                " (OpenSubdiv refined uniformly to that level, the edits applied level by level, then "
                "the limit surface of that level); at a runtime depth d below " +
                std::to_string(report.sourceEditLevel) + " only the edits of levels <= d, as the runtime applies them");
    if (report.stencilsChecked && !report.stencils.pass())
        add("A3", "error",
            "--source " + report.sourceName + ": " + std::to_string(report.stencils.failures) + " of " +
                std::to_string(report.stencils.checked) +
                " limit stencils' positions off OpenSubdiv's limit beyond their weights' float "
                "rounding; first: " +
                report.stencils.firstFailure);
    const ValidatorResult& v = report.validator;
    const ValidatorResult& source = report.sourceValidator;
    const bool inherited =
        source.state == ValidatorResult::Ran && v.errors <= source.errors && v.warnings <= source.warnings;
    if (v.state == ValidatorResult::Ran && !v.pass())
        add("V1", inherited ? "info" : "error",
            "Khronos glTF-Validator: " + std::to_string(v.errors) + " errors, " + std::to_string(v.warnings) +
                " warnings" + (v.messages.empty() ? "" : " (first: " + v.messages.front() + ")") +
                (source.state == ValidatorResult::Ran ? "; the source has " + std::to_string(source.errors) +
                                                            " errors, " + std::to_string(source.warnings) + " warnings"
                                                      : ""));
    if (v.state == ValidatorResult::Unavailable)
        add("V2", settings.strictValidator ? "error" : "warning", "Khronos glTF-Validator not available: " + v.detail);
    for (const TessellationChecks& t : report.tessellations) addTessellationFindings(settings, t, f);
}

int exitCode(const CheckReport& report) {
    if (!report.structureValid) return 2;
    for (const Finding& f : report.findings)
        if (f.severity == "error") return 3;
    return 0;
}

}  // namespace lt

// Running the checks of every tessellation case (looptess/tools/check.h runChecks):
// the case's settings, the references, then each case on the CPU and (--gpu) the GPU.
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

using Clock = std::chrono::steady_clock;

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
        ctx.say(std::string("reference") + (displace ? " (displaced): " : ": ") + std::to_string(soup.triangleCount()) +
                " triangles, welding" + (scene ? ", building the ray scene" : ""));
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

}  // namespace

Status referenceAtDepth(CheckContext& ctx, uint32_t depth, bool displace, const CheckContext::Reference*& out) {
    out = displace ? ctx.displacedReference.get() : ctx.reference.get();
    if (!out || ctx.asset->editDepth() <= depth) return Status::ok();
    auto& slot = ctx.depthReferences[{depth, displace}];
    if (!slot) {
        ctx.say("reference without the edits below depth " + std::to_string(depth));
        if (Status st = buildReference(ctx, shownAtDepth(*ctx.asset, depth), displace, slot); !st) return st;
    }
    out = slot.get();
    return Status::ok();
}

Status finerSurface(CheckContext& ctx, uint32_t depth, float factor, const SurfaceIndex*& out) {
    out = nullptr;
    if (2 * factor > ctx.referenceFactor) return Status::ok();
    const CheckContext::Reference* reference = nullptr;
    if (Status st = referenceAtDepth(ctx, depth, false, reference); !st) return st;
    if (!reference) {
        auto& slot = ctx.normalReferences[depth];
        if (!slot) {
            ctx.say("  normals: a finer surface to judge against");
            if (Status st = buildReference(ctx, shownAtDepth(*ctx.asset, depth), false, slot, false); !st) return st;
        }
        reference = slot.get();
    }
    out = &reference->surface;
    return Status::ok();
}

// Only the smooth rule: a vertex whose 1-ring winds twice round it (a fan folded over
// at a pinch) has a limit normal its triangles approach only 0.8 times closer a
// level: at F = 16 all eleven stood 65 to 100 degrees from it.
bool smoothCorner(CheckContext& ctx, const Tessellation& soup, size_t v) {
    const int corner = baseCorner(soup.uv[2 * v], soup.uv[2 * v + 1]);
    if (corner < 0) return false;
    if (!ctx.cageTried) {
        ctx.cageTried = true;
        ctx.say("  normals: OpenSubdiv's limit of the asset's own control mesh");
        ctx.cage = std::make_unique<SourceOracle>();
        if (!cageOracle(*ctx.asset, *ctx.cage, ctx.smoothVertex)) ctx.cage.reset();
    }
    return ctx.cage && ctx.smoothVertex[ctx.asset->faces[3 * size_t(soup.face[v]) + size_t(corner)]];
}

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
    ctx.say("reference: evaluating F=" + number(f) + " equal");
    for (bool displace : {false, true}) {
        if (displace && !asset.displacement.present()) break;
        const Status st = buildReference(ctx, asset, displace, displace ? ctx.displacedReference : ctx.reference);
        if (!st) return st;
    }
    ctx.referenceSeconds = secondsSince(t0);
    return Status::ok();
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
    ctx.say("[" + std::to_string(i + 1) + "/" + std::to_string(n) + "] " + cpu.name + " (cpu)");
    Tessellation soup;
    EvalSettings eval = evalSettingsFor(*in.asset, c, settings);
    eval.displace = displaced;
    std::vector<FacePiece> pieces;
    GpuPlan plan;
    if (refusedForMemory(ctx, in, eval, cpu, report, pieces, plan)) return Status::ok();
    const bool compare = in.gpuCapture && !plan.sessions && plan.notRun.empty();  // keep the soup for it
    if (Status st = checkEvaluation(ctx, eval, !displaced, seed, cpu, compare ? &soup : nullptr, pieces); !st)
        return st;
    report.tessellations.push_back(cpu);
    if (!in.gpuCapture) return Status::ok();
    TessellationChecks gpu;
    gpu.name = cpu.name;
    gpu.tess = c;
    gpu.path = "gpu";
    gpu.eval = cpu.eval;
    gpu.factor = cpu.factor;
    gpu.depth = cpu.depth;
    if (!plan.notRun.empty()) {
        gpu.triangles = cpu.triangles;
        gpu.notRun = plan.notRun;
        ctx.say("  gpu not run: " + plan.notRun);
        report.tessellations.push_back(gpu);
        return Status::ok();
    }
    ctx.say("[" + std::to_string(i + 1) + "/" + std::to_string(n) + "] " + cpu.name + " (gpu)");
    if (plan.sessions) {
        gpu.triangles = cpu.triangles;
        if (Status st = checkCaptureSessions(ctx, in, seed, gpu); !st) return st;
        report.tessellations.push_back(gpu);
        return Status::ok();
    }
    Tessellation captured;
    const auto tg = Clock::now();
    Status st = in.gpuCapture(cpu.eval, captured);
    gpu.evaluateSeconds = secondsSince(tg);
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
        ctx.say("limit stencils against OpenSubdiv's refinement");
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
    report.seconds = secondsSince(t0);
    addFindings(settings, report);
    return Status::ok();
}

}  // namespace lt

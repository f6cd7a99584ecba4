// The checks of one tessellation, whole or in pieces of base faces (check_internal.h:
// checkEvaluation, checkTessellation): accuracy, weld, normals, then the rays.
#include "check_internal.h"

#include "random.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>

namespace lt {

using Clock = std::chrono::steady_clock;

namespace {

// Adds piece result `p` to `into` (the results so far of a tessellation checked in
// pieces); `where` names the piece in a first failure ("" for the whole).
void merge(AccuracyResult& into, const AccuracyResult& p, const std::string& where) {
    into.ran = into.ran || p.ran;
    into.sampled += p.sampled, into.corners += p.corners;
    into.positionFailures += p.positionFailures, into.normalFailures += p.normalFailures;
    into.noLimit += p.noLimit, into.normalsSkipped += p.normalsSkipped;
    into.oracleLimited += p.oracleLimited, into.floatLimited += p.floatLimited;
    into.maxPositionError = std::max(into.maxPositionError, p.maxPositionError);
    into.maxNormalError = std::max(into.maxNormalError, p.maxNormalError);
    if (into.firstFailure.empty() && !p.firstFailure.empty()) into.firstFailure = where + p.firstFailure;
    into.referenceEdits = p.referenceEdits, into.referenceEditLevel = p.referenceEditLevel;
}
void merge(NormalResult& into, const NormalResult& p, const std::string& where) {
    into.judged += p.judged, into.unjudged += p.unjudged, into.folded += p.folded;
    into.refined += p.refined, into.confirmed += p.confirmed, into.against += p.against, into.zero += p.zero;
    if (into.firstFailure.empty() && !p.firstFailure.empty()) into.firstFailure = where + p.firstFailure;
}

// The checks of one tessellation given in pieces of whole base faces, in order (one
// piece: the whole soup): accuracy, normals and the weld piece by piece, then the
// weld's edge count and the rays over the welded whole. Several pieces hold only a
// piece's soup at a time; the rays then compare no hit distances (their (u, v) index
// needs the whole soup).
class PieceChecks {
public:
    // `vertices`: the pieces' in all; `pieces`: how many will be added (0: not known).
    PieceChecks(CheckContext& ctx, bool accuracy, uint64_t seed, uint64_t vertices, size_t pieces,
                TessellationChecks& out)
        : ctx_(ctx),
          accuracy_(accuracy),
          seed_(seed),
          vertices_(vertices),
          pieces_(pieces),
          out_(out),
          mesh_(std::make_shared<WeldedMesh>()),
          weld_(&ctx.topology, mesh_.get(), out.triangles, pieces != 1) {
        out.triangles = 0;
        out.accuracy = {}, out.weld = {}, out.normals = {}, out.rays = {};
        out.checkSeconds = out.accuracySeconds = out.weldSeconds = out.normalsSeconds = out.raysSeconds = 0;
    }
    // `where` names the piece in a first failure ("" for the whole).
    Status add(const Tessellation& soup, const std::string& where);
    // After the last piece: whether every piece is to be given again (addAgain), the
    // same and in the same order, before finish (PieceWeld::needsAgain).
    bool needsAgain();
    void addAgain(const Tessellation& soup);
    // `whole`: the soup when it was one piece, else null.
    Status finish(const Tessellation* whole);

private:
    CheckContext& ctx_;
    bool accuracy_;
    uint64_t seed_, vertices_;
    size_t pieces_, added_ = 0;
    TessellationChecks& out_;
    std::shared_ptr<WeldedMesh> mesh_;
    PieceWeld weld_;
};

Status PieceChecks::add(const Tessellation& soup, const std::string& where) {
    const auto t0 = Clock::now();
    CheckContext& ctx = ctx_;
    TessellationChecks& out = out_;
    const CheckSettings& settings = *ctx.settings;
    const size_t piece = added_++;
    out.triangles += soup.triangleCount();
    if (accuracy_ && ctx.source) {
        SourceOracle* oracle = nullptr;  // the edits the runtime applies at this depth
        if (Status st = ctx.source->atDepth(out.depth, oracle); !st) return st;
        if (piece == 0)
            ctx.say("  accuracy against OpenSubdiv" +
                    referenceEdits(oracle->fine.editCount(), oracle->fine.editLevel()));
        oracle->assetDepth = ctx.asset->maxDepth();
        CheckSettings share = settings;  // the piece's share of the samples, every base corner
        if (pieces_ > 1)
            share.accuracySamples =
                (settings.accuracySamples * soup.vertexCount() + vertices_ - 1) / std::max<uint64_t>(1, vertices_);
        const uint64_t seed = piece == 0 ? deriveSeed(seed_, 1) : deriveSeed(deriveSeed(seed_, 1), piece);
        AccuracyResult a;
        checkAccuracy(*oracle, soup, out.depth, ctx.diagonal, share, seed, a);
        merge(out.accuracy, a, where);
    }
    out.accuracySeconds += secondsSince(t0);
    auto tc = Clock::now();
    if (pieces_ == 1) ctx.say("  weld (" + std::to_string(soup.triangleCount()) + " triangles)");
    weld_.add(soup);
    out.weldSeconds += secondsSince(tc);
    tc = Clock::now();
    // A displaced surface is drawn with the normals of the undisplaced one (shade.frag
    // shades it from its triangles, LT_FLAG_FACETED): nothing to compare.
    if (!(out.eval.displace && ctx.asset->displacement.present())) {
        NormalResult normals;
        checkNormals(soup, normals);
        if (normals.against > 0) {  // only where something fails: judge again
            const SurfaceIndex* finer = nullptr;
            if (Status st = finerSurface(ctx, out.depth, out.factor, finer); !st) return st;
            SourceOracle* oracle = nullptr;
            if (ctx.source)  // the GPU's capture too: A1 samples the CPU's only
                if (Status st = ctx.source->atDepth(out.depth, oracle); !st) return st;
            normals = NormalResult{};
            checkNormals(soup, normals, finer, [&](size_t v) {
                if (oracle) return normalConfirmed(*oracle, soup, v, out.depth, settings);
                return smoothCorner(ctx, soup, v) && normalConfirmed(*ctx.cage, soup, v, out.depth, settings);
            });
        }
        merge(out.normals, normals, where);
    } else {
        out.normals.skipped = "displaced: its normals are the undisplaced surface's";
    }
    out.normalsSeconds += secondsSince(tc);
    out.checkSeconds += secondsSince(t0);
    return Status::ok();
}

bool PieceChecks::needsAgain() {
    const auto t0 = Clock::now();
    const bool again = weld_.needsAgain();
    out_.weldSeconds += secondsSince(t0);
    out_.checkSeconds += secondsSince(t0);
    if (again) ctx_.say("  an edge of one piece is used in another: the pieces again, for its uses");
    return again;
}

void PieceChecks::addAgain(const Tessellation& soup) {
    const auto t0 = Clock::now();
    weld_.addAgain(soup);
    out_.weldSeconds += secondsSince(t0);
    out_.checkSeconds += secondsSince(t0);
}

Status PieceChecks::finish(const Tessellation* whole) {
    const auto t0 = Clock::now();
    CheckContext& ctx = ctx_;
    TessellationChecks& out = out_;
    weld_.finish(out.weld);
    out.weldSeconds += secondsSince(t0);
    auto tc = Clock::now();
    const std::shared_ptr<WeldedMesh>& mesh = mesh_;
    const ControlTopology& t = ctx.topology;
    if (!t.closed()) {
        out.rays.skipped = t.drawnFaces == 0 ? "the control mesh draws no face"
                           : t.nonManifoldEdges
                               ? "the control mesh has " + std::to_string(t.nonManifoldEdges) + " non-manifold edges"
                               : "the control mesh is open (" + std::to_string(t.boundaryEdges) + " boundary edges)";
    } else {
        ctx.say("  rays");
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
        else if (!whole)
            why = "checked in " + std::to_string(added_) + " pieces, without the whole soup";
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
            tested.build(*whole, mesh);
            made.assign(mesh->triangleCount(), -1.0f);
            parameters = {&tested, &reference->surface, [&](uint32_t i) {
                              if (made[i] < 0) made[i] = float(reference->surface.bound(*whole, mesh->soupTriangle[i]));
                              return double(made[i]);
                          }};
        }
        const RayScene* referenceScene = reference ? reference->scene.get() : nullptr;
        if (Status st = castRays(*scene, referenceScene, ctx.diagonal, *ctx.settings, deriveSeed(seed_, 2), out.rays,
                                 dispSlack, reference ? &parameters : nullptr);
            !st)
            return st;
        if (out.rays.ran) out.rays.distanceSkipped = why;
    }
    out.raysSeconds = secondsSince(tc);
    out.checkSeconds += secondsSince(t0);
    return Status::ok();
}

}  // namespace

Status checkEvaluation(CheckContext& ctx, const EvalSettings& eval, bool accuracy, uint64_t seed,
                       TessellationChecks& out, Tessellation* keep, const std::vector<FacePiece>& pieces) {
    out.eval = eval;
    out.path = "cpu";
    out.factor = lodTessFactor(*ctx.asset, ctx.asset->positions.data(), eval);
    out.depth = runtimeDepth(*ctx.asset, out.factor);
    assert(ctx.evaluator && "prepareChecks first");
    if (pieces.size() <= 1) {
        const auto t0 = Clock::now();
        Tessellation local;
        Tessellation& soup = keep ? *keep : local;
        ctx.evaluator->evaluate(ctx.asset->positions.data(), eval, soup);
        out.evaluateSeconds = secondsSince(t0);
        return checkTessellation(ctx, soup, accuracy, seed, out);
    }
    uint64_t vertices = 0;
    out.triangles = 0, out.evaluateSeconds = 0;
    for (const FacePiece& p : pieces) vertices += p.vertices, out.triangles += p.triangles;
    out.pieces = uint32_t(pieces.size());
    PieceChecks checks(ctx, accuracy, seed, vertices, pieces.size(), out);
    Tessellation soup;  // each piece's, in the allocation of the last
    auto evaluate = [&](const FacePiece& p) {
        EvalSettings e = eval;
        e.firstFace = p.first, e.faceCount = p.count;
        const auto t0 = Clock::now();
        ctx.evaluator->evaluate(ctx.asset->positions.data(), e, soup);
        out.evaluateSeconds += secondsSince(t0);
    };
    for (size_t k = 0; k < pieces.size(); ++k) {
        const FacePiece& p = pieces[k];
        const std::string faces = "faces " + std::to_string(p.first) + " to " + std::to_string(p.first + p.count - 1);
        ctx.say("  piece " + std::to_string(k + 1) + " of " + std::to_string(pieces.size()) + ", " + faces + " (" +
                std::to_string(p.triangles) + " triangles)");
        evaluate(p);
        if (Status st = checks.add(soup, "in the piece of " + faces + ": "); !st) return st;
    }
    if (checks.needsAgain())
        for (const FacePiece& p : pieces) evaluate(p), checks.addAgain(soup);
    soup = Tessellation{};
    ctx.say("  weld and rays over the pieces");
    return checks.finish(nullptr);
}

Status checkCaptureSessions(CheckContext& ctx, const CheckInputs& in, uint64_t seed, TessellationChecks& gpu) {
    PieceChecks checks(ctx, false, seed, 3 * gpu.triangles, 0, gpu);
    uint32_t sessions = 0;
    const auto t0 = Clock::now();
    Status checked = Status::ok();  // a check's failure is the run's; the capture's is G1
    const uint64_t triangles = ctx.settings->pieceTriangles;
    const Status captured = in.gpuCaptureSessions(gpu.eval, triangles, [&](const Tessellation& session) {
        ctx.say("  capture session " + std::to_string(++sessions) + " (" + std::to_string(session.triangleCount()) +
                " triangles)");
        checked = checks.add(session, "in capture session " + std::to_string(sessions) + ": ");
        return checked;
    });
    gpu.pieces = sessions;
    if (!checked) return checked;
    Status again = captured;
    if (captured && checks.needsAgain())  // the same sessions: the capture is deterministic
        again = in.gpuCaptureSessions(gpu.eval, triangles, [&](const Tessellation& session) {
            checks.addAgain(session);
            return Status::ok();
        });
    gpu.evaluateSeconds = secondsSince(t0) - gpu.checkSeconds;
    if (!again) {
        gpu.error = again.message;
        return Status::ok();
    }
    return checks.finish(nullptr);
}

Status checkTessellation(CheckContext& ctx, const Tessellation& soup, bool accuracy, uint64_t seed,
                         TessellationChecks& out) {
    out.triangles = soup.triangleCount();
    PieceChecks checks(ctx, accuracy, seed, soup.vertexCount(), 1, out);
    if (Status st = checks.add(soup, ""); !st) return st;
    return checks.finish(&soup);
}

}  // namespace lt

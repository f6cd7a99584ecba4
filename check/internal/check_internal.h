// Private to looptess_check and its tests (looptess_check_internal): the checks of
// check.h one by one -- accuracy, weld, normals, rays, with the surface index and the
// Embree scene they use -- and the per-asset context runChecks runs them in. What
// each check judges is documented with its result in check.h.
#pragma once

#include "looptess/tools/check.h"

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace lt {

// The evaluation settings of `c` on `asset` (Screen: CheckSettings' screen camera,
// its pixelsPerEdge chosen so that lodTessFactor is c.factor where 2^maxDepth allows).
EvalSettings evalSettingsFor(const Asset& asset, const TessCase& c, const CheckSettings& settings);

// checkStructure's consistency rules C1..C6 (check.h) for an asset that passed
// validateAsset; the first rule broken, named after `name`.
Status checkConsistency(const Asset& asset, const std::string& name);

// The drawn faces and edge kinds of `asset`'s control mesh (ControlTopology).
ControlTopology analyzeControlMesh(const Asset& asset);

// The limit-stencil check (check.h's StencilResult, A3) of `asset` against `source`,
// whose control mesh is the asset's; skipped for assets with edits. The Status of
// OpenSubdiv's refinement of `source` when that fails.
Status checkStencils(const Asset& asset, const InputMesh& source, StencilResult& out);

// The accuracy check (check.h's AccuracyResult) of `soup`, a tessellation of runtime
// depth `depth` whose control mesh has bounding-box diagonal `diagonal`: every vertex
// at a base corner (baseCorner) and one vertex in each of settings.accuracySamples
// equal strata, the position in the stratum drawn from `seed`.
void checkAccuracy(SourceOracle& oracle, const Tessellation& soup, uint32_t depth, double diagonal,
                   const CheckSettings& settings, uint64_t seed, AccuracyResult& out);
// Which corner of its base face a point at (u, v) is: 0 at (0, 0), 1 at (1, 0), 2
// at (0, 1); -1 elsewhere.
inline int baseCorner(float u, float v) {
    return u == 0 && v == 0 ? 0 : u == 1 && v == 0 ? 1 : u == 0 && v == 1 ? 2 : -1;
}
// Whether emitted vertex `vertex`'s normal is OpenSubdiv's as checkAccuracy judges
// it (within settings.normalTolerance and its allowances; false where it cannot say).
bool normalConfirmed(SourceOracle& oracle, const Tessellation& soup, size_t vertex, uint32_t depth,
                     const CheckSettings& settings);
// Without --source: an oracle of `asset`'s own control mesh (its positions, faces,
// boundary rule and crease method; no creases, which the asset does not keep), and
// per control vertex whether it is on the smooth rule at level 0 (a vertex point of
// level 1 without an explicit mask). At such a vertex the limit depends on its
// 1-ring alone, so there the oracle's limit is the baked surface's, creases
// elsewhere or not. False for an asset with edits or one OpenSubdiv refuses.
bool cageOracle(const Asset& asset, SourceOracle& oracle, std::vector<char>& smoothVertex);

// A tessellation welded by the exact bits of its positions (-0 and +0 are one key),
// ready for rays: vertices (3 floats each and one float of padding at the end, as
// Embree's shared buffers need), non-degenerate triangles, and per triangle a bound
// on its distance from the surface it samples: longest edge x largest angle between
// its corner normals or a corner normal and its plane / 4 (twice the sagitta of a
// circular arc turning by that angle).
struct WeldedMesh {
    std::vector<float> positions;        // 3 per vertex + 1 padding float
    std::vector<uint32_t> triangles;     // 3 per triangle
    std::vector<float> chordBound;       // per triangle, object units
    std::vector<uint32_t> soupTriangle;  // per triangle, the soup triangle it welds
    size_t vertexCount() const { return positions.size() / 3; }
    size_t triangleCount() const { return triangles.size() / 3; }
};

// (p1 - p0) x (p2 - p0) of soup triangle t, from the float corners in double
// (unnormalized: its length is twice the area).
void geometricNormal(const Tessellation& soup, size_t t, double g[3]);

// The watertightness check (check.h's WeldResult) of `soup` over `topology`;
// `welded` (optional) receives the welded mesh.
void weldTessellation(const Tessellation& soup, const ControlTopology& topology, WeldResult& out,
                      WeldedMesh* welded = nullptr);
// weldTessellation over a tessellation given in pieces (the evaluations of ranges of
// whole base faces, EvalSettings::firstFace; capture sessions), in order: the
// vertices welded across pieces, so that a piece's memory is its own and the welded
// mesh's. An edge whose uses in its piece are one well-oriented pair is settled
// there; every other edge's uses (open, misoriented, three or more) are kept and
// counted in finish with the other pieces'; an edge settled in one piece and used in
// another is found after the last (needsAgain) and its uses counted in a second pass
// over the pieces.
class PieceWeld {
public:
    // `topology` null: the weld alone (weldMesh). `mesh` (optional) receives the welded
    // mesh, its soupTriangle numbering the pieces' triangles in order. `triangles`:
    // the pieces' in all, when known (0: not), so that the mesh is allocated once.
    // `pieces`: more than one will be added (their settled edges' keys are kept, 8
    // bytes an edge, for needsAgain).
    PieceWeld(const ControlTopology* topology, WeldedMesh* mesh, uint64_t triangles = 0, bool pieces = false);
    ~PieceWeld();
    void add(const Tessellation& piece);
    // After the last piece (with `pieces`): whether an edge one piece settled is used
    // in another too (a surface touching itself across pieces: an edge of three or
    // four uses, a pair in one piece). Then every piece is to be given again, the
    // same and in the same order (addAgain), before finish: those edges' uses are
    // counted as in one soup, so that pieces give weldTessellation's result.
    bool needsAgain();
    void addAgain(const Tessellation& piece);
    // The result over the pieces added; releases the weld's tables.
    void finish(WeldResult& out);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};
// The weld alone (for the ray reference): no edge counts.
void weldMesh(const Tessellation& soup, WeldedMesh& out);

class SurfaceIndex;
// The normals check (check.h's NormalResult) of `soup`. `finer` (optional): the
// finer surface a normal behind its triangle is judged again against; `confirmed`
// (optional): whether OpenSubdiv's normal at a vertex is the same (normalConfirmed).
void checkNormals(const Tessellation& soup, NormalResult& out, const SurfaceIndex* finer = nullptr,
                  const std::function<bool(size_t vertex)>& confirmed = {});

// A tessellation by base face and (u, v). The reference's gives a bound on how far a
// triangle of another tessellation of the same surface lies from that surface, which
// trusts only the triangle's corner parameters, never its positions. Let T be a triangle whose
// corners c0, c1, c2 are (u, v) on one base face f, R the reference's piecewise-linear
// surface on f and r_f the largest chord bound of the reference's triangles on f
// (so |S - R| <= r_f for the surface S). Then over T
//     |S(x) - sum_k b_k(x) S(c_k)| <= D + 2 r_f,   D = max_x |R(x) - sum_k b_k(x) R(c_k)|,
// b_k(x) the barycentrics of x in T. R - sum b_k R(c_k) is linear on each piece of T cut
// by the reference's triangles, so D is exact: the largest deviation over the corners
// of those pieces (each reference triangle clipped to T). A triangle whose corners are
// on S thus lies within D + 2 r_f of S, however much S bulges between corners whose
// normals agree (where the bound from its corner normals sees a flat triangle); a
// triangle whose positions are wrong gains no bound from them.
class SurfaceIndex {
public:
    // `soup` is the reference's evaluation, `mesh` its weldMesh (kept).
    void build(const Tessellation& soup, std::shared_ptr<const WeldedMesh> mesh);
    // D + 2 r_f for triangle t of `soup` (any tessellation of the reference's asset,
    // displaced alike); 0 when its corners lie on different faces, are not finite,
    // span no area, or fall outside the reference.
    double bound(const Tessellation& soup, size_t t) const;
    // The (face, u, v) of the point at barycentrics (b1, b2) of mesh triangle t (as
    // Embree reports a hit: p = (1 - b1 - b2) p0 + b1 p1 + b2 p2); false when unknown.
    bool parameters(uint32_t t, double b1, double b2, uint32_t& face, double uv[2]) const;
    // The mesh triangle over (face, u, v) and the mesh's point there; false when none is.
    bool pointAt(uint32_t face, const double uv[2], uint32_t& triangle, double p[3]) const;
    // (p1 - p0) x (p2 - p0) of the mesh triangle over (face, u, v); false when none is.
    bool normalAt(uint32_t face, const double uv[2], double g[3]) const;

private:
    bool triangleUv(uint32_t t, double q[6]) const;
    template <class Visit>
    void forEachNear(uint32_t face, const double lo[2], const double hi[2], Visit&& visit) const;
    void interpolate(uint32_t t, const double g[3], double p[3]) const;
    std::shared_ptr<const WeldedMesh> mesh_;
    std::vector<uint32_t> face_;       // per mesh triangle: its base face
    std::vector<float> uv_;            // per mesh triangle: its corners' (u, v), 6 floats
    std::vector<float> faceChord_;     // r_f per base face
    uint32_t grid_ = 1;                // cells per side of a face's (u, v) square
    int reach_ = 0;                    // cells a triangle's (u, v) box spans, at most
    std::vector<uint32_t> cellStart_;  // cell (face, y, x): its listings cellStart_[c] ..
    std::vector<uint32_t> listed_;     // per listing: the mesh triangle
};

// An Embree 3 scene (RTC_SCENE_FLAG_ROBUST: watertight between triangles that share
// bit-identical vertices) over a welded mesh, placed as is. Keeps the mesh alive.
class RayScene {
public:
    // Internal when Embree fails (its error code in the message).
    static Status create(std::shared_ptr<const WeldedMesh> mesh, std::unique_ptr<RayScene>& out);
    ~RayScene();
    const WeldedMesh& mesh() const;
    struct Impl;
    Impl& impl() const { return *impl_; }

private:
    explicit RayScene(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

// The ray check (check.h's RayResult) of `test` against `reference` (may be null:
// no distance check), `seed` picking origins and directions.
// `displacementSlack` (object units) widens every triangle's bound on a displaced
// surface, whose shading normals (the chord bound's) are the undisplaced ones and
// whose coarse triangles interpolate displaced corners: checkTessellation passes
// the map's largest |displacement| plus its range (0 undisplaced).
// `parameters` (optional; checkTessellation's) tells the distance check more:
// - testBound raises a tested triangle's bound where larger (SurfaceIndex::bound); it
//   is asked only for rays beyond the tolerance of the chord bounds, and the worst
//   ratio reported is then against the raised tolerance;
// - with both indexes, a fold ray's hit points are compared with the other surface at
//   their own (face, u, v): the tested point within b + (the bound of the reference
//   triangle there) + 2 s of the reference's point, the reference's within b' + (the
//   tested triangle's there) + 2 s. Without them, the nearest triangles stand in.
using TriangleBound = std::function<double(uint32_t triangle)>;
struct RayParameters {
    const SurfaceIndex* test = nullptr;       // the tested mesh by (face, u, v)
    const SurfaceIndex* reference = nullptr;  // the reference's
    TriangleBound testBound;                  // may be empty
};
Status castRays(const RayScene& test, const RayScene* reference, double diagonal, const CheckSettings& settings,
                uint64_t seed, RayResult& out, double displacementSlack = 0, const RayParameters* parameters = nullptr);

// What the per-tessellation checks share, prepared once per asset (prepareChecks).
struct CheckContext {
    const Asset* asset = nullptr;
    const CheckSettings* settings = nullptr;
    ControlTopology topology;
    double diagonal = 0;             // of the control mesh's bounding box
    SourceOracle* source = nullptr;  // accuracy oracle, or null
    // A ray reference: its scene and, to bound the tested triangles, its (u, v) index.
    struct Reference {
        std::unique_ptr<RayScene> scene;
        SurfaceIndex surface;
    };
    std::unique_ptr<Reference> reference;           // the ray reference, or null
    std::unique_ptr<Reference> displacedReference;  // the same, displaced (assets with a map)
    // With hierarchical edits deeper than a checked runtime depth d: the reference of
    // the asset without the edits of levels > d (the runtime shows only those <= d),
    // made when first needed. Key: (d, displaced).
    std::map<std::pair<uint32_t, bool>, std::unique_ptr<Reference>> depthReferences;
    // Where there is no ray reference (an open control mesh): the finer surface that
    // checkNormals judges normals behind their triangle against, by runtime depth (no
    // ray scene), made when first needed.
    std::map<uint32_t, std::unique_ptr<Reference>> normalReferences;
    float referenceFactor = 0;
    std::string referenceSkipped;  // why there is no reference
    double referenceSeconds = 0;
    std::function<void(const std::string&)> progress;  // may be empty
    std::unique_ptr<CpuEvaluator> evaluator;           // of *asset: checkEvaluation's, its plan kept
    // Without a source: cageOracle's, made when N1 first needs it (cageTried).
    std::unique_ptr<SourceOracle> cage;
    std::vector<char> smoothVertex;
    bool cageTried = false;
    void say(const std::string& line) const {  // a progress line
        if (progress) progress(line);
    }
};
// Fills `ctx` and, for a closed control mesh, evaluates and welds the reference
// tessellation (settings.referenceFactor, equal spacing). `asset` and `settings`
// must outlive `ctx`. Internal on an Embree failure.
Status prepareChecks(const Asset& asset, SourceOracle* source, const CheckSettings& settings, CheckContext& ctx);

// A piece of a tessellation checked in pieces (refusedForMemory, checkEvaluation).
struct FacePiece {
    uint32_t first = 0, count = 0;         // base faces [first, first + count)
    uint64_t vertices = 0, triangles = 0;  // what the piece's evaluation writes
};

// The reference for a tessellation of runtime depth `depth`: the asset's own, or,
// when it has edits deeper than that, one of the asset without them (cached in ctx):
// the runtime applies a level's edits only when it computes that level. Null
// without a reference.
Status referenceAtDepth(CheckContext& ctx, uint32_t depth, bool displace, const CheckContext::Reference*& out);
// The finer surface checkNormals judges again against for a tessellation of factor
// `factor` and runtime depth `depth`, undisplaced: the ray reference where there is
// one, else one made for the normals; null where the reference is not twice as fine.
Status finerSurface(CheckContext& ctx, uint32_t depth, float factor, const SurfaceIndex*& out);
// Whether soup vertex `v` is a base face's corner on a control vertex of the smooth
// rule, where the asset's own control mesh is an oracle (cageOracle): N1's
// confirmation without --source.
bool smoothCorner(CheckContext& ctx, const Tessellation& soup, size_t v);

// How a case's GPU capture is taken (--gpu): whole and compared with the CPU's soup
// (neither set), session by session and checked as pieces, or not at all (L1).
struct GpuPlan {
    bool sessions = false;
    std::string notRun;  // why not at all
};
// How tessellation case `cpu` (evaluated with `eval`) fits settings.maxMemoryBytes:
// whole, in `pieces` of base faces (each within what the welded whole leaves), or
// not at all: then true, and L1 goes into `report` unevaluated, for the GPU too.
bool refusedForMemory(CheckContext& ctx, const CheckInputs& in, const EvalSettings& eval, TessellationChecks& cpu,
                      CheckReport& report, std::vector<FacePiece>& pieces, GpuPlan& gpu);
// The checks of case `gpu` (its eval, factor and depth set) on the GPU's capture
// session by session (CheckInputs::gpuCaptureSessions), each checked as a piece.
Status checkCaptureSessions(CheckContext& ctx, const CheckInputs& in, uint64_t seed, TessellationChecks& gpu);

// The checks of one evaluation, repeatable for any EvalSettings (a displaced
// evaluation included: pass accuracy = false for it, the oracle knows only the
// undisplaced limit surface; its rays use the displaced reference). Evaluates on the
// CPU, then runs checkTessellation. `seed` picks the samples and rays.
// `soup` (optional) receives the evaluated tessellation.
// `pieces` (more than one): evaluated and checked piece by piece (PieceWeld), the
// rays over the welded whole without hit distances; `soup` is then not filled.
Status checkEvaluation(CheckContext& ctx, const EvalSettings& eval, bool accuracy, uint64_t seed,
                       TessellationChecks& out, Tessellation* soup = nullptr,
                       const std::vector<FacePiece>& pieces = {});
// The same checks on a tessellation made elsewhere (a GPU capture).
Status checkTessellation(CheckContext& ctx, const Tessellation& soup, bool accuracy, uint64_t seed,
                         TessellationChecks& out);

// checkBytes' parts for a tessellation of `vertices` and `indices` checked in pieces
// (checkEvaluation): what the whole keeps (its welded mesh, and the weld's vertex
// table while pieces are added, then the ray scene where `rays` run), and one
// piece's own beside it (its soup and its edge table).
uint64_t piecesKeptBytes(uint64_t vertices, uint64_t indices, bool rays);
uint64_t pieceBytes(uint64_t vertices, uint64_t indices);

inline double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// `v` as a stream writes it (findings and progress lines).
std::string number(double v);
// " (the reference includes N hierarchical edits down to level K)", or "" for none.
std::string referenceEdits(uint32_t edits, int level);

// addFindings' share of one tessellation, appended to `out` (its G, A1, W, N1 and R
// findings); reportJUnit files them under that tessellation's test cases.
void addTessellationFindings(const CheckSettings& settings, const TessellationChecks& t, std::vector<Finding>& out);

}  // namespace lt

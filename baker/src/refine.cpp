// OpenSubdiv topology and Sdc masks for the baker (see refine.h).
#include "refine.h"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/sdc/loopScheme.h>
#include <opensubdiv/sdc/crease.h>

#include <cassert>
#include <cmath>
#include <mutex>

namespace lt {
namespace {

// OpenSubdiv reports errors through a global callback: route them into a string
// owned by the thread that is building a refiner.
thread_local std::string* tlsOsdErrors = nullptr;

void osdErrorCallback(Far::ErrorType, const char* message) {
    if (tlsOsdErrors) {
        if (!tlsOsdErrors->empty()) *tlsOsdErrors += "; ";
        *tlsOsdErrors += message;
    }
}

void osdWarningCallback(const char*) {}

// Sdc's <typename EDGE> over a TopologyLevel.
class EdgeHood {
public:
    EdgeHood(const Far::TopologyLevel& level, OsdIndex edge) : level_(level), edge_(edge) {}
    int GetNumFaces() const { return level_.GetEdgeFaces(edge_).size(); }
    float GetSharpness() const { return level_.GetEdgeSharpness(edge_); }
    void GetChildSharpnesses(Sdc::Crease const&, float s[2]) const {
        s[0] = s[1] = GetSharpness() - 1.0f;
    }
    void GetNumVerticesPerFace(int counts[]) const {
        for (int i = 0; i < GetNumFaces(); ++i) counts[i] = 3;
    }

private:
    const Far::TopologyLevel& level_;
    OsdIndex edge_;
};

// Sdc's <typename VERTEX> over a parent TopologyLevel (and the child level when the
// vertex has a child).
class VertexHood {
public:
    VertexHood(const Far::TopologyLevel& parent, const Far::TopologyLevel* child, OsdIndex vertex,
               OsdIndex childVertex)
        : parent_(parent), child_(child), vertex_(vertex), childVertex_(childVertex) {}
    int GetNumEdges() const { return parent_.GetVertexEdges(vertex_).size(); }
    int GetNumFaces() const { return parent_.GetVertexFaces(vertex_).size(); }
    float GetSharpness() const { return parent_.GetVertexSharpness(vertex_); }
    float* GetSharpnessPerEdge(float s[]) const {
        auto edges = parent_.GetVertexEdges(vertex_);
        for (int i = 0; i < edges.size(); ++i) s[i] = parent_.GetEdgeSharpness(edges[i]);
        return s;
    }
    float GetChildSharpness(Sdc::Crease const&) const {
        assert(child_);
        return child_->GetVertexSharpness(childVertex_);
    }
    float* GetChildSharpnessPerEdge(Sdc::Crease const& crease, float s[]) const {
        std::vector<float> parentSharpness(GetNumEdges());
        GetSharpnessPerEdge(parentSharpness.data());
        crease.SubdivideEdgeSharpnessesAroundVertex(GetNumEdges(), parentSharpness.data(), s);
        return s;
    }

private:
    const Far::TopologyLevel& parent_;
    const Far::TopologyLevel* child_;
    OsdIndex vertex_, childVertex_;
};

using LoopScheme = Sdc::Scheme<Sdc::SCHEME_LOOP>;

} // namespace

Sdc::Options sdcOptions(BoundaryInterpolation boundary, CreaseMethod creaseMethod) {
    Sdc::Options options;
    switch (boundary) {
    case BoundaryInterpolation::None: options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_NONE); break;
    case BoundaryInterpolation::EdgeAndCorner:
        options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
        break;
    case BoundaryInterpolation::EdgeOnly: options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY); break;
    }
    options.SetCreasingMethod(creaseMethod == CreaseMethod::Chaikin ? Sdc::Options::CREASE_CHAIKIN
                                                                    : Sdc::Options::CREASE_UNIFORM);
    return options;
}

namespace {

// Routes OpenSubdiv's messages on this thread into `text` while it lives.
// OpenSubdiv's callbacks are global: installed once (nothing else in looptess sets
// them), they route each message to the thread that caused it, so refiners are
// built and refined concurrently (loopbake --threads).
struct OsdErrors {
    std::string text;
    OsdErrors() {
        static std::once_flag installed;
        std::call_once(installed, [] {
            Far::SetErrorCallback(osdErrorCallback);
            Far::SetWarningCallback(osdWarningCallback);
        });
        tlsOsdErrors = &text;
    }
    ~OsdErrors() { tlsOsdErrors = nullptr; }
    OsdErrors(const OsdErrors&) = delete;
    OsdErrors& operator=(const OsdErrors&) = delete;
};

// A Far descriptor's arrays, owned.
struct Descriptor {
    std::vector<int> vertsPerFace, faceVerts, creasePairs, cornerVerts, holes;
    std::vector<float> creaseWeights, cornerWeights;
    int vertexCount = 0;
    // Channel kIsolationChannel (refine.h): a value per face corner, or none.
    std::vector<int> isolation;
    int isolationValues = 0;

    Far::TopologyRefiner* create(Sdc::Options sdc) const {
        Far::TopologyDescriptor desc;
        Far::TopologyDescriptor::FVarChannel channel;
        if (!isolation.empty()) {
            channel.numValues = isolationValues;
            channel.valueIndices = isolation.data();
            desc.numFVarChannels = 1;
            desc.fvarChannels = &channel;
            // Linear channels are never isolated (Far::TopologyRefiner::RefineAdaptive).
            sdc.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_NONE);
        }
        desc.numVertices = vertexCount;
        desc.numFaces = int(vertsPerFace.size());
        desc.numVertsPerFace = vertsPerFace.data();
        desc.vertIndicesPerFace = faceVerts.data();
        desc.numCreases = int(creaseWeights.size());
        desc.creaseVertexIndexPairs = creasePairs.data();
        desc.creaseWeights = creaseWeights.data();
        desc.numCorners = int(cornerWeights.size());
        desc.cornerVertexIndices = cornerVerts.data();
        desc.cornerWeights = cornerWeights.data();
        desc.numHoles = int(holes.size());
        desc.holeIndices = holes.data();
        using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
        return Factory::Create(desc, Factory::Options(Sdc::SCHEME_LOOP, sdc));
    }
};

// Marks `slits` in the isolation channel: each slit's middle face takes a value of
// its own at the vertex; every other corner takes its vertex's index.
void isolate(Descriptor& d, const std::vector<SlitCorner>& slits) {
    if (slits.empty()) return;
    d.isolation = d.faceVerts;
    d.isolationValues = d.vertexCount;
    for (const SlitCorner& s : slits)
        for (size_t c = size_t(s.face) * 3; c < size_t(s.face) * 3 + 3; ++c)
            if (d.faceVerts[c] == s.vertex) d.isolation[c] = d.isolationValues++;
}

Descriptor meshDescriptor(const InputMesh& mesh) {
    Descriptor d;
    d.vertexCount = int(mesh.vertexCount());
    d.vertsPerFace.assign(mesh.faceCount(), 3);
    d.faceVerts.assign(mesh.faces.begin(), mesh.faces.end());
    for (const auto& c : mesh.creases) {
        d.creasePairs.push_back(int(c.a));
        d.creasePairs.push_back(int(c.b));
        d.creaseWeights.push_back(c.sharpness);
    }
    for (const auto& c : mesh.corners) {
        d.cornerVerts.push_back(int(c.vertex));
        d.cornerWeights.push_back(c.sharpness);
    }
    d.holes.assign(mesh.holes.begin(), mesh.holes.end());
    return d;
}

// Level `l` of `refiner` as a mesh of its own: faces, the sharpness its edges and
// vertices hold there (boundary and non-manifold edges are infinitely sharp in Far
// already), holes.
Descriptor levelDescriptor(const Far::TopologyLevel& level) {
    Descriptor d;
    d.vertexCount = level.GetNumVertices();
    for (OsdIndex f = 0; f < level.GetNumFaces(); ++f) {
        auto fv = level.GetFaceVertices(f);
        d.vertsPerFace.push_back(fv.size());
        d.faceVerts.insert(d.faceVerts.end(), fv.begin(), fv.end());
        if (level.IsFaceHole(f)) d.holes.push_back(f);
    }
    for (OsdIndex e = 0; e < level.GetNumEdges(); ++e) {
        float s = level.GetEdgeSharpness(e);
        if (!(s > 0.0f)) continue;
        auto ev = level.GetEdgeVertices(e);
        d.creasePairs.push_back(ev[0]);
        d.creasePairs.push_back(ev[1]);
        d.creaseWeights.push_back(s);
    }
    for (OsdIndex v = 0; v < level.GetNumVertices(); ++v) {
        float s = level.GetVertexSharpness(v);
        if (!(s > 0.0f)) continue;
        d.cornerVerts.push_back(v);
        d.cornerWeights.push_back(s);
    }
    if (level.GetNumFVarChannels() > kIsolationChannel) {  // as refined: the vertex points of slits
        d.isolationValues = level.GetNumFVarValues(kIsolationChannel);
        for (OsdIndex f = 0; f < level.GetNumFaces(); ++f)
            for (OsdIndex x : level.GetFaceFVarValues(f, kIsolationChannel)) d.isolation.push_back(x);
    }
    return d;
}

Status rejected(const std::string& name, const std::string& errors) {
    return Status::error(Status::BadInput,
                         name + ": OpenSubdiv rejects the topology: " + (errors.empty() ? "unknown error" : errors));
}

// With SharpEdges::Isolate infinitely sharp features are isolated like the others
// (no infinitely sharp patches), so the faces beside a sharp edge are refined and
// the baker can make the transitions across it (bake.cpp, selectCandidates).
void refineAdaptive(Far::TopologyRefiner& refiner, int depth, SharpEdges sharp) {
    Far::TopologyRefiner::AdaptiveOptions adaptive(depth);
    adaptive.useInfSharpPatch = sharp == SharpEdges::Patches;
    adaptive.considerFVarChannels = refiner.GetNumFVarChannels() > kIsolationChannel;
    refiner.RefineAdaptive(adaptive);
}

} // namespace

Status buildRefiner(const InputMesh& mesh, int maxDepth, const std::string& name,
                    std::unique_ptr<Far::TopologyRefiner>& refiner, const RefineHook& beforeRefine,
                    SharpEdges sharp) {
    OsdErrors errors;
    const Sdc::Options sdc = sdcOptions(mesh.boundary, mesh.creaseMethod);
    refiner.reset(meshDescriptor(mesh).create(sdc));
    Status hook;
    if (refiner && errors.text.empty() && beforeRefine) hook = beforeRefine(*refiner, maxDepth);
    if (refiner && errors.text.empty() && hook) {
        // Slits on regular runs are isolated: the channel that marks them goes in at
        // creation, so the refiner is made again.
        const std::vector<SlitCorner> slits = slitVertices(*refiner, mesh.positions);
        if (!slits.empty()) {
            Descriptor d = meshDescriptor(mesh);
            isolate(d, slits);
            refiner.reset(d.create(sdc));
        }
    }
    if (refiner && hook) refineAdaptive(*refiner, maxDepth, sharp);
    if (!hook) {
        refiner.reset();
        return hook;
    }
    if (!refiner || !errors.text.empty()) {
        refiner.reset();
        return rejected(name, errors.text);
    }
    return Status::ok();
}

Status buildTopology(const InputMesh& mesh, int maxDepth, int uniformDepth, const std::string& name,
                     Topology& topology, const RefineHook& beforeRefine) {
    assert(uniformDepth >= 0 && uniformDepth <= maxDepth);
    topology = Topology{};
    if (uniformDepth == 0) return buildRefiner(mesh, maxDepth, name, topology.adaptive, beforeRefine);
    OsdErrors errors;
    const Sdc::Options sdc = sdcOptions(mesh.boundary, mesh.creaseMethod);
    std::unique_ptr<Far::TopologyRefiner> uniform(meshDescriptor(mesh).create(sdc));
    if (!uniform || !errors.text.empty()) return rejected(name, errors.text);
    if (beforeRefine)
        if (Status hook = beforeRefine(*uniform, maxDepth); !hook) return hook;
    // As buildRefiner; the channel refines with the levels, and level K's goes on.
    if (const std::vector<SlitCorner> slits = slitVertices(*uniform, mesh.positions); !slits.empty()) {
        Descriptor d = meshDescriptor(mesh);
        isolate(d, slits);
        uniform.reset(d.create(sdc));
    }
    assert(maxDepth >= uniformDepth);
    Far::TopologyRefiner::UniformOptions options(uniformDepth);
    options.fullTopologyInLastLevel = true;   // the last level's edges carry its sharpness
    uniform->RefineUniform(options);
    std::unique_ptr<Far::TopologyRefiner> adaptive(levelDescriptor(uniform->GetLevel(uniformDepth)).create(sdc));
    if (adaptive && maxDepth > uniformDepth) refineAdaptive(*adaptive, maxDepth - uniformDepth, SharpEdges::Isolate);
    if (!adaptive || !errors.text.empty()) return rejected(name, errors.text);
    topology.uniform = std::move(uniform);
    topology.adaptive = std::move(adaptive);
    topology.uniformDepth = uniformDepth;
    return Status::ok();
}

float edgeCreaseWeight(const Far::TopologyRefiner& refiner, int level, OsdIndex edge) {
    const Far::TopologyLevel& parent = refiner.GetLevel(level);
    const Far::TopologyLevel& child = refiner.GetLevel(level + 1);
    OsdIndex cv = parent.GetEdgeChildVertex(edge);
    assert(cv >= 0);
    EdgeHood hood(parent, edge);
    double vw[2] = {};
    std::vector<double> fw(size_t(parent.GetEdgeFaces(edge).size()) + 1, 0.0);
    SdcMask mask(vw, vw, fw.data());
    Sdc::Crease::Rule pRule = parent.GetEdgeSharpness(edge) > 0.0f ? Sdc::Crease::RULE_CREASE : Sdc::Crease::RULE_SMOOTH;
    LoopScheme(refiner.GetSchemeOptions()).ComputeEdgeVertexMask(hood, mask, pRule, child.GetVertexRule(cv));
    // Loop's edge masks are (1-w) (3/8, 3/8; 1/8, 1/8) + w (1/2, 1/2; 0, 0).
    double w = (vw[0] - 0.375) * 8.0;
    if (mask.GetNumFaceWeights() == 0) w = 1.0;
    return float(std::min(1.0, std::max(0.0, w)));
}

bool vertexMask(const Far::TopologyRefiner& refiner, int level, OsdIndex vertex, std::vector<double>& weights) {
    const Far::TopologyLevel& parent = refiner.GetLevel(level);
    const Far::TopologyLevel& child = refiner.GetLevel(level + 1);
    OsdIndex cv = parent.GetVertexChildVertex(vertex);
    assert(cv >= 0);
    Sdc::Crease::Rule pRule = parent.GetVertexRule(vertex);
    Sdc::Crease::Rule cRule = child.GetVertexRule(cv);
    auto smoothLike = [](Sdc::Crease::Rule r) { return r == Sdc::Crease::RULE_SMOOTH || r == Sdc::Crease::RULE_DART; };
    if (smoothLike(pRule) && smoothLike(cRule)) return false;

    int n = parent.GetVertexEdges(vertex).size();
    weights.assign(size_t(n) + 1, 0.0);
    std::vector<double> faceWeights(size_t(parent.GetVertexFaces(vertex).size()) + 1, 0.0);
    SdcMask mask(&weights[0], &weights[1], faceWeights.data());
    VertexHood hood(parent, &child, vertex, cv);
    LoopScheme(refiner.GetSchemeOptions()).ComputeVertexVertexMask(hood, mask, pRule, cRule);
    assert(mask.GetNumFaceWeights() == 0);
    if (mask.GetNumEdgeWeights() == 0) std::fill(weights.begin() + 1, weights.end(), 0.0);
    return true;
}

} // namespace lt

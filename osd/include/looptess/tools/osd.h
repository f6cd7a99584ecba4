// looptess/tools/osd.h -- the OpenSubdiv bridge (library looptess_osd): an lt::InputMesh
// as OpenSubdiv's Far topology under Loop, its Sdc options, refiners made and refined
// as looptess refines, and Sdc's masks read on a refined level.
//
//   std::unique_ptr<lt::Far::TopologyRefiner> refiner;
//   lt::Status st = lt::createRefiner(mesh, "hero.obj", refiner);  // level 0
//   if (st) lt::refineAdaptive(*refiner, 4);
//
// The baker's tables and the OpenSubdiv comparisons build on this mapping; the
// accuracy oracle (looptess/tools/osd_reference.h) has its own (why: docs/loopcheck.md,
// "The OpenSubdiv oracle").
#pragma once

#include "looptess/tools/mesh.h"

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefiner.h>
#include <opensubdiv/sdc/options.h>

#include <memory>
#include <string>
#include <vector>

namespace lt {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;
using OsdIndex = OpenSubdiv::Vtr::Index;

// Sdc options for an asset's boundary interpolation and crease method; every other
// option keeps Sdc's default.
Sdc::Options sdcOptions(BoundaryInterpolation boundary, CreaseMethod creaseMethod);

// The arrays of a Far::TopologyDescriptor, owned: faces, creases as vertex pairs,
// corners, holes. No face-varying channel (a caller adds its own to descriptor()).
struct FarTopology {
    int vertexCount = 0;
    std::vector<int> vertsPerFace, faceVerts, creasePairs, cornerVerts, holes;
    std::vector<float> creaseWeights, cornerWeights;

    // A descriptor that points into this object: valid while it lives unchanged.
    Far::TopologyDescriptor descriptor() const;
};

// `mesh` as Far reads it: its vertices as numbered, its triangles in order, every
// crease (a, b, sharpness) and corner as given, its holes.
FarTopology meshTopology(const InputMesh& mesh);

// `level` as a mesh of its own: its faces in Far's numbering, the sharpness its
// edges and vertices hold there (boundary and non-manifold edges are infinitely
// sharp in Far already), its holes; vertices and faces keep the level's numbering.
FarTopology levelTopology(const Far::TopologyLevel& level);

// While it lives, OpenSubdiv's error messages raised on this thread collect here
// (OpenSubdiv reports through one global callback; this routes each message to the
// thread that caused it, so refiners are built concurrently). Scopes nest: the
// innermost collects. Warnings are dropped.
class OsdErrors {
public:
    OsdErrors();
    ~OsdErrors();
    OsdErrors(const OsdErrors&) = delete;
    OsdErrors& operator=(const OsdErrors&) = delete;

    bool empty() const { return text_.empty(); }
    // BadInput "<name>: OpenSubdiv rejects the topology: <the messages, '; '-joined,
    // or "unknown error" when there are none>".
    Status rejected(const std::string& name) const;

private:
    std::string text_;
    std::string* outer_;
};

// Far's refiner of `desc` under Loop with `options`, unrefined; null when Far
// refuses the topology (its messages go to this thread's OsdErrors).
std::unique_ptr<Far::TopologyRefiner> createRefiner(const Far::TopologyDescriptor& desc, const Sdc::Options& options);

// Level 0 of `mesh`: meshTopology with sdcOptions of its boundary and crease
// method. BadInput as OsdErrors::rejected(name) when Far reports an error or makes
// no refiner; `out` is then null.
Status createRefiner(const InputMesh& mesh, const std::string& name, std::unique_ptr<Far::TopologyRefiner>& out);

// RefineAdaptive(depth) of an unrefined `refiner` as looptess refines: extraordinary
// vertices, semi-sharp and irregular sharp features and infinitely sharp creases are
// isolated to the full depth (no infinitely sharp patches: the baker makes the
// transitions across such a crease), regular boundaries are left as patches. When
// the refiner has face-varying channels they are considered: a vertex where a channel
// is discontinuous is isolated like an extraordinary one (the way a caller marks
// vertices to isolate; Far never isolates for a linearly interpolated channel).
void refineAdaptive(Far::TopologyRefiner& refiner, int depth);

// RefineUniform(depth) of an unrefined `refiner`, the last level with its edges
// (their sharpness, the vertices' rings).
void refineUniform(Far::TopologyRefiner& refiner, int depth);

// Edge point of parent edge `edge` of `level` (its child vertex is in level + 1):
// the crease weight w in [0, 1] of  e = (1-w) smooth + w crease  that Sdc's Loop
// edge mask gives (1 where the mask has no face weights).
float edgeCreaseWeight(const Far::TopologyRefiner& refiner, int level, OsdIndex edge);

// Vertex point of parent vertex `vertex` of `level`. False when Sdc's mask is
// Loop's smooth rule (smooth or dart before and after); otherwise `weights` gets the
// vertex weight, then one weight per incident edge in TopologyLevel::GetVertexEdges
// order (all zero when the mask has no edge weights: a corner).
bool vertexMask(const Far::TopologyRefiner& refiner, int level, OsdIndex vertex, std::vector<double>& weights);

// The vertex at the other end of `edge` from `vertex` (one of its ends).
inline OsdIndex otherEnd(const Far::TopologyLevel& level, OsdIndex edge, OsdIndex vertex) {
    auto ev = level.GetEdgeVertices(edge);
    return ev[0] == vertex ? ev[1] : ev[0];
}

// A point in double for Far::PrimvarRefiner and PatchTable evaluation (the
// Clear / AddWithWeight interface they call).
struct OsdPoint {
    double p[3] = {0, 0, 0};
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const OsdPoint& src, double w) {
        for (int k = 0; k < 3; ++k) p[k] += w * src.p[k];
    }
};

// Sdc's <typename MASK>: vertex, edge and face weights written to caller storage,
// which must hold as many as the mask asks for.
class SdcMask {
public:
    typedef double Weight;
    SdcMask(double* v, double* e, double* f) : vw_(v), ew_(e), fw_(f) {}
    int GetNumVertexWeights() const { return nv_; }
    int GetNumEdgeWeights() const { return ne_; }
    int GetNumFaceWeights() const { return nf_; }
    void SetNumVertexWeights(int n) { nv_ = n; }
    void SetNumEdgeWeights(int n) { ne_ = n; }
    void SetNumFaceWeights(int n) { nf_ = n; }
    double const& VertexWeight(int i) const { return vw_[i]; }
    double const& EdgeWeight(int i) const { return ew_[i]; }
    double const& FaceWeight(int i) const { return fw_[i]; }
    double& VertexWeight(int i) { return vw_[i]; }
    double& EdgeWeight(int i) { return ew_[i]; }
    double& FaceWeight(int i) { return fw_[i]; }
    bool AreFaceWeightsForFaceCenters() const { return centers_; }
    void SetFaceWeightsForFaceCenters(bool on) { centers_ = on; }

private:
    double *vw_, *ew_, *fw_;
    int nv_ = 0, ne_ = 0, nf_ = 0;
    bool centers_ = false;
};

}  // namespace lt

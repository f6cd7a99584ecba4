// Private to the baker (tests and benchmarks reach it through looptess_baker_internal):
// the baker's own adaptive refiner of a mesh, and its exact limit stencils. Those that
// compare OpenSubdiv's refinement or tables with the baker's, vertex by vertex, need
// the very refiner the baker numbered its vertices on (BakeTrace); the mapping from
// mesh to Far underneath is looptess/tools/osd.h's.
#pragma once

#include "looptess/tools/osd.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lt {

// Builds a TopologyRefiner for `mesh` (createRefiner: its creases, corners, holes
// and boundary/crease options) and refines it adaptively to `maxDepth` as
// refineAdaptive does, isolating besides the slit tips the baker finds on the
// control mesh (slitVertices, refine.h; marked in a face-varying channel).
// Returns BadInput with OpenSubdiv's message when it rejects the topology.
// `beforeRefine`, when given, sees the unrefined refiner (level 0 only) and the depth
// about to be refined to, which it may lower (limits: the memory check and the
// automatic depth); a non-ok status from it is returned as is and nothing is refined.
using RefineHook = std::function<Status(const Far::TopologyRefiner& unrefined, int& maxDepth)>;
Status buildRefiner(const InputMesh& mesh, int maxDepth, const std::string& name,
                    std::unique_ptr<Far::TopologyRefiner>& refiner, const RefineHook& beforeRefine = nullptr);

// Exact limit stencil of `vertex` of `level` for the surface around face `face`
// (limit.cpp). `points` are the vertex then the neighbours it reads; the weights
// run parallel to it. `sector` identifies the run of faces between infinitely
// sharp edges the stencil belongs to (-1: the vertex has one tangent plane), so
// faces of the same sector share one stencil.
// With `smoothWeights` false a smooth stencil leaves its weights empty:
// smoothLimitWeights(points.size() - 1) has them (a level's thousands of sector
// stencils need no copies of a few shared vectors).
struct LimitStencil {
    std::vector<OsdIndex> points;
    std::vector<double> position, tangentU, tangentV;
    OsdIndex sector = -1;
    bool smooth = false;  // Loop's smooth limit masks on a closed ring (weights implied)
};
void limitStencil(const Far::TopologyRefiner& refiner, int level, OsdIndex vertex, OsdIndex face, LimitStencil& out,
                  bool smoothWeights = true);

// The weights of a smooth limit stencil with `valence` ring points, over the vertex
// and its ring: Loop's smooth limit masks depend on the valence alone (Sdc's read no
// option). Computed once per valence and thread; the reference stays valid for the
// thread's life.
struct SmoothWeights {
    std::vector<double> position, tangentU, tangentV;
};
const SmoothWeights& smoothLimitWeights(int valence);

// smoothLimitWeights' for `s` where limitStencil left its weights out, else null
// (`s` has its own).
const SmoothWeights* omittedWeights(const LimitStencil& s);

// `s` with its weights: its own, or omittedWeights' copied into `scratch`.
const LimitStencil& withWeights(const LimitStencil& s, LimitStencil& scratch);

// The `sector` limitStencil would report, without computing the stencil.
OsdIndex limitSector(const Far::TopologyRefiner& refiner, int level, OsdIndex vertex, OsdIndex face);

}  // namespace lt

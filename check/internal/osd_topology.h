// Private to looptess_osd_reference (tests reach it through
// looptess_osd_reference_internal, check/CMakeLists.txt): the oracle's own mapping
// of a mesh to OpenSubdiv's Far topology.
//
// The baker maps an InputMesh to Far through the bridge (looptess/tools/osd.h). The oracle
// does not: a mistake in that mapping (a crease dropped, a hole lost, the wrong
// boundary option) would then be on both sides of every accuracy check and never be
// seen. This is written apart from it, and tests/check/test_osd_mapping.cpp shows
// the two agree, level 0 against level 0, on the corpus and the real meshes.
#pragma once

#include "looptess/tools/mesh.h"

#include <opensubdiv/far/topologyRefiner.h>
#include <opensubdiv/sdc/options.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace lt {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;
using OsdIndex = OpenSubdiv::Vtr::Index;

// A triangle mesh as the oracle hands it to Far.
struct OracleMesh {
    int vertices = 0;
    std::vector<int> triangles;                  // 3 per face
    std::map<std::pair<int, int>, float> sharp;  // edge (smaller end, larger end) -> sharpness
    std::map<int, float> corners;                // vertex -> sharpness
    std::vector<int> holes;                      // faces
    // Vertices adaptive refinement is to isolate like extraordinary ones, to the
    // full depth: each face corner at one takes a value of its own in face-varying
    // channel 0 (FVAR_LINEAR_NONE), which Far isolates and no vertex rule reads.
    // Empty: no channel.
    std::vector<int> isolate;
};

// Edge a-b, either way, as a key of OracleMesh::sharp.
inline std::pair<int, int> edgeKey(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// `mesh`'s vertices, triangles, edge and vertex sharpness and holes; a crease or
// corner given twice keeps the sharpness given last, as Far would.
OracleMesh oracleMesh(const InputMesh& mesh);

// Sdc options for `mesh`'s boundary interpolation and crease method, Sdc's defaults
// otherwise.
Sdc::Options oracleOptions(const InputMesh& mesh);

// Far's refiner of `m` under Loop with `options`, unrefined; null when Far refuses
// the topology (its messages go to this thread's OsdErrors, looptess/tools/osd.h).
std::unique_ptr<Far::TopologyRefiner> oracleRefiner(const OracleMesh& m, const Sdc::Options& options);

// Level 0 of `mesh` (oracleMesh, oracleOptions). BadInput "<name>: OpenSubdiv
// rejects the topology: <its messages>" when Far reports an error or makes none;
// `out` is then null.
Status oracleRefiner(const InputMesh& mesh, const std::string& name, std::unique_ptr<Far::TopologyRefiner>& out);

}  // namespace lt

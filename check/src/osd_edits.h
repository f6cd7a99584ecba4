// Private to looptess_osd_reference: OpenSubdiv's limit surface of a mesh with
// hierarchical edits (InputMesh::edits, baker.h), for OsdLimitSurface.
//
// Far (OpenSubdiv 3) has no hierarchical edits, so with edits down to level K >= 1
// the reference is built in two refiners, from public Far APIs only:
//   1. `uniform`: the mesh refined uniformly to level K. Its points are made level
//      by level with PrimvarRefiner, each level's edits applied to that level's
//      points (level 0's to the control points) before the next level is
//      interpolated from them (docs/hierarchical-edits.md, section 1).
//   2. level K as a mesh of its own (`last`): its faces in Far's numbering, the
//      edge and vertex sharpness level K holds, its holes, the mesh's boundary and
//      crease options. No edit lies below level K, so its limit surface over the
//      edited level-K points is the edited mesh's; OsdLimitSurface builds its
//      adaptive PatchTable as for an unedited mesh.
// A sample (base face, u, v) is evaluated in the level-K sub-triangle holding it
// (locateSubface). With edits at level 0 only (K = 0) nothing of this is needed:
// the edits move control points (editedControlPoints).
#pragma once

#include "looptess/tools/mesh.h"
#include "looptess/tools/osd.h"  // OsdPoint

#include "osd_topology.h"  // the oracle's own Far topology of a mesh

#include <memory>
#include <vector>

namespace lt {

// BadInput naming the first edit of mesh.edits with a face, child or vertex out of
// range ("oracle: edit 3 (face 7, path [1 3], vertex 4): ...").
Status checkEdits(const InputMesh& mesh);

// The control points in double, as given; editedControlPoints: with mesh.edits'
// level-0 edits applied in input order (checkEdits must pass).
std::vector<OsdPoint> controlPoints(const InputMesh& mesh);
std::vector<OsdPoint> editedControlPoints(const InputMesh& mesh);

// Level-K faces a reference may refine: above this many, buildEditedPrefix refuses
// (Far needs about 1 KB per level-K face for both refiners and the patch table).
constexpr uint64_t kMaxEditedPrefixFaces = uint64_t(1) << 22;

struct EditedPrefix {
    std::unique_ptr<Far::TopologyRefiner> base;     // the mesh, unrefined
    std::unique_ptr<Far::TopologyRefiner> uniform;  // base's level 0 refined uniformly to `depth`
    int depth = 0;                                  // K
    InputMesh last;                                 // level K as a mesh (float positions)
    std::vector<OsdPoint> points;                   // level K's points, every edit applied
};

// Builds the prefix of `mesh` (checkInput passed; mesh.editDepth() >= 1).
// BadInput with OpenSubdiv's message or checkEdits'; Unsupported when level K would
// exceed kMaxEditedPrefixFaces faces.
Status buildEditedPrefix(const InputMesh& mesh, EditedPrefix& out);

// The level-`depth` face of `uniform` (a uniform refinement to at least `depth`)
// that holds (u, v) of base face `face`; (u, v) become that face's own parameters.
// Children are taken in Loop's order: child i keeps corner i, child 3 is the middle
// triangle (e1, e2, e0), rotated 180 degrees against its parent:
//
//        2                      parent (s, t)      child   child's (s', t')
//        |\                     s, t >= 0,          0      (2s, 2t)
//        | \                    s + t <= 1          1      (2s - 1, 2t)        s >= 1/2
//        |2 \                                       2      (2s, 2t - 1)        t >= 1/2
//       e2---e1                                     3      (1 - 2s, 1 - 2t)    s + t > 1/2
//        |\ 3|\                                     0      otherwise
//        | \ | \        e_i: the edge point of edge i -> i+1
//        |0 \|1 \       (the first row that applies)
//        0---e0---1
//
// Exact in binary floating point (halving and unit shifts), so a dyadic (u, v)
// keeps its value; a point on a shared sub-triangle edge goes to either side, where
// the limit surface is continuous.
OsdIndex locateSubface(const Far::TopologyRefiner& uniform, int depth, int face, double& u, double& v);

}  // namespace lt

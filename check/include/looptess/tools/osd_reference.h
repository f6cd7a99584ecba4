// looptess/tools/osd_reference.h -- OpenSubdiv's own answer for a control mesh, in double
// precision: the oracle of loopcheck's accuracy check and of the tests
// (tests/support/osd_reference.h wraps it for GoogleTest). Library looptess_osd_reference;
// links OpenSubdiv, so the runtime never links it.
//
//   lt::OsdLimitSurface limit;
//   lt::Status st = limit.build(mesh);               // mesh: lt::checkInput passed
//   double p[3], n[3];
//   if (st && limit.evaluate(face, u, v, p, n)) ...  // face, (u,v) as the runtime's captures
//
// The mesh is mapped to Far with the oracle's own code, not the baker's bridge
// (looptess/tools/osd.h). How each oracle works and why: docs/loopcheck.md, "The
// OpenSubdiv oracle".
#pragma once

#include "looptess/tools/mesh.h"

#include <memory>

namespace lt {

// Diagonal of the bounding box of `positions` (3 floats per vertex), in double;
// 0 for no vertices.
double boundingBoxDiagonal(const std::vector<float>& positions);

// OpenSubdiv's limit surface through a double-precision PatchTable at `isolation`
// (default 10): exact on regular patches and at patch corners, converging like
// 2^-isolation near extraordinary vertices. Hierarchical edits (mesh.edits) are part
// of the surface (uniform refinement to the deepest edit level K, then a PatchTable
// on level K); costs 4^K x the faces, Unsupported above 4M level-K faces.
class OsdLimitSurface {
public:
    OsdLimitSurface();
    ~OsdLimitSurface();
    OsdLimitSurface(const OsdLimitSurface&) = delete;
    OsdLimitSurface& operator=(const OsdLimitSurface&) = delete;

    // Builds the refiner and the patch table. `mesh` must have passed checkInput;
    // BadInput (OpenSubdiv's message) when OpenSubdiv rejects its topology. Costs
    // about a second for a 10k-face mesh at isolation 10.
    // A bad edit (face, child or vertex out of range) is BadInput.
    Status build(const InputMesh& mesh, int isolation = 10);
    bool built() const;
    // The edits the surface includes (mesh.edits.size()) and the deepest edit
    // level K (0: none, or level-0 edits only).
    uint32_t editCount() const;
    int editLevel() const;

    // Position and unit normal at (u,v) of base face `face` (corners 0, 1, 2 at
    // (0,0), (1,0), (0,1)); false when the face has no limit surface (a hole, or
    // `face` out of range). The normal is (dP/du x dP/dv) normalized, 0 where that
    // cross product vanishes. build() must have succeeded. `du`, `dv`, when given,
    // receive dP/du and dP/dv in the base face's (u,v) -- with edits below level 0,
    // in the level-K sub-triangle's, whose (u,v) are 2^K times the base face's.
    bool evaluate(int face, double u, double v, double pos[3], double normal[3], double du[3] = nullptr,
                  double dv[3] = nullptr) const;

    // True where the limit surface has no normal at (face, u, v): a base-face corner
    // on a non-manifold vertex, a cone, or a crease or boundary sector of six or more
    // faces (the cases: docs/loopcheck.md); each face has its own normal there
    // (OsdCornerNormals). (u,v) must be exactly the corner.
    bool normalUndefined(int face, double u, double v) const;

    // True where the normal's direction is defined but its sign is a convention: a
    // base-face corner on a sharp corner, where PatchTable's du x dv points into the
    // surface for a sector wider than 180 degrees and looptess orients by the faces'
    // winding (docs/loopcheck.md). (u,v) must be exactly the corner.
    bool normalSignAmbiguous(int face, double u, double v) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// OpenSubdiv's refined vertices of an adaptive refinement like the baker's
// (RefineAdaptive(maxDepth), every feature isolated to the full depth), per level, in
// double; it isolates a superset of the baker's slit tips, so every vertex the baker
// makes has its match here. Ignores mesh.edits.
class OsdRefinedVertices {
public:
    OsdRefinedVertices();
    ~OsdRefinedVertices();
    OsdRefinedVertices(const OsdRefinedVertices&) = delete;
    OsdRefinedVertices& operator=(const OsdRefinedVertices&) = delete;

    // As OsdLimitSurface::build.
    Status build(const InputMesh& mesh, int maxDepth);
    // Levels built (0 before build).
    int levels() const;
    // Position of vertex `vertex` of refinement level `level` (OpenSubdiv's
    // numbering); both in range.
    const double* vertex(int level, int vertex) const;
    // OpenSubdiv's vertex of level `level` (>= 1) that is the child of level-1's
    // vertex `parent`, or of the edge between its vertices `a` and `b`; -1 when
    // refinement made none, an index is out of range, or `a`-`b` is not exactly
    // one edge.
    int vertexChild(int level, int parent) const;
    int edgeChild(int level, int a, int b) const;
    // The limit position of vertex `vertex` of level `level`: Sdc's limit mask
    // (Loop's closed forms, exact for a rule that no longer changes) at the first
    // level of its chain of vertex children where no semi-sharp edge or vertex
    // sharpness is left around it, over that level's points. False when refinement
    // stops first, or an index is out of range.
    bool limitPosition(int level, int vertex, double p[3]) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// --- OsdCornerNormals ----------------------------------------------------------------
//
// The normal of a face at its corners, independent of looptess's tables and of
// PatchTable: exact Loop refinement of the corner's 1-ring, level after level, then
// the normal of the face's own corner triangle, wound like the face:
//
//        c2                 level 0 face (c0, c1, c2); at level L its descendant
//        | .                at corner c0 is (c0', a, b), with c0' the level-L
//        |   .              child of c0. normal = (a - c0') x (b - c0'), the way
//        b     .            the face winds (counter-clockwise as drawn)
//        | .     .
//        c0'-a-----c1
//
// Where the surface has a tangent plane this converges to it; where it has none it
// is the face's own limit (how, and how fast: docs/loopcheck.md).
class OsdCornerNormals {
public:
    OsdCornerNormals();
    ~OsdCornerNormals();
    OsdCornerNormals(const OsdCornerNormals&) = delete;
    OsdCornerNormals& operator=(const OsdCornerNormals&) = delete;

    // Level 0 of `mesh` (creases, corners, boundary and crease options; holes and
    // edits are not followed). BadInput when OpenSubdiv rejects the topology.
    Status build(const InputMesh& mesh);
    bool built() const;

    struct Result {
        double normal[3] = {0, 0, 0};  // unit
        int levels = 0;                // levels refined
        double lastStep = 0;           // radians the normal turned in the last level
        bool degenerate = false;       // the face has no normal there: its corner triangle
                                       // has no area at level 0 nor 1 (two corners at one
                                       // point, as refinement keeps them)
    };
    // Normal of base face `face` at its corner `corner` (0..2), refined until it
    // turns less than 1e-9 radians per level with no semi-sharp sharpness left
    // around the corner, after at least as many levels as the corner's vertex has
    // faces (a face k steps around reaches the corner at level k) and
    // `drawnLevels`, or until the corner triangle's angle falls below 1e-9 (double
    // precision), or `maxLevels` levels; turned to the side the face is drawn on
    // (spec "The side"): the side its corner triangle faces at most of the levels 0
    // .. drawnLevels (the asset's depth), as many: level 0's; drawnLevels < 0: as
    // refined (a tangent plane's, the limit's side). False when OpenSubdiv
    // refuses a refined 1-ring or `face` is out of range. Remembers each answer (a
    // checker samples a corner once per face and case); not for concurrent calls.
    bool normal(uint32_t face, int corner, int maxLevels, int drawnLevels, Result& out) const;

private:
    bool refine(uint32_t face, int corner, int maxLevels, int drawnLevels, Result& out) const;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace lt

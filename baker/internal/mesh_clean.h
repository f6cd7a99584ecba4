// Private to the baker (its tests reach it through looptess_baker_internal): input
// cleaning, the one implementation the OBJ and glTF readers share (baker.h,
// InputCleaning and CleaningReport; README "Input cleaning").
//
// A face is a cycle of control vertex indices (after welding, for glTF). Each face,
// in input order:
//   1. repair: consecutive repeats go (a a b c -> a b c), then spikes (x y x -> x:
//      out to y and back on the same edge), around the cycle, until none is left;
//   2. degenerate: fewer than 3 distinct vertices left, or a vertex still passed
//      twice (a figure-eight: two loops through one vertex) -> dropped. Splitting a
//      figure-eight into its loops would guess at what its author meant;
//   3. zero area: every fan triangle (c0, ci, ci+1) has zero area by zeroAreaTriangle
//      (but a triangle with two corners at one position is not tested: it stays, and
//      checkInput warns about its zero area; glTF's weld makes it no base face). Such
//      a face waits for the whole mesh (settleZeroArea): one that shares an edge with
//      a face of nonzero area is sewn into the surface, a sliver closing a T-junction
//      or a collapsed edge loop, and stays (dropping it would open a slit that
//      subdivision shows as a crack, or leave two faces misoriented at an edge it made
//      non-manifold); the others are dropped;
//   4. duplicate: the same cycle as a face kept before, in either winding -> dropped.
#pragma once

#include "looptess/tools/baker.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace lt {

// Edge a-b either way, as one key.
inline uint64_t undirectedEdge(uint32_t a, uint32_t b) { return a < b ? uint64_t(a) << 32 | b : uint64_t(b) << 32 | a; }

// Drops the creases of `mesh` on an edge that no face of it has and that is in
// `removedEdges` (the edges of the faces cleaning dropped or repaired, as written; it
// is sorted here): their edge is gone with those faces. A crease on an edge no face
// ever had stays, for checkInput to refuse. Counts them in mesh.cleaning and in one
// warning "<name>: ...". O(faces log faces).
void dropCreasesOfRemovedEdges(InputMesh& mesh, std::vector<uint64_t>& removedEdges, const std::string& name);

// Whether triangle (a, b, c) (3 floats each) has zero area relative to its longest
// edge: |(b - a) x (c - b)| <= 1e-7 * longest^2, in double (checkInput's warning).
bool zeroAreaTriangle(const float* a, const float* b, const float* c);

// Removes the triangles of `mesh` whose `drop` flag is set, from faces and (when it
// has 6 a triangle) faceUVs; holes and edits must not name triangles yet.
void eraseTriangles(InputMesh& mesh, const std::vector<uint8_t>& drop);

class FaceCleaner {
public:
    enum class Fate : uint8_t { Kept, Repaired, Degenerate, ZeroArea, Duplicate };

    // A face clean() found of zero area, emitted as kept until settleZeroArea: its
    // triangles [first, first + count) of the mesh, whether repair changed it.
    struct Pending {
        uint64_t tag = 0;
        uint32_t first = 0, count = 0;
        bool repaired = false;
    };

    // `positions` (3 floats a vertex) must hold every vertex a face names when that
    // face is cleaned; it may grow in between (the OBJ reader's).
    FaceCleaner(const std::vector<float>& positions, InputCleaning mode);

    // Cleans the face `vertices[0..n)`; `tag` is the caller's name for it (an OBJ
    // line; a glTF primitive and triangle), handed back to `where` in messages.
    // `corners` receives the positions (0..n-1) of the corners kept, in order, empty
    // when the face is dropped. Repaired, Degenerate and Duplicate are counted in
    // report(); a kept or repaired face is remembered for the duplicate test.
    // ZeroArea keeps `corners`: the caller emits the face as it would a kept one and
    // hands it to settleZeroArea (lastRepaired() says whether repair changed it).
    // With InputCleaning::Keep every face is Kept whole. O(n log n) in the face's
    // corners; duplicates by hashing.
    Fate clean(const uint32_t* vertices, size_t n, uint64_t tag, std::vector<uint32_t>& corners);
    bool lastRepaired() const { return lastRepaired_; }

    // Once every face is in `mesh`: which of the `pending` zero-area faces go (their
    // positions in `pending`, ascending): those none of whose triangles shares an edge
    // with a triangle of `mesh` outside `pending`. Counts them, and the repaired ones
    // that stay. O(triangles log triangles).
    std::vector<size_t> settleZeroArea(const InputMesh& mesh, const std::vector<Pending>& pending);

    const CleaningReport& report() const { return report_; }

    // What is wrong with the face that clean() last gave `fate` (not Kept), and what
    // becomes of it without InputCleaning::Refuse: "repeats a vertex (refused in
    // strict mode; repaired otherwise)". `where` names a tag.
    std::string defect(Fate fate, const std::function<std::string(uint64_t)>& where) const;

    // One warning a kind met, in the order of CleaningReport's fields: "<prefix>: 2
    // <noun>s with repeated vertices repaired (first: <where(tag)>): ..."; `noun` is
    // "polygon" or "triangle".
    void warn(const std::string& prefix, const std::string& noun, const std::function<std::string(uint64_t)>& where,
              std::vector<std::string>& warnings) const;

private:
    void repair(const uint32_t* v, size_t n, std::vector<uint32_t>& corners) const;
    bool distinct(const uint32_t* v, const std::vector<uint32_t>& corners);
    bool zeroArea(const uint32_t* v, const std::vector<uint32_t>& corners) const;
    bool duplicate(const uint32_t* v, const std::vector<uint32_t>& corners, uint64_t tag);
    void count(Fate fate, uint64_t tag);

    const std::vector<float>& positions_;
    InputCleaning mode_;
    CleaningReport report_;
    uint64_t first_[5] = {};        // per Fate: the first face's tag (tags grow in input order)
    uint64_t firstOriginal_ = 0;    // the face the first duplicate repeats
    uint64_t lastOriginal_ = 0;     // the face the last duplicate repeats
    bool lastFigureEight_ = false;  // the last Degenerate face still had 3 corners or more
    bool lastRepaired_ = false;
    std::vector<uint32_t> scratch_;
    // Kept faces: cycle f is cycles_[start_[f] .. start_[f + 1]), from its smallest
    // vertex toward its smaller neighbour; hashes_[f] its hash, tags_[f] its tag.
    // slots_: an open-addressing table (linear probing, at most half full) of f + 1.
    std::vector<uint32_t> cycles_;
    std::vector<size_t> start_{0};
    std::vector<uint64_t> hashes_, tags_;
    std::vector<uint32_t> slots_;
};

}  // namespace lt

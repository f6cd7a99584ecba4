// looptess/tools/mesh.h -- the control mesh as the readers produce it and the
// OpenSubdiv bridge, the baker and the checker consume it (looptess_mesh). Tool tier:
// an engine never needs it. Plain data; the one function does no I/O.
#pragma once

#include "looptess/asset.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lt {

// What the readers do with faces subdivision cannot use as written (README "Input
// cleaning"): a polygon or triangle with a repeated vertex, one of zero area, one with
// the vertices of an earlier face. Control vertices are never renumbered.
enum class InputCleaning : uint8_t {
    Repair,  // repair or drop them, counted in InputMesh::cleaning and in one warning a kind
    Refuse,  // the first is a BadInput error naming it (loopbake --strict)
    Keep,    // read every face as written: checkInput then refuses a repeated vertex.
             // For topology studied as it is (OpenSubdiv's test shapes)
};

// What InputCleaning::Repair did to one control mesh, one count per face as written,
// by what became of it (a repaired polygon later dropped counts as dropped).
struct CleaningReport {
    uint32_t repaired = 0;           // repeated vertices removed, the rest kept
    uint32_t droppedDegenerate = 0;  // fewer than 3 distinct vertices left, or one
                                     // still twice (a figure-eight)
    uint32_t droppedZeroArea = 0;    // every fan triangle of zero area (corners on a
                                     // line), no edge shared with a face of nonzero area
    uint32_t droppedDuplicate = 0;   // the vertices of an earlier face, either winding
    uint32_t droppedCreases = 0;     // OBJ crease tags on edges only dropped faces had
    uint32_t collapsed = 0;          // glTF triangles with two corners at one position:
                                     // no base face (in the cage, or dropped by parseGltf);
                                     // not a cleaning, counted alike
    // Whether faces were dropped or repaired: triangle indices are not the input's.
    bool renumbered() const { return repaired || droppedDegenerate || droppedZeroArea || droppedDuplicate; }
};

// A triangle control mesh as read from a file, before any checks.
struct InputMesh {
    std::vector<float> positions;  // 3 per vertex
    std::vector<uint32_t> faces;   // 3 per triangle, counter-clockwise
    std::vector<float> faceUVs;    // 6 per triangle (uv per corner, glTF's convention:
                                   // v down from the image's top), or empty
    struct Crease {
        uint32_t a, b;
        float sharpness;
    };
    struct Corner {
        uint32_t vertex;
        float sharpness;
    };
    std::vector<Crease> creases;  // edge sharpness (>= 10: infinitely sharp)
    std::vector<Corner> corners;  // vertex sharpness
    std::vector<uint32_t> holes;  // triangle indices (after triangulation)
    // Hierarchical vertex edit (OBJ `t vertexedit`, or an --edits side-car): corner
    // `vertex` (0..2) of sub-triangle (face; path[0] .. path[k-1]) is edited at level
    // k = path.size(), after level k's points, before level k+1's. Children are in
    // Loop's order: child i (0..2) keeps corner i in position i, as (v0, e0, e2),
    // (e0, v1, e1), (e2, e1, v2); child 3 is the middle triangle (e1, e2, e0), e_i
    // the edge point of edge i -> i+1. k = 0 edits a control point.
    struct VertexEdit {
        uint32_t face = 0;          // triangle index (after triangulation)
        std::vector<uint8_t> path;  // children, each 0..3
        uint8_t vertex = 0;         // 0..2
        EditOp op = EditOp::Add;
        float value[3] = {0, 0, 0};
    };
    std::vector<VertexEdit> edits;  // in input order
    // The boundary rule: an OBJ's interpolateboundary tag, else edge-only; a reader's
    // InputOptions::boundary (loopbake --boundary) overrides both.
    BoundaryInterpolation boundary = BoundaryInterpolation::EdgeOnly;
    CreaseMethod creaseMethod = CreaseMethod::Normal;
    std::vector<std::string> warnings;  // non-fatal findings, for the CLI to print
    CleaningReport cleaning;            // what the reader's input cleaning did

    uint32_t vertexCount() const { return uint32_t(positions.size() / 3); }
    uint32_t faceCount() const { return uint32_t(faces.size() / 3); }
    // The deepest level an edit names (its path length); 0 without edits.
    uint32_t editDepth() const;
};

// The boundary rules by the names loopbake's and loopcheck's --boundary take: "none",
// "edge" (EdgeOnly) and "edge-and-corner". parseBoundaryOption is false for any other
// text and leaves `out` as it was.
const char* boundaryOptionName(BoundaryInterpolation b);
bool parseBoundaryOption(std::string_view text, BoundaryInterpolation& out);

}  // namespace lt

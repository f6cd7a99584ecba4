// Test oracle: OpenSubdiv's own refinement and limit surface for a control mesh,
// in double precision. Used to check the baked tables and the CPU evaluator.
// GoogleTest wrappers (a failure to build fails the calling test) over the library
// loopcheck uses too, looptess_osd_reference (check/include/looptess/tools/osd_reference.h).
#pragma once

#include "looptess/tools/baker.h"
#include "looptess/tools/osd_reference.h"

#include <memory>
#include <string>
#include <vector>

namespace lt::test {

// Reads an OBJ from disk into an InputMesh as written, without input cleaning (fails
// the calling test on error): the oracle tests study OpenSubdiv's shapes as they are.
InputMesh loadObj(const std::string& path);

// The corpus shapes and meshes the accuracy tests run on.
std::vector<std::string> corpusShapes();   // tests/data/corpus/opensubdiv-loop/*.obj
std::string corpusMesh(const char* name);  // tests/data/corpus/meshes/<name>

// Diagonal of the control mesh's bounding box.
double bboxDiagonal(const InputMesh& mesh);

// OpenSubdiv's limit surface through a double-precision PatchTable at isolation
// 10 (exact except within about 2^-10 of an extraordinary vertex; exact at patch
// corners).
class OsdLimit {
public:
    explicit OsdLimit(const InputMesh& mesh, int isolation = 10);
    ~OsdLimit();
    // Position and unit normal at (u,v) of base face `face`; false if the face has
    // no limit surface (a hole).
    bool evaluate(int face, double u, double v, double pos[3], double normal[3]) const;

    // True where the limit surface has no normal at (face, u, v): see
    // OsdLimitSurface::normalUndefined (each face has its own there).
    bool normalUndefined(int face, double u, double v) const;

private:
    OsdLimitSurface impl_;
};

}  // namespace lt::test

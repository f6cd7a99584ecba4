// InputMesh (looptess/tools/mesh.h).
#include "looptess/tools/mesh.h"

#include <algorithm>

namespace lt {

uint32_t InputMesh::editDepth() const {
    size_t k = 0;
    for (const VertexEdit& e : edits) k = std::max(k, e.path.size());
    return uint32_t(k);
}

const char* boundaryOptionName(BoundaryInterpolation b) {
    switch (b) {
    case BoundaryInterpolation::None: return "none";
    case BoundaryInterpolation::EdgeAndCorner: return "edge-and-corner";
    case BoundaryInterpolation::EdgeOnly: break;
    }
    return "edge";
}

bool parseBoundaryOption(std::string_view text, BoundaryInterpolation& out) {
    for (BoundaryInterpolation b :
         {BoundaryInterpolation::None, BoundaryInterpolation::EdgeOnly, BoundaryInterpolation::EdgeAndCorner})
        if (text == boundaryOptionName(b)) {
            out = b;
            return true;
        }
    return false;
}

}  // namespace lt

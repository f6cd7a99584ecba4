// InputMesh (looptess/tools/mesh.h).
#include "looptess/tools/mesh.h"

#include <algorithm>

namespace lt {

uint32_t InputMesh::editDepth() const {
    size_t k = 0;
    for (const VertexEdit& e : edits) k = std::max(k, e.path.size());
    return uint32_t(k);
}

}  // namespace lt

// tests/install/consumer.cpp -- what an engine's tool chain does with an installed
// looptess: bake a control mesh, write and read the GLB, evaluate it on the CPU, and
// draw it headless on the first Vulkan device (evaluate_and_draw.h). Exit 0 when all
// of it worked and the image shows the surface.
#include <looptess/asset.h>
#include <looptess/tools/baker.h>
#include <looptess/runtime.h>

#include "evaluate_and_draw.h"

#include <cstdio>
#include <memory>
#include <vector>

int fail(const char* step, const lt::Status& st) {
    std::fprintf(stderr, "consumer: %s: %s\n", step, st.message.c_str());
    return 1;
}

int main() {
    // A tetrahedron, counter-clockwise seen from outside; its limit surface (a blob
    // about a third its size) lies inside the clip volume.
    lt::InputMesh mesh;
    mesh.positions = {-1.5f, -1.5f, 0.2f, 1.5f, -1.5f, 0.2f, 0.0f, 1.5f, 0.2f, 0.0f, 0.0f, 0.8f};
    mesh.faces = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};
    lt::BakeSettings settings;
    settings.maxDepth = 2;
    lt::Asset baked, loaded;
    if (lt::Status st = lt::bake(mesh, settings, baked); !st) return fail("bake", st);
    std::vector<uint8_t> glb;
    if (lt::Status st = lt::writeAssetGlb(baked, glb); !st) return fail("writeAssetGlb", st);
    if (lt::Status st = lt::readAssetGlb(glb.data(), glb.size(), "tetrahedron.glb", loaded); !st)
        return fail("readAssetGlb", st);

    std::printf("consumer: baked, wrote and read a %zu-byte GLB\n", glb.size());
    return evaluateAndDraw("consumer", loaded);
}

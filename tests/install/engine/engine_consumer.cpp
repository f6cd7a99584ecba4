// tests/install/engine/engine_consumer.cpp -- an engine with a runtime-only install:
// load a baked GLB, evaluate it on the CPU, draw it headless on the first Vulkan
// device (../evaluate_and_draw.h). Exit 0 when all of it worked and the image shows the
// surface.
//
//   engine_consumer ASSET.glb
#include <looptess/asset.h>
#include <looptess/version.h>

#include "../evaluate_and_draw.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

static int fail(const char* step, const lt::Status& st) {
    std::fprintf(stderr, "engine_consumer: %s: %s\n", step, st.message.c_str());
    return 1;
}

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: engine_consumer ASSET.glb\n");
        return 1;
    }
    std::ifstream file(argv[1], std::ios::binary);
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
    lt::Asset asset;
    if (lt::Status st = lt::readAssetGlb(bytes.data(), bytes.size(), argv[1], asset); !st)
        return fail("readAssetGlb", st);

    std::printf("engine_consumer: looptess %s, format layout %d\n", LOOPTESS_VERSION_STRING,
                LOOPTESS_FORMAT_LAYOUT_VERSION);
    return evaluateAndDraw("engine_consumer", asset);
}

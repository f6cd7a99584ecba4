// fuzz/usd_entry.cpp -- lt::fuzz::usd (usd_entry.h).
#include "usd_entry.h"

#include "looptess/tools/usd.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace lt::fuzz {

Status usd(const uint8_t* data, size_t size, const std::string& dir) {
    if (size >= 8 && std::memcmp(data, "PXR-USDC", 8) == 0)
        return Status::error(Status::Unsupported, "crate bytes: not fuzzed (usd_entry.h)");
    const std::string path = (std::filesystem::path(dir) / "layer.usda").string();
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    GltfScene scene;
    UsdOptions options;
    options.isolate = false;  // coverage of our code (usd_entry.h)
    Status st = parseUsdScene(path, options, scene);
    std::filesystem::remove(path);
    if (!st) return st;
    for (const GltfScene::Mesh& m : scene.meshes) {
        for (const std::vector<uint32_t>& cv : m.controlVertex)
            for (uint32_t v : cv)
                if (v >= m.mesh.vertexCount()) {
                    std::fprintf(stderr, "fuzz usd: %s: cage vertex names control vertex %u of %u\n", m.name.c_str(), v,
                                 m.mesh.vertexCount());
                    std::abort();
                }
        const Status checked = checkInput(m.mesh, m.name);
        if (!checked && checked.code != Status::BadInput) {
            std::fprintf(stderr, "fuzz usd: %s: checkInput: %s\n", m.name.c_str(), checked.message.c_str());
            std::abort();
        }
    }
    return st;
}

}  // namespace lt::fuzz

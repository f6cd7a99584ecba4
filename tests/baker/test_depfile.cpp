// tests/baker/test_depfile.cpp -- loopbake --depfile and cmake/LooptessBake.cmake (
// item 6): a build that bakes a glTF with looptess_bake() bakes again after its
// texture, its buffer file or its edits side-car changes, and only then.
#include "tool_run.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

void writeFile(const fs::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A tetrahedron whose buffer and texture are files beside it:
//   tetra.bin = | 4 positions (48 bytes) | 12 u16 indices (24 bytes) |
std::string tetraGltf(const fs::path& dir) {
    const float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint16_t indices[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    std::string bin(reinterpret_cast<const char*>(positions), sizeof positions);
    bin.append(reinterpret_cast<const char*>(indices), sizeof indices);
    writeFile(dir / "tetra.bin", bin);
    writeFile(dir / "tex map.png", "not decoded: loopbake only embeds it");
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
      "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
      "textures": [{"source": 0}], "images": [{"uri": "tex%20map.png"}],
      "buffers": [{"uri": "tetra.bin", "byteLength": 72}],
      "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 1]},
                    {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}]})";
}

class Depfile : public ::testing::Test {
protected:
    fs::path dir_ = fs::temp_directory_path() / ("looptess_depfile_" + std::to_string(getpid()));
    void SetUp() override { fs::create_directories(dir_ / "src"); }
    void TearDown() override { fs::remove_all(dir_); }

    // Builds the project; the output's modification time after it.
    fs::file_time_type build() {
        const std::string cmd = std::string("'") + CMAKE_EXE + "' --build '" + (dir_ / "build").string() + "' > '" +
                                (dir_ / "build.log").string() + "' 2>&1";
        EXPECT_EQ(std::system(cmd.c_str()), 0) << readFile(dir_ / "build.log");
        return fs::last_write_time(dir_ / "build" / "tetra.glb");
    }
    void touch(const char* file) { fs::last_write_time(dir_ / "src" / file, fs::file_time_type::clock::now()); }
};

TEST_F(Depfile, ABuildBakesAgainWhenWhatLoopbakeReadChanges) {
    const fs::path src = dir_ / "src";
    writeFile(src / "tetra.gltf", tetraGltf(src));
    writeFile(src / "edits.json",
              R"({"edits": [{"face": 0, "path": [1], "vertex": 0, "op": "add", "value": [0, 0.1, 0]}]})");
    writeFile(src / "CMakeLists.txt", std::string(R"(cmake_minimum_required(VERSION 3.20)
project(bake NONE)
set(LOOPTESS_LOOPBAKE ")") + LOOPBAKE_EXE +
                                          R"(")
include(")" + std::string(LOOPTESS_SOURCE_DIR) +
                                          R"(/cmake/LooptessBake.cmake")
looptess_bake(tetra INPUT ${CMAKE_CURRENT_SOURCE_DIR}/tetra.gltf OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/tetra.glb
              OPTIONS --max-depth 2 --edits ${CMAKE_CURRENT_SOURCE_DIR}/edits.json)
)");
    const std::string configure = std::string("'") + CMAKE_EXE + "' -S '" + src.string() + "' -B '" +
                                  (dir_ / "build").string() + "' -G '" + CMAKE_GENERATOR_NAME + "' > '" +
                                  (dir_ / "configure.log").string() + "' 2>&1";
    ASSERT_EQ(std::system(configure.c_str()), 0) << readFile(dir_ / "configure.log");

    const fs::file_time_type first = build();
    const std::string dep = readFile(dir_ / "build" / "tetra.glb.d");
    for (const char* listed : {"tetra.gltf", "tetra.bin", "tex\\ map.png", "edits.json"})
        EXPECT_NE(dep.find(listed), std::string::npos) << listed << " missing from the depfile:\n" << dep;
    EXPECT_EQ(build(), first) << "nothing changed: no bake";
    fs::file_time_type last = first;
    for (const char* file : {"tex map.png", "edits.json", "tetra.bin", "tetra.gltf"}) {
        SCOPED_TRACE(file);
        touch(file);
        const fs::file_time_type again = build();
        EXPECT_GT(again, last) << "changed: baked again";
        EXPECT_EQ(build(), again) << "nothing changed since: no bake";
        last = again;
    }
}

}  // namespace

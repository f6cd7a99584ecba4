// test_fuzz_regressions.cpp -- every fuzzer finding (tests/data/fuzz), replayed
// through the fuzzer's own entry point (fuzz/entry_points.h). A finding's file is
// named FUZZER_what_it_found.EXT; FUZZER (asset, obj, gltf, evaluate) picks the
// entry point. Each finding also has a named test stating the expected outcome.
// The sanitizer build (scripts/dev.sh sanitize) runs these under ASan + UBSan.
#include "entry_points.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

const fs::path kDir = fs::path(LOOPTESS_TEST_DATA) / "fuzz";

std::vector<uint8_t> bytesOf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in) << path;
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// An empty directory for parseGltf's sibling files, removed afterwards.
struct EmptyDir {
    std::string path;
    EmptyDir() {
        char pattern[] = "/tmp/looptess-fuzz-test-XXXXXX";
        path = mkdtemp(pattern) ? pattern : "";
    }
    ~EmptyDir() {
        if (!path.empty()) rmdir(path.c_str());
    }
};

// Runs the entry point named by the file's prefix; the caller checks the status.
lt::Status replay(const std::string& file) {
    const std::vector<uint8_t> bytes = bytesOf(kDir / file);
    const std::string prefix = file.substr(0, file.find('_'));
    if (prefix == "asset") return lt::fuzz::asset(bytes.data(), bytes.size());
    if (prefix == "obj") return lt::fuzz::obj(bytes.data(), bytes.size());
    if (prefix == "evaluate") return lt::fuzz::evaluate(bytes.data(), bytes.size());
    if (prefix == "scene") return lt::fuzz::scene(bytes.data(), bytes.size());
    if (prefix == "gltf") {
        EmptyDir dir;
        return lt::fuzz::gltf(bytes.data(), bytes.size(), dir.path);
    }
    ADD_FAILURE() << file << ": no entry point for prefix '" << prefix << "'";
    return lt::Status::error(lt::Status::Internal, "unknown prefix");
}

// Every file replays without a crash or sanitizer report (it is its own test so a
// finding added without a named test still runs).
TEST(FuzzRegression, EveryFindingReplays) {
    for (const fs::directory_entry& e : fs::directory_iterator(kDir)) {
        const std::string file = e.path().filename().string();
        if (file == "README.md") continue;
        SCOPED_TRACE(file);
        replay(file);
    }
}

// fuzz_gltf's first input crashed (ASan bad-free in ~TinyGLTF): the fuzz target's
// link line had libdraco, which exports its own older tinygltf, ahead of
// libtinygltf, so tinygltf's loader ran with another class layout. Any glTF that
// reaches tinygltf shows it; this is the seed it hit. This test target links the
// same libraries in the same shape (fix: draco::draco last, fuzz/CMakeLists.txt).
TEST(FuzzRegression, GltfTinygltfLinkOrderBadFree) {
    const lt::Status st = replay("gltf_tinygltf_link_order_bad_free.gltf");
    EXPECT_TRUE(st) << st.message;
}

}  // namespace

// OpenSubdiv oracle for the accuracy tests (see osd_reference.h): GoogleTest
// wrappers over looptess_osd_reference.
#include "osd_reference.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lt::test {

InputMesh loadObj(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in.good()) << "cannot open " << path;
    std::stringstream text;
    text << in.rdbuf();
    InputMesh mesh;
    std::string body = text.str();
    InputOptions asWritten;  // OpenSubdiv's shapes as they are (back-to-back sheets)
    asWritten.cleaning = InputCleaning::Keep;
    Status st = parseObj(body, path, asWritten, mesh);
    EXPECT_TRUE(st) << st.message;
    return mesh;
}

std::vector<std::string> corpusShapes() {
    std::vector<std::string> shapes;
    for (const auto& e : std::filesystem::directory_iterator(corpusDir() + "/opensubdiv-loop"))
        if (e.path().extension() == ".obj") shapes.push_back(e.path().string());
    std::sort(shapes.begin(), shapes.end());
    return shapes;
}

std::string corpusMesh(const char* name) { return corpusDir() + "/meshes/" + name; }

double bboxDiagonal(const InputMesh& mesh) { return boundingBoxDiagonal(mesh.positions); }

OsdLimit::OsdLimit(const InputMesh& mesh, int isolation) {
    const Status st = impl_.build(mesh, isolation);
    EXPECT_TRUE(st) << st.message;
}

OsdLimit::~OsdLimit() = default;

bool OsdLimit::evaluate(int face, double u, double v, double pos[3], double normal[3]) const {
    return impl_.evaluate(face, u, v, pos, normal);
}

bool OsdLimit::normalUndefined(int face, double u, double v) const { return impl_.normalUndefined(face, u, v); }

}  // namespace lt::test

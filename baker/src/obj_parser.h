// obj_parser.h -- private to the OBJ reader (obj_reader.cpp: statements, faces,
// triangulation, the run; obj_tags.cpp: OpenSubdiv's tags, read and applied): the
// parser both halves implement. lt::parseObj (baker.h) is its one user.
#pragma once

#include "looptess/tools/baker.h"
#include "mesh_clean.h"
#include "obj_text.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lt::obj {

class ObjParser {
public:
    ObjParser(const std::string& name, const InputOptions& options, InputMesh& mesh)
        : name_(name), options_(options), mesh_(mesh), cleaner_(mesh.positions, options.cleaning) {}

    Status run(std::string_view text);

private:
    Status fail(const std::string& what) const {
        return Status::error(Status::BadInput, name_ + ":" + std::to_string(line_) + ": " + what);
    }
    Status failAt(size_t line, const std::string& what) const {
        return Status::error(Status::BadInput, name_ + ":" + std::to_string(line) + ": " + what);
    }
    void warn(const std::string& what) { mesh_.warnings.push_back(name_ + ": " + what); }
    void warnUnknown(const std::string& kind, std::string_view word);

    Status statement(std::string_view line);
    Status readNumbers(Tokens& tokens, const char* what, size_t minCount, size_t maxCount, float* out, size_t& count);
    Status vertex(Tokens& tokens);
    Status texcoord(Tokens& tokens);
    Status resolve(std::string_view tok, size_t count, const char* what, uint32_t& out);
    Status corner(std::string_view tok, uint32_t& v, int64_t& vt);
    Status face(Tokens& tokens);
    void triangulate();
    Status tag(Tokens& tokens);
    Status checkTagShape(const Tag& t);
    Status readVertexEdit(Tag& t);
    Status applyTag(const Tag& t);
    Status applyCrease(const Tag& t);
    Status applyCorner(const Tag& t);
    Status applyHole(const Tag& t);
    Status applyVertexEdit(const Tag& t);
    Status sharpness(const Tag& t, float s);
    Status vertexIndex(const Tag& t, int64_t i, uint32_t& out);
    void finishUVs();
    Status settleZeroArea();
    static std::string lineName(uint64_t line) { return "line " + std::to_string(line); }

    const std::string& name_;
    const InputOptions& options_;
    InputMesh& mesh_;
    size_t line_ = 0;

    std::vector<float> uvs_;              // 2 per vt
    std::vector<uint32_t> polyVerts_;     // scratch: current face
    std::vector<int64_t> polyUVs_;        // scratch: vt index per corner, -1 none
    std::vector<uint32_t> polyFirstTri_;  // triangle range of polygon i: [i, i+1), once triangulated
    // Every polygon's corners kept by cleaning, in file order (triangulate() splits
    // them once all are read): keptCounts_ per polygon (0: dropped), keptVerts_ and
    // keptUVs_ (vt index, -1 none) per corner.
    std::vector<uint32_t> keptCounts_, keptVerts_;
    std::vector<int64_t> keptUVs_;
    size_t triangles_ = 0;  // what keptCounts_ will become
    FaceCleaner cleaner_;
    std::vector<uint32_t> kept_;            // scratch: the current face's corners kept
    std::vector<uint32_t> polygonCorners_;  // Triangulation::polygonCorners
    struct Polygon {
        uint32_t line;
        uint8_t fate;  // FaceCleaner::Fate, final once settleZeroArea ran
        bool uv;
    };
    std::vector<Polygon> polygons_;               // every polygon of the file
    std::vector<FaceCleaner::Pending> zeroArea_;  // for settleZeroArea
    std::vector<uint64_t> removedEdges_;          // edges of the polygons cleaning changed
    std::vector<std::string> unknown_;            // keywords already warned about
    bool unknownOverflow_ = false;
    std::vector<Tag> tags_;
    std::vector<uint8_t> holePolygon_;  // polygon already made a hole
    size_t boundaryTag_ = 0;            // the line of the interpolateboundary tag applied last
};

}  // namespace lt::obj

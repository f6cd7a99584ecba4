// bench/gen_mesh_obj -- writes one of the bench's generated meshes as an OBJ, so
// loopbake (and any other tool) can be run on it as a user would.
//
//   gen_mesh_obj NAME OUT.obj      NAME: torus or scan1m (gen_mesh.h)
//
// The same bytes on every run and machine: positions in shortest round-trip form
// (std::to_chars), so the OBJ reads back to the generated floats exactly. Exit
// status: 0 written, 1 usage error, 4 write failed.
#include "gen_mesh.h"

#include "looptess/tools/file_io.h"

#include <charconv>
#include <cstdio>
#include <string>

namespace {

void append(std::string& out, float x) {
    char buf[32];
    const auto res = std::to_chars(buf, buf + sizeof(buf), x);
    out.append(buf, res.ptr);
}

void append(std::string& out, uint32_t x) {
    char buf[16];
    const auto res = std::to_chars(buf, buf + sizeof(buf), x);
    out.append(buf, res.ptr);
}

std::string toObj(const lt::InputMesh& mesh, const std::string& comment) {
    std::string out = "# " + comment + "\n";
    out.reserve(mesh.positions.size() * 12 + mesh.faces.size() * 8);
    for (size_t i = 0; i + 2 < mesh.positions.size(); i += 3) {
        out += 'v';
        for (int k = 0; k < 3; ++k) {
            out += ' ';
            append(out, mesh.positions[i + k]);
        }
        out += '\n';
    }
    for (size_t f = 0; f + 2 < mesh.faces.size(); f += 3) {
        out += 'f';
        for (int k = 0; k < 3; ++k) {
            out += ' ';
            append(out, mesh.faces[f + k] + 1);
        }
        out += '\n';
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    ltbench::TorusParams params;
    if (argc != 3 || !ltbench::generatedParams(argv[1], params)) {
        std::fputs("usage: gen_mesh_obj torus|scan1m OUT.obj\n", stderr);
        return 1;
    }
    const lt::InputMesh mesh = ltbench::makeTorus(params);
    const std::string comment = std::string("gen_mesh_obj ") + argv[1] + ": torus " + std::to_string(params.around) +
                                "x" + std::to_string(params.across) + " cells, 1 in " +
                                std::to_string(params.flipOneIn) + " diagonals flipped";
    const std::string obj = toObj(mesh, comment);
    lt::Status st = lt::writeFileAtomic(argv[2], reinterpret_cast<const uint8_t*>(obj.data()), obj.size());
    if (!st) {
        std::fprintf(stderr, "gen_mesh_obj: %s\n", st.message.c_str());
        return 4;
    }
    std::fprintf(stderr, "gen_mesh_obj: %s: %u vertices, %u triangles, %u extraordinary\n", argv[2], mesh.vertexCount(),
                 mesh.faceCount(), ltbench::countExtraordinary(mesh));
    return 0;
}

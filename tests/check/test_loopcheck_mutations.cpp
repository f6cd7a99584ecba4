// tests/check/test_loopcheck_mutations.cpp -- loopcheck's sensitivity: one
// defect at a time planted in a good baked file, as a wrong baker would write it
// (a consistent GLB, tables uncompressed so the test edits them in place), then
// `loopcheck ASSET --source INPUT`. Each defect must fail with one of its rules, on
// a line that names the mesh and where the defect is; one N1 catches, N1 catches
// without --source too. The assets: a corpus shape
// with semi-sharp creases, an open real mesh with texture coordinates, an open CAD
// part, and a multi-mesh glTF scene (its first surface is edited). The table of
// which rule caught what is printed as "[ figures  ]" lines.
#include "format_fixture.h"
#include "sanitizer.h"
#include "tool_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using fmttest::Glb;
using fmttest::Json;

fs::path workDir() {
    static const fs::path d = fs::temp_directory_path() / ("looptess_loopcheck_mutations_" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
}

// Levels the default --tess list draws from (F <= 8 reaches depth 3).
constexpr size_t kCheckedLevels = 4;

// The surface's first level l < kCheckedLevels (and l < levels) whose `prop` accessor
// holds at least one element; -1 when none does.
int firstLevelWith(Glb& g, const char* prop) {
    Json& levels = g.ext()["levels"];
    for (size_t l = 0; l < std::min(levels.size(), kCheckedLevels); ++l)
        if (levels[l].contains(prop) && g.doc["accessors"][levels[l][prop].get<int>()]["count"].get<size_t>() > 0)
            return int(l);
    return -1;
}

float floatAt(Glb& g, int acc, size_t i) {
    float f;
    std::memcpy(&f, g.element(acc, i), 4);
    return f;
}

// A defect: plants itself in `g` and says where ("" when the asset has no such
// thing, e.g. no masked stencil); `rules`: the findings that may catch it.
struct Defect {
    const char* name;
    std::vector<std::string> rules;
    std::function<std::string(Glb&)> plant;
};

std::string at(const char* prop, int level, size_t i) {
    return "levels[" + std::to_string(level) + "]." + prop + "[" + std::to_string(i) + "]";
}

const std::vector<Defect>& defects() {
    static const std::vector<Defect> d = {
        {"flipped normal stencil",
         {"A1", "N1", "S1"},
         [](Glb& g) -> std::string {
             // A masked stencil: its two tangents swapped (normal = Tu x Tv turns over).
             // Else a smooth one: its ring reversed after the first neighbour (Tv's
             // sines change sign).
             if (const int l = firstLevelWith(g, "limitMasked"); l >= 0) {
                 const int s = g.accessor(size_t(l), "limitMaskStart"), u = g.accessor(size_t(l), "limitTangentU"),
                           v = g.accessor(size_t(l), "limitTangentV");
                 for (uint32_t k = g.index(s, 0); k < g.index(s, 1); ++k) {
                     const float a = floatAt(g, u, k), b = floatAt(g, v, k);
                     g.setFloat(u, k, b);
                     g.setFloat(v, k, a);
                 }
                 return at("limitTangentU/V", l, g.index(s, 0)) + " (stencil " +
                        std::to_string(g.index(g.accessor(size_t(l), "limitMasked"), 0)) + ")";
             }
             const int l = firstLevelWith(g, "limitRing");
             if (l < 0) return "";
             const int s = g.accessor(size_t(l), "limitStart"), r = g.accessor(size_t(l), "limitRing");
             const uint32_t b = g.index(s, 0), e = g.index(s, 1);
             if (e - b < 3) return "";
             for (uint32_t i = b + 1, j = e - 1; i < j; ++i, --j) {
                 const uint32_t x = g.index(r, i);
                 g.setIndex(r, i, g.index(r, j));
                 g.setIndex(r, j, x);
             }
             return at("limitRing", l, b) + " (stencil 0, smooth)";
         }},
        {"control point moved 1e-4 of the diagonal",
         {"M1", "M2"},
         [](Glb& g) -> std::string {
             // The control vertex of the cage's vertex 0, in every cage vertex that
             // copies it (primitives share control vertices, and a cage splits at
             // texture seams), with the accessors' bounds, as a writer would.
             Json& mesh = g.doc["meshes"][0];
             auto controlOf = [&](Json& p, size_t i) -> uint32_t {
                 const Json& cage = p["extensions"][fmttest::kExt];
                 return cage.contains("controlVertex") ? g.index(cage["controlVertex"].get<int>(), i) : uint32_t(i);
             };
             const uint32_t moved = controlOf(mesh["primitives"][0], 0);
             Json& first = g.doc["accessors"][mesh["primitives"][0]["attributes"]["POSITION"].get<int>()];
             double d2 = 0;
             for (int k = 0; k < 3; ++k)
                 d2 += std::pow(first["max"][k].get<double>() - first["min"][k].get<double>(), 2);
             const float x = floatAt(g, mesh["primitives"][0]["attributes"]["POSITION"].get<int>(), 0) +
                             float(1e-4 * std::sqrt(d2));
             for (Json& p : mesh["primitives"]) {
                 if (!p.contains("extensions") || !p["extensions"].contains(fmttest::kExt)) continue;
                 const int acc = p["attributes"]["POSITION"].get<int>();
                 Json& a = g.doc["accessors"][acc];
                 bool any = false;
                 for (size_t i = 0; i < a["count"].get<size_t>(); ++i)
                     if (controlOf(p, i) == moved) g.setFloat(acc, 3 * i, x), any = true;
                 if (!any) continue;
                 a["min"][0] = std::min(a["min"][0].get<double>(), double(x));
                 a["max"][0] = std::max(a["max"][0].get<double>(), double(x));
             }
             return "POSITION[0].x";
         }},
        {"shared edge opened in one patch",
         {"W1", "A1", "S1"},
         [](Glb& g) -> std::string {
             // Point 1 of a regular patch without boundary edges (the row beside edge
             // 0, c0 -> c1) made a copy of point 4 (c0): the edge's curve moves on
             // this side only.
             Json& levels = g.ext()["levels"];
             for (size_t l = 0; l < std::min(levels.size(), kCheckedLevels); ++l) {
                 if (!levels[l].contains("regularPoints")) continue;
                 const int acc = g.accessor(l, "regularPoints");
                 const int mask = levels[l].contains("regularBoundaryMask") ? g.accessor(l, "regularBoundaryMask") : -1;
                 const size_t n = g.doc["accessors"][acc]["count"].get<size_t>() / 12;
                 for (size_t p = 0; p < n; ++p)
                     if (mask < 0 || g.index(mask, p) == 0) {
                         g.setIndex(acc, 12 * p + 1, g.index(acc, 12 * p + 4));
                         return at("regularPoints", int(l), 12 * p + 1) + " (patch " + std::to_string(p) + ")";
                     }
             }
             return "";
         }},
        {"wrong patch class",
         {"W1", "S1"},
         [](Glb& g) -> std::string {
             // A plain regular patch (RPP) of a level the checks refine past, marked
             // non-plain (NPP) on edge 0, or an NPP made plain.
             Json& levels = g.ext()["levels"];
             for (size_t l = 0; l + 1 < std::min(levels.size(), kCheckedLevels); ++l) {
                 if (!levels[l].contains("regularSplitMask")) continue;
                 const int acc = g.accessor(l, "regularSplitMask");
                 const size_t n = g.doc["accessors"][acc]["count"].get<size_t>();
                 for (size_t i = 0; i < n; ++i)
                     if (g.index(acc, i) == 0) {
                         g.setIndex(acc, i, 1);
                         return at("regularSplitMask", int(l), i) + " (RPP -> NPP)";
                     }
                 g.setIndex(acc, 0, 0);
                 return at("regularSplitMask", int(l), 0) + " (NPP -> RPP)";
             }
             return "";
         }},
        {"limit stencil weight, last bits",
         {"A3"},
         [](Glb& g) -> std::string {
             // The largest position weight of the first masked stencil, 64 ulps off
             // (bit 6 of its significand flipped).
             const int l = firstLevelWith(g, "limitMasked");
             if (l < 0) return "";
             const int s = g.accessor(size_t(l), "limitMaskStart"), w = g.accessor(size_t(l), "limitPosition");
             uint32_t best = g.index(s, 0);
             for (uint32_t k = best; k < g.index(s, 1); ++k)
                 if (std::fabs(floatAt(g, w, k)) > std::fabs(floatAt(g, w, best))) best = k;
             uint32_t bits;
             std::memcpy(&bits, g.element(w, best), 4);
             bits ^= 1u << 6;
             std::memcpy(g.element(w, best), &bits, 4);
             return at("limitPosition", l, best);
         }},
        {"crease dropped",
         {"A1"},
         [](Glb& g) -> std::string {
             // The first creased edge point's blend weight to the smallest float: the
             // smooth rule there.
             const int l = firstLevelWith(g, "creaseWeight");
             if (l < 0) return "";
             g.setFloat(g.accessor(size_t(l), "creaseWeight"), 0, std::ldexp(1.0f, -126));
             return at("creaseWeight", l, 0) + " (edge point " +
                    std::to_string(g.index(g.accessor(size_t(l), "creaseEdge"), 0)) + ")";
         }},
        {"face corners swapped",
         {"M1", "S1"},
         [](Glb& g) -> std::string {
             const int acc = fmttest::prim(g)["indices"].get<int>();
             const uint32_t b = g.index(acc, 1);
             g.setIndex(acc, 1, g.index(acc, 2));
             g.setIndex(acc, 2, b);
             return "indices[1..2] (face 0)";
         }},
        {"texture coordinate moved",
         {"M1", "M2"},
         [](Glb& g) -> std::string {
             Json& attributes = fmttest::prim(g)["attributes"];
             if (!attributes.contains("TEXCOORD_0")) return "";
             const int acc = attributes["TEXCOORD_0"].get<int>();
             g.setFloat(acc, 0, floatAt(g, acc, 0) + 0.01f);
             return "TEXCOORD_0[0].u";
         }},
    };
    return d;
}

struct AssetCase {
    std::string name;
    fs::path input;
    std::vector<std::string> options;  // loopbake's, and loopcheck's again
};

std::vector<AssetCase> assets() {
    const fs::path data = LOOPTESS_TEST_DATA, corpus = LOOPTESS_CORPUS_DIR;
    std::vector<AssetCase> out = {
        {"loop_icos_semisharp", corpus / "opensubdiv-loop" / "loop_icos_semisharp.obj", {}},
        {"avocado", data / "real" / "avocado.obj", {}},
        {"kenney_alien", data / "real" / "kenney_alien.glb", {}},
        {"pr2_l_finger", data / "real" / "pr2_l_finger.obj", {}},
    };
    return lt::test::asanSample(std::move(out), 2);
}

// The first error line of loopcheck's output ("" if none).
std::string firstError(const std::string& out) {
    const size_t e = out.find(": error ");
    if (e == std::string::npos) return "";
    const size_t begin = out.rfind('\n', e), end = out.find('\n', e);
    return out.substr(begin == std::string::npos ? 0 : begin + 1, end == std::string::npos ? end : end - begin - 1);
}

TEST(LoopcheckMutations, EveryPlantedDefectFailsWithItsRule) {
    std::printf("[ figures  ] %-20s %-42s %-14s %s\n", "asset", "defect", "caught by", "first error");
    for (const AssetCase& a : assets()) {
        SCOPED_TRACE(a.name);
        const fs::path good = workDir() / (a.name + ".glb");
        std::vector<std::string> bake = {a.input.string(), "-o", good.string(), "--compress", "none"};
        bake.insert(bake.end(), a.options.begin(), a.options.end());
        const lt::test::RunResult baked = lt::test::runTool(LOOPBAKE_EXE, bake, workDir());
        ASSERT_EQ(baked.exitCode, 0) << baked.err;
        auto check = [&](const fs::path& asset, bool source = true) {
            std::vector<std::string> args = {asset.string(), "--rays", "3000", "--no-validator"};
            if (source) args.insert(args.end(), {"--source", a.input.string()});
            args.insert(args.end(), a.options.begin(), a.options.end());
            return lt::test::runTool(LOOPCHECK_EXE, args, workDir());
        };
        const lt::test::RunResult clean = check(good);
        ASSERT_EQ(clean.exitCode, 0) << "the good file fails:\n" << clean.out << clean.err;
        std::ifstream in(good, std::ios::binary);
        const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const bool scene = Glb(bytes).doc["meshes"].size() > 1;
        for (const Defect& d : defects()) {
            SCOPED_TRACE(d.name);
            Glb g(bytes);
            const std::string where = d.plant(g);
            if (where.empty()) {
                std::printf("[ figures  ] %-20s %-42s %-14s\n", a.name.c_str(), d.name, "(not in asset)");
                continue;
            }
            const fs::path bad = workDir() / (a.name + "_bad.glb");
            const std::vector<uint8_t> out = g.bytes();
            std::ofstream(bad, std::ios::binary)
                .write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
            const lt::test::RunResult r = check(bad);
            const std::vector<std::string> ids = lt::test::loopcheckErrorIds(r.out);
            std::string caught;
            for (const std::string& rule : d.rules)
                if (std::find(ids.begin(), ids.end(), rule) != ids.end()) caught += (caught.empty() ? "" : "+") + rule;
            const std::string first = firstError(r.out);
            std::printf("[ figures  ] %-20s %-42s %-14s %s: %s\n", a.name.c_str(), d.name,
                        caught.empty() ? "MISSED" : caught.c_str(), where.c_str(), first.substr(0, 200).c_str());
            EXPECT_NE(r.exitCode, 0) << where << "\n" << r.out;
            EXPECT_FALSE(caught.empty()) << where << ": caught by none of its rules\n" << r.out;
            // What N1 catches it catches without a source too: there it confirms a
            // normal against the asset's own control mesh, never the asset's tables.
            if (std::find(ids.begin(), ids.end(), "N1") != ids.end()) {
                const std::vector<std::string> alone = lt::test::loopcheckErrorIds(check(bad, false).out);
                EXPECT_NE(std::find(alone.begin(), alone.end(), "N1"), alone.end()) << where << " without --source";
            }
            if (scene) { EXPECT_TRUE(lt::test::contains(first, "meshes[0]")) << first; }
            // Where: a face, a control vertex or a table entry.
            EXPECT_TRUE(lt::test::contains(first, "face ") || lt::test::contains(first, "vertex ") ||
                        lt::test::contains(first, "levels["))
                << first;
        }
    }
    fs::remove_all(workDir());
}

}  // namespace

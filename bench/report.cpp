// bench/report.cpp -- text table and JSON of bench_bake's figures (report.h).
#include "report.h"

#include "format.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <functional>

namespace ltbench {
namespace {

constexpr int kLabelWidth = 40, kColumnWidth = 14;

std::string ms(double seconds) { return format("%.2f", seconds * 1e3); }
std::string kib(size_t bytes) { return format("%.1f", double(bytes) / 1024.0); }
std::string count(uint64_t n) { return format("%llu", static_cast<unsigned long long>(n)); }

// Builds the table row by row: a label, one cell per mesh, a target cell.
class Table {
public:
    explicit Table(const Report& r) : r_(r) {}

    void header() {
        line(
            "figure", [](const MeshResult& m) { return m.name; }, "target");
        out_ += std::string(size_t(kLabelWidth + kColumnWidth * (r_.meshes.size() + 1)), '-') + "\n";
    }
    void section(const std::string& title) { out_ += title + "\n"; }
    void line(const std::string& label, const std::function<std::string(const MeshResult&)>& cell,
              const std::string& target = "") {
        std::string row = format("%-*s", kLabelWidth, label.c_str());
        for (const MeshResult& m : r_.meshes) row += format("%*s", kColumnWidth, cell(m).c_str());
        row += format("%*s", kColumnWidth, target.c_str());
        out_ += row.erase(row.find_last_not_of(' ') + 1) + "\n";
    }
    std::string take() { return std::move(out_); }

private:
    const Report& r_;
    std::string out_;
};

std::string verdict(bool pass) { return pass ? "PASS" : "MISS"; }

}  // namespace

std::string formatTable(const Report& r) {
    const Machine& mc = r.machine;
    std::string out = format(
        "looptess %s bench_bake%s: depth %d, median of %d runs, wall clock, ours on %u thread%s, OpenSubdiv on 1\n",
        mc.looptessVersion.c_str(), r.quick ? " --quick" : "", r.depth, r.runs, r.threads, r.threads == 1 ? "" : "s");
    out += format("machine: %s, nproc %d; %s, %s; OpenSubdiv %s\n\n", mc.cpuModel.c_str(), mc.nproc,
                  mc.compiler.c_str(), mc.buildType.c_str(), mc.osdVersion.c_str());
    Table t(r);
    t.header();
    t.line("control vertices", [](const MeshResult& m) { return count(m.vertices); });
    t.line("control triangles", [](const MeshResult& m) { return count(m.triangles); });
    t.line("extraordinary control vertices", [](const MeshResult& m) { return count(m.extraordinary); });

    t.section("1. bake time (ms)");
    t.line("  ours: lt::bake", [](const MeshResult& m) { return ms(m.bake); });
    // The stages of the first mesh, by name (every bake runs the same ones).
    if (!r.meshes.empty())
        for (const auto& stage : r.meshes[0].bakeStages)
            t.line("    stage: " + stage.first, [name = stage.first](const MeshResult& m) {
                for (const auto& s : m.bakeStages)
                    if (s.first == name) return ms(s.second);
                return std::string("-");
            });
    t.line("  ours: lt::writeAssetGlb (--compress fast)", [](const MeshResult& m) { return ms(m.write); });
    t.line(
        "  ours: lt::writeAssetGlb, none", [](const MeshResult& m) { return ms(m.writeNone); }, "(info)");
    t.line(
        "  ours: lt::writeAssetGlb, max (one run)", [](const MeshResult& m) { return ms(m.writeMax); }, "(info)");
    t.line("  ours: bake + write", [](const MeshResult& m) { return ms(m.bake + m.write); });
    t.line("  osd: refiner (factory + RefineAdaptive)", [](const MeshResult& m) { return ms(m.osd.refiner); });
    t.line("  osd: StencilTableFactory", [](const MeshResult& m) { return ms(m.osd.stencils); });
    t.line("  osd: PatchTableFactory", [](const MeshResult& m) { return ms(m.osd.patches); });
    t.line("  osd: AppendLocalPointStencilTable", [](const MeshResult& m) { return ms(m.osd.append); });
    t.line("  osd: total", [](const MeshResult& m) { return ms(m.osdTotal); });
    t.line(
        "  ratio ours (bake + write) / osd", [](const MeshResult& m) { return format("%.2f", m.bakeRatio()); },
        format("<= %.2f", kMaxBakeRatio));
    t.line(
        "  ratio of the medians", [](const MeshResult& m) { return format("%.2f", m.medianBakeRatio()); }, "(info)");

    t.section("2. table bytes (KiB)");
    t.line("  ours: refinement", [](const MeshResult& m) { return kib(m.tables.refinement); });
    t.line("  ours: masks", [](const MeshResult& m) { return kib(m.tables.masks); });
    t.line("  ours: patches", [](const MeshResult& m) { return kib(m.tables.patches); });
    t.line("  ours: irregular", [](const MeshResult& m) { return kib(m.tables.irregular); });
    t.line("  ours: limit", [](const MeshResult& m) { return kib(m.tables.limit); });
    t.line("  ours: tables (all but control mesh)", [](const MeshResult& m) { return kib(m.oursTableBytes()); });
    t.line("  ours: control mesh (fallback prim)", [](const MeshResult& m) { return kib(m.tables.controlMesh); });
    t.line("  ours: GLB file, --compress none", [](const MeshResult& m) { return kib(m.glbBytes); });
    t.line("  ours: GLB file, --compress fast", [](const MeshResult& m) { return kib(m.glbFast); });
    t.line(
        "  ours: GLB file, --compress max", [](const MeshResult& m) { return kib(m.glbMax); }, "(info)");
    t.line(
        "  ratio GLB fast / none", [](const MeshResult& m) { return format("%.3f", m.compressedRatio()); },
        format("<= %.2f", kMaxCompressedRatio));
    t.line(
        "  ratio GLB max / none", [](const MeshResult& m) { return format("%.3f", double(m.glbMax) / m.glbBytes); },
        "(info)");
    t.line("  fast: refinement in the file", [](const MeshResult& m) { return kib(m.tables.encoded.refinement); });
    t.line("  fast: patches in the file", [](const MeshResult& m) { return kib(m.tables.encoded.patches); });
    t.line("  fast: irregular in the file", [](const MeshResult& m) { return kib(m.tables.encoded.irregular); });
    t.line("  fast: limit in the file", [](const MeshResult& m) { return kib(m.tables.encoded.limit); });
    t.line("  osd: stencil sizes + offsets",
           [](const MeshResult& m) { return kib(m.osdBytes.stencilSizes + m.osdBytes.stencilOffsets); });
    t.line("  osd: stencil indices", [](const MeshResult& m) { return kib(m.osdBytes.stencilIndices); });
    t.line("  osd: stencil weights", [](const MeshResult& m) { return kib(m.osdBytes.stencilWeights); });
    t.line("  osd: patch vertices", [](const MeshResult& m) { return kib(m.osdBytes.patchVertices); });
    t.line("  osd: patch params + arrays + other",
           [](const MeshResult& m) { return kib(m.osdBytes.patchParams + m.osdBytes.patchArrays + m.osdBytes.other); });
    t.line("  osd: total", [](const MeshResult& m) { return kib(m.osdBytes.total()); });
    t.line(
        "  ratio ours tables / osd", [](const MeshResult& m) { return format("%.3f", m.bytesRatio()); },
        format("<= %.2f", kMaxBytesRatio));
    t.line(
        "  ratio ours GLB file (none) / osd", [](const MeshResult& m) { return format("%.3f", m.glbRatio()); },
        "(info)");
    t.line(
        "  osd: varying indices (not counted)", [](const MeshResult& m) { return kib(m.osdBytes.varyingVertices); },
        "(info)");

    t.section("3. load time (ms)");
    t.line("  ours: lt::readAssetGlb, --compress fast", [](const MeshResult& m) { return ms(m.load); });
    t.line(
        "  ours: lt::readAssetGlb, none", [](const MeshResult& m) { return ms(m.loadNone); }, "(info)");
    t.line(
        "  ours: fast load throughput (MB of tables / s)",
        [](const MeshResult& m) { return format("%.0f", m.loadThroughput()); }, "(info)");
    t.line("  osd: build tables (1. osd total)", [](const MeshResult& m) { return ms(m.osdTotal); });
    t.line(
        "  speed-up osd / ours (fast)", [](const MeshResult& m) { return format("%.1fx", m.loadSpeedup()); },
        format(">= %.0fx", kMinLoadSpeedup));
    t.line(
        "  speed-up osd / ours (none)", [](const MeshResult& m) { return format("%.1fx", m.osdTotal / m.loadNone); },
        "(info)");
    t.line(
        "  floor: one copy of the GLB", [](const MeshResult& m) { return ms(m.copy); }, "(info)");
    t.line(
        "  floor: zero-copy scan of the GLB", [](const MeshResult& m) { return ms(m.scan); }, "(info)");
    t.line(
        "  speed-up osd / zero-copy scan", [](const MeshResult& m) { return format("%.1fx", m.osdTotal / m.scan); },
        "(info)");

    t.section("counts");
    t.line("  ours: refined vertices kept", [](const MeshResult& m) { return count(m.refinedVertices); });
    t.line("  ours: regular patches (RPP + NPP)", [](const MeshResult& m) { return count(m.regularPatches); });
    t.line("  ours: irregular faces (all levels)", [](const MeshResult& m) { return count(m.irregularFaces); });
    t.line("  ours: limit stencils", [](const MeshResult& m) { return count(m.limitStencils); });
    t.line("  osd: refined vertices", [](const MeshResult& m) { return count(m.osdCounts.refinedVertices); });
    t.line("  osd: local (end cap) points", [](const MeshResult& m) { return count(m.osdCounts.localPoints); });
    t.line("  osd: stencil entries", [](const MeshResult& m) { return count(m.osdCounts.stencilWeights); });
    t.line("  osd: regular patches", [](const MeshResult& m) { return count(m.osdCounts.regularPatches); });
    t.line("  osd: end cap patches", [](const MeshResult& m) { return count(m.osdCounts.endCapPatches); });

    t.section("our bytes by property, all levels (KiB / share in u32 accessors)");
    std::vector<std::string> names;
    for (const MeshResult& m : r.meshes)
        for (const PropertyBytes& p : m.properties)
            if (std::find(names.begin(), names.end(), p.name) == names.end()) names.push_back(p.name);
    for (const std::string& name : names)
        t.line("  " + name, [&](const MeshResult& m) {
            for (const PropertyBytes& p : m.properties)
                if (p.name == name)
                    return format("%s/%.0f%%", kib(p.bytes).c_str(), p.bytes ? 100.0 * p.wideBytes / p.bytes : 0.0);
            return std::string("-");
        });

    t.section("estimated savings (KiB -> ratio ours tables / osd)");
    auto saving = [](const std::function<size_t(const Savings&)>& get) {
        return [get](const MeshResult& m) {
            const size_t s = get(m.estimates);
            return format("%.0f->%.3f", double(s) / 1024.0,
                          double(m.oursTableBytes() - s) / double(m.osdBytes.total()));
        };
    };
    t.line("  patch points in u16 chunks", saving([](const Savings& s) { return s.chunkedPatchPoints; }));
    t.line("  limit rings shared with refinement", saving([](const Savings& s) { return s.sharedLimitRings; }));
    t.line("  both of the above", saving([](const Savings& s) { return s.combined; }),
           format("<= %.2f", kMaxBytesRatio));
    t.line("  patch points in u16 chunks, renumbered",
           saving([](const Savings& s) { return s.renumberedChunkedPatchPoints; }), "(info)");
    out += t.take();

    bool bytesAll = true, loadAll = true, packedAll = true, bakeAll = true;
    std::string bytesLine, loadLine, packedLine, bakeLine, verdicts;
    for (const MeshResult& m : r.meshes) {
        bakeAll = bakeAll && m.bakePass();
        bakeLine += format(" %s %s (%.2f);", m.name.c_str(), verdict(m.bakePass()).c_str(), m.bakeRatio());
        verdicts += format("verdict %s: bake+write / OpenSubdiv %.2fx (target <= %.1fx): %s\n", m.name.c_str(),
                           m.bakeRatio(), kMaxBakeRatio, m.bakePass() ? "met" : "MISSED");
        verdicts += format("verdict %s: load speed-up %.1fx (target >= %.0fx): %s\n", m.name.c_str(), m.loadSpeedup(),
                           kMinLoadSpeedup, m.loadPass() ? "met" : "MISSED");
        bytesAll = bytesAll && m.bytesPass();
        loadAll = loadAll && m.loadPass();
        packedAll = packedAll && m.compressedPass();
        bytesLine += format(" %s %s (%.3f);", m.name.c_str(), verdict(m.bytesPass()).c_str(), m.bytesRatio());
        packedLine +=
            format(" %s %s (%.3f);", m.name.c_str(), verdict(m.compressedPass()).c_str(), m.compressedRatio());
        loadLine += format(" %s %s (%.1fx);", m.name.c_str(), verdict(m.loadPass()).c_str(), m.loadSpeedup());
    }
    out += format("\ntargets:\n  table bytes ours/osd <= %.2f: %s --%s\n", kMaxBytesRatio, verdict(bytesAll).c_str(),
                  bytesLine.c_str());
    out += format("  GLB fast/none <= %.2f: %s --%s\n", kMaxCompressedRatio, verdict(packedAll).c_str(),
                  packedLine.c_str());
    out += format("  load speed-up osd/ours (fast) >= %.0fx: %s --%s\n", kMinLoadSpeedup, verdict(loadAll).c_str(),
                  loadLine.c_str());
    out += format("  bake + write / osd <= %.2f: %s --%s\n", kMaxBakeRatio, verdict(bakeAll).c_str(), bakeLine.c_str());
    out += "\n" + verdicts;
    out += "(verdicts are reported, not asserted: the exit status is 0 whether a target is met or missed)\n";
    return out;
}

std::string formatJson(const Report& r) {
    using Json = nlohmann::ordered_json;
    auto msOf = [](double s) { return s * 1e3; };
    Json doc;
    doc["machine"] = {{"nproc", r.machine.nproc},           {"cpuModel", r.machine.cpuModel},
                      {"compiler", r.machine.compiler},     {"buildType", r.machine.buildType},
                      {"openSubdiv", r.machine.osdVersion}, {"looptess", r.machine.looptessVersion}};
    doc["depth"] = r.depth;
    doc["runs"] = r.runs;
    doc["threads"] = r.threads;
    doc["quick"] = r.quick;
    doc["targets"] = {{"maxBytesRatio", kMaxBytesRatio},
                      {"maxCompressedRatio", kMaxCompressedRatio},
                      {"minLoadSpeedup", kMinLoadSpeedup},
                      {"maxBakeRatio", kMaxBakeRatio}};
    Json meshes = Json::array();
    bool bytesAll = true, loadAll = true, packedAll = true, bakeAll = true;
    for (const MeshResult& m : r.meshes) {
        bakeAll = bakeAll && m.bakePass();
        bytesAll = bytesAll && m.bytesPass();
        loadAll = loadAll && m.loadPass();
        packedAll = packedAll && m.compressedPass();
        Json j;
        j["name"] = m.name;
        j["source"] = m.source;
        j["vertices"] = m.vertices;
        j["triangles"] = m.triangles;
        j["extraordinaryVertices"] = m.extraordinary;
        j["bakeMs"] = {{"oursBake", msOf(m.bake)},           {"oursWrite", msOf(m.write)},
                       {"oursWriteNone", msOf(m.writeNone)}, {"oursWriteMaxOneRun", msOf(m.writeMax)},
                       {"osdRefiner", msOf(m.osd.refiner)},  {"osdStencils", msOf(m.osd.stencils)},
                       {"osdPatches", msOf(m.osd.patches)},  {"osdAppend", msOf(m.osd.append)},
                       {"osdTotal", msOf(m.osdTotal)}};
        j["bytes"] = {{"oursControlMesh", m.tables.controlMesh},
                      {"oursRefinement", m.tables.refinement},
                      {"oursMasks", m.tables.masks},
                      {"oursPatches", m.tables.patches},
                      {"oursIrregular", m.tables.irregular},
                      {"oursLimit", m.tables.limit},
                      {"oursTables", m.oursTableBytes()},
                      {"oursGlb", m.glbBytes},
                      {"oursGlbFast", m.glbFast},
                      {"oursGlbMax", m.glbMax},
                      {"oursFastRefinement", m.tables.encoded.refinement},
                      {"oursFastPatches", m.tables.encoded.patches},
                      {"oursFastIrregular", m.tables.encoded.irregular},
                      {"oursFastLimit", m.tables.encoded.limit},
                      {"osdStencilSizes", m.osdBytes.stencilSizes},
                      {"osdStencilOffsets", m.osdBytes.stencilOffsets},
                      {"osdStencilIndices", m.osdBytes.stencilIndices},
                      {"osdStencilWeights", m.osdBytes.stencilWeights},
                      {"osdPatchArrays", m.osdBytes.patchArrays},
                      {"osdPatchVertices", m.osdBytes.patchVertices},
                      {"osdPatchParams", m.osdBytes.patchParams},
                      {"osdOther", m.osdBytes.other},
                      {"osdTotal", m.osdBytes.total()}};
        j["bytes"]["osdVaryingVerticesNotCounted"] = m.osdBytes.varyingVertices;
        Json props = Json::object();
        for (const PropertyBytes& p : m.properties) props[p.name] = {{"bytes", p.bytes}, {"u32Bytes", p.wideBytes}};
        j["oursBytesByProperty"] = std::move(props);
        j["estimatedSavingsBytes"] = {{"chunkedPatchPoints", m.estimates.chunkedPatchPoints},
                                      {"sharedLimitRings", m.estimates.sharedLimitRings},
                                      {"combined", m.estimates.combined},
                                      {"renumberedChunkedPatchPoints", m.estimates.renumberedChunkedPatchPoints}};
        j["loadMs"] = {{"oursRead", msOf(m.load)},
                       {"oursReadNone", msOf(m.loadNone)},
                       {"osdBuild", msOf(m.osdTotal)},
                       {"copyFloor", msOf(m.copy)},
                       {"zeroCopyScanFloor", msOf(m.scan)}};
        j["counts"] = {{"oursRefinedVertices", m.refinedVertices},
                       {"oursRegularPatches", m.regularPatches},
                       {"oursIrregularFaces", m.irregularFaces},
                       {"oursLimitStencils", m.limitStencils},
                       {"osdRefinedVertices", m.osdCounts.refinedVertices},
                       {"osdLocalPoints", m.osdCounts.localPoints},
                       {"osdStencilEntries", m.osdCounts.stencilWeights},
                       {"osdRegularPatches", m.osdCounts.regularPatches},
                       {"osdEndCapPatches", m.osdCounts.endCapPatches}};
        j["bytesRatio"] = m.bytesRatio();
        j["glbRatio"] = m.glbRatio();
        j["loadSpeedup"] = m.loadSpeedup();
        j["loadThroughputMBps"] = m.loadThroughput();
        j["compressedRatio"] = m.compressedRatio();
        j["compressedPass"] = m.compressedPass();
        j["bytesPass"] = m.bytesPass();
        j["loadPass"] = m.loadPass();
        j["bakeRatio"] = m.bakeRatio();
        j["medianBakeRatio"] = m.medianBakeRatio();
        j["bakePass"] = m.bakePass();
        meshes.push_back(std::move(j));
    }
    doc["meshes"] = std::move(meshes);
    doc["bytesPass"] = bytesAll;
    doc["loadPass"] = loadAll;
    doc["compressedPass"] = packedAll;
    doc["bakePass"] = bakeAll;
    return doc.dump(2) + "\n";
}

}  // namespace ltbench

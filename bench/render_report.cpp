// bench/render_report.cpp -- text tables and JSON of bench_render (render_report.h).
#include "render_report.h"

#include "format.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdarg>
#include <cstdio>

namespace ltbench {
namespace {

std::string mib(uint64_t bytes) { return format("%.2f", double(bytes) / (1024.0 * 1024.0)); }
std::string millions(uint64_t n) { return format("%.3f", double(n) * 1e-6); }
std::string verdict(bool pass) { return pass ? "PASS" : "MISS"; }

// "12.34" or the reason a path was not measured.
std::string frameCell(const PathResult& p) { return p.measured ? format("%.1f", p.frameMs) : "-"; }

// "1" for global refinement in one asset, the chunk count for chunks, "-" if neither.
std::string partsCell(const PathResult& p) { return p.measured ? std::to_string(p.chunks ? p.chunks : 1) : "-"; }

std::string comparisonTable(const RenderReport& r) {
    std::string out = format("%-6s %4s %5s | %10s %10s %9s | %6s %10s %10s %9s %9s | %7s %7s %7s\n", "model", "F",
                             "depth", "adapt Mtri", "adapt ms", "adapt MiB", "parts", "glob Mtri", "glob ms",
                             "glob MiB", "lean MiB", "speedup", "mem", "memLean");
    out += std::string(out.size() - 1, '-') + "\n";
    for (const RenderRow& row : r.rows) {
        const PathResult &a = row.adaptive, &g = row.baseline();
        out += format("%-6s %4g %5u | %10s %10s %9s | %6s %10s %10s %9s %9s | %7s %7s %7s\n", row.mesh.c_str(),
                      double(row.factor), a.depth, millions(a.triangles).c_str(), frameCell(a).c_str(),
                      mib(a.memory.total()).c_str(), partsCell(g).c_str(),
                      g.measured ? millions(g.triangles).c_str() : "-", frameCell(g).c_str(),
                      g.measured ? mib(g.memory.total()).c_str() : "-", mib(row.leanGlobalBytes).c_str(),
                      g.measured ? format("%.2fx", row.speedup()).c_str() : "-",
                      g.measured ? format("%.3f", row.memoryRatio()).c_str() : "-",
                      format("%.3f", row.leanMemoryRatio()).c_str());
    }
    return out;
}

std::string passTimes(const RenderReport& r) {
    std::string out =
        "GPU ms per pass (median; chunks: sum of the chunks' medians): subdivide / limit / evaluate / draw\n";
    auto passes = [](const char* name, const PathResult& p) {
        return format("    %-22s %9.2f %9.2f %9.2f %9.2f   (warm-up %u frames)\n", name, p.subdivideMs, p.limitMs,
                      p.evaluateMs, p.drawMs, p.warmup);
    };
    for (const RenderRow& row : r.rows) {
        out += format("  %s F %g\n", row.mesh.c_str(), double(row.factor));
        out += passes("tessellator", row.adaptive);
        if (row.patterns.measured) out += passes("patterns", row.patterns);
        if (row.compute.measured) out += passes("compute", row.compute);
        out += row.global.measured ? passes("global", row.global) : "    global -- " + row.global.note + "\n";
        if (row.chunked.measured)
            out += passes(format("global in %u chunks", row.chunked.chunks).c_str(), row.chunked);
        else if (!row.chunked.note.empty())
            out += "    global in chunks -- " + row.chunked.note + "\n";
    }
    return out;
}

// Where global refinement was measured both whole and in chunks: what chunking
// itself costs (per-chunk fixed costs, points along the cuts computed twice).
std::string chunkingTable(const RenderReport& r) {
    std::string out = "chunking's own cost (global refinement whole against the same in chunks)\n";
    out += format("  %-6s %4s %6s %10s %10s %8s %10s %10s %8s\n", "model", "F", "chunks", "whole ms", "chunks ms",
                  "time", "whole MiB", "chunks MiB", "memory");
    for (const RenderRow& row : r.rows) {
        if (!row.global.measured || !row.chunked.measured) continue;
        out += format("  %-6s %4g %6u %10.2f %10.2f %+7.1f%% %10s %10s %+7.1f%%\n", row.mesh.c_str(),
                      double(row.factor), row.chunked.chunks, row.global.frameMs, row.chunked.frameMs,
                      row.chunkingTimeCost() * 100, mib(row.global.memory.total()).c_str(),
                      mib(row.chunked.memory.total()).c_str(), row.chunkingMemoryCost() * 100);
    }
    return out;
}

std::string targets(const RenderReport& r) {
    std::string out = format("targets at F = %g: adaptive memory <= %.0f%% of global, frame time >= %.0fx faster\n",
                             double(kTargetFactor), kMaxMemoryRatio * 100, kMinSpeedup);
    for (const RenderRow& row : r.rows) {
        if (row.factor != kTargetFactor) continue;
        const PathResult& g = row.baseline();
        out += format(
            "  %-6s memory: %s of measured global, %.3f of lean global (%s); speed-up: %s\n", row.mesh.c_str(),
            g.measured
                ? format("%.3f (%s)", row.memoryRatio(), verdict(row.memoryRatio() <= kMaxMemoryRatio).c_str()).c_str()
                : "-",
            row.leanMemoryRatio(), verdict(row.leanMemoryRatio() <= kMaxMemoryRatio).c_str(),
            g.measured ? format("%.2fx (%s)", row.speedup(), verdict(row.speedup() >= kMinSpeedup).c_str()).c_str()
                       : "not measured (global refinement not measured)");
        if (g.chunks) out += format("         (global refinement measured in %u chunks: their sums)\n", g.chunks);
    }
    return out;
}

// Paper 4.6: the watertight variant against --no-watertight. Memory: the table
// words only watertight evaluation reads, over everything else the asset keeps.
std::string watertightTable(const RenderReport& r) {
    std::string out =
        format("watertight evaluation cost (target: at most +%.0f%% frame time; paper: +80%% time, +50%% memory)\n",
               kMaxWatertightCost * 100);
    out += format("  %-6s %4s %10s %10s %8s %6s %12s %8s\n", "model", "F", "wt ms", "plain ms", "time", "", "wt MiB",
                  "memory");
    for (const RenderRow& row : r.rows) {
        if (!row.plain.measured) continue;
        out += format("  %-6s %4g %10.2f %10.2f %+7.1f%% %6s %12s %+7.1f%%\n", row.mesh.c_str(), double(row.factor),
                      row.adaptive.frameMs, row.plain.frameMs, row.watertightTimeCost() * 100,
                      verdict(row.watertightTimeCost() <= kMaxWatertightCost).c_str(),
                      mib(row.adaptive.memory.watertight).c_str(), row.watertightMemoryCost() * 100);
    }
    return out;
}

// The draw path without the tessellator (DrawPath::Patterns) against the tessellator
// path and global refinement (the targets: at F = 32 at least 1.2x global
// refinement's and 2x the tessellator path's frame rate; memory at most 5% of global).
std::string patternTable(const RenderReport& r) {
    std::string out =
        "pattern path (refinement patterns, no tessellator) against the tessellator path and global refinement\n";
    out += format("  %-6s %4s %10s %10s %10s %10s %9s %9s %7s\n", "model", "F", "pat Mtri", "pat ms", "tess ms",
                  "glob ms", "vs tess", "vs glob", "mem");
    for (const RenderRow& row : r.rows) {
        const PathResult &p = row.patterns, &g = row.baseline();
        if (!p.measured) continue;
        out +=
            format("  %-6s %4g %10s %10.1f %10.1f %10s %8.2fx %9s %7s\n", row.mesh.c_str(), double(row.factor),
                   millions(p.triangles).c_str(), p.frameMs, row.adaptive.frameMs, frameCell(g).c_str(),
                   row.adaptive.frameMs / p.frameMs, g.measured ? format("%.2fx", g.frameMs / p.frameMs).c_str() : "-",
                   g.measured ? format("%.3f", RenderRow::ratio(p.memory.total(), g.memory.total())).c_str() : "-");
    }
    return out;
}

// The compute path (DrawPath::Compute) against global refinement, which draws the
// same triangles at a power-of-two F, and the targets set for a hardware GPU.
std::string computeTable(const RenderReport& r) {
    std::string out = format(
        "compute path against global refinement (targets on a hardware GPU: at F = 8 and 32 at least "
        "%.1fx its frame rate; at F = 32 memory at most %.0f%% of its)\n",
        kMinComputeRate, kMaxMemoryRatio * 100);
    out += format("  %-6s %4s %10s %10s %10s %10s %9s %9s %8s %6s\n", "model", "F", "cmp Mtri", "cmp ms", "glob ms",
                  "rate", "cmp MiB", "mem", "batches", "");
    for (const RenderRow& row : r.rows) {
        const PathResult &c = row.compute, &g = row.baseline();
        if (!c.measured) continue;
        const double rate = g.measured && c.frameMs > 0 ? g.frameMs / c.frameMs : 0;
        const double mem = RenderRow::ratio(c.memory.total(), g.memory.total());
        std::string verdicts;
        if (g.measured && (row.factor == 8 || row.factor == 32)) verdicts += "rate " + verdict(rate >= kMinComputeRate);
        if (g.measured && row.factor == kTargetFactor) verdicts += " mem " + verdict(mem <= kMaxMemoryRatio);
        out += format("  %-6s %4g %10s %10.1f %10s %10s %9s %9s %8u %s\n", row.mesh.c_str(), double(row.factor),
                      millions(c.triangles).c_str(), c.frameMs, frameCell(g).c_str(),
                      g.measured ? format("%.2fx", rate).c_str() : "-", mib(c.memory.total()).c_str(),
                      g.measured ? format("%.3f", mem).c_str() : "-", c.drawCalls, verdicts.c_str());
    }
    return out;
}

// Paper Table 2's columns: model, control triangles, F, depth, frame time, for each
// path; beside the paper's GTX 570 where it has the model at F = 32 (the Duck; its
// Big Guy has no copy here whose licence the repository could carry).
std::string table2(const RenderReport& r) {
    std::string out = "Table 2 style (GPU frame time, ms):\n";
    out += format("  %-6s %9s %4s %5s %12s %10s %10s %10s %14s\n", "model", "triangles", "F", "depth", "drawn Mtri",
                  "tess", "patterns", "compute", "paper GTX 570");
    for (const RenderRow& row : r.rows) {
        const bool paper = row.mesh == "duck" && row.factor == 32;
        out += format("  %-6s %9u %4g %5u %12s %10.2f %10s %10s %14s\n", row.mesh.c_str(), row.controlTriangles,
                      double(row.factor), row.adaptive.depth, millions(row.adaptive.triangles).c_str(),
                      row.adaptive.frameMs, frameCell(row.patterns).c_str(), frameCell(row.compute).c_str(),
                      paper ? format("%.2f", kPaperDuckMs).c_str() : "-");
    }
    return out;
}

nlohmann::json pathJson(const PathResult& p) {
    nlohmann::json j = {{"measured", p.measured}, {"chunks", p.chunks}};
    if (!p.note.empty()) j["note"] = p.note;
    if (!p.measured) return j;
    j.update({{"depth", p.depth},
              {"triangles", p.triangles},
              {"drawCalls", p.drawCalls},
              {"gpuMs",
               {{"subdivide", p.subdivideMs},
                {"limit", p.limitMs},
                {"evaluate", p.evaluateMs},
                {"draw", p.drawMs},
                {"frame", p.frameMs}}},
              {"warmupFrames", p.warmup},
              {"wallMs", p.wallMs},
              {"frameMsEach", p.frames},
              {"buildMs", p.buildMs},
              {"gpuMemoryBytes",
               {{"total", p.memory.total()},
                {"tables", p.memory.tables},
                {"vertices", p.memory.vertices},
                {"limit", p.memory.limit},
                {"upload", p.memory.upload},
                {"watertight", p.memory.watertight},
                {"compute", p.memory.compute}}}});
    return j;
}

}  // namespace

double RenderRow::watertightTimeCost() const {
    const std::vector<double>&w = adaptive.frames, &p = plain.frames;
    if (w.empty() || w.size() != p.size()) return plain.frameMs > 0 ? adaptive.frameMs / plain.frameMs - 1 : 0;
    std::vector<double> ratios;
    for (size_t i = 0; i < w.size(); ++i) ratios.push_back(p[i] > 0 ? w[i] / p[i] : 0);
    return median(ratios) - 1;
}

std::string formatTables(const RenderReport& r) {
    std::string out =
        format("looptess bench_render: %ux%u, median of %u timed frames after a steady warm-up; device %s; %s\n\n",
               r.width, r.height, r.frames, r.device.c_str(), r.machine.c_str());
    out += comparisonTable(r) + "\n" + passTimes(r) + "\n" + chunkingTable(r) + "\n" + targets(r) + "\n" +
           watertightTable(r) + "\n" + patternTable(r) + "\n" + computeTable(r) + "\n" + table2(r);
    return out;
}

std::string formatJson(const RenderReport& r) {
    nlohmann::json doc = {
        {"device", r.device}, {"machine", r.machine}, {"size", {r.width, r.height}}, {"frames", r.frames}};
    doc["targets"] = {{"factor", kTargetFactor},
                      {"maxMemoryRatio", kMaxMemoryRatio},
                      {"minSpeedup", kMinSpeedup},
                      {"maxWatertightCost", kMaxWatertightCost}};
    nlohmann::json rows = nlohmann::json::array();
    for (const RenderRow& row : r.rows)
        rows.push_back({{"mesh", row.mesh},
                        {"controlVertices", row.controlVertices},
                        {"controlTriangles", row.controlTriangles},
                        {"factor", row.factor},
                        {"adaptive", pathJson(row.adaptive)},
                        {"global", pathJson(row.global)},
                        {"globalChunked", pathJson(row.chunked)},
                        {"noWatertight", pathJson(row.plain)},
                        {"patterns", pathJson(row.patterns)},
                        {"compute", pathJson(row.compute)},
                        {"watertightTimeCost", row.watertightTimeCost()},
                        {"watertightMemoryCost", row.watertightMemoryCost()},
                        {"leanGlobalBytes", row.leanGlobalBytes},
                        {"speedup", row.speedup()},
                        {"memoryRatio", row.memoryRatio()},
                        {"leanMemoryRatio", row.leanMemoryRatio()}});
    doc["rows"] = rows;
    return doc.dump(2) + "\n";
}

}  // namespace ltbench

// The findings of a check report (check.h's addFindings and exitCode): one line
// each, with its id and severity, from the results run.cpp gathers.
#include "check_internal.h"

#include <sstream>

namespace lt {

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// " (the reference includes N hierarchical edits down to level K)", or "".
std::string referenceEdits(uint32_t edits, int level) {
    if (edits == 0) return "";
    return " (the reference includes " + std::to_string(edits) + " hierarchical edit" + (edits == 1 ? "" : "s") +
           " down to level " + std::to_string(level) + ")";
}

void addTessellationFindings(const CheckSettings& settings, const TessellationChecks& t, std::vector<Finding>& f) {
    auto add = [&](const char* id, const char* severity, const std::string& text) {
        f.push_back({id, severity, text});
    };
    const std::string at = t.name + " (" + t.path + "): ";
    if (!t.notRun.empty()) {
        add("L1", "error", at + "not run: " + t.notRun);
        return;
    }
    if (!t.error.empty()) {
        add("G1", "error", at + "capture failed: " + t.error);
        return;
    }
    if (t.compared && t.equalVertices != t.cpuVertices)
        add("G2", "info",
            at + std::to_string(t.equalVertices) + " of " + std::to_string(t.cpuVertices) +
                " CPU vertices bitwise equal in the GPU capture");
    const AccuracyResult& a = t.accuracy;
    if (a.positionFailures + a.normalFailures + a.noLimit > 0)
        add("A1", "error",
            at + std::to_string(a.positionFailures) + " positions and " + std::to_string(a.normalFailures) +
                " normals of " + std::to_string(a.sampled) + " vertices (all " + std::to_string(a.corners) +
                " at base corners, a sample of the rest) off OpenSubdiv's limit surface" +
                referenceEdits(a.referenceEdits, a.referenceEditLevel) + " (tolerances " +
                number(settings.positionTolerance) + " of the diagonal, 1 - cos " + number(settings.normalTolerance) +
                "); " + std::to_string(a.noLimit) + " on faces without one; first: " + a.firstFailure +
                " (an asset baked with --crease-angle or --hard-edges needs the same option here)");
    const WeldResult& w = t.weld;
    if (w.nonFiniteVertices) add("W5", "error", at + std::to_string(w.nonFiniteVertices) + " vertices are not finite");
    if (w.crackEdges)
        add("W1", "error",
            at + std::to_string(w.crackEdges) + " open edges off the control mesh's boundary (cracks), " +
                std::to_string(w.tJunctions) + " of them T-junctions, after welding " + std::to_string(w.vertices) +
                " vertices by exact bits into " + std::to_string(w.weldedVertices) + "; first: " + w.firstFailure);
    if (w.unexpectedNonManifoldEdges)
        add("W2", "error",
            at + std::to_string(w.unexpectedNonManifoldEdges) +
                " edges used by three or more triangles off the control mesh's non-manifold edges; "
                "first: " +
                w.firstFailure);
    if (w.contactEdges)
        add("W6", "warning",
            at + std::to_string(w.contactEdges) +
                " edges used three or more times where control faces fold back onto each other (a doubled "
                "triangle) or the limit surface folds: the surface touches itself within float resolution");
    if (w.misorientedEdges)
        add("W3", "error",
            at + std::to_string(w.misorientedEdges) +
                " edges used twice in the same direction; first: " + w.firstFailure);
    const NormalResult& nr = t.normals;
    if (!nr.pass())
        add("N1", "error",
            at + std::to_string(nr.against) + " vertex normals point behind their triangle and " +
                std::to_string(nr.zero) + " are zero or not finite, of " + std::to_string(nr.judged) +
                " triangles judged; first: " + nr.firstFailure);
    const RayResult& r = t.rays;
    if (!r.ran) {
        add("R3", "info", at + "rays skipped: " + r.skipped);
        return;
    }
    // A first hit on a front face: the surface overlaps itself (a displacement too
    // large for a thin part, say) or is inside out, so "inside" is ambiguous and
    // an escaped ray need not be a crack.
    const std::string overlap = std::to_string(r.frontHits) + " of " + std::to_string(r.rays) +
                                " rays first hit a front face: the surface overlaps itself or is inside out";
    if (r.escaped)
        add("R1", "error",
            at + std::to_string(r.escaped) + " of " + std::to_string(r.rays) + " rays from interior points escaped" +
                (r.frontHits && w.crackEdges == 0 ? " (no open edge: " + overlap + ", so an origin may be outside)"
                                                  : std::string()));
    else if (r.frontHits)
        add("R5", "info", at + overlap);
    if (r.distanceFailures)
        add("R2", "error",
            at + std::to_string(r.distanceFailures) + " of " + std::to_string(r.compared) +
                " hit distances disagree with the reference beyond the chord bounds (worst " +
                number(r.maxToleranceRatio) + "x the tolerance)");
    if (!r.distanceSkipped.empty()) add("R4", "info", at + "hit distances not compared: " + r.distanceSkipped);
}

void addFindings(const CheckSettings& settings, CheckReport& report) {
    std::vector<Finding>& f = report.findings;
    f.clear();
    auto add = [&](const char* id, const char* severity, const std::string& text) {
        f.push_back({id, severity, text});
    };
    if (!report.structureValid) {
        add("S1", "error", report.structureMessage);
        return;
    }
    if (!report.sourceMismatch.empty())
        add("M1", "error", "--source " + report.sourceName + ": " + report.sourceMismatch);
    for (const std::string& d : report.sceneDifferences)
        add("M2", "error", "--source " + report.sourceName + ": the scene is not the source's: " + d);
    if (report.sourceEdits > 0)
        add("A2", "info",
            "--source " + report.sourceName + ": the accuracy reference includes the source's " +
                std::to_string(report.sourceEdits) + " hierarchical edit" + (report.sourceEdits == 1 ? "" : "s") +
                " down to level " + std::to_string(report.sourceEditLevel) +
                " (OpenSubdiv refined uniformly to that level, the edits applied level by level, then "
                "the limit surface of that level); at a runtime depth d below " +
                std::to_string(report.sourceEditLevel) + " only the edits of levels <= d, as the runtime applies them");
    if (report.stencilsChecked && !report.stencils.pass())
        add("A3", "error",
            "--source " + report.sourceName + ": " + std::to_string(report.stencils.failures) + " of " +
                std::to_string(report.stencils.checked) +
                " limit stencils' positions off OpenSubdiv's limit beyond their weights' float "
                "rounding; first: " +
                report.stencils.firstFailure);
    const ValidatorResult& v = report.validator;
    const ValidatorResult& source = report.sourceValidator;
    const bool inherited =
        source.state == ValidatorResult::Ran && v.errors <= source.errors && v.warnings <= source.warnings;
    if (v.state == ValidatorResult::Ran && !v.pass())
        add("V1", inherited ? "info" : "error",
            "Khronos glTF-Validator: " + std::to_string(v.errors) + " errors, " + std::to_string(v.warnings) +
                " warnings" + (v.messages.empty() ? "" : " (first: " + v.messages.front() + ")") +
                (source.state == ValidatorResult::Ran ? "; the source has " + std::to_string(source.errors) +
                                                            " errors, " + std::to_string(source.warnings) + " warnings"
                                                      : ""));
    if (v.state == ValidatorResult::Unavailable)
        add("V2", settings.strictValidator ? "error" : "warning", "Khronos glTF-Validator not available: " + v.detail);
    for (const TessellationChecks& t : report.tessellations) addTessellationFindings(settings, t, f);
}

int exitCode(const CheckReport& report) {
    if (!report.structureValid) return 2;
    for (const Finding& f : report.findings)
        if (f.severity == "error") return 3;
    return 0;
}

}  // namespace lt

// The report: JSON (formats/loopcheck-report.schema.json) and text (looptess/tools/check.h [6]).
#include "looptess/tools/check.h"
#include "looptess/version.h"

#include <nlohmann/json.hpp>

#include <sstream>
#include <string>

namespace lt {
namespace {

using Json = nlohmann::ordered_json;

// Six significant digits: a float setting prints as written (3.3, not 3.2999999523).
double shortest(double v) {
    std::ostringstream s;
    s << v;
    return std::stod(s.str());
}

const char* spacingName(Spacing s) { return s == Spacing::Equal ? "equal" : "fractional_odd"; }

std::string resultName(const CheckReport& r) {
    const int code = exitCode(r);
    return code == 0 ? "pass" : code == 2 ? "invalid" : "fail";
}

Json accuracyJson(const AccuracyResult& a) {
    if (!a.ran) return nullptr;
    return {{"sampled", a.sampled},
            {"positionFailures", a.positionFailures},
            {"normalFailures", a.normalFailures},
            {"noLimitSurface", a.noLimit},
            {"normalsSkipped", a.normalsSkipped},
            {"oracleLimited", a.oracleLimited},
            {"floatLimited", a.floatLimited},
            {"maxPositionError", a.maxPositionError},
            {"maxNormalError", a.maxNormalError},
            {"firstFailure", a.firstFailure.empty() ? Json(nullptr) : Json(a.firstFailure)}};
}

Json weldJson(const WeldResult& w) {
    return {{"vertices", w.vertices},           {"weldedVertices", w.weldedVertices},
            {"triangles", w.triangles},         {"degenerateTriangles", w.degenerateTriangles},
            {"nonFiniteVertices", w.nonFiniteVertices}, {"edges", w.edges},
            {"openEdges", w.openEdges},         {"boundaryEdges", w.boundaryEdges},
            {"crackEdges", w.crackEdges},       {"tJunctions", w.tJunctions},
            {"tJunctionVertices", w.tJunctionVertices}, {"nonManifoldEdges", w.nonManifoldEdges},
            {"unexpectedNonManifoldEdges", w.unexpectedNonManifoldEdges},
            {"misorientedEdges", w.misorientedEdges},   {"normalSplitVertices", w.normalSplitVertices},
            {"firstFailure", w.firstFailure.empty() ? Json(nullptr) : Json(w.firstFailure)},
            {"pass", w.pass()}};
}

Json raysJson(const RayResult& r) {
    Json j = {{"ran", r.ran}};
    if (!r.ran) {
        j["skipped"] = r.skipped;
        return j;
    }
    j["candidates"] = r.candidates;
    j["origins"] = r.origins;
    j["rays"] = r.rays;
    j["escaped"] = r.escaped;
    j["frontHits"] = r.frontHits;
    Json d = {{"checked", r.distanceChecked}};
    if (r.distanceChecked) {
        d["compared"] = r.compared;
        d["failures"] = r.distanceFailures;
        d["foldRays"] = r.foldRays;
        d["referenceEscaped"] = r.referenceEscaped;
        d["maxError"] = r.maxDistanceError;
        d["maxToleranceRatio"] = r.maxToleranceRatio;
    } else {
        d["skipped"] = r.distanceSkipped;
    }
    j["distances"] = d;
    j["pass"] = r.pass();
    return j;
}

} // namespace

std::string reportJson(const CheckReport& r, const CheckSettings& s, bool timings) {
    Json j;
    j["tool"] = "loopcheck";
    j["version"] = LOOPTESS_VERSION_STRING;
    j["asset"] = {{"file", r.assetName}, {"bytes", r.assetBytes}};
    j["result"] = resultName(r);
    j["exitCode"] = exitCode(r);
    Json cases = Json::array();
    for (const TessCase& c : s.cases) cases.push_back(tessCaseName(c));
    j["settings"] = {{"tessellations", cases},
                     {"watertight", s.watertight},
                     {"drawPath", s.path == DrawPath::Tessellator ? "tessellator" : s.path == DrawPath::Patterns ? "patterns" : "compute"},
                     {"gpu", r.gpu},
                     {"source", r.sourceName.empty() ? Json(nullptr) : Json(r.sourceName)},
                     {"rays", s.rays},
                     {"rayOrigins", s.rayOrigins},
                     {"seed", s.seed},
                     {"accuracySamples", s.accuracySamples},
                     {"positionTolerance", s.positionTolerance},
                     {"normalTolerance", s.normalTolerance},
                     {"distanceSlack", s.distanceSlack},
                     {"strictValidator", s.strictValidator}};
    Json st = {{"valid", r.structureValid}};
    if (!r.structureValid) st["message"] = r.structureMessage;
    else
        st.update({{"controlVertices", r.controlVertices}, {"baseFaces", r.baseFaces}, {"maxDepth", r.maxDepth},
                   {"vertices", r.vertices}});
    j["structure"] = st;
    if (r.structureValid) {
        const ControlTopology& t = r.topology;
        j["controlMesh"] = {{"drawnFaces", t.drawnFaces},       {"edges", t.edges},
                            {"boundaryEdges", t.boundaryEdges}, {"nonManifoldEdges", t.nonManifoldEdges},
                            {"closed", t.closed()}};
    }
    j["source"] = r.sourceName.empty() ? Json(nullptr)
                                       : Json{{"file", r.sourceName},
                                              {"matches", r.sourceMismatch.empty()},
                                              {"message", r.sourceMismatch.empty() ? Json(nullptr) : Json(r.sourceMismatch)}};
    if (r.stencilsChecked) {
        const StencilResult& st = r.stencils;
        j["source"]["stencils"] = {{"checked", st.checked},       {"failures", st.failures},
                                   {"unmatched", st.unmatched},   {"worstRatio", st.worstRatio},
                                   {"firstFailure", st.firstFailure.empty() ? Json(nullptr) : Json(st.firstFailure)},
                                   {"pass", st.pass()}};
        if (!st.skipped.empty()) j["source"]["stencils"]["skipped"] = st.skipped;
    }
    const ValidatorResult& v = r.validator;
    static const char* kState[] = {"skipped", "unavailable", "ran"};
    Json vj = {{"state", kState[v.state]}};
    if (v.state == ValidatorResult::Ran)
        vj.update({{"pass", v.pass()}, {"errors", v.errors}, {"warnings", v.warnings}, {"infos", v.infos},
                   {"hints", v.hints}, {"messages", v.messages}});
    if (v.state == ValidatorResult::Unavailable) vj["detail"] = v.detail;
    j["validator"] = vj;
    if (r.sourceValidator.state == ValidatorResult::Ran)
        j["sourceValidator"] = {{"errors", r.sourceValidator.errors}, {"warnings", r.sourceValidator.warnings}};
    j["reference"] = {{"factor", shortest(r.referenceFactor)},
                      {"skipped", r.referenceSkipped.empty() ? Json(nullptr) : Json(r.referenceSkipped)}};
    Json ts = Json::array();
    for (const TessellationChecks& t : r.tessellations) {
        Json tj = {{"name", t.name},
                   {"path", t.path},
                   {"mode", t.tess.mode == TessMode::Global ? "global" : "screen"},
                   {"factor", shortest(t.tess.factor)},
                   {"spacing", spacingName(t.tess.spacing)},
                   {"watertight", t.eval.watertight},
                   {"displaced", t.eval.displace},
                   {"lodFactor", shortest(t.factor)},
                   {"depth", t.depth},
                   {"pass", t.pass()}};
        if (!t.error.empty()) {
            tj["error"] = t.error;
        } else {
            tj["triangles"] = t.triangles;
            tj["accuracy"] = accuracyJson(t.accuracy);
            tj["weld"] = weldJson(t.weld);
            const NormalResult& n = t.normals;
            tj["normals"] = {{"judged", n.judged}, {"unjudged", n.unjudged}, {"folded", n.folded},
                             {"refined", n.refined}, {"confirmed", n.confirmed}, {"against", n.against}, {"zero", n.zero},
                             {"firstFailure", n.firstFailure.empty() ? Json(nullptr) : Json(n.firstFailure)},
                             {"pass", n.pass()}};
            if (!n.skipped.empty()) tj["normals"]["skipped"] = n.skipped;
            tj["rays"] = raysJson(t.rays);
        }
        if (t.compared)
            tj["cpuComparison"] = {{"cpuVertices", t.cpuVertices},     {"equalVertices", t.equalVertices},
                                   {"equalPositions", t.equalPositions}, {"equalNormals", t.equalNormals}};
        if (timings) tj["timing"] = {{"evaluateSeconds", t.evaluateSeconds}, {"checkSeconds", t.checkSeconds}};
        ts.push_back(tj);
    }
    j["tessellations"] = ts;
    Json fs = Json::array();
    for (const Finding& f : r.findings) fs.push_back({{"id", f.id}, {"severity", f.severity}, {"text", f.text}});
    j["findings"] = fs;
    if (timings)
        j["timing"] = {{"seconds", r.seconds},
                       {"referenceSeconds", r.referenceSeconds},
                       {"sourceSeconds", r.sourceSeconds},
                       {"validatorSeconds", r.validatorSeconds}};
    // Invalid UTF-8 (a file name, a validator message) is replaced, never thrown.
    return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

std::string reportJson(const std::vector<CheckReport>& reports, const CheckSettings& s, bool timings) {
    if (reports.size() == 1) return reportJson(reports[0], s, timings);
    Json j;
    j["tool"] = "loopcheck";
    j["version"] = LOOPTESS_VERSION_STRING;
    const std::string file = reports.empty() ? "" : reports[0].assetName.substr(0, reports[0].assetName.find(": meshes["));
    j["asset"] = {{"file", file}, {"bytes", reports.empty() ? 0 : reports[0].assetBytes}};
    int code = 0;
    for (const CheckReport& r : reports) code = std::max(code, exitCode(r));
    j["result"] = code == 0 ? "pass" : code == 2 ? "invalid" : "fail";
    j["exitCode"] = code;
    j["surfaces"] = Json::array();
    for (const CheckReport& r : reports) j["surfaces"].push_back(Json::parse(reportJson(r, s, timings)));
    return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

std::string reportText(const CheckReport& r, bool failuresOnly, bool verbose) {
    std::ostringstream s;
    const std::string& a = r.assetName;
    if (!failuresOnly && r.structureValid) {
        const ControlTopology& t = r.topology;
        s << a << ": structure valid: " << r.controlVertices << " control vertices, " << r.baseFaces
          << " base faces, depth " << r.maxDepth << ", " << r.vertices << " refined vertices; control mesh "
          << (t.closed() ? "closed" : "not closed") << " (" << t.drawnFaces << " drawn faces, " << t.edges
          << " edges, " << t.boundaryEdges << " boundary, " << t.nonManifoldEdges << " non-manifold)\n";
        if (!r.sourceName.empty() && r.sourceMismatch.empty())
            s << a << ": source " << r.sourceName << ": the same control mesh\n";
        if (r.stencilsChecked) {
            const StencilResult& st = r.stencils;
            s << a << ": limit stencils: ";
            if (!st.skipped.empty()) s << "not checked: " << st.skipped << "\n";
            else s << st.checked << " checked against OpenSubdiv, " << st.failures << " off, worst " << st.worstRatio
                   << "x their rounding" << (st.unmatched ? ", " + std::to_string(st.unmatched) + " unmatched" : "")
                   << "\n";
        }
        const ValidatorResult& v = r.validator;
        if (v.state == ValidatorResult::Ran)
            s << a << ": Khronos glTF-Validator: " << v.errors << " errors, " << v.warnings << " warnings, " << v.infos
              << " infos, " << v.hints << " hints\n";
        if (r.referenceFactor > 0) s << a << ": ray reference: F=" << r.referenceFactor << " equal\n";
        for (const TessellationChecks& t : r.tessellations) {
            if (!t.error.empty()) continue;
            s << a << ": " << t.name << " (" << t.path << "): F " << t.factor << ", depth " << t.depth << ", "
              << t.triangles << " triangles";
            if (t.accuracy.ran)
                s << "; accuracy: " << t.accuracy.sampled << " vertices, max error " << t.accuracy.maxPositionError
                  << " of the diagonal, max 1 - cos " << t.accuracy.maxNormalError;
            const WeldResult& w = t.weld;
            s << "; weld: " << w.openEdges << " open edges (" << w.boundaryEdges << " on the boundary, "
              << w.tJunctions << " T-junctions), " << w.nonManifoldEdges << " non-manifold";
            s << "; normals: " << t.normals.against << " behind their triangle";
            if (t.normals.refined) s << " (" << t.normals.refined << " more in front of the finer surface)";
            if (t.normals.confirmed) s << " (" << t.normals.confirmed << " more as OpenSubdiv's)";
            s << ", " << t.normals.zero << " zero";
            const RayResult& y = t.rays;
            if (y.ran) {
                s << "; rays: " << y.escaped << " of " << y.rays << " escaped";
                if (y.distanceChecked)
                    s << ", distances max " << y.maxDistanceError << " of the diagonal (" << y.maxToleranceRatio
                      << "x tolerance), " << y.distanceFailures << " beyond";
            }
            if (t.compared) s << "; " << t.equalVertices << " of " << t.cpuVertices << " vertices equal to the CPU's";
            s << (t.pass() ? ": ok" : ": FAILED") << "\n";
            if (verbose) {
                s << "    weld: " << w.vertices << " vertices -> " << w.weldedVertices << ", " << w.edges << " edges, "
                  << w.degenerateTriangles << " degenerate triangles, " << w.normalSplitVertices
                  << " welded vertices with differing normals, " << w.misorientedEdges << " misoriented edges\n";
                if (t.accuracy.ran)
                    s << "    accuracy: " << t.accuracy.oracleLimited << " within the oracle's convergence, "
                      << t.accuracy.floatLimited << " within float resolution, "
                      << t.accuracy.normalsSkipped << " normals undefined\n";
                if (y.ran)
                    s << "    rays: " << y.origins << " interior points of " << y.candidates << " candidates, "
                      << y.frontHits << " front-face hits, " << y.compared << " distances compared, "
                      << y.foldRays << " past a fold, " << y.referenceEscaped << " escaped the reference\n";
                s << "    time: evaluate " << t.evaluateSeconds << " s, checks " << t.checkSeconds << " s\n";
            }
        }
    }
    for (const Finding& f : r.findings)
        if (!failuresOnly || f.severity != "info") s << a << ": " << f.severity << " " << f.id << ": " << f.text << "\n";
    if (verbose && r.structureValid)
        s << a << ": time: OpenSubdiv oracle " << r.sourceSeconds << " s, validator " << r.validatorSeconds
          << " s, checks " << r.seconds << " s (of which the ray reference " << r.referenceSeconds << " s)\n";
    const int code = exitCode(r);
    s << a << ": " << (code == 0 ? "PASS" : code == 2 ? "INVALID" : "FAILED") << "\n";
    return s.str();
}

} // namespace lt

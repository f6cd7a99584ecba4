// The report: JSON (formats/loopcheck-report.schema.json), JUnit XML and text (looptess/tools/check.h).
#include "looptess/tools/check.h"
#include "looptess/version.h"

#include "check_internal.h"

#include <nlohmann/json.hpp>

#include <cstdio>
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
            {"corners", a.corners},
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
    return {{"vertices", w.vertices},
            {"weldedVertices", w.weldedVertices},
            {"triangles", w.triangles},
            {"degenerateTriangles", w.degenerateTriangles},
            {"nonFiniteVertices", w.nonFiniteVertices},
            {"edges", w.edges},
            {"openEdges", w.openEdges},
            {"boundaryEdges", w.boundaryEdges},
            {"crackEdges", w.crackEdges},
            {"tJunctions", w.tJunctions},
            {"tJunctionVertices", w.tJunctionVertices},
            {"nonManifoldEdges", w.nonManifoldEdges},
            {"unexpectedNonManifoldEdges", w.unexpectedNonManifoldEdges},
            {"misorientedEdges", w.misorientedEdges},
            {"contactEdges", w.contactEdges},
            {"normalSplitVertices", w.normalSplitVertices},
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

}  // namespace

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
                     {"drawPath", s.path == DrawPath::Tessellator ? "tessellator"
                                  : s.path == DrawPath::Patterns  ? "patterns"
                                                                  : "compute"},
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
    if (!r.structureValid)
        st["message"] = r.structureMessage;
    else
        st.update({{"controlVertices", r.controlVertices},
                   {"baseFaces", r.baseFaces},
                   {"maxDepth", r.maxDepth},
                   {"vertices", r.vertices}});
    j["structure"] = st;
    if (r.structureValid) {
        const ControlTopology& t = r.topology;
        j["controlMesh"] = {{"drawnFaces", t.drawnFaces},
                            {"edges", t.edges},
                            {"boundaryEdges", t.boundaryEdges},
                            {"nonManifoldEdges", t.nonManifoldEdges},
                            {"closed", t.closed()}};
    }
    j["source"] = r.sourceName.empty()
                      ? Json(nullptr)
                      : Json{{"file", r.sourceName},
                             {"matches", r.sourceMismatch.empty()},
                             {"message", r.sourceMismatch.empty() ? Json(nullptr) : Json(r.sourceMismatch)}};
    if (r.stencilsChecked) {
        const StencilResult& st = r.stencils;
        j["source"]["stencils"] = {{"checked", st.checked},
                                   {"failures", st.failures},
                                   {"unmatched", st.unmatched},
                                   {"worstRatio", st.worstRatio},
                                   {"firstFailure", st.firstFailure.empty() ? Json(nullptr) : Json(st.firstFailure)},
                                   {"pass", st.pass()}};
        if (!st.skipped.empty()) j["source"]["stencils"]["skipped"] = st.skipped;
    }
    const ValidatorResult& v = r.validator;
    static const char* kState[] = {"skipped", "unavailable", "ran"};
    Json vj = {{"state", kState[v.state]}};
    if (v.state == ValidatorResult::Ran)
        vj.update({{"pass", v.pass()},
                   {"errors", v.errors},
                   {"warnings", v.warnings},
                   {"infos", v.infos},
                   {"hints", v.hints},
                   {"messages", v.messages}});
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
        if (!t.notRun.empty()) {
            tj["triangles"] = t.triangles;
            tj["estimatedBytes"] = t.estimatedBytes;
            tj["notRun"] = t.notRun;
        } else if (!t.error.empty()) {
            tj["error"] = t.error;
        } else {
            tj["triangles"] = t.triangles;
            if (t.pieces > 1) tj["pieces"] = t.pieces;
            tj["accuracy"] = accuracyJson(t.accuracy);
            tj["weld"] = weldJson(t.weld);
            const NormalResult& n = t.normals;
            tj["normals"] = {{"judged", n.judged},
                             {"unjudged", n.unjudged},
                             {"folded", n.folded},
                             {"refined", n.refined},
                             {"confirmed", n.confirmed},
                             {"against", n.against},
                             {"zero", n.zero},
                             {"firstFailure", n.firstFailure.empty() ? Json(nullptr) : Json(n.firstFailure)},
                             {"pass", n.pass()}};
            if (!n.skipped.empty()) tj["normals"]["skipped"] = n.skipped;
            tj["rays"] = raysJson(t.rays);
        }
        if (t.compared)
            tj["cpuComparison"] = {{"cpuVertices", t.cpuVertices},
                                   {"equalVertices", t.equalVertices},
                                   {"equalPositions", t.equalPositions},
                                   {"equalNormals", t.equalNormals}};
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
    const std::string file =
        reports.empty() ? "" : reports[0].assetName.substr(0, reports[0].assetName.find(": meshes["));
    j["asset"] = {{"file", file}, {"bytes", reports.empty() ? 0 : reports[0].assetBytes}};
    int code = 0;
    for (const CheckReport& r : reports) code = std::max(code, exitCode(r));
    j["result"] = code == 0 ? "pass" : code == 2 ? "invalid" : "fail";
    j["exitCode"] = code;
    j["surfaces"] = Json::array();
    for (const CheckReport& r : reports) j["surfaces"].push_back(Json::parse(reportJson(r, s, timings)));
    return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

std::string xmlEscape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    const auto* p = reinterpret_cast<const unsigned char*>(text.data());
    const size_t n = text.size();
    const char* const kReplacement = "\xEF\xBF\xBD";  // U+FFFD
    for (size_t i = 0; i < n;) {
        const unsigned char c = p[i];
        if (c < 0x80) {
            switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            case '\t': out += "&#9;"; break;  // kept through attribute-value normalization
            case '\n': out += "&#10;"; break;
            case '\r': out += "&#13;"; break;
            default:
                if (c < 0x20 || c == 0x7F)
                    out += kReplacement;  // XML 1.0 forbids C0; DEL is allowed but invisible
                else
                    out += char(c);
            }
            ++i;
            continue;
        }
        // A UTF-8 sequence: its length from the lead byte, then continuation bytes,
        // no overlong form, no surrogate, nothing past U+10FFFF, not U+FFFE / U+FFFF.
        const size_t len = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
        uint32_t cp = len == 2 ? c & 0x1F : len == 3 ? c & 0x0F : c & 0x07;
        bool ok = len > 0 && i + len <= n;
        for (size_t k = 1; ok && k < len; ++k) {
            ok = (p[i + k] & 0xC0) == 0x80;
            cp = cp << 6 | (p[i + k] & 0x3F);
        }
        ok = ok && !(len == 3 && cp < 0x800) && !(len == 4 && (cp < 0x10000 || cp > 0x10FFFF)) &&
             !(cp >= 0xD800 && cp <= 0xDFFF) && cp != 0xFFFE && cp != 0xFFFF;
        if (ok) {
            out.append(text, i, len);
            i += len;
        } else {
            out += kReplacement;  // one per bad byte
            ++i;
        }
    }
    return out;
}

namespace {

// One <testcase>: passed, failed (error findings), an error (the check could not
// run and had to), or skipped (why).
struct JUnitCase {
    enum Kind { Pass, Failure, Error, Skipped };
    std::string name, classname;
    double seconds = 0;
    Kind kind = Pass;
    std::string message, body, out;  // failure / error message and text, skip reason, system-out
};

std::string seconds3(double s) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3f", s > 0 ? s : 0.0);
    return b;
}

// The case of check `ids` (its findings among `findings`): failed on an error
// finding, else passed; info and warning findings go to its system-out.
JUnitCase judged(const std::string& name, const char* classname, double seconds, const std::vector<Finding>& findings,
                 std::initializer_list<const char*> ids) {
    JUnitCase c;
    c.name = name, c.classname = classname, c.seconds = seconds;
    for (const Finding& f : findings) {
        bool mine = false;
        for (const char* id : ids) mine = mine || f.id == id;
        if (!mine) continue;
        const std::string line = f.id + " " + f.severity + ": " + f.text + "\n";
        if (f.severity == "error") {
            if (c.kind == JUnitCase::Pass) c.kind = JUnitCase::Failure, c.message = f.text;
            c.body += line;
        } else {
            c.out += line;
        }
    }
    return c;
}

JUnitCase skipped(const std::string& name, const char* classname, const std::string& why) {
    JUnitCase c;
    c.name = name, c.classname = classname;
    c.kind = JUnitCase::Skipped;
    c.message = why;
    return c;
}

// The four checks of a tessellation (`at`: " F=8 equal (cpu)"), skipped for `why`.
void skipTessellation(std::vector<JUnitCase>& cases, const std::string& at, const std::string& why) {
    cases.push_back(skipped("A1 accuracy" + at, "accuracy", why));
    cases.push_back(skipped("W1-W5 watertight" + at, "watertight", why));
    cases.push_back(skipped("N1 normals" + at, "normals", why));
    cases.push_back(skipped("R1-R5 rays" + at, "rays", why));
}

std::vector<JUnitCase> junitCases(const CheckReport& r, const CheckSettings& s) {
    std::vector<JUnitCase> cases;
    const std::vector<Finding>& f = r.findings;
    if (!r.structureValid) {
        cases.push_back(judged("S1 structure", "structure", 0, f, {"S1"}));
        const std::string why = "not run: the asset is invalid (S1)";
        for (const char* check : {"M1-M2 source", "A3 limit stencils", "V1-V2 validator"})
            cases.push_back(skipped(check, "", why));
        cases[1].classname = "source", cases[2].classname = "stencils", cases[3].classname = "validator";
        for (const TessCase& t : s.cases) skipTessellation(cases, " " + tessCaseName(t) + " (cpu)", why);
        return cases;
    }
    cases.push_back(judged("S1 structure", "structure", 0, f, {"S1"}));
    if (r.sourceName.empty())
        cases.push_back(skipped("M1-M2 source", "source", "no --source"));
    else
        cases.push_back(judged("M1-M2 source", "source", r.sourceSeconds, f, {"M1", "M2", "A2"}));
    if (!r.stencilsChecked)
        cases.push_back(skipped(
            "A3 limit stencils", "stencils",
            r.sourceName.empty() ? "no --source" : "not run: the source's control mesh is not the asset's (M1)"));
    else if (!r.stencils.skipped.empty())
        cases.push_back(skipped("A3 limit stencils", "stencils", r.stencils.skipped));
    else
        cases.push_back(judged("A3 limit stencils", "stencils", 0, f, {"A3"}));
    const ValidatorResult& v = r.validator;
    if (v.state == ValidatorResult::Skipped) {
        cases.push_back(skipped("V1-V2 validator", "validator", "--no-validator"));
    } else if (v.state == ValidatorResult::Unavailable && !s.strictValidator) {
        cases.push_back(skipped("V1-V2 validator", "validator", "Khronos glTF-Validator not available: " + v.detail));
    } else {
        JUnitCase c = judged("V1-V2 validator", "validator", r.validatorSeconds, f, {"V1", "V2"});
        if (v.state == ValidatorResult::Unavailable) c.kind = JUnitCase::Error;  // --strict-validator: could not run
        cases.push_back(c);
    }
    for (const TessellationChecks& t : r.tessellations) {
        std::vector<Finding> tf;
        addTessellationFindings(s, t, tf);
        const std::string at = " " + t.name + " (" + t.path + ")";
        if (!t.notRun.empty()) {
            JUnitCase c = judged("L1 memory" + at, "memory", 0, tf, {"L1"});
            c.kind = JUnitCase::Error;  // could not run
            cases.push_back(c);
            skipTessellation(cases, at, "not run: over the memory limit (L1)");
            continue;
        }
        if (t.path == "gpu")
            cases.push_back(judged("G1-G2 capture" + at, "capture", t.evaluateSeconds, tf, {"G1", "G2"}));
        if (!t.error.empty()) {
            skipTessellation(cases, at, "not run: the GPU capture failed (G1)");
            continue;
        }
        if (t.accuracy.ran)
            cases.push_back(judged("A1 accuracy" + at, "accuracy", t.accuracySeconds, tf, {"A1"}));
        else
            cases.push_back(skipped("A1 accuracy" + at, "accuracy",
                                    r.sourceName.empty()        ? "no --source"
                                    : !r.sourceMismatch.empty() ? "the source's control mesh is not the asset's (M1)"
                                    : t.eval.displace ? "displaced: OpenSubdiv's limit is the undisplaced surface's"
                                    : t.path != "cpu" ? "A1 samples the CPU's evaluation"
                                                      : "not run"));
        cases.push_back(judged("W1-W5 watertight" + at, "watertight", t.weldSeconds, tf, {"W1", "W2", "W3", "W5"}));
        if (!t.normals.skipped.empty())
            cases.push_back(skipped("N1 normals" + at, "normals", t.normals.skipped));
        else
            cases.push_back(judged("N1 normals" + at, "normals", t.normalsSeconds, tf, {"N1"}));
        if (!t.rays.ran)
            cases.push_back(skipped("R1-R5 rays" + at, "rays", t.rays.skipped));
        else
            cases.push_back(judged("R1-R5 rays" + at, "rays", t.raysSeconds, tf, {"R1", "R2", "R4", "R5"}));
    }
    return cases;
}

}  // namespace

std::string reportJUnit(const std::vector<CheckReport>& reports, const CheckSettings& settings) {
    std::ostringstream suites;
    uint64_t tests = 0, failures = 0, errors = 0;
    double total = 0;
    for (const CheckReport& r : reports) {
        const std::vector<JUnitCase> cases = junitCases(r, settings);
        uint64_t fails = 0, errs = 0, skips = 0;
        for (const JUnitCase& c : cases) {
            fails += c.kind == JUnitCase::Failure;
            errs += c.kind == JUnitCase::Error;
            skips += c.kind == JUnitCase::Skipped;
        }
        // The whole run of this surface: its checks, the source's oracle, the validator.
        const double seconds = r.seconds + r.sourceSeconds + r.validatorSeconds;
        tests += cases.size(), failures += fails, errors += errs, total += seconds;
        suites << "  <testsuite name=\"" << xmlEscape(r.assetName) << "\" tests=\"" << cases.size() << "\" failures=\""
               << fails << "\" errors=\"" << errs << "\" skipped=\"" << skips << "\" time=\"" << seconds3(seconds)
               << "\">\n";
        suites << "    <properties>\n"
               << "      <property name=\"loopcheck.version\" value=\"" << xmlEscape(LOOPTESS_VERSION_STRING)
               << "\"/>\n"
               << "      <property name=\"exitCode\" value=\"" << exitCode(r) << "\"/>\n";
        if (!r.sourceName.empty())
            suites << "      <property name=\"source\" value=\"" << xmlEscape(r.sourceName) << "\"/>\n";
        if (!r.gpuDevice.empty())
            suites << "      <property name=\"gpuDevice\" value=\"" << xmlEscape(r.gpuDevice) << "\"/>\n";
        suites << "    </properties>\n";
        for (const JUnitCase& c : cases) {
            suites << "    <testcase name=\"" << xmlEscape(c.name) << "\" classname=\"" << xmlEscape(c.classname)
                   << "\" time=\"" << seconds3(c.seconds) << "\"";
            if (c.kind == JUnitCase::Pass && c.out.empty()) {
                suites << "/>\n";
                continue;
            }
            suites << ">\n";
            auto lines = [](const std::string& s) { return xmlEscape(s.substr(0, s.find_last_not_of('\n') + 1)); };
            // The schema's order: skipped, error, failure, system-out.
            if (c.kind == JUnitCase::Skipped) suites << "      <skipped>" << xmlEscape(c.message) << "</skipped>\n";
            const char* element = c.kind == JUnitCase::Failure ? "failure"
                                  : c.kind == JUnitCase::Error ? "error"
                                                               : nullptr;
            if (element)
                suites << "      <" << element << " message=\"" << xmlEscape(c.message) << "\" type=\""
                       << xmlEscape(c.body.substr(0, c.body.find(' '))) << "\">" << lines(c.body) << "</" << element
                       << ">\n";
            if (!c.out.empty()) suites << "      <system-out>" << lines(c.out) << "</system-out>\n";
            suites << "    </testcase>\n";
        }
        suites << "  </testsuite>\n";
    }
    std::ostringstream x;
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuites name=\"loopcheck\" tests=\"" << tests << "\" failures=\"" << failures << "\" errors=\"" << errors
      << "\" time=\"" << seconds3(total) << "\">\n"
      << suites.str() << "</testsuites>\n";
    return x.str();
}

std::string reportText(const CheckReport& r, bool failuresOnly, bool verbose) {
    std::ostringstream s;
    const std::string& a = r.assetName;
    if (!failuresOnly && r.structureValid) {
        const ControlTopology& t = r.topology;
        s << a << ": structure valid: " << r.controlVertices << " control vertices, " << r.baseFaces
          << " base faces, depth " << r.maxDepth << ", " << r.vertices << " refined vertices; control mesh "
          << (t.closed() ? "closed" : "not closed") << " (" << t.drawnFaces << " drawn faces, " << t.edges << " edges, "
          << t.boundaryEdges << " boundary, " << t.nonManifoldEdges << " non-manifold)\n";
        if (!r.sourceName.empty() && r.sourceMismatch.empty())
            s << a << ": source " << r.sourceName << ": the same control mesh\n";
        if (r.stencilsChecked) {
            const StencilResult& st = r.stencils;
            s << a << ": limit stencils: ";
            if (!st.skipped.empty())
                s << "not checked: " << st.skipped << "\n";
            else
                s << st.checked << " checked against OpenSubdiv, " << st.failures << " off, worst " << st.worstRatio
                  << "x their rounding" << (st.unmatched ? ", " + std::to_string(st.unmatched) + " unmatched" : "")
                  << "\n";
        }
        const ValidatorResult& v = r.validator;
        if (v.state == ValidatorResult::Ran)
            s << a << ": Khronos glTF-Validator: " << v.errors << " errors, " << v.warnings << " warnings, " << v.infos
              << " infos, " << v.hints << " hints\n";
        if (r.referenceFactor > 0) s << a << ": ray reference: F=" << r.referenceFactor << " equal\n";
        for (const TessellationChecks& t : r.tessellations) {
            if (!t.error.empty() || !t.notRun.empty()) continue;
            s << a << ": " << t.name << " (" << t.path << "): F " << t.factor << ", depth " << t.depth << ", "
              << t.triangles << " triangles";
            if (t.pieces > 1)
                s << " in " << t.pieces << (t.path == "gpu" ? " capture sessions" : " pieces of base faces");
            if (t.accuracy.ran)
                s << "; accuracy: " << t.accuracy.sampled << " vertices (" << t.accuracy.corners
                  << " at base corners), max error " << t.accuracy.maxPositionError << " of the diagonal, max 1 - cos "
                  << t.accuracy.maxNormalError;
            const WeldResult& w = t.weld;
            s << "; weld: " << w.openEdges << " open edges (" << w.boundaryEdges << " on the boundary, " << w.tJunctions
              << " T-junctions), " << w.nonManifoldEdges << " non-manifold";
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
                      << t.accuracy.floatLimited << " within float resolution, " << t.accuracy.normalsSkipped
                      << " normals undefined\n";
                if (y.ran)
                    s << "    rays: " << y.origins << " interior points of " << y.candidates << " candidates, "
                      << y.frontHits << " front-face hits, " << y.compared << " distances compared, " << y.foldRays
                      << " past a fold, " << y.referenceEscaped << " escaped the reference\n";
                s << "    time: evaluate " << t.evaluateSeconds << " s, checks " << t.checkSeconds << " s\n";
            }
        }
    }
    for (const Finding& f : r.findings)
        if (!failuresOnly || f.severity != "info")
            s << a << ": " << f.severity << " " << f.id << ": " << f.text << "\n";
    if (verbose && r.structureValid)
        s << a << ": time: OpenSubdiv oracle " << r.sourceSeconds << " s, validator " << r.validatorSeconds
          << " s, checks " << r.seconds << " s (of which the ray reference " << r.referenceSeconds << " s)\n";
    const int code = exitCode(r);
    s << a << ": " << (code == 0 ? "PASS" : code == 2 ? "INVALID" : "FAILED") << "\n";
    return s.str();
}

}  // namespace lt

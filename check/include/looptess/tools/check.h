// looptess/tools/check.h -- loopcheck's checks as a library (looptess_check): validates a
// baked EXT_mesh_loop_subdivision asset for CI; the loopcheck tool parses its command
// line into CheckSettings, reads files and prints. What each check computes and why:
// docs/loopcheck.md ("The library: what each check computes"), with a usage example.
// No function here throws, calls exit() or does I/O, except those marked "I/O".
#pragma once

#include "looptess/asset.h"
#include "looptess/tools/baker.h"
#include "looptess/tools/osd_reference.h"
#include "looptess/runtime.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lt {

// --- [1] Settings ----------------------------------------------------------------------

// One tessellation the checks run on: the global factor `factor`, or per-edge
// screen-space factors (LodMode::Screen) whose largest is `factor` (docs/loopcheck.md).
enum class TessMode : uint8_t { Global, Screen };
struct TessCase {
    TessMode mode = TessMode::Global;
    float factor = 1.0f;
    Spacing spacing = Spacing::Equal;
};

// "F=8 equal", "F=3.3 fractional_odd", "screen F<=8 equal".
std::string tessCaseName(const TessCase& c);
// Parses loopcheck's --tess item: F[:equal|:odd] or screen[=F][:equal|:odd] (F in
// [1, 64]; `odd` is fractional_odd; screen alone is screen=8). Usage on a bad item.
Status parseTessCase(const std::string& text, TessCase& out);

// Every default of every check, in this one place.
struct CheckSettings {
    // The tessellations: F = 1, 3.3 fractional_odd, 5, 8, and a screen-space case.
    std::vector<TessCase> cases = {{TessMode::Global, 1.0f, Spacing::Equal},
                                   {TessMode::Global, 3.3f, Spacing::FractionalOdd},
                                   {TessMode::Global, 5.0f, Spacing::Equal},
                                   {TessMode::Global, 8.0f, Spacing::Equal},
                                   {TessMode::Screen, 8.0f, Spacing::FractionalOdd}};
    bool watertight = true;  // EvalSettings::watertight (--no-watertight)
    unsigned threads = 0;    // EvalSettings::threads (--threads; 0: every hardware thread)
    // Whose domain points are evaluated and checked (--path): the tessellator's, or the
    // refinement patterns' (Patterns; with --gpu, Compute captures its compute path).
    DrawPath path = DrawPath::Tessellator;
    bool strictValidator = false;  // an unavailable Khronos validator fails the run

    // Accuracy (with a source): every captured vertex against OpenSubdiv's limit.
    double positionTolerance = 1e-5;    // |P - P_osd|, of the bounding-box diagonal
    double normalTolerance = 1e-5;      // 1 - cos(N, N_osd)
    uint64_t accuracySamples = 100000;  // vertices per tessellation, one per stratum, besides every base corner
    int isolation = 10;                 // of the oracle's PatchTable

    // Rays (closed manifold control meshes only).
    uint64_t rays = 100000;                      // per tessellation (--rays)
    uint64_t seed = 0x6c6f6f70636b;              // every random choice derives from it
    uint32_t rayOrigins = 1000;                  // interior points, rays / rayOrigins rays each
    uint32_t originProbes = 8;                   // rays that classify a candidate origin
    double distanceSlack = 1e-5;                 // of the diagonal, added to the chord bounds
    float referenceFactor = 0;                   // 0: the finest power of two <= 2^maxDepth,
    uint64_t referenceTriangleBudget = 4000000;  //   <= 64, whose estimate 2 F^2 faces fits this

    // Memory: a tessellation whose checks would take the process past this many bytes
    // (its resident memory before the case plus checkBytes) is not evaluated whole
    // (--max-memory-mb). 0: the process's resident memory plus 90% of what the machine
    // has available when the case starts (availableMemoryBytes).
    uint64_t maxMemoryBytes = 0;
    // Over it, a tessellation is evaluated and checked in pieces of whole base faces
    // (EvalSettings::firstFace), each within what the welded whole leaves; L1 only
    // where that does not fit either. Pieces hold no whole soup: the rays compare no
    // hit distances, and a --gpu capture is taken session by session (checked alike,
    // not compared with the CPU's). pieceTriangles > 0: pieces and sessions of at most
    // that many triangles whatever the memory (--piece-triangles).
    uint64_t pieceTriangles = 0;

    // The screen-space camera: 40 degrees, 1080 rows, from the bounding-box centre
    // along (0.3, 0.2, 1) at the distance where the bounding sphere fills the view.
    float screenFovDegrees = 40.0f;
    uint32_t screenRows = 1080;
};

// --- [2] Structure -----------------------------------------------------------------------

// Reads a GLB (readAssetGlb: the spec's rules) and checks that the tables are a Loop
// refinement of the control mesh (checks C1-C6, docs/loopcheck.md). Safe on untrusted
// bytes; the message names the file, the table and the rule.
Status checkStructure(const uint8_t* data, size_t size, const std::string& name, Asset& asset);
// As above for every surface of a scene (readSceneGlb), each checked on its own.
Status checkSceneStructure(const uint8_t* data, size_t size, const std::string& name,
                           std::vector<SceneSurface>& surfaces);
// How findings name surface `s` of `file`: the file alone when it has one surface,
// else "file: meshes[2] (arm)".
std::string surfaceName(const std::string& file, const std::vector<SceneSurface>& surfaces, const SceneSurface& s);

// --- [3] Control mesh and source -------------------------------------------------------

// The control mesh's drawn faces (with a patch or irregular face at some level) and
// their edges. Closed: every drawn edge has exactly two drawn faces, oppositely
// oriented; only then do the ray tests run.
struct ControlTopology {
    std::vector<uint8_t> drawn;     // per base face
    std::vector<uint8_t> edgeKind;  // per face edge (3 per face): kInterior, kBoundary, kNonManifold
    // Per base face: folded onto a neighbour across an interior edge, the two planes
    // within kFoldSine of each other and wound apart (a triangle doubled back on
    // itself), or with no area to speak of beside one (twice its area under kFoldSine
    // of its longest edge squared): their surfaces may touch within float resolution
    // (W6).
    std::vector<uint8_t> folded;
    static constexpr double kFoldSine = 1e-4;
    uint64_t drawnFaces = 0, edges = 0, boundaryEdges = 0, nonManifoldEdges = 0;
    bool closed() const { return drawnFaces > 0 && boundaryEdges == 0 && nonManifoldEdges == 0; }
    static constexpr uint8_t kInterior = 0, kBoundary = 1, kNonManifold = 2;
};

// How the source was read (loopbake's options that change the control mesh).
struct SourceOptions {
    float creaseAngle = -1;  // loopbake --crease-angle; < 0: off
    bool strict = false;     // loopbake --strict (no input cleaning: refused)
    bool hardEdges = false;  // loopbake --hard-edges (glTF split normals: creases)
    std::string edits;       // loopbake --edits EDITS.json (hierarchical edits); "" none
    // loopbake --boundary: every source mesh's boundary rule; unset: the source's own
    // (an OBJ's tag, else edge-only). The asset's stored rule must be the result.
    std::optional<BoundaryInterpolation> boundary;
};
// A source's control meshes as the baker reads them: an OBJ's one (index -1), or each
// glTF mesh's with triangles, in its own space (parseGltfScene), with its mesh index.
struct SourceMeshes {
    std::vector<InputMesh> meshes;
    std::vector<int64_t> index;  // parallel to meshes
};
// I/O: reads an .obj, .gltf or .glb with the baker's readers (a .gltf's sibling files
// from its directory), once for all its surfaces. BadInput / Unsupported with the
// reader's message.
Status loadSource(const std::string& path, const SourceOptions& options, SourceMeshes& source);
// I/O (options.edits): the control mesh of glTF mesh `mesh` of `source` (-1: its
// first), with the edits of options.edits appended (parseEditsJson), checkInput run
// and creaseAngle applied, as loopbake does. `path` (the source's) names it in messages.
Status sourceMesh(const SourceMeshes& source, int64_t mesh, const std::string& path, const SourceOptions& options,
                  InputMesh& out);

// "" when the source's control mesh is the asset's (vertex and face counts, then
// positions and corners bit for bit, boundary and crease options, the number of
// hierarchical edits); else what differs.
std::string compareControlMesh(const InputMesh& source, const Asset& asset);

// Limit stencils (A3; with a source whose control mesh is the asset's, no edits): each
// explicit-weight stencil must give OpenSubdiv's limit point within the weights' own
// float rounding (bound and reasoning: docs/loopcheck.md).
struct StencilResult {
    uint64_t checked = 0, failures = 0;
    uint64_t unmatched = 0;  // stencils whose vertices or limit OpenSubdiv's refinement lacks
    double worstRatio = 0;   // the largest |error| / bound
    std::string firstFailure, skipped;
    bool pass() const { return failures == 0; }
};

// I/O: with a glTF source, whether everything in the baked file but its surfaces is
// the source's (read as loopbake reads it): asset, scenes, nodes, cameras,
// materials, textures, samplers, skins, animations, extensions and extras as JSON,
// images and the source's accessors and bufferViews with their bytes, meshes but
// for the extension's objects. `differences` receives what differs (at most 20),
// empty when nothing does. BadInput when a file cannot be read.
Status compareScene(const std::string& assetPath, const std::string& sourcePath, std::vector<std::string>& differences);

// The accuracy oracle for a source: OpenSubdiv at settings.isolation, and at
// isolation - 2 and - 4 (built on first need) to bound its own convergence; the
// source's hierarchical edits included. atDepth(d): the oracle of the surface the
// runtime draws at depth d (edits of levels <= d), built on first need; its Status is
// build()'s. Details: docs/loopcheck.md.
struct SourceOracle {
    InputMesh mesh;
    OsdLimitSurface fine, coarse, coarser;
    OsdCornerNormals corners;  // built on first need (meshes without edits)
    uint32_t assetDepth = 0;   // the asset's deepest level (a spike's face normals)
    int isolation = 10;
    Status build();  // builds `fine` from `mesh`
    Status atDepth(uint32_t depth, SourceOracle*& oracle);
    std::vector<std::unique_ptr<SourceOracle>> shallower;  // [d]: edits of levels <= d
};

// --- [4] What the checks of one tessellation find ---------------------------------------

// Accuracy (with a source): every vertex at a base-face corner ((u, v) = (0, 0),
// (1, 0), (0, 1)) and one vertex in each of settings.accuracySamples equal strata,
// compared with the oracle; allowances for the oracle's convergence
// (oracleLimited) and float resolution (floatLimited) are in docs/loopcheck.md.
struct AccuracyResult {
    bool ran = false;
    uint64_t sampled = 0;  // vertices compared
    uint64_t corners = 0;  // of them at a base-face corner: every one emitted
    uint64_t positionFailures = 0, normalFailures = 0;
    uint64_t noLimit = 0;         // vertices on a face OpenSubdiv draws nothing on
    uint64_t normalsSkipped = 0;  // where the limit has no normal
    uint64_t oracleLimited = 0;   // within the oracle's own isolation 8 -> 10 change
    uint64_t floatLimited = 0;    // within float resolution: far from the origin, a thin face's normal
    double maxPositionError = 0;  // of the diagonal
    double maxNormalError = 0;    // 1 - cos
    std::string firstFailure;     // "vertex i face f (u, v): ..." or ""
    uint32_t referenceEdits = 0;  // hierarchical edits the oracle includes
    int referenceEditLevel = 0;   //   and the deepest of their levels
};

// Watertightness by exact bits over the welded, non-degenerate triangles: open edges
// off the control boundary are cracks (T-junctions among them), non-manifold and
// misoriented edges fail, differing normals at a weld are reported. Definitions:
// docs/loopcheck.md.
struct WeldResult {
    uint64_t vertices = 0, weldedVertices = 0, triangles = 0, degenerateTriangles = 0, nonFiniteVertices = 0;
    uint64_t edges = 0, openEdges = 0, boundaryEdges = 0, crackEdges = 0;
    uint64_t nonManifoldEdges = 0, unexpectedNonManifoldEdges = 0, misorientedEdges = 0;
    // Edges used three or more times only by folded faces (ControlTopology::folded),
    // or by triangles facing opposite ways (the limit surface folds there): the
    // surface touching itself, not counted as unexpected (W6).
    uint64_t contactEdges = 0;
    uint64_t tJunctions = 0, tJunctionVertices = 0;
    uint64_t normalSplitVertices = 0;
    // The failing edge of the lowest soup triangle: "crack: face F (u, v) = (...) to
    // (...)" (or "non-manifold" / "misoriented"); "" when none fails.
    std::string firstFailure;
    bool pass() const {
        return nonFiniteVertices == 0 && crackEdges == 0 && unexpectedNonManifoldEdges == 0 && misorientedEdges == 0;
    }
};

// Normals against the drawn triangles (no oracle: any asset): every emitted normal
// finite, non-zero and in front of each judged triangle it belongs to; a normal behind
// is judged again against a finer surface and OpenSubdiv. Which triangles are judged,
// and why: docs/loopcheck.md.
struct NormalResult {
    uint64_t judged = 0;       // triangles judged
    uint64_t unjudged = 0;     // slivers and coarse triangles over strong curvature
    uint64_t folded = 0;       // triangles the drawn surface turns over at (not judged)
    uint64_t refined = 0;      // normals behind their triangle but not behind the finer surface's
    uint64_t confirmed = 0;    // normals behind both that OpenSubdiv's normal agrees with
    uint64_t against = 0;      // vertex normals behind a judged triangle (n . g <= 0)
    uint64_t zero = 0;         // vertex normals zero or not finite
    std::string firstFailure;  // "vertex V, face F (u, v) = (...): ..."
    std::string skipped;       // why not checked (a displaced evaluation)
    bool pass() const { return against == 0 && zero == 0; }
};

// Rays from interior points of a closed mesh: none may escape, and first-hit
// distances must agree with a finer reference within the chord bounds. Origins,
// bounds and fold handling: docs/loopcheck.md.
struct RayResult {
    bool ran = false;
    std::string skipped;  // why the rays did not run ("" when they ran)
    uint64_t candidates = 0, origins = 0, rays = 0, escaped = 0;
    uint64_t frontHits = 0;  // first hits on a front face (inside-out or self-overlapping)
    bool distanceChecked = false;
    std::string distanceSkipped;  // why not, when the rays ran
    uint64_t compared = 0, distanceFailures = 0, referenceEscaped = 0;
    uint64_t foldRays = 0;         // beyond the tolerance, but each hit lies on the other surface
    double maxDistanceError = 0;   // |t - t'| of the diagonal, over the other compared rays
    double maxToleranceRatio = 0;  // |t - t'| / tolerance, the worst of them
    bool pass() const { return escaped == 0 && distanceFailures == 0; }
};

// --- [5] The Khronos glTF-Validator --------------------------------------------------------

struct ValidatorResult {
    enum State : uint8_t { Skipped, Unavailable, Ran };
    State state = Skipped;
    uint64_t errors = 0, warnings = 0, infos = 0, hints = 0;
    std::vector<std::string> messages;  // the first 20: "severity code pointer: message"
    std::string detail;                 // why unavailable
    bool pass() const { return state == Ran && errors == 0 && warnings == 0; }
};
// I/O: runs `node SCRIPT FILE` (SCRIPT: validate.js, printing the validator's JSON
// report) and reads its counts. Unavailable (with `detail`) when node, the script or
// its gltf-validator package is missing, or its output is not a report.
ValidatorResult runKhronosValidator(const std::string& file, const std::string& script);

// --- [6] Running everything, the report ---------------------------------------------------

// The checks of one tessellation (CPU evaluation or GPU capture).
struct TessellationChecks {
    std::string name;  // tessCaseName
    std::string path;  // "cpu" or "gpu"
    TessCase tess;
    EvalSettings eval;
    float factor = 0;    // lodTessFactor
    uint32_t depth = 0;  // runtimeDepth
    uint64_t triangles = 0;
    AccuracyResult accuracy;
    WeldResult weld;
    NormalResult normals;
    RayResult rays;
    // Over settings.maxMemoryBytes: why nothing ran (L1), with the estimate.
    std::string notRun;
    uint64_t estimatedBytes = 0;  // checkBytes of this case (its CPU and GPU paths; in pieces, a piece's)
    uint32_t pieces = 1;          // of whole base faces it was checked in, or (the GPU) capture sessions
    // GPU only: the capture against the CPU evaluation of the same settings.
    std::string error;  // the GPU capture failed: why (nothing else ran)
    bool compared = false;
    uint64_t cpuVertices = 0, equalVertices = 0, equalPositions = 0, equalNormals = 0;
    double evaluateSeconds = 0, checkSeconds = 0;
    double accuracySeconds = 0, weldSeconds = 0, normalsSeconds = 0,
           raysSeconds = 0;  // each check's share of checkSeconds
    bool pass() const {
        return error.empty() && notRun.empty() && weld.pass() && normals.pass() && rays.pass() &&
               (!accuracy.ran || accuracy.positionFailures + accuracy.normalFailures + accuracy.noLimit == 0);
    }
};

// One finding of the report: id (S structure, C consistency, M control mesh vs source,
// A accuracy, W watertight, R rays, V validator, G GPU), severity "error", "warning"
// or "info", and the text.
struct Finding {
    std::string id, severity, text;
};

struct CheckReport {
    std::string assetName;
    uint64_t assetBytes = 0;
    bool structureValid = false;
    std::string structureMessage;  // "" or the reader's / consistency message
    uint32_t baseFaces = 0, controlVertices = 0, maxDepth = 0, vertices = 0;
    ControlTopology topology;
    std::string sourceName;                     // "" without --source
    std::string sourceMismatch;                 // compareControlMesh's answer
    std::vector<std::string> sceneDifferences;  // compareScene's (a glTF --source)
    bool stencilsChecked = false;               // with a source: checkStencils ran
    StencilResult stencils;
    uint32_t sourceEdits = 0;  // hierarchical edits of the source the accuracy
    int sourceEditLevel = 0;   //   reference includes, the deepest of their levels
    ValidatorResult validator;
    // The validator on a glTF --source: V1 is an error only for errors or warnings
    // beyond the source's (a scene keeps what its input had), else an info.
    ValidatorResult sourceValidator;
    bool gpu = false;
    std::string gpuDevice;
    float referenceFactor = 0;
    std::string referenceSkipped;
    std::vector<TessellationChecks> tessellations;
    std::vector<Finding> findings;
    // Wall-clock seconds: the whole of runChecks, its ray reference, and the caller's
    // source oracle and validator runs (reported with timings only).
    double seconds = 0, referenceSeconds = 0, sourceSeconds = 0, validatorSeconds = 0;
};

// What loopcheck hands the library besides settings.
// A consumer of a capture's sessions (CheckInputs::gpuCaptureSessions).
using SessionFn = std::function<Status(const Tessellation& session)>;

struct CheckInputs {
    const Asset* asset = nullptr;  // passed checkStructure
    std::string assetName;
    SourceOracle* source = nullptr;  // --source, built (SourceOracle::build); or null
    // --gpu: captures `eval` through the Vulkan runtime; empty: CPU only.
    std::function<Status(const EvalSettings& eval, Tessellation& soup)> gpuCapture;
    // --gpu, for a case whose capture does not fit whole beside the CPU's soup: the
    // capture session by session, each soup handed on as it is read back (checked as
    // pieces, not compared with the CPU's), sessions of at most `triangles` (0: the
    // capture's largest). Empty: such a case's GPU capture is L1.
    std::function<Status(const EvalSettings& eval, uint64_t triangles, const SessionFn& each)> gpuCaptureSessions;
    std::function<void(const std::string&)> progress;  // progress lines; may be empty
};

// What checking one tessellation adds to the process at its peak, estimated from its
// size (CpuEvaluator::count: `vertices`, and `indices`, 0 for a soup): the soup and
// the larger of its checks (the welded mesh, and the larger of the weld's tables and
// Embree's ray scene) and, with `gpu`, the capture beside it (a second soup and the
// capture's buffers).
uint64_t checkBytes(uint64_t vertices, uint64_t indices, bool gpu);
// The machine's physical memory, what it could give more now without swapping
// (Linux: MemAvailable; elsewhere the physical memory), and this process's
// resident memory now, in bytes (0 where the system does not say).
uint64_t physicalMemoryBytes();
uint64_t availableMemoryBytes();
uint64_t residentBytes();

// Runs the accuracy, watertight and ray checks of every settings.cases entry on the
// CPU (and the GPU), appending to `report` (its structure, source and validator
// fields are the caller's), then addFindings. Internal only for failures of the
// machinery (Embree, a GPU capture's Status is a finding).
Status runChecks(const CheckInputs& in, const CheckSettings& settings, CheckReport& report);

// Recomputes report.findings from everything in it (errors and what was skipped).
void addFindings(const CheckSettings& settings, CheckReport& report);

// 0 every check passed, 2 the structure is invalid, 3 another check failed.
int exitCode(const CheckReport& report);

// The machine-readable report (formats/loopcheck-report.schema.json). Byte-stable
// for the same inputs unless `timings`.
std::string reportJson(const CheckReport& report, const CheckSettings& settings, bool timings);
// The report of a file with several surfaces (one CheckReport each): tool, version,
// asset, result and exitCode (the worst) of the file, and "surfaces": each one's
// report as above. With one report, exactly reportJson(reports[0], ...).
std::string reportJson(const std::vector<CheckReport>& reports, const CheckSettings& settings, bool timings);
// The human-readable summary: one line per check and tessellation (all of them, or
// with `failuresOnly` only the findings), statistics with `verbose`.
std::string reportText(const CheckReport& report, bool failuresOnly, bool verbose);
// JUnit XML for CI test reporters (GitLab, Jenkins, GitHub actions; docs/loopcheck.md
// "JUnit"): a <testsuite> per report (named by its assetName), a <testcase> per check
// of the file (S1, M, A3, V) and per check and tessellation (G1, A1, W, N1, R; named
// "A1 accuracy F=8 equal (cpu)", classname the check), the error findings as its
// <failure>, checks not run <skipped>, each check's seconds. Valid against the Jenkins
// JUnit schema; byte-stable for the same inputs but for the times.
std::string reportJUnit(const std::vector<CheckReport>& reports, const CheckSettings& settings);
// `text` as XML 1.0 character data or attribute value: & < > " ' and tab, LF, CR as
// references; characters XML 1.0 forbids (other C0 controls, U+FFFE, U+FFFF) and
// invalid UTF-8 as U+FFFD.
std::string xmlEscape(const std::string& text);

}  // namespace lt

// formats/src/layout.h -- private to looptess_formats: the numbered validity rules of
// formats/EXT_mesh_loop_subdivision/README.md and the one table of per-level
// accessor properties that the GLB writer, the reader and TableBytes walk, with
// the typed codecs that move a property between a Level and its file values.
//
// Adding a per-level array to the format = one row in kLevelProperties (layout.cpp)
// and its Row below, one row in the README's property table and one in the JSON
// schema.
#pragma once

#include "looptess/asset.h"
#include "looptess/glb.h"
#include "looptess/version.h"  // kFormatLayoutVersion

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace lt::fmt {

inline constexpr const char* kExtensionName = "EXT_mesh_loop_subdivision";
inline constexpr uint32_t kMaxDepthLimit = 15;  // rule kRuleLevelCount

// The spec's validity rules. The numbers are part of the spec (error messages cite
// them) and numbered contiguously.
enum Rule : int {
    // Container (checked by the reader).
    kRuleGlbHeader = 1,
    kRuleGlbChunks = 2,
    kRuleJson = 3,
    kRuleSelfContained = 4,
    kRuleBufferView = 5,
    kRuleAccessor = 6,
    kRuleAccessorForm = 7,
    kRuleExtensionPlacement = 8,
    kRuleFallbackPrimitive = 9,
    kRuleControlVertexCover = 10,
    kRuleControlVertexPositions = 11,
    kRuleVersion = 12,
    kRuleExtensionObject = 13,
    kRuleAccessorsDisjoint = 14,
    kRulePatchArrays = 15,
    // Tables (checked by validateAsset, on every Asset).
    kRuleControlMesh = 16,
    kRuleFinite = 17,
    kRuleFaces = 18,
    kRuleEnums = 19,
    kRuleLevelCount = 20,
    kRuleLevelZero = 21,
    kRuleVertexNumbering = 22,
    kRuleCsr = 23,
    kRuleParallelSizes = 24,
    kRuleRefinementIndex = 25,
    kRuleVertexPoints = 26,
    kRuleMasks = 27,
    kRuleEdgePoints = 28,
    kRuleCreases = 29,
    kRulePatchPoints = 30,
    kRulePatchMasks = 31,
    kRulePatchParam = 32,
    kRuleIrregularCorners = 33,
    kRuleLimitStencils = 34,
    kRuleLimitMasks = 35,
    // Displacement map (36 by the reader, 37..39 by validateAsset).
    kRuleDisplacementObject = 36,
    kRuleDisplacementParams = 37,
    kRuleFaceEdges = 38,
    kRuleDisplacementSamples = 39,
    // Hierarchical edits (40 by the reader and validateAsset, 41..44 by validateAsset).
    kRuleEditValues = 40,
    kRuleEditCsr = 41,
    kRuleEditVertices = 42,
    kRuleEditOps = 43,
    kRuleEditFinite = 44,
    // Scenes (the reader).
    kRuleCageSize = 45,
    // Compression (the reader).
    kRuleCompression = 46,
};
inline constexpr int kRuleCount = 46;
inline constexpr uint32_t kMaxDisplacementResolution = 64;  // rule kRuleDisplacementParams

// "<file>: <path>: rule <n>: <what>" as a BadInput status.
Status ruleError(const std::string& file, const std::string& path, int rule, const std::string& what);

// validateAsset, except that with `patchesChecked` the caller has applied
// regularOk and irregularOk (below) to every patch and irregular face of every
// level, with the limits the validator would use, and all passed: the reader does
// while it decodes them. A patch that fails is left to this function to explain.
// The per-level rules run on up to tableThreads(the asset's table values, `threads`)
// threads; the status is the same for every `threads` (the first failing level's).
Status validateTables(const Asset& asset, const std::string& name, bool patchesChecked, size_t threads = 0);

// Global vertex indices [begin, begin + count) of one level (rule 22 keeps the
// end below 2^32).
struct Range {
    uint32_t begin = 0, count = 0;
    bool has(uint32_t v) const { return v - begin < count; }  // mod 2^32: v < begin wraps high
};

// What the patches of level `level` are checked against.
struct PatchLimits {
    Range range;  // the level's vertices
    uint32_t level = 0, faces = 0, stencils = 0;
    bool finest = false;  // level maxDepth: no split bits
};

// Fast forms of rules 30..33 for one patch, branch-free: true when it passes. The
// validator's explainRegular / explainIrregular state the same checks one by one
// and build the message; these only decide whether to ask them.
inline bool paramOk(const PatchParam& p, const PatchLimits& k) {
    const uint32_t n = 1u << k.level, ui = p.ui, vi = p.vi;
    const bool origin = p.rotated ? (ui - 1 < n) & (vi - 1 < n) & (ui + vi <= n) : ui + vi < n;
    return (p.level == k.level) & (p.baseFace < k.faces) & origin;
}

inline bool regularOk(const RegularPatch& p, const PatchLimits& k) {
    uint32_t outside = 0;
    for (int i = 0; i < 12; ++i) outside |= uint32_t(p.points[i] - k.range.begin >= k.range.count);
    const uint32_t b = p.boundaryMask, edges = b & 7u, corners = b >> 3;
    const uint32_t edgesAtCorner = (edges | edges << 1 | edges >> 2) & 7u;  // bit c: edge c or (c + 2) % 3
    return (outside == 0) & (b < 64) & ((corners & edgesAtCorner) == 0) & (p.splitMask < (k.finest ? 1u : 8u)) &
           paramOk(p.param, k);
}

inline bool irregularOk(const IrregularFace& f, const PatchLimits& k) {
    return (f.corners[0] < k.stencils) & (f.corners[1] < k.stencils) & (f.corners[2] < k.stencils) &
           paramOk(f.param, k);
}

// glTF enums and names shared by writer and reader.
inline constexpr int kU8 = 5121, kU16 = 5123, kU32 = 5125, kF32 = 5126;
const char* boundaryName(BoundaryInterpolation b);  // "EDGE_ONLY", ...
const char* creaseMethodName(CreaseMethod c);       // "NORMAL", "CHAIKIN"
bool parseBoundaryName(const std::string& s, BoundaryInterpolation& out);
bool parseCreaseMethodName(const std::string& s, CreaseMethod& out);
const char* accessorTypeName(int components);  // 1 -> "SCALAR", 2 -> "VEC2", 3 -> "VEC3"

// glTF buffer targets and little-endian helpers (the GLB words: looptess/glb.h).
inline constexpr int kTargetArrayBuffer = 34962, kTargetElementArrayBuffer = 34963;

inline uint32_t readU32(const uint8_t* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
inline void appendU32(std::vector<uint8_t>& out, uint32_t v) {
    for (int b = 0; b < 4; ++b) out.push_back(uint8_t(v >> (8 * b)));
}
// Bytes per component of a glTF componentType, 0 for anything else (5124 included).
inline int componentSize(int componentType) {
    switch (componentType) {
    case 5120:
    case 5121: return 1;
    case 5122:
    case 5123: return 2;
    case 5125:
    case 5126: return 4;
    default: return 0;
    }
}

// One little-endian value of type T (an unsigned integer or float) at `p`, which
// need not be aligned.
template <typename T>
inline T loadLE(const uint8_t* p) {
    T v;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    std::memcpy(&v, p, sizeof v);
#else
    uint32_t u = 0;
    for (size_t b = 0; b < sizeof v; ++b) u |= uint32_t(p[b]) << (8 * b);
    if constexpr (sizeof v == 4)
        std::memcpy(&v, &u, 4);
    else
        v = T(u);
#endif
    return v;
}

// How the values of one property are stored.
enum class Elem : uint8_t {
    Index,  // u16 (5123) when every stored value < 65536, else u32 (5125)
    Small,  // u8 (5121) when every stored value < 256, else u16 (5123)
    U8,     // 5121
    Float,  // 5126
};

// Which TableBytes counter a property's bytes go to.
enum class Kind : uint8_t { Refinement, Masks, Patches, Irregular, Limit, Edits };

// Per-patch arrays are grouped: the group's first row fixes the patch count n,
// every row of the group then holds n * perItem values.
enum class Group : uint8_t { None, Regular, Irregular };

// What a property's values are relative to in the file. Vertex indices are
// stored relative to the first vertex of the level they point into; the Asset
// holds global indices (writer: global - first, reader: stored + first).
enum class Base : uint8_t {
    None,    // not vertex indices: local indices, masks, CSR starts, floats
    Parent,  // vertices of level l - 1 (refinement tables of level l)
    Own,     // vertices of level l (patch points, limit stencils, edited vertices)
};

// The values of one property, flattened: `u` for integer elements, `f` for Float.
struct Column {
    std::vector<uint32_t> u;
    std::vector<float> f;
    size_t size() const { return u.size() + f.size(); }
};

// A tightly packed accessor in the BIN chunk whose range the reader has checked:
// `count` values (elements times components) of `componentType` from `data`.
// count == 0: the property is absent (an empty array).
struct Packed {
    const uint8_t* data = nullptr;
    size_t count = 0;
    int componentType = 0;
};

struct LevelProperty {
    const char* name;  // JSON property name in a level object
    Elem elem;
    uint8_t components;  // accessor type: 1 SCALAR, 2 VEC2, 3 VEC3
    Group group;
    uint8_t perItem;  // values per patch (grouped rows only)
    Kind kind;
    Base base;
    bool zeroWhenAbsent;  // absent = all zero (the writer omits an all-zero array)
    // Writer: level -> values as the Asset holds them (global vertex indices).
    void (*get)(const Level&, Column&);
    // Reader, ungrouped rows: values -> level, `add` added (mod 2^32) to every
    // integer value. Grouped rows are decoded together by decodePatches.
    void (*decode)(Level&, const Packed&, uint32_t add);
};

// Rows of kLevelProperties, in file order. Never reorder (byte-identical output);
// the rows of a group are contiguous, in the order decodePatches reads them.
enum Row : size_t {
    kVertexParent,
    kVertexRingStart,
    kVertexRing,
    kEdgeVerts,
    kCreaseEdge,
    kCreaseWeight,
    kMaskedVertex,
    kMaskStart,
    kMaskWeights,
    kRegularPoints,
    kRegularBoundaryMask,
    kRegularSplitMask,
    kRegularBaseFace,
    kRegularOrigin,
    kIrregularCorners,
    kIrregularBaseFace,
    kIrregularOrigin,
    kLimitVertex,
    kLimitStart,
    kLimitRing,
    kLimitMasked,
    kLimitMaskStart,
    kLimitPosition,
    kLimitTangentU,
    kLimitTangentV,
    kEditVertex,
    kEditStart,
    kEditOp,  // VertexEdits; its values are the extension's editValues
    kRowCount
};

extern const LevelProperty kLevelProperties[kRowCount];
inline constexpr size_t kLevelPropertyCount = kRowCount;

// Reader: `s`'s values into `out` (replaced), built in one pass. Integers
// (u8/u16/u32 widened to u32) get `add` added mod 2^32; floats are copied bitwise.
void loadValues(std::vector<uint32_t>& out, const Packed& s, uint32_t add = 0);
void loadValues(std::vector<float>& out, const Packed& s);

// Patch origins in the file: (ui, vi) of an upright patch as they are, a rotated
// one's as (2^l - ui, 2^l - vi) (OpenSubdiv's Far::PatchParam convention), so that
// the stored origin tells the rotation: rotated iff u + v >= 2^l.
void encodeOrigin(const PatchParam& p, uint32_t* uv);  // p.level is the patch's level
void decodeOrigin(uint32_t u, uint32_t v, uint32_t level, PatchParam& p);

// Reader: decodes level `k.level`'s regular patches and irregular faces in one
// pass per group from rows[kRegularPoints .. kIrregularOrigin] (rows indexed by
// Row), with k.range.begin (the level's first vertex) added to patch points, and
// applies regularOk / irregularOk to each: true when all pass. The caller has
// checked that each row holds the group's patch count times perItem values, or is
// absent and zeroWhenAbsent (rule 15).
bool decodePatches(Level& level, const PatchLimits& k, const Packed* rows);

// One level's accessors as the reader found them, indexed by Row (count 0: absent).
using LevelRows = std::array<Packed, kRowCount>;

// Table values from which the per-level work of a read or a validation (decoding,
// rules 25..44) is worth spreading over threads. Below, a phase lasts well under a
// millisecond and waking a helper costs about as much. With the helper threads kept
// for the process (parallel.h), spot and bob (0.9M and 0.8M values) read in half the
// time on two cores into fresh memory, and no slower with both cores busy
// (bench/README.md, "Load on threads").
inline constexpr uint64_t kParallelValues = uint64_t(1) << 19;

// Threads for per-level work over `values` table values: `threads` when non-zero,
// else one per core from kParallelValues on, else 1.
size_t tableThreads(uint64_t values, size_t threads);

// Reader: rule 15 on every level's grouped rows (each holds the group's patch count
// times perItem values, or is absent where zeroWhenAbsent), in level order, then
// every level's arrays decoded from `rows` (one entry per level of asset.levels,
// whose firstVertex and control mesh are already set) on up to tableThreads(all
// values, threads) threads: ungrouped rows with their Base added, patches by
// decodePatches. `patchesChecked` receives whether every patch passed. Messages
// name rows under `extPath` in `file`. Same asset and status for every `threads`.
Status decodeLevels(Asset& asset, const std::vector<LevelRows>& rows, size_t threads, const std::string& file,
                    const std::string& extPath, bool& patchesChecked);

// One cage primitive of a surface, decoded (rules 9, 10): indices below the vertex
// count, cv (if any) one entry per vertex.
struct CagePrimitive {
    std::vector<float> positions;   // 3 per primitive vertex
    std::vector<float> uvs;         // 2 per primitive vertex, or empty
    std::vector<float> uvs1;        // TEXCOORD_1: 2 per primitive vertex, or empty
    std::vector<float> colors;      // COLOR_0: 4 per primitive vertex (RGB: alpha 1), or empty
    std::vector<uint32_t> indices;  // 3 per triangle
    std::vector<uint32_t> cv;       // per primitive vertex; empty: the identity
    std::string path, cvPath;       // JSON paths of the primitive and its controlVertex
};

// Rules 10 and 11 over all cage primitives of a surface, then its control mesh:
// positions from any copy, base faces and per-corner UVs (spec "Scenes"; (0, 0)
// for a primitive without TEXCOORD_0 when another has it), TEXCOORD_1 likewise, and
// COLOR_0 ((1, 1, 1, 1) where a primitive has none). primitiveFaces receives
// prims.size() + 1 face starts. Fills an empty cv with the identity.
Status rebuildControlMesh(std::vector<CagePrimitive>& prims, const std::string& file, Asset& asset,
                          std::vector<uint32_t>& primitiveFaces);

// --- hierarchical edits (edits_io.cpp) ---------------------------------------------

// Writer: every level's VertexEdits::value in the flat edit order (level 0's first),
// the extension's `editValues`. Empty when the asset has no edits.
Column editValues(const Asset& asset);

// Reader, rule 40: `values` (the editValues accessor, count 0 when absent; 3 floats
// per edit) split into every level's VertexEdits::value by the levels' op counts.
// `path` names the accessor in messages.
Status assignEditValues(Asset& asset, const Packed& values, const std::string& file, const std::string& path);

// validateAsset, rules 40..44 for level `l`'s edits; `range` is level l's vertices
// (level 0: the control vertices).
Status validateEdits(const Asset& asset, size_t l, const Range& range, const std::string& file);

}  // namespace lt::fmt

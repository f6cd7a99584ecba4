// formats/src/layout.h -- private to looptess_formats: the numbered validity rules of
// formats/EXT_mesh_loop_subdivision/README.md and the one table of per-level
// accessor properties that both the GLB writer and the reader walk.
//
// Adding a per-level array to the format = one row in kLevelProperties (layout.cpp),
// one row in the README's property table and one in the JSON schema.
#pragma once

#include "looptess/asset.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lt::fmt {

inline constexpr const char* kExtensionName = "EXT_mesh_loop_subdivision";
inline constexpr int kExtensionVersion = 1;
inline constexpr uint32_t kMaxDepthLimit = 15;      // rule kRuleLevelCount
inline constexpr uint8_t kRotatedBit = 0x80;        // in the *Level u8 arrays

// The spec's validity rules. The numbers are part of the spec (error messages cite
// them): never renumber, only append.
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
};
inline constexpr int kRuleCount = 34;

// "<file>: <path>: rule <n>: <what>" as a BadInput status.
Status ruleError(const std::string& file, const std::string& path, int rule,
                 const std::string& what);

// glTF enums and names shared by writer and reader.
inline constexpr int kU8 = 5121, kU16 = 5123, kU32 = 5125, kF32 = 5126;
const char* boundaryName(BoundaryInterpolation b);   // "EDGE_ONLY", ...
const char* creaseMethodName(CreaseMethod c);        // "NORMAL", "CHAIKIN"
bool parseBoundaryName(const std::string& s, BoundaryInterpolation& out);
bool parseCreaseMethodName(const std::string& s, CreaseMethod& out);
const char* accessorTypeName(int components);         // 1 -> "SCALAR", 2 -> "VEC2", 3 -> "VEC3"

// GLB container constants and little-endian helpers.
inline constexpr uint32_t kGlbMagic = 0x46546C67;    // "glTF"
inline constexpr uint32_t kChunkJson = 0x4E4F534A;   // "JSON"
inline constexpr uint32_t kChunkBin = 0x004E4942;    // "BIN\0"
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
    case 5120: case 5121: return 1;
    case 5122: case 5123: return 2;
    case 5125: case 5126: return 4;
    default: return 0;
    }
}

// How the values of one property are stored.
enum class Elem : uint8_t {
    Index,   // u16 (5123) when every value < 65536, else u32 (5125)
    U8,      // 5121
    U16,     // 5123
    Float,   // 5126
};

// Which TableBytes counter a property's bytes go to.
enum class Kind : uint8_t { Refinement, Masks, Patches, Irregular, Limit };

// Per-patch arrays are grouped: the group's first row fixes the patch count n,
// every row of the group then holds n * perItem values.
enum class Group : uint8_t { None, Regular, Irregular };

// The values of one property, flattened: `u` for integer elements, `f` for Float.
struct Column {
    std::vector<uint32_t> u;
    std::vector<float> f;
    size_t size() const { return u.size() + f.size(); }
};

struct LevelProperty {
    const char* name;       // JSON property name in a level object
    Elem elem;
    uint8_t components;     // accessor type: 1 SCALAR, 2 VEC2, 3 VEC3
    Group group;
    uint8_t perItem;        // values per patch (grouped rows only)
    Kind kind;
    void (*get)(const Level&, Column&);  // flatten level -> column
    void (*put)(Level&, Column&);        // column -> level; grouped rows need the
                                         // group's patch arrays already sized
};

extern const LevelProperty kLevelProperties[];
extern const size_t kLevelPropertyCount;

} // namespace lt::fmt

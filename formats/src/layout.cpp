// formats/src/layout.cpp -- the per-level property table (see layout.h) and the
// small name/enum helpers shared by the writer, the reader and the validator.
#include "layout.h"

#include <cassert>
#include <type_traits>

namespace lt::fmt {

Status ruleError(const std::string& file, const std::string& path, int rule,
                 const std::string& what) {
    std::string m = file;
    m += ": ";
    if (!path.empty()) m += path + ": ";
    m += "rule " + std::to_string(rule) + ": " + what;
    return Status::error(Status::BadInput, std::move(m));
}

namespace {

struct BoundaryNameRow { BoundaryInterpolation value; const char* name; };
const BoundaryNameRow kBoundaryNames[] = {
    {BoundaryInterpolation::None, "NONE"},
    {BoundaryInterpolation::EdgeAndCorner, "EDGE_AND_CORNER"},
    {BoundaryInterpolation::EdgeOnly, "EDGE_ONLY"},
};
struct CreaseNameRow { CreaseMethod value; const char* name; };
const CreaseNameRow kCreaseNames[] = {
    {CreaseMethod::Normal, "NORMAL"},
    {CreaseMethod::Chaikin, "CHAIKIN"},
};

} // namespace

const char* boundaryName(BoundaryInterpolation b) {
    for (const auto& r : kBoundaryNames)
        if (r.value == b) return r.name;
    return nullptr;
}

const char* creaseMethodName(CreaseMethod c) {
    for (const auto& r : kCreaseNames)
        if (r.value == c) return r.name;
    return nullptr;
}

bool parseBoundaryName(const std::string& s, BoundaryInterpolation& out) {
    for (const auto& r : kBoundaryNames)
        if (s == r.name) { out = r.value; return true; }
    return false;
}

bool parseCreaseMethodName(const std::string& s, CreaseMethod& out) {
    for (const auto& r : kCreaseNames)
        if (s == r.name) { out = r.value; return true; }
    return false;
}

const char* accessorTypeName(int components) {
    switch (components) {
    case 1: return "SCALAR";
    case 2: return "VEC2";
    case 3: return "VEC3";
    case 4: return "VEC4";
    default: return nullptr;
    }
}

namespace {

// --- plain vectors: Level::*Outer then ::*Inner -------------------------------

template <typename T> std::vector<T>& columnValues(Column& c);
template <> std::vector<uint32_t>& columnValues<uint32_t>(Column& c) { return c.u; }
template <> std::vector<float>& columnValues<float>(Column& c) { return c.f; }

template <auto Outer, auto Inner>
void getVec(const Level& l, Column& c) {
    const auto& v = (l.*Outer).*Inner;
    columnValues<typename std::decay_t<decltype(v)>::value_type>(c) = v;
}

template <auto Outer, auto Inner>
void putVec(Level& l, Column& c) {
    auto& v = (l.*Outer).*Inner;
    v = std::move(columnValues<typename std::decay_t<decltype(v)>::value_type>(c));
}

// --- per-patch fields: N values per element of Level::*Arr ---------------------

template <auto Arr, size_t N, auto Enc>
void getItems(const Level& l, Column& c) {
    const auto& items = l.*Arr;
    c.u.assign(items.size() * N, 0);
    for (size_t i = 0; i < items.size(); ++i) Enc(items[i], &c.u[i * N]);
}

template <auto Arr, size_t N, auto Dec>
void putItems(Level& l, Column& c) {
    auto& items = l.*Arr;
    assert(c.u.size() == items.size() * N);
    for (size_t i = 0; i < items.size(); ++i) Dec(items[i], &c.u[i * N]);
}

void encPoints(const RegularPatch& p, uint32_t* o) { for (int k = 0; k < 12; ++k) o[k] = p.points[k]; }
void decPoints(RegularPatch& p, const uint32_t* v) { for (int k = 0; k < 12; ++k) p.points[k] = v[k]; }
void encCorners(const IrregularFace& f, uint32_t* o) { for (int k = 0; k < 3; ++k) o[k] = f.corners[k]; }
void decCorners(IrregularFace& f, const uint32_t* v) { for (int k = 0; k < 3; ++k) f.corners[k] = v[k]; }
void encBoundary(const RegularPatch& p, uint32_t* o) { o[0] = p.boundaryMask; }
void decBoundary(RegularPatch& p, const uint32_t* v) { p.boundaryMask = uint8_t(v[0]); }
void encSplit(const RegularPatch& p, uint32_t* o) { o[0] = p.splitMask; }
void decSplit(RegularPatch& p, const uint32_t* v) { p.splitMask = uint8_t(v[0]); }

template <typename P> void encBaseFace(const P& p, uint32_t* o) { o[0] = p.param.baseFace; }
template <typename P> void decBaseFace(P& p, const uint32_t* v) { p.param.baseFace = v[0]; }
template <typename P> void encOrigin(const P& p, uint32_t* o) { o[0] = p.param.ui; o[1] = p.param.vi; }
template <typename P> void decOrigin(P& p, const uint32_t* v) {
    p.param.ui = uint16_t(v[0]);   // U16 elements: the reader guarantees < 65536
    p.param.vi = uint16_t(v[1]);
}
// Level byte: bits 0..6 the level, bit 7 rotated.
template <typename P> void encLevel(const P& p, uint32_t* o) {
    o[0] = uint32_t(p.param.level & 0x7f) | (p.param.rotated ? kRotatedBit : 0u);
}
template <typename P> void decLevel(P& p, const uint32_t* v) {
    p.param.level = uint8_t(v[0] & 0x7f);
    p.param.rotated = (v[0] & kRotatedBit) != 0;
}

#define LT_VEC(outer, inner) getVec<&Level::outer, &inner>, putVec<&Level::outer, &inner>
#define LT_ITEMS(arr, n, enc, dec) \
    getItems<&Level::arr, n, enc>, putItems<&Level::arr, n, dec>

} // namespace

// The file order of every level's accessors. Never reorder (byte-identical output).
const LevelProperty kLevelProperties[] = {
    {"vertexParent", Elem::Index, 1, Group::None, 0, Kind::Refinement,
     LT_VEC(refinement, Refinement::vertexParent)},
    {"vertexRingStart", Elem::Index, 1, Group::None, 0, Kind::Refinement,
     LT_VEC(refinement, Refinement::vertexRingStart)},
    {"vertexRing", Elem::Index, 1, Group::None, 0, Kind::Refinement,
     LT_VEC(refinement, Refinement::vertexRing)},
    {"edgeVerts", Elem::Index, 1, Group::None, 0, Kind::Refinement,
     LT_VEC(refinement, Refinement::edgeVerts)},
    {"creaseEdge", Elem::Index, 1, Group::None, 0, Kind::Refinement,
     LT_VEC(refinement, Refinement::creaseEdge)},
    {"creaseWeight", Elem::Float, 1, Group::None, 0, Kind::Refinement,
     LT_VEC(refinement, Refinement::creaseWeight)},
    {"maskedVertex", Elem::Index, 1, Group::None, 0, Kind::Masks,
     LT_VEC(refinement, Refinement::maskedVertex)},
    {"maskStart", Elem::Index, 1, Group::None, 0, Kind::Masks,
     LT_VEC(refinement, Refinement::maskStart)},
    {"maskWeights", Elem::Float, 1, Group::None, 0, Kind::Masks,
     LT_VEC(refinement, Refinement::maskWeights)},
    {"regularPoints", Elem::Index, 1, Group::Regular, 12, Kind::Patches,
     LT_ITEMS(regular, 12, encPoints, decPoints)},
    {"regularBoundaryMask", Elem::U8, 1, Group::Regular, 1, Kind::Patches,
     LT_ITEMS(regular, 1, encBoundary, decBoundary)},
    {"regularSplitMask", Elem::U8, 1, Group::Regular, 1, Kind::Patches,
     LT_ITEMS(regular, 1, encSplit, decSplit)},
    {"regularBaseFace", Elem::Index, 1, Group::Regular, 1, Kind::Patches,
     LT_ITEMS(regular, 1, encBaseFace<RegularPatch>, decBaseFace<RegularPatch>)},
    {"regularOrigin", Elem::U16, 2, Group::Regular, 2, Kind::Patches,
     LT_ITEMS(regular, 2, encOrigin<RegularPatch>, decOrigin<RegularPatch>)},
    {"regularLevel", Elem::U8, 1, Group::Regular, 1, Kind::Patches,
     LT_ITEMS(regular, 1, encLevel<RegularPatch>, decLevel<RegularPatch>)},
    {"irregularCorners", Elem::Index, 3, Group::Irregular, 3, Kind::Irregular,
     LT_ITEMS(irregular, 3, encCorners, decCorners)},
    {"irregularBaseFace", Elem::Index, 1, Group::Irregular, 1, Kind::Irregular,
     LT_ITEMS(irregular, 1, encBaseFace<IrregularFace>, decBaseFace<IrregularFace>)},
    {"irregularOrigin", Elem::U16, 2, Group::Irregular, 2, Kind::Irregular,
     LT_ITEMS(irregular, 2, encOrigin<IrregularFace>, decOrigin<IrregularFace>)},
    {"irregularLevel", Elem::U8, 1, Group::Irregular, 1, Kind::Irregular,
     LT_ITEMS(irregular, 1, encLevel<IrregularFace>, decLevel<IrregularFace>)},
    {"limitVertex", Elem::Index, 1, Group::None, 0, Kind::Limit,
     LT_VEC(limit, LimitStencils::vertex)},
    {"limitStart", Elem::Index, 1, Group::None, 0, Kind::Limit,
     LT_VEC(limit, LimitStencils::start)},
    {"limitRing", Elem::Index, 1, Group::None, 0, Kind::Limit,
     LT_VEC(limit, LimitStencils::ring)},
    {"limitPosition", Elem::Float, 1, Group::None, 0, Kind::Limit,
     LT_VEC(limit, LimitStencils::position)},
    {"limitTangentU", Elem::Float, 1, Group::None, 0, Kind::Limit,
     LT_VEC(limit, LimitStencils::tangentU)},
    {"limitTangentV", Elem::Float, 1, Group::None, 0, Kind::Limit,
     LT_VEC(limit, LimitStencils::tangentV)},
};
const size_t kLevelPropertyCount = sizeof(kLevelProperties) / sizeof(kLevelProperties[0]);

#undef LT_VEC
#undef LT_ITEMS

} // namespace lt::fmt

// formats/src/layout.cpp -- the per-level property table (see layout.h), its
// codecs, and the small name/enum helpers shared by the writer, the reader and
// the validator.
#include "layout.h"

#include <iterator>
#include <type_traits>

// Forces inlining where GCC's heuristics give up in the large decode templates.
#if defined(__GNUC__)
#define LT_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define LT_ALWAYS_INLINE inline
#endif

namespace lt::fmt {

Status ruleError(const std::string& file, const std::string& path, int rule, const std::string& what) {
    std::string m = file;
    m += ": ";
    if (!path.empty()) m += path + ": ";
    m += "rule " + std::to_string(rule) + ": " + what;
    return Status::error(Status::BadInput, std::move(m));
}

namespace {

struct BoundaryNameRow {
    BoundaryInterpolation value;
    const char* name;
};
const BoundaryNameRow kBoundaryNames[] = {
    {BoundaryInterpolation::None, "NONE"},
    {BoundaryInterpolation::EdgeAndCorner, "EDGE_AND_CORNER"},
    {BoundaryInterpolation::EdgeOnly, "EDGE_ONLY"},
};
struct CreaseNameRow {
    CreaseMethod value;
    const char* name;
};
const CreaseNameRow kCreaseNames[] = {
    {CreaseMethod::Normal, "NORMAL"},
    {CreaseMethod::Chaikin, "CHAIKIN"},
};

}  // namespace

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
        if (s == r.name) {
            out = r.value;
            return true;
        }
    return false;
}

bool parseCreaseMethodName(const std::string& s, CreaseMethod& out) {
    for (const auto& r : kCreaseNames)
        if (s == r.name) {
            out = r.value;
            return true;
        }
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

// --- decoding: one typed loop per (stored type, destination) pair ----------------

// Calls fn(T{}) with T the unsigned type of an integer componentType (5121, 5123,
// 5125; the reader has checked it against the property's Elem; an absent row's 0
// picks u32, whose loops then run over nothing).
template <typename Fn>
void withComponentType(int componentType, Fn&& fn) {
    switch (componentType) {
    case kU8: fn(uint8_t{}); break;
    case kU16: fn(uint16_t{}); break;
    default: fn(uint32_t{}); break;
    }
}

// Random-access iterator over packed little-endian Src values yielding
// Dst(value) + add (integers; mod 2^32) or the value itself (floats), so that
// vector::assign builds a decoded array in one pass, without zero-filling it
// first. Only what assign, std::distance, std::advance and std::copy use is
// provided.
template <typename Src, typename Dst>
class Loader {
public:
    using iterator_category = std::random_access_iterator_tag;
    using value_type = Dst;
    using difference_type = std::ptrdiff_t;
    using pointer = const Dst*;
    using reference = Dst;

    Loader(const uint8_t* p, Dst add) : p_(p), add_(add) {}
    Dst operator*() const {
        if constexpr (std::is_integral_v<Dst>)
            return Dst(loadLE<Src>(p_)) + add_;
        else
            return Dst(loadLE<Src>(p_));
    }
    Dst operator[](difference_type i) const { return *(*this + i); }
    Loader& operator++() {
        p_ += sizeof(Src);
        return *this;
    }
    Loader operator++(int) {
        Loader old = *this;
        ++*this;
        return old;
    }
    Loader& operator--() {
        p_ -= sizeof(Src);
        return *this;
    }
    Loader& operator+=(difference_type n) {
        p_ += n * difference_type(sizeof(Src));
        return *this;
    }
    Loader& operator-=(difference_type n) { return *this += -n; }
    Loader operator+(difference_type n) const {
        Loader r = *this;
        return r += n;
    }
    difference_type operator-(const Loader& o) const { return (p_ - o.p_) / difference_type(sizeof(Src)); }
    bool operator==(const Loader& o) const { return p_ == o.p_; }
    bool operator!=(const Loader& o) const { return p_ != o.p_; }
    bool operator<(const Loader& o) const { return p_ < o.p_; }

private:
    const uint8_t* p_;
    Dst add_;
};

template <typename Src, typename Dst>
void loadAll(std::vector<Dst>& out, const Packed& s, Dst add) {
    const Loader<Src, Dst> begin(s.data, add);
    out.assign(begin, begin + std::ptrdiff_t(s.count));
}

// --- plain vectors: Level::*Outer then ::*Inner -------------------------------

template <typename T>
std::vector<T>& columnValues(Column& c);
template <>
std::vector<uint32_t>& columnValues<uint32_t>(Column& c) {
    return c.u;
}
template <>
std::vector<float>& columnValues<float>(Column& c) {
    return c.f;
}

template <auto Outer, auto Inner>
void getVec(const Level& l, Column& c) {
    const auto& v = (l.*Outer).*Inner;
    columnValues<typename std::decay_t<decltype(v)>::value_type>(c) = v;
}

template <auto Outer, auto Inner>
void decodeVec(Level& l, const Packed& s, uint32_t add) {
    auto& v = (l.*Outer).*Inner;
    if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::vector<float>>)
        loadValues(v, s);
    else
        loadValues(v, s, add);
}

// --- per-patch fields: N values per element of Level::*Arr ---------------------

template <auto Arr, size_t N, auto Enc>
void getItems(const Level& l, Column& c) {
    const auto& items = l.*Arr;
    c.u.assign(items.size() * N, 0);
    for (size_t i = 0; i < items.size(); ++i) Enc(items[i], &c.u[i * N]);
}

void encPoints(const RegularPatch& p, uint32_t* o) {
    for (int k = 0; k < 12; ++k) o[k] = p.points[k];
}
void encCorners(const IrregularFace& f, uint32_t* o) {
    for (int k = 0; k < 3; ++k) o[k] = f.corners[k];
}
void encBoundary(const RegularPatch& p, uint32_t* o) { o[0] = p.boundaryMask; }
void encSplit(const RegularPatch& p, uint32_t* o) { o[0] = p.splitMask; }
// Base faces are stored as differences to the previous patch's, mod 2^32.
template <auto Arr>
void getBaseFaceDeltas(const Level& l, Column& c) {
    const auto& items = l.*Arr;
    c.u.resize(items.size());
    uint32_t previous = 0;
    for (size_t i = 0; i < items.size(); ++i) {
        c.u[i] = items[i].param.baseFace - previous;
        previous = items[i].param.baseFace;
    }
}
template <typename P>
void encOrigin(const P& p, uint32_t* o) {
    encodeOrigin(p.param, o);
}

// Edit operations: EditOp <-> u8. Any stored byte is kept (EditOp's underlying type
// is uint8_t); rule 43 rejects those above 2.
void getEditOps(const Level& l, Column& c) {
    c.u.resize(l.edits.op.size());
    for (size_t i = 0; i < c.u.size(); ++i) c.u[i] = uint32_t(l.edits.op[i]);
}
void decodeEditOps(Level& l, const Packed& s, uint32_t) {
    l.edits.op.resize(s.count);
    for (size_t i = 0; i < s.count; ++i) l.edits.op[i] = EditOp(s.data[i]);
}

// Patch i's parameters of level l from the group's baseFace (F values: deltas,
// summed into `face`) and origin (O VEC2) rows, which start at rows[0] and
// rows[1]. Assigned field by field in place (a returned temporary costs
// store-forwarding stalls).
template <typename F, typename O>
LT_ALWAYS_INLINE void loadParam(PatchParam& p, const Packed* rows, size_t i, uint32_t l, uint32_t& face) {
    face += loadLE<F>(rows[0].data + i * sizeof(F));
    p.baseFace = face;
    decodeOrigin(loadLE<O>(rows[1].data + 2 * i * sizeof(O)), loadLE<O>(rows[1].data + (2 * i + 1) * sizeof(O)), l, p);
}

static_assert(kRegularOrigin == kRegularBaseFace + 1 && kIrregularOrigin == kIrregularBaseFace + 1,
              "loadParam reads a group's baseFace and origin rows in this order");

// Regular patches with points stored as P, base faces as F and origins as O;
// true when regularOk passes on all.
template <typename P, typename F, typename O>
bool decodeRegular(std::vector<RegularPatch>& out, const PatchLimits& limits, const Packed* rows) {
    const PatchLimits k = limits;  // a local copy: stores into `out` cannot alias it
    const uint32_t first = k.range.begin;
    const size_t n = rows[kRegularPoints].count / 12;
    const uint8_t* points = rows[kRegularPoints].data;
    const uint8_t* boundary = rows[kRegularBoundaryMask].data;  // null: all zero
    const uint8_t* split = rows[kRegularSplitMask].data;
    uint32_t face = 0;
    bool ok = true;
    out.clear();
    out.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        RegularPatch& p = out.emplace_back();  // in place: every field is assigned below
        for (size_t j = 0; j < 12; ++j) p.points[j] = uint32_t(loadLE<P>(points + (12 * i + j) * sizeof(P))) + first;
        p.boundaryMask = boundary ? boundary[i] : 0;
        p.splitMask = split ? split[i] : 0;
        loadParam<F, O>(p.param, rows + kRegularBaseFace, i, k.level, face);
        ok &= regularOk(p, k);
    }
    return ok;
}

// Irregular faces with corners stored as C, base faces as F and origins as O;
// true when irregularOk passes on all.
template <typename C, typename F, typename O>
bool decodeIrregular(std::vector<IrregularFace>& out, const PatchLimits& limits, const Packed* rows) {
    const PatchLimits k = limits;  // a local copy: stores into `out` cannot alias it
    const size_t n = rows[kIrregularCorners].count / 3;
    const uint8_t* corners = rows[kIrregularCorners].data;
    uint32_t face = 0;
    bool ok = true;
    out.clear();
    out.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        IrregularFace& f = out.emplace_back();
        for (size_t j = 0; j < 3; ++j) f.corners[j] = loadLE<C>(corners + (3 * i + j) * sizeof(C));
        loadParam<F, O>(f.param, rows + kIrregularBaseFace, i, k.level, face);
        ok &= irregularOk(f, k);
    }
    return ok;
}

// Calls fn(T{}) with T the unsigned type of row r's componentType, among the two
// its Elem allows (rule 7; an absent row picks the first, its loops run over
// nothing): fewer instantiations of the patch loops than withComponentType.
template <typename Fn>
void withRowType(const Packed* rows, Row r, Fn&& fn) {
    const int type = rows[r].componentType;
    if (kLevelProperties[r].elem == Elem::Index) {
        if (type == kU32)
            fn(uint32_t{});
        else
            fn(uint16_t{});
    } else {
        if (type == kU16)
            fn(uint16_t{});
        else
            fn(uint8_t{});
    }
}

// fn(A{}, B{}, C{}) with the stored types of three rows.
template <typename Fn>
void withRowTypes(const Packed* rows, Row a, Row b, Row c, Fn&& fn) {
    withRowType(rows, a, [&](auto x) {
        withRowType(rows, b, [&](auto y) { withRowType(rows, c, [&](auto z) { fn(x, y, z); }); });
    });
}

#define LT_VEC(outer, inner)  getVec<&Level::outer, &inner>, decodeVec<&Level::outer, &inner>
#define LT_ITEMS(arr, n, enc) getItems<&Level::arr, n, enc>, nullptr

}  // namespace

void loadValues(std::vector<uint32_t>& out, const Packed& s, uint32_t add) {
    withComponentType(s.componentType, [&](auto src) { loadAll<decltype(src)>(out, s, add); });
}

void loadValues(std::vector<float>& out, const Packed& s) { loadAll<float>(out, s, 0.0f); }

void encodeOrigin(const PatchParam& p, uint32_t* uv) {
    const uint32_t n = 1u << p.level;
    uv[0] = p.rotated ? n - p.ui : p.ui;
    uv[1] = p.rotated ? n - p.vi : p.vi;
}

// Any stored (u, v) (u8 or u16) maps to some (ui, vi, rotated); those with u or v
// >= 2^l land outside the base triangle (rule 32): u = 2^l gives a rotated ui = 0,
// and u > 2^l wraps ui mod 2^16 to more than 2^l.
void decodeOrigin(uint32_t u, uint32_t v, uint32_t level, PatchParam& p) {
    const uint32_t n = 1u << level;
    const bool rotated = u + v >= n;
    p.ui = uint16_t(rotated ? n - u : u);
    p.vi = uint16_t(rotated ? n - v : v);
    p.level = uint8_t(level);
    p.rotated = rotated;
}

bool decodePatches(Level& level, const PatchLimits& k, const Packed* rows) {
    bool ok = true;
    withRowTypes(rows, kRegularPoints, kRegularBaseFace, kRegularOrigin, [&](auto p, auto f, auto o) {
        ok = decodeRegular<decltype(p), decltype(f), decltype(o)>(level.regular, k, rows);
    });
    withRowTypes(rows, kIrregularCorners, kIrregularBaseFace, kIrregularOrigin, [&](auto c, auto f, auto o) {
        ok &= decodeIrregular<decltype(c), decltype(f), decltype(o)>(level.irregular, k, rows);
    });
    return ok;
}

// The file order of every level's accessors, one row per Row (layout.h).
const LevelProperty kLevelProperties[kRowCount] = {
    {"vertexParent", Elem::Index, 1, Group::None, 0, Kind::Refinement, Base::Parent, false,
     LT_VEC(refinement, Refinement::vertexParent)},
    {"vertexRingStart", Elem::Index, 1, Group::None, 0, Kind::Refinement, Base::None, false,
     LT_VEC(refinement, Refinement::vertexRingStart)},
    {"vertexRing", Elem::Index, 1, Group::None, 0, Kind::Refinement, Base::Parent, false,
     LT_VEC(refinement, Refinement::vertexRing)},
    {"edgeVerts", Elem::Index, 1, Group::None, 0, Kind::Refinement, Base::Parent, false,
     LT_VEC(refinement, Refinement::edgeVerts)},
    {"creaseEdge", Elem::Index, 1, Group::None, 0, Kind::Refinement, Base::None, false,
     LT_VEC(refinement, Refinement::creaseEdge)},
    {"creaseWeight", Elem::Float, 1, Group::None, 0, Kind::Refinement, Base::None, false,
     LT_VEC(refinement, Refinement::creaseWeight)},
    {"maskedVertex", Elem::Index, 1, Group::None, 0, Kind::Masks, Base::None, false,
     LT_VEC(refinement, Refinement::maskedVertex)},
    {"maskStart", Elem::Index, 1, Group::None, 0, Kind::Masks, Base::None, false,
     LT_VEC(refinement, Refinement::maskStart)},
    {"maskWeights", Elem::Float, 1, Group::None, 0, Kind::Masks, Base::None, false,
     LT_VEC(refinement, Refinement::maskWeights)},
    {"regularPoints", Elem::Index, 1, Group::Regular, 12, Kind::Patches, Base::Own, false,
     LT_ITEMS(regular, 12, encPoints)},
    {"regularBoundaryMask", Elem::U8, 1, Group::Regular, 1, Kind::Patches, Base::None, true,
     LT_ITEMS(regular, 1, encBoundary)},
    {"regularSplitMask", Elem::U8, 1, Group::Regular, 1, Kind::Patches, Base::None, true,
     LT_ITEMS(regular, 1, encSplit)},
    {"regularBaseFace", Elem::Index, 1, Group::Regular, 1, Kind::Patches, Base::None, false,
     getBaseFaceDeltas<&Level::regular>, nullptr},
    {"regularOrigin", Elem::Small, 2, Group::Regular, 2, Kind::Patches, Base::None, false,
     LT_ITEMS(regular, 2, encOrigin<RegularPatch>)},
    {"irregularCorners", Elem::Index, 3, Group::Irregular, 3, Kind::Irregular, Base::None, false,
     LT_ITEMS(irregular, 3, encCorners)},
    {"irregularBaseFace", Elem::Index, 1, Group::Irregular, 1, Kind::Irregular, Base::None, false,
     getBaseFaceDeltas<&Level::irregular>, nullptr},
    {"irregularOrigin", Elem::Small, 2, Group::Irregular, 2, Kind::Irregular, Base::None, false,
     LT_ITEMS(irregular, 2, encOrigin<IrregularFace>)},
    {"limitVertex", Elem::Index, 1, Group::None, 0, Kind::Limit, Base::Own, false,
     LT_VEC(limit, LimitStencils::vertex)},
    {"limitStart", Elem::Index, 1, Group::None, 0, Kind::Limit, Base::None, false, LT_VEC(limit, LimitStencils::start)},
    {"limitRing", Elem::Index, 1, Group::None, 0, Kind::Limit, Base::Own, false, LT_VEC(limit, LimitStencils::ring)},
    {"limitMasked", Elem::Index, 1, Group::None, 0, Kind::Limit, Base::None, false,
     LT_VEC(limit, LimitStencils::masked)},
    {"limitMaskStart", Elem::Index, 1, Group::None, 0, Kind::Limit, Base::None, false,
     LT_VEC(limit, LimitStencils::maskStart)},
    {"limitPosition", Elem::Float, 1, Group::None, 0, Kind::Limit, Base::None, false,
     LT_VEC(limit, LimitStencils::position)},
    {"limitTangentU", Elem::Float, 1, Group::None, 0, Kind::Limit, Base::None, false,
     LT_VEC(limit, LimitStencils::tangentU)},
    {"limitTangentV", Elem::Float, 1, Group::None, 0, Kind::Limit, Base::None, false,
     LT_VEC(limit, LimitStencils::tangentV)},
    {"editVertex", Elem::Index, 1, Group::None, 0, Kind::Edits, Base::Own, false, LT_VEC(edits, VertexEdits::vertex)},
    {"editStart", Elem::Index, 1, Group::None, 0, Kind::Edits, Base::None, false, LT_VEC(edits, VertexEdits::start)},
    {"editOp", Elem::U8, 1, Group::None, 0, Kind::Edits, Base::None, false, getEditOps, decodeEditOps},
};

#undef LT_VEC
#undef LT_ITEMS

}  // namespace lt::fmt

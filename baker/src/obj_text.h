// Private to obj_reader.cpp: OBJ tokens, strict locale-independent numbers, and tags.
#pragma once

#include "looptess/tools/baker.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace lt::obj {

inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Printable, bounded rendering of untrusted text for messages.
inline std::string printable(std::string_view s) {
    std::string out;
    for (char c : s.substr(0, 40)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
    if (s.size() > 40) out += "...";
    return out;
}

// Splits one line into whitespace-separated tokens, lazily.
class Tokens {
public:
    explicit Tokens(std::string_view line) : rest_(line) {}
    bool next(std::string_view& tok) {
        size_t i = 0;
        while (i < rest_.size() && isSpace(rest_[i])) ++i;
        size_t j = i;
        while (j < rest_.size() && !isSpace(rest_[j])) ++j;
        tok = rest_.substr(i, j - i);
        rest_ = rest_.substr(j);
        return !tok.empty();
    }

private:
    std::string_view rest_;
};

// Strict number parsing: the whole token must be consumed; no locale.
inline bool parseInt(std::string_view tok, int64_t& out) {
    if (tok.empty()) return false;
    auto res = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    return res.ec == std::errc() && res.ptr == tok.data() + tok.size();
}

enum class NumResult { Ok, Bad, OutOfRange };

// Parses a decimal float ("1", "-2.5e3", "+0.5", "nan", "inf"); out may be non-finite.
inline NumResult parseFloat(std::string_view tok, float& out) {
    if (!tok.empty() && tok[0] == '+') {
        tok.remove_prefix(1);
        if (!tok.empty() && (tok[0] == '+' || tok[0] == '-')) return NumResult::Bad;
    }
    if (tok.empty()) return NumResult::Bad;
    double d = 0;
    auto res = std::from_chars(tok.data(), tok.data() + tok.size(), d);
    if (res.ptr != tok.data() + tok.size()) return NumResult::Bad;
    if (res.ec == std::errc::result_out_of_range) return NumResult::OutOfRange;
    if (res.ec != std::errc()) return NumResult::Bad;
    if (std::isfinite(d) && std::fabs(d) > double(std::numeric_limits<float>::max())) return NumResult::OutOfRange;
    out = float(d);
    return NumResult::Ok;
}

// One OpenSubdiv tag, checked for shape when read and applied after the last line
// (tags may precede the vertices and faces they name).
struct Tag {
    size_t line = 0;
    std::string name;
    std::vector<int64_t> ints;
    std::vector<float> floats;
    std::vector<std::string> strings;
    std::vector<InputMesh::VertexEdit> edits;  // vertexedit; face: the file's polygon index
};

// "face 7 path 1 3 vertex 2" (or "face 7 vertex 2" at level 0): an edit as written.
template <typename It>
inline std::string editText(int64_t face, It first, It last, int64_t vertex) {
    std::string s = "face " + std::to_string(face);
    if (first != last) s += " path";
    for (; first != last; ++first) s += " " + std::to_string(int64_t(*first));
    return s + " vertex " + std::to_string(vertex);
}

// Declared argument counts of each known tag but vertexedit, as a predicate on
// (ints, floats, strings).
inline bool tagShapeOk(const Tag& t) {
    const size_t ni = t.ints.size(), nf = t.floats.size(), ns = t.strings.size();
    if (t.name == "crease") return ni >= 2 && ni % 2 == 0 && (nf == 1 || nf == ni / 2) && ns == 0;
    if (t.name == "corner") return ni >= 1 && (nf == 1 || nf == ni) && ns == 0;
    if (t.name == "hole") return ni >= 1 && nf == 0 && ns == 0;
    if (t.name == "interpolateboundary") return ni == 1 && nf == 0 && ns == 0;
    if (t.name == "creasemethod") return ni == 0 && nf == 0 && ns == 1;
    return false;
}

}  // namespace lt::obj

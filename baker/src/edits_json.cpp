// edits_json.cpp -- lt::parseEditsJson: the hierarchical-edits side-car (loopbake
// --edits), the JSON twin of an OBJ's `t vertexedit` tags:
//
//   {"edits": [{"face": 7, "path": [1, 3], "vertex": 2, "op": "add", "value": [0, 0.1, 0]}]}
//
// Strict: every key of an entry is required, no other key is allowed, and each has
// one type (face: integer 0..2^32-1, a triangle index after triangulation; path:
// array of integers 0..3, possibly empty; vertex: integer 0..2; op: "set", "add"
// or "subtract"; value: 3 numbers, finite as floats). Errors name the file and the
// entry, e.g. "e.json: edits[3].vertex: must be an integer 0..2, not 5".
//
// Safety: the text is at most kMaxBytes; values nested deeper than the format's
// 4 levels are discarded while parsing (and then rejected), so the parsed document
// stays proportional to the text and shallow.
#include "looptess/tools/baker.h"
#include "text.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace lt {
namespace {

using Json = nlohmann::json;

constexpr size_t kMaxBytes = size_t(16) << 20;  // about 200,000 edits
constexpr int kMaxNesting = 4;                  // {"edits": [{"path": [...]}]}

// A bounded, printable rendering of a JSON value (or of a parser message) for errors.
std::string shown(const std::string& s) {
    std::string out;
    for (char c : s.substr(0, 60)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
    return s.size() > 60 ? out + "..." : out;
}
std::string shown(const Json& v) { return shown(v.dump(-1, ' ', false, Json::error_handler_t::replace)); }

class Reader {
public:
    explicit Reader(const std::string& name) : name_(name) {}

    Status read(std::string_view text, std::vector<InputMesh::VertexEdit>& edits) {
        if (text.size() > kMaxBytes)
            return fail("", std::to_string(text.size()) + " bytes, more than the side-car limit of " +
                                std::to_string(kMaxBytes));
        bool tooDeep = false;
        Json doc;
        try {
            doc = Json::parse(text.begin(), text.end(), [&](int depth, Json::parse_event_t, Json&) {
                if (depth > kMaxNesting) tooDeep = true;
                return depth <= kMaxNesting;
            });
        } catch (const Json::exception& e) {  // parse_error, out_of_range (number overflow)
            std::string what = e.what();      // "[json.exception.parse_error.101] parse error at ..."
            const size_t at = what.find("] ");
            return fail("", "is not valid JSON: " + shown(at == std::string::npos ? what : what.substr(at + 2)));
        }
        if (tooDeep)
            return fail("", "nests values deeper than the format's " + std::to_string(kMaxNesting) + " levels");
        if (!doc.is_object()) return fail("", "the top level must be an object with an \"edits\" array");
        for (auto it = doc.begin(); it != doc.end(); ++it)
            if (it.key() != "edits") return fail(shown(it.key()), "unknown key (the top level has only \"edits\")");
        auto list = doc.find("edits");
        if (list == doc.end() || !list->is_array()) return fail("edits", "missing, or not an array");
        edits.reserve(list->size());
        for (size_t i = 0; i < list->size(); ++i) {
            InputMesh::VertexEdit e;
            if (Status st = entry((*list)[i], "edits[" + std::to_string(i) + "]", e); !st) return st;
            edits.push_back(std::move(e));
        }
        return Status::ok();
    }

private:
    Status fail(const std::string& at, const std::string& what) const {
        return Status::error(Status::BadInput, name_ + ": " + (at.empty() ? "" : at + ": ") + what);
    }

    // An integer in [0, hi] (JSON 7.0 is a float, not an integer).
    Status integer(const Json& v, const std::string& at, uint64_t hi, uint64_t& out) const {
        if (!v.is_number_unsigned() || v.get<uint64_t>() > hi)
            return fail(at, "must be an integer 0.." + std::to_string(hi) + ", not " + shown(v));
        out = v.get<uint64_t>();
        return Status::ok();
    }

    Status entry(const Json& j, const std::string& at, InputMesh::VertexEdit& e) const {
        static const char* const kKeys[] = {"face", "path", "vertex", "op", "value"};
        if (!j.is_object())
            return fail(at, "must be an object with \"face\", \"path\", \"vertex\", \"op\" and \"value\"");
        for (auto it = j.begin(); it != j.end(); ++it)
            if (std::find(std::begin(kKeys), std::end(kKeys), it.key()) == std::end(kKeys))
                return fail(at + "." + shown(it.key()), "unknown key (an edit has face, path, vertex, op, value)");
        for (const char* key : kKeys)
            if (!j.contains(key)) return fail(at + "." + key, "missing");
        uint64_t n = 0;
        if (Status st = integer(j.at("face"), at + ".face", std::numeric_limits<uint32_t>::max(), n); !st) return st;
        e.face = uint32_t(n);
        const Json& path = j.at("path");
        if (!path.is_array()) return fail(at + ".path", "must be an array of children 0..3, not " + shown(path));
        for (size_t k = 0; k < path.size(); ++k) {
            if (Status st = integer(path[k], at + ".path[" + std::to_string(k) + "]", 3, n); !st) return st;
            e.path.push_back(uint8_t(n));
        }
        if (Status st = integer(j.at("vertex"), at + ".vertex", 2, n); !st) return st;
        e.vertex = uint8_t(n);
        const Json& op = j.at("op");
        const std::string opName = op.is_string() ? op.get<std::string>() : std::string();
        if (opName == "set")
            e.op = EditOp::Set;
        else if (opName == "add")
            e.op = EditOp::Add;
        else if (opName == "subtract")
            e.op = EditOp::Subtract;
        else
            return fail(at + ".op", "must be \"set\", \"add\" or \"subtract\", not " + shown(op));
        const Json& value = j.at("value");
        if (!value.is_array() || value.size() != 3)
            return fail(at + ".value", "must be an array of 3 numbers (x, y, z), not " + shown(value));
        for (size_t c = 0; c < 3; ++c) {
            const double d = value[c].is_number() ? value[c].get<double>() : std::nan("");
            if (!std::isfinite(d) || std::fabs(d) > double(std::numeric_limits<float>::max()))
                return fail(at + ".value[" + std::to_string(c) + "]",
                            "must be a finite number (as a float), not " + shown(value[c]));
            e.value[c] = float(d);
        }
        return Status::ok();
    }

    const std::string& name_;
};

}  // namespace

Status parseEditsJson(std::string_view text, const std::string& name, InputMesh& mesh) {
    try {
        std::vector<InputMesh::VertexEdit> edits;
        Status st = Reader(name).read(text, edits);
        const CleaningReport& c = mesh.cleaning;
        if (st && !edits.empty() && c.renumbered())
            return Status::error(
                Status::BadInput,
                name + ": edits name faces by triangle index, and input cleaning renumbered the mesh's triangles (" +
                    std::to_string(c.repaired) + " faces repaired, " +
                    std::to_string(c.droppedDegenerate + c.droppedZeroArea + c.droppedDuplicate) +
                    " dropped; see the warnings): fix those faces in the mesh first");
        if (st) mesh.edits.insert(mesh.edits.end(), edits.begin(), edits.end());
        return st;
    } catch (const std::exception& e) {  // bad_alloc, in practice
        return Status::error(Status::Internal, name + ": " + e.what());
    }
}

}  // namespace lt

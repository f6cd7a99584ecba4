// formats/src/glb_container.cpp -- the GLB container: readGlb (looptess/glb.h), and
// on top of it readGlbContainer (glb_container.h), the first step of readAssetGlb,
// which cites the spec's rules 1 and 2 for what readGlb rejects and adds rule 3 (JSON).
#include "glb_container.h"

#include "layout.h"

namespace lt {
namespace {

using namespace fmt;
using Json = nlohmann::json;

constexpr int kMaxJsonDepth = 64;

std::string str(uint64_t v) { return std::to_string(v); }

const Json* member(const Json& obj, const char* key) {
    if (!obj.is_object()) return nullptr;
    auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
}

// What is wrong with a GLB's layout, and the spec rule it breaks (0: nothing).
struct Fault {
    int rule = 0;
    std::string what;
};

Fault header(std::string what) { return {kRuleGlbHeader, std::move(what)}; }
Fault chunks(std::string what) { return {kRuleGlbChunks, std::move(what)}; }

// The one parser of the layout. Every length read from the file is compared with
// the bytes left after `pos` (size - pos, which never wraps since pos <= size)
// before pos moves past it.
Fault layout(const uint8_t* data, size_t size, GlbLayout mode, GlbChunks& out) {
    const bool strict = mode == GlbLayout::Strict;
    if (size < 12) return header("GLB header truncated: " + str(size) + " bytes, shorter than the 12-byte header");
    if (readU32(data) != kGlbMagic) return header("not a GLB: magic is not 'glTF'");
    if (readU32(data + 4) != kGlbVersion) return header("GLB version " + str(readU32(data + 4)) + ", expected 2");
    if (readU32(data + 8) != size)
        return header("GLB header length " + str(readU32(data + 8)) + " differs from the file size " + str(size));
    size_t pos = 12;
    bool haveJson = false, haveBin = false;
    for (uint64_t chunk = 0; pos < size; ++chunk) {
        const std::string what = "GLB chunk " + str(chunk);
        if (size - pos < 8)
            return chunks(what + ": header truncated at byte " + str(pos) + " (" + str(size - pos) + " bytes left)");
        const uint32_t length = readU32(data + pos), type = readU32(data + pos + 4);
        pos += 8;
        if (strict && length % 4 != 0) return chunks(what + ": length " + str(length) + " is not a multiple of 4");
        if (length > size - pos)
            return chunks(what + ": length " + str(length) + " overruns the file (the chunk's data starts at byte " +
                          str(pos) + " of " + str(size) + ")");
        const uint8_t* body = data + pos;
        pos += length;
        if (chunk == 0) {
            if (type != kGlbChunkJson) return chunks(what + " is not JSON");
            if (strict && length == 0) return chunks("GLB JSON chunk is empty");
            out.json = std::string_view(reinterpret_cast<const char*>(body), length);
            haveJson = true;
        } else if (type == kGlbChunkJson) {
            if (strict) return chunks(what + " is a second JSON chunk");
        } else if (type == kGlbChunkBin) {
            if (chunk == 1) {
                out.bin = body;
                out.binLength = length;
                haveBin = true;
            } else if (strict) {
                return chunks(what +
                              (haveBin ? " is a second BIN chunk" : " is a BIN chunk, which only chunk 1 may be"));
            }
        }  // other types: skipped, as glTF requires
    }
    if (!haveJson) return chunks("GLB has no JSON chunk");
    return {};
}

class ContainerReader {
public:
    ContainerReader(const uint8_t* data, size_t size, const std::string& name, GlbContainer& out)
        : data_(data), size_(size), name_(name), out_(out) {}

    Status run() {
        GlbChunks chunks;
        const Fault f = layout(data_, size_, GlbLayout::Strict, chunks);
        if (f.rule) return ruleError(name_, "", f.rule, f.what);
        out_.bin = chunks.bin;
        out_.binLength = chunks.binLength;
        parseJson(chunks.json);
        return status_;
    }

private:
    const uint8_t* data_;
    size_t size_;
    const std::string& name_;
    GlbContainer& out_;
    Status status_;

    bool fail(const std::string& path, int rule, const std::string& what) {
        if (status_) status_ = ruleError(name_, path, rule, what);
        return false;
    }

    // --- rule 3: JSON ------------------------------------------------------------
    bool parseJson(std::string_view text) {
        int depth = 0;
        bool inString = false;
        for (size_t i = 0; i < text.size(); ++i) {  // nesting pre-scan: bounded recursion
            const char c = text[i];
            if (inString) {
                if (c == '\\')
                    ++i;
                else if (c == '"')
                    inString = false;
            } else if (c == '"') {
                inString = true;
            } else if (c == '[' || c == '{') {
                if (++depth > kMaxJsonDepth)
                    return fail("", kRuleJson, "JSON nesting deeper than " + str(kMaxJsonDepth));
            } else if (c == ']' || c == '}') {
                --depth;
            }
        }
        out_.json = Json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
        if (out_.json.is_discarded() || !out_.json.is_object())
            return fail("", kRuleJson, "the JSON chunk is not a JSON object");
        const Json* asset = member(out_.json, "asset");
        const Json* version = asset && asset->is_object() ? member(*asset, "version") : nullptr;
        if (!version || !version->is_string() || version->get<std::string>() != "2.0")
            return fail("asset.version", kRuleJson, "missing or not \"2.0\"");
        return true;
    }
};

}  // namespace

bool isGlb(const uint8_t* data, size_t size) { return size >= 4 && readU32(data) == kGlbMagic; }

Status readGlb(const uint8_t* data, size_t size, const std::string& name, GlbLayout mode, GlbChunks& out) {
    out = GlbChunks{};
    const Fault f = layout(data, size, mode, out);
    if (!f.rule) return Status::ok();
    out = GlbChunks{};
    return Status::error(Status::BadInput, name + ": " + f.what);
}

Status readGlbContainer(const uint8_t* data, size_t size, const std::string& name, GlbContainer& out) {
    out = GlbContainer{};
    return ContainerReader(data, size, name, out).run();
}

}  // namespace lt

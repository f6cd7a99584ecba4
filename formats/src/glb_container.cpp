// formats/src/glb_container.cpp -- the GLB container layer of readAssetGlb
// (glb_container.h): header and chunks (rules 1, 2), then the JSON chunk (rule 3).
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

class ContainerReader {
public:
    ContainerReader(const uint8_t* data, size_t size, const std::string& name, GlbContainer& out)
        : data_(data), size_(size), name_(name), out_(out) {}

    Status run() {
        if (glb()) parseJson();
        return status_;
    }

private:
    const uint8_t* data_;
    size_t size_;
    const std::string& name_;
    GlbContainer& out_;
    Status status_;
    size_t jsonOffset_ = 0, jsonLength_ = 0;

    bool fail(const std::string& path, int rule, const std::string& what) {
        if (status_) status_ = ruleError(name_, path, rule, what);
        return false;
    }

    // --- rules 1, 2: GLB header and chunks ------------------------------------
    bool glb() {
        if (size_ < 12) return fail("", kRuleGlbHeader, str(size_) + " bytes is shorter than the 12-byte GLB header");
        if (readU32(data_) != kGlbMagic) return fail("", kRuleGlbHeader, "magic is not 'glTF'");
        if (readU32(data_ + 4) != 2)
            return fail("", kRuleGlbHeader, "GLB version " + str(readU32(data_ + 4)) + ", expected 2");
        if (readU32(data_ + 8) != size_)
            return fail("", kRuleGlbHeader,
                        "header length " + str(readU32(data_ + 8)) + " differs from the file size " + str(size_));
        size_t pos = 12;
        bool haveBin = false;
        for (int chunk = 0; pos < size_; ++chunk) {
            if (size_ - pos < 8) return fail("", kRuleGlbChunks, "truncated chunk header at byte " + str(pos));
            const uint32_t length = readU32(data_ + pos), type = readU32(data_ + pos + 4);
            const std::string where = "chunk " + str(chunk) + " at byte " + str(pos);
            if (length % 4 != 0) return fail("", kRuleGlbChunks, where + ": length " + str(length) + " is not a multiple of 4");
            if (length > size_ - pos - 8)
                return fail("", kRuleGlbChunks, where + ": length " + str(length) + " runs past the end of the file");
            if (chunk == 0) {
                if (type != kChunkJson) return fail("", kRuleGlbChunks, "the first chunk is not JSON");
                if (length == 0) return fail("", kRuleGlbChunks, "the JSON chunk is empty");
                jsonOffset_ = pos + 8;
                jsonLength_ = length;
            } else if (type == kChunkJson || (type == kChunkBin && (chunk != 1 || haveBin))) {
                return fail("", kRuleGlbChunks, where + ": a JSON or BIN chunk out of place");
            } else if (type == kChunkBin) {
                haveBin = true;
                out_.bin = data_ + pos + 8;
                out_.binLength = length;
            }   // other chunk types: ignored, as glTF requires
            pos += 8 + size_t(length);
        }
        if (jsonLength_ == 0) return fail("", kRuleGlbChunks, "no JSON chunk");
        return true;
    }

    // --- rule 3: JSON ------------------------------------------------------------
    bool parseJson() {
        const char* text = reinterpret_cast<const char*>(data_ + jsonOffset_);
        int depth = 0;
        bool inString = false;
        for (size_t i = 0; i < jsonLength_; ++i) {   // nesting pre-scan: bounded recursion
            const char c = text[i];
            if (inString) {
                if (c == '\\') ++i;
                else if (c == '"') inString = false;
            } else if (c == '"') {
                inString = true;
            } else if (c == '[' || c == '{') {
                if (++depth > kMaxJsonDepth)
                    return fail("", kRuleJson, "JSON nesting deeper than " + str(kMaxJsonDepth));
            } else if (c == ']' || c == '}') {
                --depth;
            }
        }
        out_.json = Json::parse(text, text + jsonLength_, nullptr, /*allow_exceptions=*/false);
        if (out_.json.is_discarded() || !out_.json.is_object()) return fail("", kRuleJson, "the JSON chunk is not a JSON object");
        const Json* asset = member(out_.json, "asset");
        const Json* version = asset && asset->is_object() ? member(*asset, "version") : nullptr;
        if (!version || !version->is_string() || version->get<std::string>() != "2.0")
            return fail("asset.version", kRuleJson, "missing or not \"2.0\"");
        return true;
    }

};

} // namespace

Status readGlbContainer(const uint8_t* data, size_t size, const std::string& name, GlbContainer& out) {
    out = GlbContainer{};
    return ContainerReader(data, size, name, out).run();
}

} // namespace lt

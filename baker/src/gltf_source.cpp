// baker/src/gltf_source.cpp -- lt::gltf::loadModel: container and JSON checks, file
// access confined to the base directory, then tinygltf. See gltf_source.h.
#include "gltf_source.h"

#include "resource_limits.h"
#include "text.h"

#include "looptess/glb.h"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <climits>
#include <cstring>
#include <map>

namespace lt::gltf {
namespace {

using Json = nlohmann::json;

constexpr const char* kDraco = "KHR_draco_mesh_compression";

std::string str(uint64_t v) { return std::to_string(v); }

void putLe32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}

// The JSON text and the BIN chunk of the input.
struct Container {
    bool glb = false;
    const char* json = nullptr;
    size_t jsonSize = 0;
    const uint8_t* bin = nullptr;  // GLB BIN chunk, when present
    size_t binSize = 0;
};

// A GLB is read leniently (looptess/glb.h): input comes from every writer there is,
// and a chunk length not a multiple of 4 or a chunk out of place still has one
// meaning. buildGlb hands tinygltf a well-formed copy.
Status splitContainer(const uint8_t* data, size_t size, const std::string& name, Container& c) {
    if (!isGlb(data, size)) {
        c.json = reinterpret_cast<const char*>(data);
        c.jsonSize = size;
        return Status::ok();
    }
    c.glb = true;
    GlbChunks chunks;
    if (Status st = readGlb(data, size, name, GlbLayout::Lenient, chunks); !st) return st;
    c.json = chunks.json.data();
    c.jsonSize = chunks.json.size();
    c.bin = chunks.bin;
    c.binSize = chunks.binLength;
    // Some writers pad the JSON chunk with NULs instead of spaces.
    while (c.jsonSize > 0 && (c.json[c.jsonSize - 1] == '\0' || c.json[c.jsonSize - 1] == ' ')) --c.jsonSize;
    return Status::ok();
}

// A position in the JSON document, rendered only for messages.
struct JsonPath {
    const JsonPath* parent = nullptr;  // nullptr: the document root
    const std::string* key = nullptr;  // member name, or nullptr for an array element
    size_t index = 0;

    std::string str() const {
        if (!parent) return "the JSON root";
        std::string s = parent->parent ? parent->str() : std::string();
        if (key) return s + (s.empty() ? "" : ".") + *key;
        return s + "[" + std::to_string(index) + "]";
    }
};

bool isSizeKey(const std::string& k) {
    return k == "byteOffset" || k == "byteLength" || k == "byteStride" || k == "count";
}

// Depth everywhere; 32-bit integer range where tinygltf reads ints (not in extras,
// accessor min/max, or extensions other than Draco's); sizes not negative.
Status checkJson(const Json& v, const JsonPath& at, int depth, bool checkInts, const std::string& name) {
    if (depth > kMaxJsonDepth)
        return badInput(name, at.str() + ": JSON nested deeper than " + str(kMaxJsonDepth) + " levels");
    const bool inExtensions = at.key && *at.key == "extensions";
    if (v.is_object()) {
        for (auto it = v.begin(); it != v.end(); ++it) {
            const std::string& k = it.key();
            const bool ints = checkInts && k != "extras" && k != "min" && k != "max" && (!inExtensions || k == kDraco);
            Status st = checkJson(*it, JsonPath{&at, &k, 0}, depth + 1, ints, name);
            if (!st) return st;
        }
    } else if (v.is_array()) {
        for (size_t i = 0; i < v.size(); ++i) {
            Status st = checkJson(v[i], JsonPath{&at, nullptr, i}, depth + 1, checkInts, name);
            if (!st) return st;
        }
    } else if (checkInts && v.is_number_integer()) {
        const bool fits = v.is_number_unsigned() ? v.get<uint64_t>() <= uint64_t(INT_MAX)
                                                 : v.get<int64_t>() >= INT_MIN && v.get<int64_t>() <= INT_MAX;
        if (!fits)
            return badInput(name, at.str() + ": integer " + v.dump() + " is outside the 32-bit range tinygltf reads");
        if (at.key && isSizeKey(*at.key) && !v.is_number_unsigned())
            return badInput(name, at.str() + ": " + v.dump() + " is negative");
    }
    return Status::ok();
}

Status checkVersion(const Json& doc, const std::string& name) {
    auto asset = doc.find("asset");
    if (asset == doc.end() || !asset->is_object() || !asset->contains("version") || !(*asset)["version"].is_string())
        return badInput(name, "asset.version is missing or not a string");
    const std::string& version = (*asset)["version"].get_ref<const std::string&>();
    if (version.rfind("2.", 0) != 0)
        return Status::error(Status::Unsupported,
                             name + ": glTF version \"" + version.substr(0, 20) + "\" is not supported (2.x)");
    return Status::ok();
}

// Required extensions we read, and prefixes of those that only affect materials,
// textures or lights (which a control mesh ignores).
Status checkExtensions(const Json& doc, const std::string& name) {
    static const char* const kRead[] = {kDraco, "KHR_mesh_quantization"};
    static const char* const kIgnorable[] = {"KHR_materials_", "KHR_texture_", "EXT_texture_",
                                             "MSFT_texture_",  "KHR_lights_",  "KHR_xmp"};
    auto req = doc.find("extensionsRequired");
    if (req == doc.end()) return Status::ok();
    if (!req->is_array()) return badInput(name, "extensionsRequired is not an array");
    for (size_t i = 0; i < req->size(); ++i) {
        const Json& e = (*req)[i];
        if (!e.is_string()) return badInput(name, "extensionsRequired[" + str(i) + "] is not a string");
        const std::string& ext = e.get_ref<const std::string&>();
        bool ok = false;
        for (const char* r : kRead) ok = ok || ext == r;
        for (const char* p : kIgnorable) ok = ok || ext.rfind(p, 0) == 0;
        if (!ok)
            return Status::error(Status::Unsupported,
                                 name + ": requires extension " + excerpt(ext) + ", which looptess cannot read");
    }
    return Status::ok();
}

bool isBase64(char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '+' || ch == '/'; }

// Bytes a base64 buffer data URI decodes to (as tinygltf decodes it), or size_t(-1)
// when it is not one of the two media types glTF allows for buffers.
size_t base64Bytes(const std::string& uri) {
    size_t start = 0;
    for (const char* prefix : {"data:application/octet-stream;base64,", "data:application/gltf-buffer;base64,"})
        if (uri.rfind(prefix, 0) == 0) start = std::strlen(prefix);
    if (start == 0) return size_t(-1);
    size_t n = 0;  // base64 characters before the first other one ('=' included)
    while (start + n < uri.size() && isBase64(uri[start + n])) ++n;
    return n * 3 / 4;
}

// Where the payload of a base64 data URI (from its comma) has a character that is
// neither base64 nor '=' padding at its end (tinygltf would stop there and the
// buffer's length would be the only sign), or npos.
size_t base64Garbage(const std::string& uri) {
    const size_t comma = uri.find(',');
    if (comma == std::string::npos) return std::string::npos;
    size_t end = uri.size();
    while (end > comma + 1 && end + 2 > uri.size() && uri[end - 1] == '=') --end;
    for (size_t i = comma + 1; i < end; ++i)
        if (!isBase64(uri[i])) return i;
    return std::string::npos;
}

// Strict RFC 3986 percent-decoding ('+' stays '+').
bool percentDecode(const std::string& in, std::string& out) {
    auto hex = [](char ch) -> int {
        if (ch >= '0' && ch <= '9') return ch - '0';
        if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
        if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
        return -1;
    };
    out.clear();
    for (size_t i = 0; i < in.size(); ++i) {
        if (in[i] != '%') {
            out += in[i];
            continue;
        }
        if (i + 2 >= in.size() || hex(in[i + 1]) < 0 || hex(in[i + 2]) < 0) return false;
        out += char(hex(in[i + 1]) * 16 + hex(in[i + 2]));
        i += 2;
    }
    return true;
}

// Why `file` (a decoded uri) is not a plain file name inside the base directory, or "".
std::string fileNameProblem(const std::string& file) {
    if (file.empty()) return "is empty";
    for (size_t start = 0; start <= file.size();) {
        size_t end = file.find_first_of("/\\", start);
        if (end == std::string::npos) end = file.size();
        if (file.compare(start, end - start, "..") == 0) return "refers outside the base directory";
        start = end + 1;
    }
    if (file[0] == '/' || file[0] == '\\') return "is an absolute path";
    if (file.find(':') != std::string::npos) return "is not a relative file name (has a scheme or drive)";
    for (unsigned char ch : file)
        if (ch < 0x20 || ch == 0x7f) return "contains a control character";
    if (file.find_first_of("/\\") != std::string::npos)
        return "is not a plain file name (sub-directories are not followed)";
    if (file == "." || file.size() > 255) return "is not a file name";
    return "";
}

// An external buffer file, allowed by checkBuffers, known to tinygltf by a token.
struct ExternalFile {
    std::string path;       // baseDir/name
    size_t byteLength = 0;  // the buffer's byteLength: the file must have exactly this size
    std::string what;       // buffers[i].uri "name", for messages
};

struct FsContext {
    const std::map<std::string, ExternalFile>* files = nullptr;  // by token
    std::string error;                                           // the first read failure, with file name and buffer
};

// `inputBytes` is the size of the .gltf/.glb itself: with its buffer files it must stay
// within limits.maxInputBytes.
Status checkBuffers(Json& doc, const std::string& name, const std::string& baseDir, const Container& c,
                    const Limits& limits, uint64_t inputBytes, std::map<std::string, ExternalFile>& files) {
    auto buffers = doc.find("buffers");
    if (buffers == doc.end() || !buffers->is_array()) return Status::ok();
    for (size_t i = 0; i < buffers->size(); ++i) {
        Json& b = (*buffers)[i];
        const std::string at = "buffers[" + str(i) + "]";
        if (!b.is_object()) continue;  // tinygltf rejects it
        auto length = b.find("byteLength");
        if (length == b.end() || !length->is_number_unsigned())
            return badInput(name, at + ".byteLength is missing or not an unsigned integer");
        const size_t byteLength = length->get<size_t>();
        auto uri = b.find("uri");
        if (uri == b.end()) {
            if (!c.glb || i != 0 || !c.bin)
                return badInput(name, at + " has no uri" + (c.glb && i == 0 ? " and the GLB has no BIN chunk" : ""));
            if (byteLength > c.binSize)
                return badInput(name, at + ".byteLength " + str(byteLength) + " exceeds the GLB BIN chunk (" +
                                          str(c.binSize) + " bytes)");
            continue;
        }
        if (!uri->is_string()) return badInput(name, at + ".uri is not a string");
        const std::string text = uri->get<std::string>();
        const std::string what = at + ".uri \"" + text.substr(0, 80) + "\"";
        if (text.compare(0, 5, "data:") == 0) {
            const size_t bytes = base64Bytes(text);
            if (bytes == size_t(-1))
                return badInput(name, what +
                                          ": unsupported data URI (expected base64 "
                                          "application/octet-stream or application/gltf-buffer)");
            if (const size_t bad = base64Garbage(text); bad != std::string::npos)
                return badInput(name, what + ": character " + str(bad) + " of the data URI is not base64 ('" +
                                          excerpt(text.substr(bad, 1)) + "')");
            if (bytes != byteLength)
                return badInput(name,
                                what + ": data URI holds " + str(bytes) + " bytes, byteLength is " + str(byteLength));
            continue;
        }
        std::string file;
        if (!percentDecode(text, file)) return badInput(name, what + ": malformed %-escape");
        const std::string problem = fileNameProblem(file);
        if (!problem.empty()) return badInput(name, what + ": " + problem);
        if (baseDir.empty()) return badInput(name, what + ": external file but no base directory given");
        inputBytes += byteLength;
        if (inputBytes > limits.maxInputBytes)
            return badInput(name, what + ": the file and its buffer files have " +
                                      limitMessage("at least " + str(inputBytes), "bytes", limits.maxInputBytes,
                                                   "--max-input-bytes"));
        const std::string token = "looptess-buffer-" + str(i);
        files[token] = {baseDir + (baseDir.back() == '/' ? "" : "/") + file, byteLength, what};
        *uri = token;
    }
    return Status::ok();
}

// Drops `indices` of Draco primitives (see gltf_source.h).
void dropDracoIndices(Json& doc) {
    auto meshes = doc.find("meshes");
    if (meshes == doc.end() || !meshes->is_array()) return;
    for (Json& mesh : *meshes) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (Json& prim : mesh["primitives"]) {
            if (!prim.is_object()) continue;
            auto ext = prim.find("extensions");
            if (ext != prim.end() && ext->is_object() && ext->contains(kDraco)) prim.erase("indices");
        }
    }
}

// Reads a regular file (no symbolic link, FIFO or device) of exactly `expected` bytes,
// or (expected = kAnySize) of at most `most` bytes.
constexpr size_t kAnySize = size_t(-1);
std::string readRegularFile(const std::string& path, size_t expected, std::vector<unsigned char>& out,
                            uint64_t most = kMaxFileBytes) {
    if (expected != kAnySize && expected > kMaxFileBytes) return "byteLength " + str(expected) + " exceeds the limit";
    const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (fd < 0) {
        if (errno == ELOOP) return "is a symbolic link (not followed)";
        return std::string("cannot be opened: ") + std::strerror(errno);
    }
    struct Closer {
        int fd;
        ~Closer() { close(fd); }
    } closer{fd};
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) return "is not a regular file";
    if (expected == kAnySize) {
        if (uint64_t(st.st_size) > std::min<uint64_t>(most, kMaxFileBytes))
            return "file has " + str(uint64_t(st.st_size)) + " bytes, more than the " +
                   str(std::min<uint64_t>(most, kMaxFileBytes)) + " left by the input limit (--max-input-bytes)";
        expected = size_t(st.st_size);
    } else if (uint64_t(st.st_size) != expected)
        return "file has " + str(uint64_t(st.st_size)) + " bytes, the buffer's byteLength is " + str(expected);
    out.resize(expected);
    size_t done = 0;
    while (done < expected) {
        const ssize_t n = read(fd, out.data() + done, expected - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return "read failed after " + str(done) + " bytes";
        done += size_t(n);
    }
    return "";
}

// tinygltf FsCallbacks: only the tokens of checkBuffers exist; nothing is expanded
// or written.
bool fileExists(const std::string& path, void* user) { return static_cast<FsContext*>(user)->files->count(path) != 0; }

std::string expandFilePath(const std::string& path, void*) { return path; }

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* ctx = static_cast<FsContext*>(user);
    auto it = ctx->files->find(path);
    const std::string problem = it == ctx->files->end() ? std::string("not a buffer file checked by looptess")
                                                        : readRegularFile(it->second.path, it->second.byteLength, *out);
    if (problem.empty()) return true;
    if (ctx->error.empty() && it != ctx->files->end()) ctx->error = it->second.what + ": " + problem;
    if (err) *err = problem;
    return false;
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err = "looptess never writes through tinygltf";
    return false;
}

bool ignoreImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

// A GLB holding `json` and the input's BIN chunk, both padded to 4 bytes.
std::vector<uint8_t> buildGlb(const std::string& json, const Container& c) {
    auto padded = [](size_t n) { return (n + 3) & ~size_t(3); };
    const bool bin = c.bin && c.binSize > 0;
    const size_t total = 12 + 8 + padded(json.size()) + (bin ? 8 + padded(c.binSize) : 0);
    std::vector<uint8_t> out;
    out.reserve(total);
    putLe32(out, kGlbMagic);
    putLe32(out, kGlbVersion);
    putLe32(out, uint32_t(total));
    putLe32(out, uint32_t(padded(json.size())));
    putLe32(out, kGlbChunkJson);
    out.insert(out.end(), json.begin(), json.end());
    out.resize(12 + 8 + padded(json.size()), ' ');
    if (bin) {
        putLe32(out, uint32_t(padded(c.binSize)));
        putLe32(out, kGlbChunkBin);
        out.insert(out.end(), c.bin, c.bin + c.binSize);
        out.resize(total, 0);
    }
    return out;
}

void addWarnings(const std::string& text, const std::string& name, std::vector<std::string>& warnings) {
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        if (end > start) warnings.push_back(name + ": tinygltf: " + shortenQuotes(text.substr(start, end - start)));
        start = end + 1;
    }
}

// Standard base64 (RFC 4648) up to the first character outside its alphabet.
std::vector<uint8_t> decodeBase64(const std::string& text, size_t start) {
    std::vector<uint8_t> out;
    uint32_t acc = 0;
    int bits = 0;
    for (size_t i = start; i < text.size(); ++i) {
        const char ch = text[i];
        const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        const char* at = ch ? std::strchr(alphabet, ch) : nullptr;
        if (!at) break;
        acc = acc << 6 | uint32_t(at - alphabet);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(uint8_t(acc >> bits));
        }
    }
    return out;
}

}  // namespace

Status loadImageUri(const std::string& uri, const std::string& what, const std::string& baseDir, uint64_t& budget,
                    std::vector<uint8_t>& bytes, std::string& mimeType, std::string& path) {
    if (uri.compare(0, 5, "data:") == 0) {
        const size_t comma = uri.find(',');
        const size_t semi = uri.find(";base64,");
        if (comma == std::string::npos || semi == std::string::npos || semi + 7 != comma)
            return badInput(what, "unsupported data URI (expected data:MEDIA-TYPE;base64,...)");
        mimeType = uri.substr(5, semi - 5);
        bytes = decodeBase64(uri, comma + 1);
        return Status::ok();
    }
    std::string file;
    if (!percentDecode(uri, file)) return badInput(what, "malformed %-escape");
    if (const std::string problem = fileNameProblem(file); !problem.empty()) return badInput(what, problem);
    if (baseDir.empty()) return badInput(what, "external file but no base directory given");
    std::string ext = file.substr(file.find_last_of('.') == std::string::npos ? file.size() : file.find_last_of('.'));
    for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    static const std::map<std::string, const char*> kTypes = {{".png", "image/png"},
                                                              {".jpg", "image/jpeg"},
                                                              {".jpeg", "image/jpeg"},
                                                              {".ktx2", "image/ktx2"},
                                                              {".webp", "image/webp"}};
    auto type = kTypes.find(ext);
    if (type == kTypes.end())
        return badInput(what, "unknown image type '" + ext + "' (expected .png, .jpg, .jpeg, .ktx2 or .webp)");
    mimeType = type->second;
    std::vector<unsigned char> data;
    path = baseDir + (baseDir.back() == '/' ? "" : "/") + file;
    const std::string problem = readRegularFile(path, kAnySize, data, budget);
    if (!problem.empty()) return badInput(what, problem);
    budget -= data.size();
    bytes.assign(data.begin(), data.end());
    return Status::ok();
}

Status loadModel(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                 const Limits& limits, tinygltf::Model& model, std::vector<std::string>& warnings,
                 std::string* document, std::vector<std::string>* bufferFiles) {
    if (size == 0) return badInput(name, "empty file");
    if (size > kMaxFileBytes)
        return badInput(name, "file has " + str(size) + " bytes, more than the limit " + str(kMaxFileBytes));
    Container c;
    Status st = splitContainer(data, size, name, c);
    if (!st) return st;
    if (document) document->assign(c.json, c.json + c.jsonSize);

    Json doc;
    try {
        doc = Json::parse(c.json, c.json + c.jsonSize);
    } catch (const Json::exception& e) { return badInput(name, "invalid JSON: " + shortenQuotes(e.what())); }
    if (!doc.is_object()) return badInput(name, "the JSON root is not an object");
    if (!(st = checkJson(doc, JsonPath{}, 0, true, name))) return st;
    if (!(st = checkVersion(doc, name)) || !(st = checkExtensions(doc, name))) return st;
    std::map<std::string, ExternalFile> files;
    if (!(st = checkBuffers(doc, name, baseDir, c, limits, size, files))) return st;
    if (bufferFiles)
        for (const auto& [token, file] : files) bufferFiles->push_back(file.path);
    doc.erase("images");
    dropDracoIndices(doc);
    const std::string json = doc.dump(-1, ' ', false, Json::error_handler_t::replace);

    FsContext ctx;
    ctx.files = &files;
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(tinygltf::FsCallbacks{&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &ctx});
    loader.SetImageLoader(&ignoreImage, nullptr);
    std::string err, warn;
    bool ok;
    if (c.glb) {
        const std::vector<uint8_t> glb = buildGlb(json, c);
        ok = loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), unsigned(glb.size()), "");
    } else {
        ok = loader.LoadASCIIFromString(&model, &err, &warn, json.data(), unsigned(json.size()), "");
    }
    addWarnings(warn, name, warnings);
    if (!ok) {
        if (!ctx.error.empty()) return badInput(name, ctx.error);
        while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
        return badInput(name, "tinygltf rejected the file: " + shortenQuotes(err));
    }
    return Status::ok();
}

Status nodeParents(const tinygltf::Model& model, const std::string& name, std::vector<int>& parent) {
    const size_t n = model.nodes.size();
    parent.assign(n, -1);
    for (size_t i = 0; i < n; ++i)
        for (int c : model.nodes[i].children) {
            const std::string where = name + ": nodes[" + str(i) + "].children";
            if (c < 0 || size_t(c) >= n) return badInput(where, "node " + std::to_string(c) + " does not exist");
            if (parent[size_t(c)] >= 0)
                return badInput(where, "nodes[" + str(uint64_t(c)) + "] already has parent nodes[" +
                                           str(uint64_t(parent[size_t(c)])) + "] (nodes must form trees)");
            parent[size_t(c)] = int(i);
        }
    // With one parent each, a node is in a cycle when the walk up from it meets a node
    // of the same walk before a root: each node is walked once (0 unseen, 1 this
    // walk's, 2 reaches a root).
    std::vector<uint8_t> state(n, 0);
    std::vector<int> walk;
    for (size_t i = 0; i < n; ++i) {
        walk.clear();
        int v = int(i);
        for (; v >= 0 && state[size_t(v)] == 0; v = parent[size_t(v)]) {
            state[size_t(v)] = 1;
            walk.push_back(v);
        }
        if (v >= 0 && state[size_t(v)] == 1)
            return badInput(name + ": nodes[" + str(uint64_t(v)) + "]", "is its own ancestor (a cycle of children)");
        for (int w : walk) state[size_t(w)] = 2;
    }
    return Status::ok();
}

}  // namespace lt::gltf

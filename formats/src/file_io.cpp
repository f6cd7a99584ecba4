// File helpers for the command-line tools (see looptess/tools/file_io.h).
#include "looptess/tools/file_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace lt {

Status readFile(const std::string& path, std::vector<uint8_t>& bytes, size_t maxBytes) {
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return Status::error(Status::BadInput, path + ": cannot open: " + std::strerror(errno));
    bytes.clear();
    uint8_t chunk[1 << 16];
    size_t n;
    while ((n = std::fread(chunk, 1, sizeof(chunk), f)) > 0) {
        if (bytes.size() + n > maxBytes) {
            std::fclose(f);
            return Status::error(Status::BadInput,
                                 path + ": larger than the limit of " + std::to_string(maxBytes) + " bytes");
        }
        bytes.insert(bytes.end(), chunk, chunk + n);
    }
    bool failed = std::ferror(f) != 0;
    std::fclose(f);
    if (failed) return Status::error(Status::BadInput, path + ": read error");
    return Status::ok();
}

std::string fileKey(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path abs = fs::weakly_canonical(fs::absolute(path, ec), ec);
    return (ec ? fs::path(path).lexically_normal() : abs).string();
}

Status checkDistinctFiles(const std::vector<NamedFile>& files) {
    std::vector<std::string> keys;
    for (const NamedFile& f : files) keys.push_back(f.path.empty() ? std::string() : fileKey(f.path));
    for (size_t j = 1; j < files.size(); ++j)
        for (size_t i = 0; i < j; ++i)
            if ((files[i].written || files[j].written) && !files[i].path.empty() && !files[j].path.empty() &&
                keys[i] == keys[j])
                return Status::error(Status::Usage,
                                     files[j].name + " '" + files[j].path + "' is also " + files[i].name);
    return Status::ok();
}

Status writeFileAtomic(const std::string& path, const uint8_t* data, size_t size) {
    std::string temp = path + ".tmp-" + std::to_string(getpid());
    FILE* f = std::fopen(temp.c_str(), "wb");
    if (!f) return Status::error(Status::WriteFailed, path + ": cannot create: " + std::strerror(errno));
    bool ok = std::fwrite(data, 1, size, f) == size;
    ok = std::fflush(f) == 0 && ok;
    ok = std::fclose(f) == 0 && ok;
    if (ok && std::rename(temp.c_str(), path.c_str()) == 0) return Status::ok();
    std::string why = std::strerror(errno);
    std::remove(temp.c_str());
    return Status::error(Status::WriteFailed, path + ": cannot write: " + why);
}

bool isUsdPath(const std::string& path) {
    const size_t dot = path.rfind('.');
    if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return false;
    std::string ext = path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".usd" || ext == ".usda" || ext == ".usdc" || ext == ".usdz";
}

}  // namespace lt

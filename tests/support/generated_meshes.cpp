// Generated test meshes (see generated_meshes.h).
#include "generated_meshes.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

#include <unistd.h>

namespace lt::test {

std::string randomDiagonalTorusObj(int n, uint32_t seed) {
    std::ostringstream out;
    std::mt19937 random(seed);
    const double pi = std::acos(-1.0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double u = 2 * pi * i / n, v = 2 * pi * j / n, ring = 3.0 + std::cos(v);
            out << "v " << ring * std::cos(u) << " " << ring * std::sin(u) << " " << std::sin(v) << "\n";
        }
    auto id = [n](int i, int j) { return (i % n) * n + (j % n) + 1; };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if (random() & 1)
                out << "f " << a << " " << b << " " << c << "\nf " << a << " " << c << " " << d << "\n";
            else
                out << "f " << a << " " << b << " " << d << "\nf " << b << " " << c << " " << d << "\n";
        }
    return out.str();
}

namespace {

// The files randomDiagonalTorusFile wrote, removed when the process exits (a test
// run left one per test binary in the temporary directory).
struct WrittenFiles {
    std::vector<std::filesystem::path> paths;
    ~WrittenFiles() {
        std::error_code ignored;
        for (const std::filesystem::path& path : paths) std::filesystem::remove(path, ignored);
    }
};

}  // namespace

std::string randomDiagonalTorusFile(int n, uint32_t seed) {
    static WrittenFiles written;
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("looptess_torus_" + std::to_string(n) + "_" + std::to_string(seed) + "_" + std::to_string(getpid()) + ".obj");
    if (!std::filesystem::exists(path)) {
        std::ofstream(path) << randomDiagonalTorusObj(n, seed);
        written.paths.push_back(path);
    }
    return path.string();
}

}  // namespace lt::test

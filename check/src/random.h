// Private to looptess_check: the one random generator every sampled check uses, so a
// seed gives the same samples and rays on every platform (the standard library's
// distributions are implementation-defined).
#pragma once

#include <cmath>
#include <cstdint>

namespace lt {

// SplitMix64 (Steele, Lea and Flood 2014): a 64-bit state, every seed usable.
class Random {
public:
    explicit Random(uint64_t seed) : state_(seed) {}
    uint64_t next() {
        uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1), 53 bits.
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }
    // Uniform in [0, n), n > 0 (the modulo bias is below 2^-40 for n < 2^24).
    uint64_t below(uint64_t n) { return next() % n; }
    // A uniformly distributed unit vector.
    void direction(double d[3]) {
        const double z = 1.0 - 2.0 * uniform(), phi = 6.283185307179586 * uniform();
        const double r = std::sqrt(std::fmax(0.0, 1.0 - z * z));
        d[0] = r * std::cos(phi);
        d[1] = r * std::sin(phi);
        d[2] = z;
    }

private:
    uint64_t state_;
};

// A seed for part `part` of a run seeded with `seed`.
inline uint64_t deriveSeed(uint64_t seed, uint64_t part) {
    Random r(seed ^ (part * 0xd1b54a32d192ed03ull));
    return r.next();
}

}  // namespace lt

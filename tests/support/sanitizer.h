// Whether a test is compiled with AddressSanitizer (scripts/dev.sh sanitize):
// LOOPTESS_ASAN is defined then, so tests too heavy for that run can skip or shrink
// (each says why).
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define LOOPTESS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LOOPTESS_ASAN 1
#endif
#endif

#include <cstddef>
#include <vector>

namespace lt::test {

#ifdef LOOPTESS_ASAN
constexpr bool kAsan = true;
#else
constexpr bool kAsan = false;
#endif

// Under ASan every `stride`-th element of `all` (the first included), else all of
// them: the sweeps over whole corpora run on a sample there, the release run checks
// every one (the sanitizer run looks for memory errors, which the sample exercises).
template <class T>
std::vector<T> asanSample(std::vector<T> all, size_t stride) {
    if (!kAsan) return all;
    std::vector<T> out;
    for (size_t i = 0; i < all.size(); i += stride) out.push_back(std::move(all[i]));
    return out;
}

}  // namespace lt::test

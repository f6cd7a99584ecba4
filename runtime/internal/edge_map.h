// EdgeMap (private to looptess_runtime): the watertight plan's tables keyed by
// edge (sub_patches.h edgeKey: smaller vertex << 32 | larger), mapping to a
// uint32_t. Open addressing with linear probing in one array: the plan inserts
// millions of edges once per asset, and std::unordered_map's allocation per node
// cost more than the rest of the plan together. No erase; iteration order is never
// used, so the layout is free.
//
// Slots keep neighbouring vertices' edges near each other: a region of 64 slots
// per 16 consecutive smaller vertices (the region itself hashed), 4 slots per vertex
// picked by the larger one. The patches of a level come in base-face order and
// their vertices are numbered in runs, so consecutive lookups mostly hit cache lines
// already loaded, where a hash over the whole key made each one a cache miss.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace lt {

class EdgeMap {
public:
    // Room for `n` keys before the table grows.
    void reserve(size_t n) {
        size_t capacity = kRegion;
        while (capacity < 2 * n) capacity *= 2;
        if (capacity > slots_.size()) rehash(capacity);
    }

    // The value of `key`, inserting `value` first when the key is new (then `added`).
    std::pair<uint32_t*, bool> emplace(uint64_t key, uint32_t value) {
        if (2 * (size_ + 1) > slots_.size()) rehash(slots_.empty() ? kRegion : 2 * slots_.size());
        for (size_t i = slot(key);; i = (i + 1) & (slots_.size() - 1)) {
            Slot& s = slots_[i];
            if (s.key == key) return {&s.value, false};
            if (s.key == kEmpty) {
                s = Slot{key, value};
                ++size_;
                return {&s.value, true};
            }
        }
    }

    // The value of `key`, or null when it is absent.
    const uint32_t* find(uint64_t key) const {
        if (slots_.empty()) return nullptr;
        for (size_t i = slot(key);; i = (i + 1) & (slots_.size() - 1)) {
            const Slot& s = slots_[i];
            if (s.key == key) return &s.value;
            if (s.key == kEmpty) return nullptr;
        }
    }

    size_t size() const { return size_; }
    void clear() {
        slots_.assign(slots_.size(), Slot{});
        size_ = 0;
    }
    void swap(EdgeMap& o) {
        slots_.swap(o.slots_);
        std::swap(size_, o.size_);
    }

private:
    static constexpr uint64_t kEmpty = ~uint64_t(0);  // never a key: edgeKey's ends differ
    struct Slot {
        uint64_t key = kEmpty;
        uint32_t value = 0;
    };
    std::vector<Slot> slots_;  // a power of two (at least kRegion), at most half full
    size_t size_ = 0;

    static constexpr size_t kRegion = 64;  // slots per 16 smaller vertices

    // The region by Fibonacci hashing of the smaller vertex / 16, then 4 slots for
    // the smaller vertex and one of them by the larger's top bits (times 2^32 / golden ratio).
    size_t slot(uint64_t key) const {
        const uint32_t a = uint32_t(key >> 32), b = uint32_t(key);
        const uint64_t region = (uint64_t(a >> 4) * 0x9E3779B97F4A7C15ull) >> 32;
        return size_t(region * kRegion + (a & 15u) * 4 + ((b * 0x9E3779B1u) >> 30)) & (slots_.size() - 1);
    }
    void rehash(size_t capacity) {
        std::vector<Slot> old(capacity);
        old.swap(slots_);
        for (const Slot& s : old)
            if (s.key != kEmpty)
                for (size_t i = slot(s.key);; i = (i + 1) & (slots_.size() - 1))
                    if (slots_[i].key == kEmpty) {
                        slots_[i] = s;
                        break;
                    }
    }
};

}  // namespace lt

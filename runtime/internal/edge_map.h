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

#include "huge_pages.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <utility>

namespace lt {

class EdgeMap {
public:
    // Empty, with room for `n` keys. Emptying keeps the table and starts a new stamp
    // (a slot of another stamp is empty), so a map emptied and refilled level after
    // level is neither filled again nor faulted in again: on a first frame the fresh
    // pages and the fill cost more than the probing.
    void reset(size_t n) {
        size_ = 0;
        if (capacityFor(n) > capacity_) {
            allocate(capacityFor(n));
        } else if (++stamp_ == 0) {  // after 2^32 - 1 resets: every stamp may be in use
            for (size_t i = 0; i < capacity_; ++i) slots_[i].stamp = 0;
            stamp_ = 1;
        }
    }

    // The value of `key`, inserting `value` first when the key is new (then `added`).
    std::pair<uint32_t*, bool> emplace(uint64_t key, uint32_t value) {
        if (2 * (size_ + 1) > capacity_) rehash(capacity_ ? 2 * capacity_ : kRegion);
        for (size_t i = slot(key);; i = (i + 1) & (capacity_ - 1)) {
            Slot& s = slots_[i];
            if (s.stamp != stamp_) {
                s = Slot{key, value, stamp_};
                ++size_;
                return {&s.value, true};
            }
            if (s.key == key) return {&s.value, false};
        }
    }

    // The value of `key`, or null when it is absent.
    const uint32_t* find(uint64_t key) const {
        if (!capacity_) return nullptr;
        for (size_t i = slot(key);; i = (i + 1) & (capacity_ - 1)) {
            const Slot& s = slots_[i];
            if (s.stamp != stamp_) return nullptr;
            if (s.key == key) return &s.value;
        }
    }

    size_t size() const { return size_; }
    void swap(EdgeMap& o) {
        slots_.swap(o.slots_);
        std::swap(capacity_, o.capacity_);
        std::swap(size_, o.size_);
        std::swap(stamp_, o.stamp_);
    }

private:
    struct Slot {
        uint64_t key;
        uint32_t value;
        uint32_t stamp;  // the map's stamp when the slot was filled; 0: never
    };
    struct Free {
        void operator()(Slot* p) const { std::free(p); }
    };
    std::unique_ptr<Slot[], Free> slots_;
    size_t capacity_ = 0;  // a power of two (at least kRegion), at most half full; 0: none
    size_t size_ = 0;
    uint32_t stamp_ = 1;

    static constexpr size_t kRegion = 64;  // slots per 16 smaller vertices

    // A power of two, at least kRegion, that keeps `n` keys at most half full.
    static size_t capacityFor(size_t n) {
        size_t capacity = kRegion;
        while (capacity < 2 * n) capacity *= 2;
        return capacity;
    }

    // The region by Fibonacci hashing of the smaller vertex / 16, then 4 slots for
    // the smaller vertex and one of them by the larger's top bits (times 2^32 / golden ratio).
    size_t slot(uint64_t key) const {
        const uint32_t a = uint32_t(key >> 32), b = uint32_t(key);
        const uint64_t region = (uint64_t(a >> 4) * 0x9E3779B97F4A7C15ull) >> 32;
        return size_t(region * kRegion + (a & 15u) * 4 + ((b * 0x9E3779B1u) >> 30)) & (capacity_ - 1);
    }

    // A table of `capacity` empty slots, stamp 1, on huge pages from 2 MiB
    // (huge_pages.h): the maps are a first frame's largest fresh memory after its output.
    void allocate(size_t capacity) {
        const size_t bytes = capacity * sizeof(Slot);
        Slot* p = static_cast<Slot*>(fmt::allocateHugePages(bytes));
        if (!p) throw std::bad_alloc();
        std::memset(static_cast<void*>(p), 0, bytes);
        slots_.reset(p);
        capacity_ = capacity;
        stamp_ = 1;
    }

    void rehash(size_t capacity) {
        std::unique_ptr<Slot[], Free> old = std::move(slots_);
        const size_t oldCapacity = capacity_;
        const uint32_t oldStamp = stamp_;
        allocate(capacity);
        for (size_t k = 0; k < oldCapacity; ++k)
            if (old[k].stamp == oldStamp)
                for (size_t i = slot(old[k].key);; i = (i + 1) & (capacity_ - 1))
                    if (slots_[i].stamp != stamp_) {
                        slots_[i] = Slot{old[k].key, old[k].value, stamp_};
                        break;
                    }
    }
};

}  // namespace lt

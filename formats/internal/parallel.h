// formats/internal/parallel.h -- private to the libraries (the stream codec, the reader,
// the writer, the baker, the runtime's watertight plan): independent tasks on a few
// std::threads, joined before returning.
//
// Results do not depend on the thread count as long as each task writes only its own
// preallocated slots and the caller combines the slots in task order afterwards.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace lt::fmt {

// `threads` resolved: 0 means one per core (std::thread::hardware_concurrency(), at
// least 1).
inline size_t threadCount(size_t threads) {
    return threads ? threads : std::max<size_t>(1, std::thread::hardware_concurrency());
}

// Runs body(task, worker) for task 0 .. tasks - 1 on up to `threads` threads (worker
// 0 is the caller; threadCount(threads), and never more than `tasks`), each thread
// taking the next task in turn. The first exception a task throws is rethrown here
// after every thread has joined; a thread that cannot start leaves its share to the
// others.
template <class F>
void parallelTasks(size_t tasks, size_t threads, F&& body) {
    const size_t wanted = std::min(threadCount(threads), tasks);
    if (wanted <= 1) {
        for (size_t k = 0; k < tasks; ++k) body(k, size_t(0));
        return;
    }
    std::atomic<size_t> next{0};
    std::exception_ptr failure;
    std::mutex failureLock;
    auto work = [&](size_t worker) {
        for (size_t k; (k = next.fetch_add(1)) < tasks;) {
            try {
                body(k, worker);
            } catch (...) {
                std::lock_guard<std::mutex> lock(failureLock);
                if (!failure) failure = std::current_exception();
                next = tasks;
            }
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(wanted);
    for (size_t t = 1; t < wanted; ++t) {
        try {
            pool.emplace_back(work, t);
        } catch (const std::system_error&) { break; }
    }
    work(0);
    for (std::thread& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

// How many contiguous ranges parallelRanges splits `count` items into on `threads`
// threads: several per thread (so that one costly range, or a thread the system
// runs late, does not keep the others waiting long), each of at least `grain` items;
// 1 below 2 * grain items or on one thread.
inline size_t rangeCount(size_t count, size_t threads, size_t grain) {
    const size_t most = count / std::max<size_t>(grain, 1);
    const size_t n = std::min(threadCount(threads), most);
    return n <= 1 ? (count ? 1 : 0) : std::min(most, 8 * n);
}

// Runs body(range, begin, end, worker) for range 0 .. rangeCount(count, threads,
// grain) - 1, whose [begin, end) cover 0 .. count - 1 in order, on up to `threads`
// threads (parallelTasks).
template <class F>
void parallelRanges(size_t count, size_t threads, size_t grain, F&& body) {
    const size_t ranges = rangeCount(count, threads, grain);
    parallelTasks(ranges, threads,
                  [&](size_t r, size_t worker) { body(r, count * r / ranges, count * (r + 1) / ranges, worker); });
}

// Runs body(i, worker) for i 0 .. count - 1 over parallelRanges.
template <class F>
void parallelFor(size_t count, size_t threads, size_t grain, F&& body) {
    parallelRanges(count, threads, grain, [&](size_t, size_t begin, size_t end, size_t worker) {
        for (size_t i = begin; i < end; ++i) body(i, worker);
    });
}

}  // namespace lt::fmt

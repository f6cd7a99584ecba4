// formats/internal/parallel.h -- private to the libraries (the stream codec, the reader,
// the writer, the baker, the runtime's watertight plan and CPU evaluation): independent
// tasks on the caller's thread and a few helper threads, all finished before returning.
//
// Results do not depend on the thread count as long as each task writes only its own
// preallocated slots and the caller combines the slots in task order afterwards.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <pthread.h>
#endif

namespace lt::fmt {

// `threads` resolved: 0 means one per core (std::thread::hardware_concurrency(), at
// least 1).
inline size_t threadCount(size_t threads) {
    return threads ? threads : std::max<size_t>(1, std::thread::hardware_concurrency());
}

namespace detail {

// Helper threads that live as long as the process, so that a parallel stage costs
// no thread creation and its workers keep their thread_local caches (limit stencil
// buffers, malloc arenas) from one stage to the next: a bake runs about a hundred
// short stages, each a millisecond on a small mesh, and fresh threads made two
// threads no faster than one there.
//
// A job is offered to up to `helpers` of them; its caller takes tasks too, so a job
// finishes even when every helper is busy with another (nested or concurrent jobs
// never wait on each other). The pool grows to the most helpers one job asks for,
// not to what the jobs at once ask for: a job nested in another's task takes the
// helpers that are idle, and the outer job's caller, once its own tasks are done,
// joins it while its helpers finish theirs. So jobs in jobs on N threads keep N
// threads busy, not N^2 runnable on N cores (bench/README.md "Levels two at a
// time"). The pool is never destroyed: helpers may still be waiting on it while
// the process exits.
//
// Waking a thread that sleeps on a condition variable took about 100 us on a virtual
// machine (its core halts), as long as a short stage itself: so a helper, and a
// caller waiting for its helpers, first polls for up to kSpin, yielding the core to
// any other runnable thread, and only then sleeps (bench/README.md "Helpers that
// poll before they sleep").
class HelperPool {
public:
    struct Job {
        const std::function<void(size_t worker)>* work;  // takes tasks until none are left
        size_t helpers;                                  // helpers that may still join
        const Job* parent = nullptr;                     // the job in whose task this one was made (set by run)
        size_t joined = 0;                               // helpers that joined: workers 1 .. joined
        std::atomic<size_t> running{0};                  // helpers inside `work` (changed under the mutex)
    };

    static HelperPool& instance() {
#if defined(__unix__) || defined(__APPLE__)
        // A child of fork() has none of the helpers, and the parent's mutex and
        // condition variables in whatever state they were: it starts a pool of its own.
        // The forking thread's job is its parent's.
        static const int registered = pthread_atfork(nullptr, nullptr, [] {
            current() = new HelperPool;
            runningJob() = nullptr;
        });
        (void)registered;
#endif
        return *current();
    }

    // Runs work(0) here and work(1 .. k) on up to job.helpers helpers, and returns
    // once every one of them has returned (having run tasks of jobs nested in this
    // one's meanwhile).
    void run(Job& job) {
        job.parent = runningJob();
        {
            std::lock_guard<std::mutex> lock(mutex_);
            while (threads_ < job.helpers && threads_ < kMostThreads) {
                try {
                    std::thread(&HelperPool::serve, this).detach();
                } catch (const std::system_error&) { break; }  // the caller and the others do its share
                ++threads_;
            }
            queue_.push_back(&job);
            offered_ = queue_.size();
            ++queued_;
        }
        wake_.notify_all();
        done_.notify_all();  // callers waiting for their helpers join it too
        work(job, 0);
        {
            // No helper joins after this; those that did are finishing their last task.
            std::lock_guard<std::mutex> lock(mutex_);
            queue_.erase(std::remove(queue_.begin(), queue_.end(), &job), queue_.end());
            offered_ = queue_.size();
        }
        // While its helpers finish their last tasks, the caller joins the jobs nested
        // in this one's tasks that still take helpers (not other callers' jobs: it
        // returns as soon as its own work is done).
        const auto finished = [&] { return job.running.load(std::memory_order_acquire) == 0; };
        const auto joinable = [&] { return finished() || nested(job); };
        std::unique_lock<std::mutex> lock(mutex_);
        while (!finished()) {
            if (Job* inner = nested(job)) {
                join(lock, *inner);
                continue;
            }
            // Poll until finished or until another job is queued (nested or not:
            // the mutex tells), then sleep.
            const size_t seen = queued_.load(std::memory_order_relaxed);
            lock.unlock();
            const bool ready = poll([&] { return finished() || queued_.load(std::memory_order_relaxed) != seen; });
            lock.lock();
            if (!ready) done_.wait(lock, joinable);
        }
    }

private:
    static constexpr auto kSpin = std::chrono::milliseconds(2);

    static HelperPool*& current() {
        static HelperPool* pool = new HelperPool;  // never destroyed (above)
        return pool;
    }

    // Whether `ready()` became true within kSpin.
    template <class P>
    static bool poll(P ready) {
        const auto until = std::chrono::steady_clock::now() + kSpin;
        while (!ready()) {
            if (std::chrono::steady_clock::now() > until) return false;
            std::this_thread::yield();
        }
        return true;
    }

    // The job whose work this thread runs, or null.
    static const Job*& runningJob() {
        thread_local const Job* job = nullptr;
        return job;
    }

    static void work(const Job& job, size_t worker) {
        struct Running {  // restored however `work` returns
            const Job* outer = runningJob();
            ~Running() { runningJob() = outer; }
        } running;
        runningJob() = &job;
        (*job.work)(worker);
    }

    // The oldest queued job made in a task of `job` or of a job nested in it, or
    // null. Under the mutex (a job outlives the jobs made in its tasks).
    Job* nested(const Job& job) const {
        for (Job* queued : queue_)
            for (const Job* p = queued->parent; p; p = p->parent)
                if (p == &job) return queued;
        return nullptr;
    }

    // Runs `job`, queued, as its next worker. `lock` holds the mutex before and
    // after, not while the job runs.
    void join(std::unique_lock<std::mutex>& lock, Job& job) {
        const size_t worker = ++job.joined;
        job.running.fetch_add(1, std::memory_order_relaxed);
        if (job.joined == job.helpers) queue_.erase(std::find(queue_.begin(), queue_.end(), &job));
        offered_ = queue_.size();
        lock.unlock();
        work(job, worker);
        lock.lock();
        if (job.running.fetch_sub(1, std::memory_order_release) == 1) done_.notify_all();
    }

    void serve() {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            if (queue_.empty()) {
                lock.unlock();
                poll([&] { return offered_.load(std::memory_order_relaxed) != 0; });
                lock.lock();
                wake_.wait(lock, [&] { return !queue_.empty(); });
            }
            join(lock, *queue_.front());
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_, done_;
    static constexpr size_t kMostThreads = 256;
    std::vector<Job*> queue_;         // jobs that still take helpers, oldest first
    std::atomic<size_t> offered_{0};  // queue_.size(), for helpers polling without the mutex
    std::atomic<size_t> queued_{0};   // jobs ever queued (changed under the mutex), for waiting callers
    size_t threads_ = 0;              // helpers started
};

}  // namespace detail

// Runs body(task, worker) for task 0 .. tasks - 1 on up to `threads` threads (worker
// 0 is the caller, the others the process's helper threads; threadCount(threads),
// and never more than `tasks`), each thread taking the next task in turn. The first
// exception a task throws is rethrown here after every thread has finished with the
// job; a helper that cannot start, or is busy elsewhere, leaves its share to the
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
    const std::function<void(size_t)> work = [&](size_t worker) {
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
    detail::HelperPool::Job job{&work, wanted - 1};
    detail::HelperPool::instance().run(job);
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

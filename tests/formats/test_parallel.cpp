// tests/formats/test_parallel.cpp -- the libraries' task runner (formats/internal/parallel.h):
// every task runs once on a worker index below the thread count, a task's exception
// reaches the caller, nested and concurrent jobs finish, and the helper threads
// persist from one job to the next (a bake runs about a hundred short jobs).
#include "parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#if defined(__unix__)
#include <sys/wait.h>
#include <unistd.h>
#endif

namespace {

using lt::fmt::parallelFor;
using lt::fmt::parallelTasks;

TEST(Parallel, EveryTaskRunsOnceOnAWorkerBelowTheThreadCount) {
    for (size_t threads : {1, 2, 3, 8}) {
        std::vector<std::atomic<int>> runs(1000);
        std::atomic<bool> workerInRange{true};
        parallelTasks(runs.size(), threads, [&](size_t task, size_t worker) {
            if (worker >= threads) workerInRange = false;
            ++runs[task];
        });
        EXPECT_TRUE(workerInRange) << threads << " threads";
        for (size_t k = 0; k < runs.size(); ++k) ASSERT_EQ(runs[k], 1) << "task " << k << ", " << threads << " threads";
    }
}

TEST(Parallel, TheFirstExceptionReachesTheCallerAndLaterJobsRun) {
    EXPECT_THROW(parallelTasks(64, 4,
                               [](size_t task, size_t) {
                                   if (task == 5) throw std::runtime_error("task 5");
                               }),
                 std::runtime_error);
    std::atomic<size_t> sum{0};
    parallelFor(10000, 4, 16, [&](size_t i, size_t) { sum += i; });
    EXPECT_EQ(sum, size_t(10000) * 9999 / 2);
}

TEST(Parallel, NestedAndConcurrentJobsFinish) {
    std::atomic<size_t> inner{0};
    // Jobs from several threads at once, each of whose tasks runs a job of its own:
    // a caller never waits for a helper that is busy elsewhere.
    std::vector<std::thread> callers;
    for (int c = 0; c < 4; ++c)
        callers.emplace_back([&] {
            parallelTasks(8, 3, [&](size_t, size_t) { parallelTasks(16, 3, [&](size_t, size_t) { ++inner; }); });
        });
    for (std::thread& t : callers) t.join();
    EXPECT_EQ(inner, size_t(4 * 8 * 16));
}

// Threads that have run a task of this test (a thread's id may be reused after it
// ends, its thread_local storage not).
std::atomic<int> threadsSeen{0};
thread_local bool seen = false;

TEST(Parallel, HelperThreadsPersistFromOneJobToTheNext) {
    for (int job = 0; job < 200; ++job)
        parallelTasks(64, 2, [&](size_t, size_t) {
            std::this_thread::yield();
            if (!seen) seen = true, ++threadsSeen;
        });
    // A thread per job would be about 200; the pool has what the most jobs at once
    // asked for (the nested test's few dozen, in this process).
    EXPECT_LE(threadsSeen, 64);
}

#if defined(__unix__)
// A child of fork() (a test that caps its address space, a tool's worker) has none
// of its parent's helpers: its jobs still finish, on a pool of its own.
TEST(Parallel, AForkedChildRunsJobs) {
    parallelTasks(64, 4, [](size_t, size_t) {});  // the parent's helpers exist
    const pid_t pid = fork();
    if (pid == 0) {
        std::atomic<size_t> sum{0};
        parallelFor(10000, 4, 16, [&](size_t i, size_t) { sum += i; });
        _exit(sum == size_t(10000) * 9999 / 2 ? 0 : 1);
    }
    int status = -1;
    waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status;
}

// Jobs in jobs keep to the outer job's threads, and a caller whose tasks are done
// joins the job nested in its helper's task: two threads, both at work on the inner
// job. (Before, the nested job started a helper of its own: three threads.) In a
// child of fork(), whose pool starts empty.
TEST(Parallel, NestedJobsShareTheOuterJobsThreads) {
    const pid_t pid = fork();
    if (pid == 0) {
        std::mutex mutex;
        std::set<std::thread::id> all, inner;
        std::atomic<bool> innerStarted{false};
        const auto note = [&](std::set<std::thread::id>& ids) {
            std::lock_guard<std::mutex> lock(mutex);
            ids.insert(std::this_thread::get_id());
        };
        parallelTasks(2, 2, [&](size_t, size_t worker) {
            note(all);
            if (worker == 0) {  // the caller: busy until the helper's job has begun
                while (!innerStarted) std::this_thread::yield();
                return;
            }
            parallelTasks(64, 2, [&](size_t, size_t) {
                innerStarted = true;
                std::this_thread::sleep_for(std::chrono::microseconds(500));
                note(all);
                note(inner);
            });
        });
        _exit(all.size() == 2 && inner.size() == 2 ? 0 : 10 * int(all.size()) + int(inner.size()));
    }
    int status = -1;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << "status " << status;
    EXPECT_EQ(WEXITSTATUS(status), 0) << "threads in all (tens) and on the inner job (units)";
}
#endif

}  // namespace

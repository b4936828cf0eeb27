// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_worker.cpp
 * @brief  The outputs' thread (hif::apps::Worker): jobs in order, one in hand, the caller goes
 *         on while it runs, an error thrown back once, and the job in hand finished on the way out.
 */
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "hif/apps/Worker.h"

using namespace std::chrono_literals;

TEST(Worker, RunsTheJobsInOrderOneAtATimeWhileTheCallerGoesOn)
{
    std::vector<int> done;
    std::atomic<int> running{0}, most{0};
    std::atomic<bool> caller_went_on{false};
    bool job_saw_caller = false;
    {
        hif::apps::Worker w;
        // The first job waits (up to 5 s) for the caller to get past run(): it does at once if
        // run() only hands the job over.
        w.run(
            [&]
            {
                const auto until = std::chrono::steady_clock::now() + 5s;
                while (!caller_went_on && std::chrono::steady_clock::now() < until)
                    std::this_thread::sleep_for(1ms);
                job_saw_caller = caller_went_on;
                done.push_back(0);
            });
        caller_went_on = true;
        for (int i = 1; i < 50; ++i)
            w.run(
                [&, i]
                {
                    most = std::max(most.load(), ++running);
                    std::this_thread::sleep_for(std::chrono::microseconds(100 * (i % 3)));
                    done.push_back(i);
                    --running;
                });
        w.wait();
        EXPECT_EQ(done.size(), 50u);  // wait() returned once the last job was done
    }
    EXPECT_TRUE(job_saw_caller) << "run() waited for its own job";
    EXPECT_EQ(most.load(), 1);
    for (int i = 0; i < 50; ++i) EXPECT_EQ(done[std::size_t(i)], i);
}

TEST(Worker, AJobsErrorIsThrownByTheNextCallOnceAndItsJobIsNotRun)
{
    hif::apps::Worker w;
    bool ran = false;
    w.run([] { throw std::runtime_error("disk full"); });
    try
    {
        w.run([&] { ran = true; });
        FAIL() << "the error was not thrown back";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_STREQ(e.what(), "disk full");
    }
    w.wait();
    EXPECT_FALSE(ran);
    w.run([] { throw std::logic_error("bad scan"); });
    EXPECT_THROW(w.wait(), std::logic_error);
    EXPECT_NO_THROW(w.wait());  // said once
    w.run([&] { ran = true; });
    w.wait();
    EXPECT_TRUE(ran);
}

TEST(Worker, TheJobInHandIsFinishedBeforeTheWorkerGoes)
{
    std::atomic<bool> finished{false};
    {
        hif::apps::Worker w;
        w.run(
            [&]
            {
                std::this_thread::sleep_for(50ms);
                finished = true;
            });
    }
    EXPECT_TRUE(finished);
    {
        hif::apps::Worker w;  // an error left in it is dropped, not thrown from the destructor
        w.run([] { throw std::runtime_error("left"); });
    }
}

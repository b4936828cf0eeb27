// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   make_sequences.cpp
 * @brief  Test tool: the short synthetic sequences and their rawlogs that several app suites
 *         share (synthetic_suite.h), made once for a CTest run (the fixture `hif_sequences`)
 *         instead of once in each test process. Made by the same in-process jobs, with the same
 *         options, as a suite makes them when run on its own.
 *         Usage: hif_make_sequences <folder> <scans>... -> <folder>/<scans>/{seq/,scans.rawlog}
 */
#include <exception>
#include <iostream>
#include <string>

#include "job_runner.h"
#include "synthetic_suite.h"

int main(int argc, char** argv)
{
    if (argc < 3)
    {
        std::cerr << "usage: hif_make_sequences <folder> <scans>...\n";
        return 2;
    }
    for (int i = 2; i < argc; ++i)
    {
        const std::string dir = std::string(argv[1]) + "/" + argv[i];
        long long scans = 0;
        try
        {
            scans = std::stoll(argv[i]);
        }
        catch (const std::exception&)
        {
            std::cerr << "hif_make_sequences: '" << argv[i] << "' is not a number of scans\n";
            return 2;
        }
        const auto r = hif::test::makeSequence(dir, scans);
        if (r.code != 0)
        {
            std::cerr << "hif_make_sequences: " << dir << ":\n" << r.output;
            return 1;
        }
        std::cout << "made " << dir << "\n";
    }
    return 0;
}

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   fuzz_kitti.cpp
 * @brief  libFuzzer target: the KITTI readers (calib.txt, poses.txt, times.txt, a velodyne .bin
 *         scan, its SemanticKITTI .label). The input is the five files in that order, separated
 *         by a line "@@@"; the readers must accept them or throw, never crash.
 */
#include <exception>

#include "FuzzFiles.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size)
{
    using namespace hif::fuzz;
    const auto parts = splitParts(data, size, "\n@@@\n", 5);
    const auto dir = workDir() / "kitti";
    std::filesystem::remove_all(dir);
    writeFile(dir / "calib.txt", parts[0]);
    writeFile(dir / "poses.txt", parts[1]);
    writeFile(dir / "times.txt", parts[2]);
    writeFile(dir / "velodyne" / "000000.bin", parts[3]);
    writeFile(dir / "labels" / "000000.label", parts[4]);
    try
    {
        const hif::io::KittiSequence seq(dir.string());
        for (std::size_t i = 0; i < seq.size(); ++i)
        {
            const auto cloud = seq.readScan(i);
            (void)seq.pose(i);
            if (seq.hasLabels())
            {
                const auto labels = hif::io::readLabels(seq.labelFile(i));
                (void)labels;
            }
            (void)cloud;
        }
    }
    catch (const std::exception&)
    {
    }
    return 0;
}

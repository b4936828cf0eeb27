// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_kitti_data.cpp
 * @brief  The map on real KITTI scans: the interval bound holds and the static map is kept.
 */
#include <gtest/gtest.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/poses/CPose3D.h>

#include <iostream>

#include "hif/CHeightIntervalMap.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"
#include "kitti_fixture.h"

using namespace hif;
using hif::io::KittiSequence;

namespace
{
struct OfflineRun
{
    io::Scores scores;
    double mean_intervals = 0;
    std::size_t max_intervals = 0, pillars = 0;
};

OfflineRun runOffline(const KittiSequence& seq, int scans, int scored, const Params& prm)
{
    OfflineRun r;
    PillarGrid grid(GridGeometry(), prm);
    std::vector<mrpt::maps::CPointsMapXYZI> clouds(scans);
    for (int i = 0; i < scans; ++i)
    {
        EXPECT_TRUE(clouds[i].loadFromKittiVelodyneFile(seq.scanFile(i))) << seq.scanFile(i);
        const auto& c = clouds[i];
        grid.insertScan({c.getPointsBufferRef_x().data(), c.getPointsBufferRef_y().data(),
                         c.getPointsBufferRef_z().data(), c.size()},
                        seq.pose(i));
    }
    for (int i = 0; i < scored; ++i)
    {
        const auto& c = clouds[i];
        std::vector<uint8_t> dyn;
        grid.classify({c.getPointsBufferRef_x().data(), c.getPointsBufferRef_y().data(),
                       c.getPointsBufferRef_z().data(), c.size()},
                      dyn, seq.pose(i));
        const auto labels = io::readLabels(seq.labelFile(i));
        EXPECT_EQ(labels.size(), dyn.size()) << seq.labelFile(i);
        for (std::size_t k = 0; k < std::min(labels.size(), dyn.size()); ++k)
            r.scores.add(labels[k], dyn[k] != 0);
    }
    r.pillars = grid.pillarCount();
    r.max_intervals = grid.maxIntervalsInAPillar();
    r.mean_intervals = double(grid.intervalCount()) / double(grid.pillarCount());
    return r;
}
}  // namespace

TEST(KittiData, Seq08IntervalBoundHoldsAndStaticMapIsKept)
{
    const std::string dir = test::kittiRoot() + "/sequences/08";
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    const KittiSequence seq(dir);
    const Params prm;
    const OfflineRun r = runOffline(seq, 40, 10, prm);
    std::cout << "[ kitti 08 ] 40 scans, scored 0-9: SA " << r.scores.sa() << " DA "
              << r.scores.da() << "; pillars " << r.pillars << ", intervals per pillar mean "
              << r.mean_intervals << " max " << r.max_intervals << "\n";
    EXPECT_LE(r.max_intervals, prm.max_intervals_per_pillar);
    EXPECT_LT(r.mean_intervals, 8.0);           // measured 6.9 with the default bound of 16
    EXPECT_GT(r.scores.dynamic_total, 10000u);  // the labels were read
    EXPECT_GE(r.scores.sa(), 93.0);             // measured 94.9
}

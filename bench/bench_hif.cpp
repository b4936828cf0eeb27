// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   bench_hif.cpp
 * @brief  Speed of HIF on real KITTI scans (sequence 08 by default): the lower-bound pass,
 *         insertion (the map growing scan by scan), classification, and the 40-scan offline run.
 */
#include <benchmark/benchmark.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservationPointCloud.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "hif/CHeightIntervalMap.h"
#include "hif/FreeSpaceTest.h"
#include "hif/PillarGrid.h"
#include "hif/detail/InsertSteps.h"
#include "hif/io/KittiSequence.h"

namespace
{
/** The scans of one sequence, in memory (sensor frame), with their poses. */
struct Scans
{
    std::vector<hif::io::Cloud> clouds;
    std::vector<Eigen::Isometry3d> poses;
    std::string error;  // why the sequence could not be loaded

    [[nodiscard]] std::size_t size() const { return clouds.size(); }
    [[nodiscard]] hif::PointsView view(std::size_t i) const
    {
        const auto& c = clouds[i];
        return {c.x.data(), c.y.data(), c.z.data(), c.size()};
    }
};

std::string sequenceDir()
{
    if (const char* s = std::getenv("HIF_BENCH_SEQUENCE")) return s;
    const char* root = std::getenv("HIF_KITTI_DIR");
    return std::string(root ? root : HIF_DEFAULT_KITTI_DIR) + "/sequences/08";
}

const Scans& scans()
{
    static const Scans s = []
    {
        Scans r;
        try
        {
            const hif::io::KittiSequence seq(sequenceDir());
            for (std::size_t i = 0; i < seq.size(); ++i)
            {
                r.clouds.push_back(seq.readScan(i));
                r.poses.push_back(seq.pose(i));
            }
        }
        catch (const std::exception& e)
        {
            r.clouds.clear();
            r.error = e.what();
        }
        return r;
    }();
    return s;
}

/** Skips the benchmark with the reason when the scans are missing. */
bool haveScans(benchmark::State& state)
{
    if (scans().size() > 0) return true;
    state.SkipWithError(("KITTI scans not available: " + scans().error).c_str());
    return false;
}

/** The grid after inserting every scan. */
const hif::PillarGrid& fullMap()
{
    static const hif::PillarGrid g = []
    {
        hif::PillarGrid m;
        for (std::size_t i = 0; i < scans().size(); ++i)
            m.insertScan(scans().view(i), scans().poses[i]);
        return m;
    }();
    return g;
}

/** Lower bound: one pass that reads every point of the scan, transforms it to the world frame
 *  and computes its pillar key; no bucketing, no map. */
void BM_LowerBound(benchmark::State& state)
{
    if (!haveScans(state)) return;
    const hif::GridGeometry prm;
    std::vector<uint64_t> keys;
    std::size_t k = 0, points = 0;
    for (auto _ : state)
    {
        const auto v = scans().view(k);
        const Eigen::Isometry3d& T = scans().poses[k];
        const Eigen::Matrix3f R = T.linear().cast<float>();
        const Eigen::Vector3f t = T.translation().cast<float>();
        keys.resize(v.size);
        for (std::size_t i = 0; i < v.size; ++i)
        {
            const Eigen::Vector3f p = R * Eigen::Vector3f(v.x[i], v.y[i], v.z[i]) + t;
            const auto m =
                static_cast<int32_t>(std::floor((p.x() - prm.origin_x) / prm.pillar_size));
            const auto n =
                static_cast<int32_t>(std::floor((p.y() - prm.origin_y) / prm.pillar_size));
            keys[i] = hif::packKey({m, n});
        }
        benchmark::DoNotOptimize(keys.data());
        benchmark::ClobberMemory();
        points += v.size;
        k = (k + 1) % scans().size();
    }
    state.counters["points/scan"] = double(points) / double(state.iterations());
}
BENCHMARK(BM_LowerBound)->Unit(benchmark::kMillisecond);

/** Gives `g` the sensor model its first insertion would estimate from scan 0 (when its
 *  parameters ask for one), before anything is timed: a long run estimates the model once
 *  (about 20 ms, PillarGrid::insertScan()), a start-up cost rather than a per-scan one. The
 *  check every PillarGrid::kSensorCheckInterval scans stays in the timings, as in a long run. */
void estimateSensorFirst(hif::PillarGrid& g)
{
    if (g.params().sensor_from_scans && !g.sensorModel())
        g.setSensorModel(hif::SensorModel::estimate(scans().view(0)));
}

/** Empties `g` for the next pass over the scans, keeping its sensor model (as above: not
 *  estimated again every 40 scans). */
void restartKeepingSensor(hif::PillarGrid& g)
{
    const auto model = g.sensorModel();
    g.clear();
    g.setSensorModel(model);
}

/** Inserts the scans in sequence into `g`, the map growing; the map restarts empty after the
 *  last scan (not timed). */
void insertInSequence(benchmark::State& state, hif::PillarGrid& g)
{
    estimateSensorFirst(g);
    std::size_t k = 0;
    for (auto _ : state)
    {
        benchmark::DoNotOptimize(g.insertScan(scans().view(k), scans().poses[k]));
        if (++k == scans().size())
        {
            state.PauseTiming();
            k = 0;
            restartKeepingSensor(g);
            state.ResumeTiming();
        }
    }
}

/** Insertion with the default parameters (those of kitti-online.ini). Argument: threads. */
void BM_Insert(benchmark::State& state)
{
    if (!haveScans(state)) return;
    hif::PillarGrid g;
    g.setThreads(static_cast<std::size_t>(state.range(0)));
    insertInSequence(state, g);
}
BENCHMARK(BM_Insert)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

/** The grid geometry and parameters of a shipped config (share/hif/config/), read through
 *  MRPT. */
std::pair<hif::GridGeometry, hif::Params> shippedConfig(const std::string& file)
{
    mrpt::config::CConfigFile cfg(std::string(HIF_SHARE_DIR "/config/") + file);
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(cfg, "map");
    const mrpt::maps::CMultiMetricMap maps(inits);
    const auto map = maps.mapByClass<hif::CHeightIntervalMap>();
    return {map->geometry(), map->params()};
}
std::pair<hif::GridGeometry, hif::Params> offlineConfig() { return shippedConfig("kitti.ini"); }

/** Insertion with the offline configuration, read from share/hif/config/kitti.ini (see-through
 *  misses, p_empty_init 0.42, ground seen once, surfaces at pillars' edges; its free-space test
 *  is part of classification). The difference to BM_Insert is the cost of the see-through
 *  misses, the ground test and the edges. Arguments: threads, ground 0 to turn the ground test
 *  off and edge 0 the surfaces at pillars' edges (their costs). */
void BM_InsertOfflineConfig(benchmark::State& state)
{
    if (!haveScans(state)) return;
    auto [geometry, params] = offlineConfig();
    if (state.range(1) == 0) params.ground_max_slope_deg = 0.0;
    if (state.range(2) == 0) params.pillar_edge_margin = 0.0;
    hif::PillarGrid g(geometry, params);
    g.setThreads(static_cast<std::size_t>(state.range(0)));
    insertInSequence(state, g);
}
BENCHMARK(BM_InsertOfflineConfig)
    ->ArgNames({"threads", "ground", "edge"})
    ->Args({1, 1, 1})
    ->Args({1, 0, 1})
    ->Args({1, 1, 0})
    ->Args({2, 1, 1})
    ->Unit(benchmark::kMillisecond);

/** The steps of one insertion, each timed alone on the same scans and the same growing map:
 *  0 = quantization and bucketing, 1 = interval construction (sort heights, spans), 2 = merge
 *  into the map (find or create pillars, Bayes update). Arguments: step, threads. */
void BM_InsertStep(benchmark::State& state)
{
    if (!haveScans(state)) return;
    const auto step = state.range(0);
    hif::PillarGrid g;
    g.setThreads(static_cast<std::size_t>(state.range(1)));
    estimateSensorFirst(g);  // as insertScan() would: the image layout and the gates use it
    hif::detail::ScanBuckets sp;
    std::size_t k = 0, pillars = 0;
    for (auto _ : state)
    {
        const auto v = scans().view(k);
        const auto& T = scans().poses[k];
        if (step == 0)
            hif::detail::bucketPoints(g, v, T, sp);
        else
        {
            state.PauseTiming();
            hif::detail::bucketPoints(g, v, T, sp);
            if (step == 2) hif::detail::buildSpans(g, sp);
            if (step == 2 && hif::detail::needsScanImage(g.params()))
                hif::detail::buildScanImage(g, v);
            state.ResumeTiming();
            if (step == 1) hif::detail::buildSpans(g, sp);
        }
        // Keep the map growing as in BM_Insert (not timed for steps 0 and 1).
        if (step == 2)
            hif::detail::updatePillars(g, sp);
        else
        {
            state.PauseTiming();
            if (step == 0) hif::detail::buildSpans(g, sp);
            if (hif::detail::needsScanImage(g.params())) hif::detail::buildScanImage(g, v);
            hif::detail::updatePillars(g, sp);
            state.ResumeTiming();
        }
        benchmark::DoNotOptimize(sp.cells.data());
        pillars += sp.pillarCount();
        if (++k == scans().size())
        {
            state.PauseTiming();
            k = 0;
            restartKeepingSensor(g);
            state.ResumeTiming();
        }
    }
    state.counters["pillars/scan"] = double(pillars) / double(state.iterations());
}
BENCHMARK(BM_InsertStep)
    ->ArgNames({"step", "threads"})
    ->ArgsProduct({{0, 1, 2}, {1, 2}})
    ->Unit(benchmark::kMillisecond);

/** BM_Insert through MRPT: CHeightIntervalMap::insertObservation() of a CObservationPointCloud
 *  at a CPose3D, what rawlog tools and SLAM call. The difference to BM_Insert is the adapter. */
void BM_InsertThroughMrpt(benchmark::State& state)
{
    if (!haveScans(state)) return;
    std::vector<mrpt::obs::CObservationPointCloud> obs(scans().size());
    std::vector<mrpt::poses::CPose3D> poses;
    for (std::size_t i = 0; i < scans().size(); ++i)
    {
        const hif::io::Cloud& c = scans().clouds[i];
        auto cloud = mrpt::maps::CPointsMapXYZI::Create();
        cloud->resize(c.size());
        for (std::size_t k = 0; k < c.size(); ++k)
        {
            cloud->setPointFast(k, c.x[k], c.y[k], c.z[k]);
            cloud->setPointIntensity(k, c.intensity[k]);
        }
        obs[i].pointcloud = cloud;
        poses.emplace_back(mrpt::math::CMatrixDouble44(scans().poses[i].matrix()));
    }
    hif::CHeightIntervalMap map;
    std::size_t k = 0;
    for (auto _ : state)
    {
        benchmark::DoNotOptimize(map.insertObservation(obs[k], poses[k]));
        if (++k == scans().size())
        {
            state.PauseTiming();
            k = 0;
            map.clear();
            state.ResumeTiming();
        }
    }
}
BENCHMARK(BM_InsertThroughMrpt)->Unit(benchmark::kMillisecond);

/** Classification of one scan's points against the map of all scans. */
void BM_Classify(benchmark::State& state)
{
    if (!haveScans(state)) return;
    hif::PillarGrid g = fullMap();
    g.setThreads(static_cast<std::size_t>(state.range(0)));
    std::vector<uint8_t> dyn;
    std::size_t k = 0;
    for (auto _ : state)
    {
        benchmark::DoNotOptimize(g.classify(scans().view(k), dyn, scans().poses[k]));
        k = (k + 1) % scans().size();
    }
}
BENCHMARK(BM_Classify)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

/** Classification with the offline configuration (kitti.ini), as hif-clean does it: against
 *  the map of all scans and, for the free-space test, the free_space_window scans on each
 *  side (the test holds every scan here, built once; hif-clean gives it each scan's image as
 *  it reads it: that is BM_WindowImage). */
void BM_ClassifyOfflineConfig(benchmark::State& state)
{
    if (!haveScans(state)) return;
    const auto [geometry, params] = offlineConfig();
    hif::PillarGrid g(geometry, params);
    hif::FreeSpaceTest test(scans().size());
    for (std::size_t i = 0; i < scans().size(); ++i)
    {
        g.insertScan(scans().view(i), scans().poses[i]);
        test.add(scans().view(i), scans().poses[i], g.imageLayout());
    }
    g.setThreads(static_cast<std::size_t>(state.range(0)));
    std::vector<uint8_t> dyn;
    std::size_t k = 0, seen_through = 0;
    for (auto _ : state)
    {
        seen_through +=
            g.classify(scans().view(k), dyn, scans().poses[k], &test).seen_through_points;
        k = (k + 1) % scans().size();
    }
    state.counters["seen_through/scan"] = double(seen_through) / double(state.iterations());
}
BENCHMARK(BM_ClassifyOfflineConfig)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond);

/** One scan added to a FreeSpaceTest (its fingerprint and range image built and stored),
 *  the test holding 21 scans (offline, 10 on each side). Argument image: 0, built from the
 *  scan's points (FreeSpaceTest::add(points, pose, layout), as offline); 1, taken from the
 *  image the map's insertion of the scan just built (add(points, pose, grid), as online: the
 *  map of kitti-online.ini, the insertion not timed). */
void BM_WindowImage(benchmark::State& state)
{
    if (!haveScans(state)) return;
    const bool from_insertion = state.range(0) != 0;
    hif::FreeSpaceTest test(21);
    const auto [geometry, params] = shippedConfig("kitti-online.ini");
    hif::PillarGrid g(geometry, params);
    g.insertScan(scans().view(0), scans().poses[0]);  // its sensor model, from the first scan
    std::size_t id = 0;
    for (auto _ : state)
    {
        const std::size_t k = id % scans().size();
        if (from_insertion)
        {
            state.PauseTiming();
            g.insertScan(scans().view(k), scans().poses[k]);
            state.ResumeTiming();
            test.add(scans().view(k), scans().poses[k], g);
        }
        else
            test.add(scans().view(k), scans().poses[k], g.imageLayout());
        ++id;
    }
}
BENCHMARK(BM_WindowImage)->ArgName("image")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

/** One scan online, as a SLAM system uses the map (share/hif/config/kitti-online.ini):
 *  inserted, kept by the free-space test and classified against the past. Argument image: 0,
 *  the test builds the scan's range image from its points (FreeSpaceTest::add(points, pose,
 *  layout)); 1, it takes the image the insertion built (FreeSpaceTest::add(points, pose,
 *  grid)), as CHeightIntervalMap does. After the last scan the map and the test restart empty
 *  (not timed). */
void BM_OnlineScan(benchmark::State& state)
{
    if (!haveScans(state)) return;
    const bool from_insertion = state.range(0) != 0;
    const auto [geometry, params] = shippedConfig("kitti-online.ini");
    hif::PillarGrid g(geometry, params);
    hif::FreeSpaceTest test(hif::FreeSpaceTest::capacityFor(params));
    estimateSensorFirst(g);
    std::vector<uint8_t> dyn;
    std::size_t k = 0;
    for (auto _ : state)
    {
        const auto v = scans().view(k);
        const Eigen::Isometry3d& T = scans().poses[k];
        g.insertScan(v, T);
        if (from_insertion)
            test.add(v, T, g);
        else
            test.add(v, T, g.imageLayout());
        g.classify(v, dyn, T, &test);
        if (++k == scans().size())
        {
            state.PauseTiming();
            k = 0;
            restartKeepingSensor(g);
            test.clear();
            state.ResumeTiming();
        }
    }
}
BENCHMARK(BM_OnlineScan)->ArgName("image")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

/** The offline run in memory: insert every scan, then classify every point. */
void BM_OfflineRun(benchmark::State& state)
{
    if (!haveScans(state)) return;
    std::vector<uint8_t> dyn;
    for (auto _ : state)
    {
        hif::PillarGrid g;
        g.setThreads(static_cast<std::size_t>(state.range(0)));
        for (std::size_t i = 0; i < scans().size(); ++i)
            g.insertScan(scans().view(i), scans().poses[i]);
        for (std::size_t i = 0; i < scans().size(); ++i)
            g.classify(scans().view(i), dyn, scans().poses[i]);
        benchmark::DoNotOptimize(dyn.data());
    }
    state.counters["scans"] = double(scans().size());
}
BENCHMARK(BM_OfflineRun)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

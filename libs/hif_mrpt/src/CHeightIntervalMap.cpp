// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CHeightIntervalMap.cpp
 * @brief  MRPT adapter of hif::PillarGrid: construction, observations in, queries out.
 */
#include "hif/CHeightIntervalMap.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "ObservationPoints.h"

using namespace hif;
using hif::mrpt_adapter::SensorPoints;

// Both names work as the map's class name in .ini files: "CHeightIntervalMap_count=1".
MAP_DEFINITION_REGISTER("hif::CHeightIntervalMap,CHeightIntervalMap", hif::CHeightIntervalMap)

CHeightIntervalMap::CHeightIntervalMap(const GridGeometry& geometry, const Params& params)
    : mrpt::system::COutputLogger("hif::CHeightIntervalMap"), grid_(geometry, params)
{
    static_cast<Params&>(insertionOptions) = params;
}

mrpt::maps::CMetricMap* CHeightIntervalMap::internal_CreateFromMapDefinition(
    const mrpt::maps::TMetricMapInitializer& _def)
{
    const auto& def = dynamic_cast<const CHeightIntervalMap::TMapDefinition&>(_def);
    auto* obj = new CHeightIntervalMap(def.geometry, def.insertionOpts);
    obj->insertionOptions = def.insertionOpts;
    obj->applyOptions();
    return obj;
}

void CHeightIntervalMap::applyOptions()
{
    if (insertionOptions.threads == 0)
        throw std::invalid_argument("hif::CHeightIntervalMap: invalid threads = 0 (must be >= 1)");
    const Params& p = insertionOptions;
    if (p != grid_.params()) grid_.setParams(p);
    free_space_.setCapacity(FreeSpaceTest::capacityFor(p));
    if (insertionOptions.threads != grid_.threads())
        grid_.setThreads(static_cast<std::size_t>(insertionOptions.threads));
    if (insertionOptions.sensor && grid_.sensorModel() != insertionOptions.sensor)
        grid_.setSensorModel(insertionOptions.sensor);  // given in the .ini
}

void CHeightIntervalMap::internal_clear()
{
    grid_.clear();
    last_insert_ = {};
    free_space_.clear();
    classified_ = warned_no_neighbours_ = warned_inserted_after_ = false;
}

bool CHeightIntervalMap::internal_insertObservation(
    const mrpt::obs::CObservation& obs, const std::optional<const mrpt::poses::CPose3D>& robotPose)
{
    SensorPoints sp;
    if (!mrpt_adapter::sensorPoints(obs, sp) || sp.view.size == 0) return false;
    applyOptions();
    const mrpt::poses::CPose3D robot = robotPose ? *robotPose : mrpt::poses::CPose3D();
    const Eigen::Isometry3d T = mrpt_adapter::toIsometry(robot + sp.sensor_pose);
    last_insert_ = grid_.insertScan(sp.view, T);
    if (params().online)
        free_space_.add(sp.view, T, grid_);  // the past of the next classify()
    else if (classified_ && !warned_inserted_after_)
    {
        warned_inserted_after_ = true;
        MRPT_LOG_WARN(
            "A scan was inserted after scans were classified, with "
            "an offline map (online=false): those were judged by a map that had not seen the "
            "scans after them, and offline settings (kitti.ini: p_empty_init 0.42) find a "
            "height seen once dynamic. To classify each scan as it comes, use an online map "
            "(online=true, kitti-online.ini).");
    }
    return last_insert_.points_used > 0;
}

namespace
{
/** Points [first, end) of `v` in the world frame (`T_w` the sensor's pose), into xs, ys, zs
 *  from their start: the one transform of observationToWorldPoints() and its chunks. */
template <typename T>
void toWorld(const Eigen::Isometry3d& T_w, const PointsView& v, std::size_t first, std::size_t end,
             T* xs, T* ys, T* zs)
{
    for (std::size_t i = first; i < end; ++i)
    {
        const Eigen::Vector3d p = T_w * Eigen::Vector3d(v.x[i], v.y[i], v.z[i]);
        xs[i - first] = static_cast<T>(p.x());
        ys[i - first] = static_cast<T>(p.y());
        zs[i - first] = static_cast<T>(p.z());
    }
}

template <typename T>
bool worldPointsOf(const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& robotPose,
                   std::vector<T>& xs, std::vector<T>& ys, std::vector<T>& zs)
{
    SensorPoints sp;
    if (!mrpt_adapter::sensorPoints(obs, sp)) return false;
    const PointsView& v = sp.view;
    xs.resize(v.size);
    ys.resize(v.size);
    zs.resize(v.size);
    toWorld(mrpt_adapter::toIsometry(robotPose + sp.sensor_pose), v, 0, v.size, xs.data(),
            ys.data(), zs.data());
    return true;
}
}  // namespace

bool CHeightIntervalMap::observationToWorldPoints(const mrpt::obs::CObservation& obs,
                                                  const mrpt::poses::CPose3D& robotPose,
                                                  std::vector<float>& xs, std::vector<float>& ys,
                                                  std::vector<float>& zs)
{
    return worldPointsOf(obs, robotPose, xs, ys, zs);
}

bool CHeightIntervalMap::observationToWorldPoints(const mrpt::obs::CObservation& obs,
                                                  const mrpt::poses::CPose3D& robotPose,
                                                  std::vector<double>& xs, std::vector<double>& ys,
                                                  std::vector<double>& zs)
{
    return worldPointsOf(obs, robotPose, xs, ys, zs);
}

bool CHeightIntervalMap::forEachWorldPointsChunk(
    const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& robotPose, std::size_t chunk,
    const std::function<void(const WorldPointsChunk&)>& fn)
{
    if (chunk == 0) throw std::invalid_argument("forEachWorldPointsChunk: a chunk of 0 points");
    SensorPoints sp;
    if (!mrpt_adapter::sensorPoints(obs, sp)) return false;
    const PointsView& v = sp.view;
    const Eigen::Isometry3d T_w = mrpt_adapter::toIsometry(robotPose + sp.sensor_pose);
    std::vector<double> xs(std::min(chunk, v.size)), ys(xs.size()), zs(xs.size());
    for (std::size_t first = 0; first < v.size; first += chunk)
    {
        const std::size_t n = std::min(chunk, v.size - first);
        toWorld(T_w, v, first, first + n, xs.data(), ys.data(), zs.data());
        fn(WorldPointsChunk{first, n, v.size, xs.data(), ys.data(), zs.data()});
    }
    return true;
}

double CHeightIntervalMap::staticProbability(const mrpt::math::TPoint3D& p) const
{
    return grid_.staticProbability(p.x, p.y, p.z);
}

bool CHeightIntervalMap::isStatic(const mrpt::math::TPoint3D& p) const
{
    return grid_.isStatic(p.x, p.y, p.z);
}

ClassifyStats CHeightIntervalMap::classify(const mrpt::maps::CPointsMap& worldPoints,
                                           std::vector<uint8_t>& isDynamic) const
{
    const PointsView view{worldPoints.getPointsBufferRef_x().data(),
                          worldPoints.getPointsBufferRef_y().data(),
                          worldPoints.getPointsBufferRef_z().data(), worldPoints.size()};
    return grid_.classify(view, isDynamic);
}

ClassifyStats CHeightIntervalMap::classify(const mrpt::obs::CObservation& obs,
                                           const mrpt::poses::CPose3D& robotPose,
                                           std::vector<uint8_t>& isDynamic) const
{
    SensorPoints sp;
    if (!mrpt_adapter::sensorPoints(obs, sp))
        throw std::invalid_argument(std::string("hif::CHeightIntervalMap::classify: cannot read "
                                                "points from a ") +
                                    obs.GetRuntimeClass()->className);
    const Params& p = params();
    if (!p.online)
    {
        classified_ = true;
        if (p.free_space_window > 0 && free_space_.empty() && !warned_no_neighbours_)
        {
            warned_no_neighbours_ = true;
            MRPT_LOG_WARN(
                "An offline map (online=false) classified a scan "
                "without the scans around it: the free-space test judges it with the scans "
                "given to addToFreeSpaceTest() after every scan is inserted (the second pass), "
                "none so far. To classify each scan as it comes, use an online map "
                "(online=true, kitti-online.ini).");
        }
    }
    return grid_.classify(sp.view, isDynamic, mrpt_adapter::toIsometry(robotPose + sp.sensor_pose),
                          &free_space_);
}

bool CHeightIntervalMap::addToFreeSpaceTest(const mrpt::obs::CObservation& obs,
                                            const mrpt::poses::CPose3D& robotPose)
{
    SensorPoints sp;
    if (!mrpt_adapter::sensorPoints(obs, sp)) return false;
    applyOptions();
    free_space_.add(sp.view, mrpt_adapter::toIsometry(robotPose + sp.sensor_pose),
                    grid_.imageLayout());
    return true;
}

std::optional<FreeSpaceTest::Scan> CHeightIntervalMap::makeFreeSpaceScan(
    const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& robotPose,
    FreeSpaceTest::ScanMaker& maker) const
{
    SensorPoints sp;
    if (!mrpt_adapter::sensorPoints(obs, sp)) return std::nullopt;
    return maker.make(sp.view, mrpt_adapter::toIsometry(robotPose + sp.sensor_pose),
                      grid_.imageLayout());
}

void CHeightIntervalMap::addToFreeSpaceTest(FreeSpaceTest::Scan scan)
{
    applyOptions();
    if (!(scan.layout == grid_.imageLayout()))
        throw std::invalid_argument(
            "hif::CHeightIntervalMap::addToFreeSpaceTest: a scan made for another sensor "
            "model's range image than the map's");
    free_space_.add(std::move(scan));
}

bool CHeightIntervalMap::internal_canComputeObservationLikelihood(
    const mrpt::obs::CObservation& obs) const
{
    return mrpt_adapter::isSupported(obs);
}

double CHeightIntervalMap::internal_computeObservationLikelihood(
    const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& takenFrom) const
{
    std::vector<double> xs, ys, zs;  // world coordinates: double (UTM keeps its millimetres)
    if (!observationToWorldPoints(obs, takenFrom, xs, ys, zs)) return 0.0;
    double loglik = 0.0;
    for (std::size_t i = 0; i < xs.size(); ++i)
    {
        if (!std::isfinite(xs[i]) || !std::isfinite(ys[i]) || !std::isfinite(zs[i])) continue;
        loglik += std::log(grid_.staticProbability(xs[i], ys[i], zs[i]));
    }
    return loglik;
}

bool CHeightIntervalMap::isEmpty() const { return grid_.empty(); }

std::string CHeightIntervalMap::asString() const
{
    const GridGeometry& g = geometry();
    std::ostringstream os;
    os << "hif::CHeightIntervalMap: " << grid_.pillarCount() << " pillars, "
       << grid_.intervalCount() << " intervals; pillar " << g.pillar_size << " m, origin ("
       << g.origin_x << ", " << g.origin_y << "), height resolution " << g.height_resolution
       << " m";
    return os.str();
}

float CHeightIntervalMap::compute3DMatchingRatio(const mrpt::maps::CMetricMap* otherMap,
                                                 const mrpt::poses::CPose3D& otherMapPose,
                                                 const mrpt::maps::TMatchingRatioParams& mp) const
{
    const auto* pts = dynamic_cast<const mrpt::maps::CPointsMap*>(otherMap);
    if (!pts || pts->empty()) return 0.0f;
    const GridGeometry& geo = geometry();
    const double d = mp.maxDistForCorr;
    const auto& xs = pts->getPointsBufferRef_x();
    const auto& ys = pts->getPointsBufferRef_y();
    const auto& zs = pts->getPointsBufferRef_z();
    std::size_t matched = 0;
    for (std::size_t i = 0; i < pts->size(); ++i)
    {
        const auto w = otherMapPose.composePoint(mrpt::math::TPoint3D(xs[i], ys[i], zs[i]));
        const auto idx = geo.pillarOf(w.x, w.y);
        const Pillar* pillar = idx ? grid_.findPillar(*idx) : nullptr;
        if (!pillar) continue;
        for (const Interval& iv : pillar->intervals)
            if (grid_.isStaticLogOdds(iv.logodds) && w.z >= geo.cellBottom(iv.lo) - d &&
                w.z <= geo.cellBottom(iv.hi) + d)
            {
                ++matched;
                break;
            }
    }
    return static_cast<float>(static_cast<double>(matched) / static_cast<double>(pts->size()));
}

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CHeightIntervalMap.cpp
 * @brief  MRPT adapter of hif::PillarGrid: observations, options, serialization, rendering.
 */
#include "hif/CHeightIntervalMap.h"

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/format.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/opengl/CSetOfTriangles.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

using namespace hif;

// Both names work as the map's class name in .ini files: "CHeightIntervalMap_count=1".
MAP_DEFINITION_REGISTER("hif::CHeightIntervalMap,CHeightIntervalMap", hif::CHeightIntervalMap)

IMPLEMENTS_SERIALIZABLE(CHeightIntervalMap, CMetricMap, hif)

namespace
{
Eigen::Isometry3d toIsometry(const mrpt::poses::CPose3D& pose)
{
    mrpt::math::CMatrixDouble44 H;
    pose.getHomogeneousMatrix(H);
    Eigen::Isometry3d T;
    T.matrix() = H.asEigen();
    return T;
}

/** Points of a supported observation in its sensor frame (a view into the observation where
 *  possible, else into `storage`), and the sensor pose on the robot. False if unsupported. */
bool sensorPoints(const mrpt::obs::CObservation& obs, PointsView& view,
                  mrpt::poses::CPose3D& sensorPose, std::vector<float> (&storage)[3])
{
    using namespace mrpt::obs;
    auto fromStorage = [&]() {
        view = {storage[0].data(), storage[1].data(), storage[2].data(), storage[0].size()};
    };
    if (const auto* pc = dynamic_cast<const CObservationPointCloud*>(&obs))
    {
        pc->load();  // no-op unless stored externally (lazy-load)
        if (!pc->pointcloud) return false;
        const auto& m = *pc->pointcloud;
        view = {m.getPointsBufferRef_x().data(), m.getPointsBufferRef_y().data(),
                m.getPointsBufferRef_z().data(), m.size()};
        sensorPose = pc->sensorPose;
        return true;
    }
    if (const auto* o3d = dynamic_cast<const CObservation3DRangeScan*>(&obs))
    {
        o3d->load();
        sensorPose = o3d->sensorPose;
        if (o3d->hasPoints3D)
        {
            view = {o3d->points3D_x.data(), o3d->points3D_y.data(), o3d->points3D_z.data(),
                    o3d->points3D_x.size()};
            return true;
        }
        if (!o3d->hasRangeImage) return false;
        CObservation3DRangeScan copy = *o3d;  // unprojectInto() is not const
        mrpt::maps::CSimplePointsMap pts;
        copy.unprojectInto(pts);  // sensor frame by default
        storage[0].assign(pts.getPointsBufferRef_x().begin(), pts.getPointsBufferRef_x().end());
        storage[1].assign(pts.getPointsBufferRef_y().begin(), pts.getPointsBufferRef_y().end());
        storage[2].assign(pts.getPointsBufferRef_z().begin(), pts.getPointsBufferRef_z().end());
        fromStorage();
        return true;
    }
    if (const auto* o2d = dynamic_cast<const CObservation2DRangeScan*>(&obs))
    {
        sensorPose = o2d->sensorPose;
        const std::size_t n = o2d->getScanSize();
        for (auto& s : storage) s.clear();
        // MRPT's convention: beam i at -aperture/2 + i * aperture / (n-1), mirrored when
        // scanning right to left is false.
        double ang = -0.5 * o2d->aperture;
        double dA = n > 1 ? o2d->aperture / static_cast<double>(n - 1) : 0.0;
        if (!o2d->rightToLeft)
        {
            ang = -ang;
            dA = -dA;
        }
        for (std::size_t i = 0; i < n; ++i, ang += dA)
        {
            if (!o2d->getScanRangeValidity(i)) continue;
            const double r = o2d->getScanRange(i);
            storage[0].push_back(static_cast<float>(r * std::cos(ang)));
            storage[1].push_back(static_cast<float>(r * std::sin(ang)));
            storage[2].push_back(0.0f);
        }
        fromStorage();
        return true;
    }
    return false;
}

template <typename F>
void forEachWorldPoint(const mrpt::maps::CPointsMap& pts, F&& f)
{
    const auto& xs = pts.getPointsBufferRef_x();
    const auto& ys = pts.getPointsBufferRef_y();
    const auto& zs = pts.getPointsBufferRef_z();
    for (std::size_t i = 0; i < pts.size(); ++i) f(i, xs[i], ys[i], zs[i]);
}
}  // namespace

// ---------------------------------------------------------------------------------------------
// Construction and options
// ---------------------------------------------------------------------------------------------

CHeightIntervalMap::CHeightIntervalMap(double pillar_size, double origin_x, double origin_y,
                                       double height_resolution)
    : grid_(
          [&]
          {
              Params p;
              p.pillar_size = pillar_size;
              p.origin_x = origin_x;
              p.origin_y = origin_y;
              p.height_resolution = height_resolution;
              return p;
          }())
{
}

Params CHeightIntervalMap::params() const
{
    Params p = grid_.params();  // geometry
    const TInsertionOptions& o = insertionOptions;
    p.merge_gap = o.merge_gap;
    p.interval_padding = o.interval_padding;
    p.alpha = o.alpha;
    p.beta = o.beta;
    p.p_min = o.p_min;
    p.p_max = o.p_max;
    p.p_empty_init = o.p_empty_init;
    p.low_height_preservation = o.low_height_preservation;
    p.high_height_preservation = o.high_height_preservation;
    p.unseen_height_prior = o.unseen_height_prior;
    p.beam_spacing_deg = o.beam_spacing_deg;
    p.see_through_range = o.see_through_range;
    p.see_through_margin = o.see_through_margin;
    p.static_threshold = o.static_threshold;
    p.max_intervals_per_pillar = static_cast<std::size_t>(o.max_intervals_per_pillar);
    return p;
}

void CHeightIntervalMap::syncParams() const
{
    const Params p = params();
    if (p != grid_.params()) grid_.setParams(p);
    if (insertionOptions.threads != grid_.threads())
        grid_.setThreads(static_cast<std::size_t>(insertionOptions.threads));
}

const PillarGrid& CHeightIntervalMap::grid() const
{
    syncParams();
    return grid_;
}

void CHeightIntervalMap::TInsertionOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
    MRPT_LOAD_CONFIG_VAR_CS(merge_gap, double);
    MRPT_LOAD_CONFIG_VAR_CS(interval_padding, double);
    MRPT_LOAD_CONFIG_VAR_CS(alpha, double);
    MRPT_LOAD_CONFIG_VAR_CS(beta, double);
    MRPT_LOAD_CONFIG_VAR_CS(p_min, double);
    MRPT_LOAD_CONFIG_VAR_CS(p_max, double);
    MRPT_LOAD_CONFIG_VAR_CS(p_empty_init, double);
    MRPT_LOAD_CONFIG_VAR_CS(low_height_preservation, bool);
    MRPT_LOAD_CONFIG_VAR_CS(high_height_preservation, bool);
    MRPT_LOAD_CONFIG_VAR_CS(unseen_height_prior, bool);
    MRPT_LOAD_CONFIG_VAR_CS(beam_spacing_deg, double);
    MRPT_LOAD_CONFIG_VAR_CS(static_threshold, double);
    MRPT_LOAD_CONFIG_VAR_CS(max_intervals_per_pillar, uint64_t);
    MRPT_LOAD_CONFIG_VAR_CS(see_through_range, double);
    MRPT_LOAD_CONFIG_VAR_CS(see_through_margin, double);
    MRPT_LOAD_CONFIG_VAR_CS(threads, uint64_t);
    if (threads == 0) throw std::invalid_argument("[" + s + "] threads = 0: must be >= 1");
    // Validate now, so that a bad value is reported with the section it came from.
    CHeightIntervalMap probe;
    probe.insertionOptions = *this;
    try
    {
        probe.params().validate();
    }
    catch (const std::invalid_argument& e)
    {
        throw std::invalid_argument("[" + s + "] " + e.what());
    }
}

void CHeightIntervalMap::TInsertionOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                             const std::string& s) const
{
    // Unpadded keys (MRPT 2.5.8's CConfigFileMemory keeps padding in the key, so a padded
    // key cannot be read back from the same object) and doubles that read back exactly.
    auto exact = [&](const char* name, double v, const char* comment)
    {
        std::string txt = mrpt::format("%.15g", v);
        if (std::stod(txt) != v) txt = mrpt::format("%.17g", v);
        c.write(s, name, txt, -1, -1, comment);
    };
    exact("merge_gap", merge_gap, "Max gap between heights of one interval [m]");
    exact("interval_padding", interval_padding, "Widening of scan intervals [m]");
    exact("alpha", alpha, "P_S when observed (Eq. 6), in (0.5, 1)");
    exact("beta", beta, "P_D when observed (Eq. 6), in (0, 0.5)");
    exact("p_min", p_min, "Lower clipping bound (Eq. 17)");
    exact("p_max", p_max, "Upper clipping bound (Eq. 17)");
    exact("p_empty_init", p_empty_init, "p_empty of a new pillar");
    c.write(s, "low_height_preservation", low_height_preservation, -1, -1, "LHP (Eq. 15-16)");
    c.write(s, "high_height_preservation", high_height_preservation, -1, -1,
            "Keep intervals above the field of view (not in the paper)");
    c.write(s, "unseen_height_prior", unseen_height_prior, -1, -1,
            "New intervals above every seen height start at p_empty_init (not in the paper)");
    exact("beam_spacing_deg", beam_spacing_deg,
          "Range-adaptive intervals: vertical beam spacing [deg], 0 = off (not in the paper)");
    exact("see_through_range", see_through_range,
          "See-through misses within this distance [m], 0 = off (not in the paper)");
    exact("see_through_margin", see_through_margin,
          "A return this far beyond a pillar passed through it [m]");
    exact("static_threshold", static_threshold, "Static when P(static) >= this");
    c.write(s, "max_intervals_per_pillar", max_intervals_per_pillar, -1, -1,
            "Bound on intervals per pillar");
    c.write(s, "threads", threads, -1, -1,
            "Threads for insertion and classification (same map for any count)");
}

void CHeightIntervalMap::TInsertionOptions::writeToStream(mrpt::serialization::CArchive& out) const
{
    out << merge_gap << interval_padding << alpha << beta << p_min << p_max << p_empty_init
        << low_height_preservation << high_height_preservation << unseen_height_prior
        << beam_spacing_deg << static_threshold << max_intervals_per_pillar << see_through_range
        << see_through_margin;
}

void CHeightIntervalMap::TInsertionOptions::readFromStream(mrpt::serialization::CArchive& in,
                                                           uint8_t version)
{
    in >> merge_gap >> interval_padding >> alpha >> beta >> p_min >> p_max >> p_empty_init >>
        low_height_preservation >> high_height_preservation >> unseen_height_prior >>
        beam_spacing_deg >> static_threshold >> max_intervals_per_pillar;
    see_through_range = Params().see_through_range;  // version 0: the option did not exist
    see_through_margin = Params().see_through_margin;
    if (version >= 1) in >> see_through_range >> see_through_margin;
}

CHeightIntervalMap::TMapDefinition::TMapDefinition() = default;

void CHeightIntervalMap::TMapDefinition::loadFromConfigFile_map_specific(
    const mrpt::config::CConfigFileBase& source, const std::string& sectionNamePrefix)
{
    const std::string s = sectionNamePrefix + "_creationOpts";
    MRPT_LOAD_CONFIG_VAR(pillar_size, double, source, s);
    MRPT_LOAD_CONFIG_VAR(origin_x, double, source, s);
    MRPT_LOAD_CONFIG_VAR(origin_y, double, source, s);
    MRPT_LOAD_CONFIG_VAR(height_resolution, double, source, s);
    Params geometry;
    geometry.pillar_size = pillar_size;
    geometry.origin_x = origin_x;
    geometry.origin_y = origin_y;
    geometry.height_resolution = height_resolution;
    try
    {
        geometry.validate();
    }
    catch (const std::invalid_argument& e)
    {
        throw std::invalid_argument("[" + s + "] " + e.what());
    }
    insertionOpts.loadFromConfigFile(source, sectionNamePrefix + "_insertOpts");
}

void CHeightIntervalMap::TMapDefinition::dumpToTextStream_map_specific(std::ostream& out) const
{
    LOADABLEOPTS_DUMP_VAR(pillar_size, double);
    LOADABLEOPTS_DUMP_VAR(origin_x, double);
    LOADABLEOPTS_DUMP_VAR(origin_y, double);
    LOADABLEOPTS_DUMP_VAR(height_resolution, double);
    insertionOpts.dumpToTextStream(out);
}

mrpt::maps::CMetricMap* CHeightIntervalMap::internal_CreateFromMapDefinition(
    const mrpt::maps::TMetricMapInitializer& _def)
{
    const auto& def = dynamic_cast<const CHeightIntervalMap::TMapDefinition&>(_def);
    auto* obj =
        new CHeightIntervalMap(def.pillar_size, def.origin_x, def.origin_y, def.height_resolution);
    obj->insertionOptions = def.insertionOpts;
    return obj;
}

// ---------------------------------------------------------------------------------------------
// Insertion and queries
// ---------------------------------------------------------------------------------------------

void CHeightIntervalMap::internal_clear()
{
    grid_.clear();
    last_insert_ = {};
}

bool CHeightIntervalMap::internal_insertObservation(
    const mrpt::obs::CObservation& obs, const std::optional<const mrpt::poses::CPose3D>& robotPose)
{
    PointsView view;
    mrpt::poses::CPose3D sensorPose;
    std::vector<float> storage[3];
    if (!sensorPoints(obs, view, sensorPose, storage) || view.size == 0) return false;
    syncParams();
    const mrpt::poses::CPose3D robot = robotPose ? *robotPose : mrpt::poses::CPose3D();
    last_insert_ = grid_.insertScan(view, toIsometry(robot + sensorPose));
    return last_insert_.points_used > 0;
}

bool CHeightIntervalMap::observationToWorldPoints(const mrpt::obs::CObservation& obs,
                                                  const mrpt::poses::CPose3D& robotPose,
                                                  std::vector<float>& xs, std::vector<float>& ys,
                                                  std::vector<float>& zs)
{
    PointsView view;
    mrpt::poses::CPose3D sensorPose;
    std::vector<float> storage[3];
    if (!sensorPoints(obs, view, sensorPose, storage)) return false;
    const Eigen::Isometry3d T = toIsometry(robotPose + sensorPose);
    xs.resize(view.size);
    ys.resize(view.size);
    zs.resize(view.size);
    for (std::size_t i = 0; i < view.size; ++i)
    {
        const Eigen::Vector3d p = T * Eigen::Vector3d(view.x[i], view.y[i], view.z[i]);
        xs[i] = static_cast<float>(p.x());
        ys[i] = static_cast<float>(p.y());
        zs[i] = static_cast<float>(p.z());
    }
    return true;
}

double CHeightIntervalMap::staticProbability(const mrpt::math::TPoint3D& p) const
{
    return grid().staticProbability(p.x, p.y, p.z);
}

bool CHeightIntervalMap::isStatic(const mrpt::math::TPoint3D& p) const
{
    return grid().isStatic(p.x, p.y, p.z);
}

ClassifyStats CHeightIntervalMap::classify(const mrpt::maps::CPointsMap& worldPoints,
                                           std::vector<uint8_t>& isDynamic) const
{
    const PointsView view{worldPoints.getPointsBufferRef_x().data(),
                          worldPoints.getPointsBufferRef_y().data(),
                          worldPoints.getPointsBufferRef_z().data(), worldPoints.size()};
    return grid().classify(view, isDynamic);
}

bool CHeightIntervalMap::internal_canComputeObservationLikelihood(
    const mrpt::obs::CObservation& obs) const
{
    using namespace mrpt::obs;
    return dynamic_cast<const CObservationPointCloud*>(&obs) != nullptr ||
           dynamic_cast<const CObservation3DRangeScan*>(&obs) != nullptr ||
           dynamic_cast<const CObservation2DRangeScan*>(&obs) != nullptr;
}

double CHeightIntervalMap::internal_computeObservationLikelihood(
    const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& takenFrom) const
{
    std::vector<float> xs, ys, zs;
    if (!observationToWorldPoints(obs, takenFrom, xs, ys, zs)) return 0.0;
    const PillarGrid& g = grid();
    double loglik = 0.0;
    for (std::size_t i = 0; i < xs.size(); ++i)
    {
        if (!std::isfinite(xs[i]) || !std::isfinite(ys[i]) || !std::isfinite(zs[i])) continue;
        loglik += std::log(g.staticProbability(xs[i], ys[i], zs[i]));
    }
    return loglik;
}

// ---------------------------------------------------------------------------------------------
// CMetricMap interface
// ---------------------------------------------------------------------------------------------

bool CHeightIntervalMap::isEmpty() const { return grid_.empty(); }

std::string CHeightIntervalMap::asString() const
{
    const Params p = params();
    std::ostringstream os;
    os << "hif::CHeightIntervalMap: " << grid_.pillarCount() << " pillars, "
       << grid_.intervalCount() << " intervals; pillar " << p.pillar_size << " m, origin ("
       << p.origin_x << ", " << p.origin_y << "), height resolution " << p.height_resolution
       << " m";
    return os.str();
}

void CHeightIntervalMap::getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const
{
    if (!genericMapParams.enableSaveAs3DObject) return;
    const Params p = params();
    auto tris = mrpt::opengl::CSetOfTriangles::Create();
    tris->setName("hif::CHeightIntervalMap");
    const double inset = 0.05 * p.pillar_size;  // a small gap shows pillar borders
    for (const auto& [idx, pillar] : grid_.sortedPillars())
    {
        const float x0 = static_cast<float>(p.origin_x + idx.m * p.pillar_size + inset);
        const float y0 = static_cast<float>(p.origin_y + idx.n * p.pillar_size + inset);
        const float x1 = static_cast<float>(x0 + p.pillar_size - 2 * inset);
        const float y1 = static_cast<float>(y0 + p.pillar_size - 2 * inset);
        for (const Interval& iv : pillar->intervals)
        {
            const float z0 = static_cast<float>(grid_.cellBottom(iv.lo));
            const float z1 = static_cast<float>(grid_.cellBottom(iv.hi));
            const double t = (logistic(iv.logodds) - p.p_min) / (p.p_max - p.p_min);
            const auto g8 = static_cast<uint8_t>(std::lround(255.0 * std::clamp(t, 0.0, 1.0)));
            const mrpt::img::TColor color(static_cast<uint8_t>(255 - g8), g8, 0);
            const mrpt::math::TPoint3D c[8] = {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0},
                                               {x0, y1, z0}, {x0, y0, z1}, {x1, y0, z1},
                                               {x1, y1, z1}, {x0, y1, z1}};
            static const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                            {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
            for (const auto& f : faces)
                for (const auto& tri :
                     {std::array<int, 3>{f[0], f[1], f[2]}, std::array<int, 3>{f[0], f[2], f[3]}})
                {
                    mrpt::opengl::TTriangle t3(c[tri[0]], c[tri[1]], c[tri[2]]);
                    t3.setColor(color);
                    tris->insertTriangle(t3);
                }
        }
    }
    o.insert(tris);
}

void CHeightIntervalMap::saveMetricMapRepresentationToFile(const std::string& prefix) const
{
    const Params p = params();
    const std::string txt = prefix + "_intervals.txt";
    std::ofstream f(txt);
    if (!f) THROW_EXCEPTION_FMT("Error writing to target file '%s'", txt.c_str());
    f << "# x_min y_min x_max y_max z_bottom z_top p_static\n";
    for (const auto& [idx, pillar] : grid_.sortedPillars())
    {
        const double x0 = p.origin_x + idx.m * p.pillar_size;
        const double y0 = p.origin_y + idx.n * p.pillar_size;
        for (const Interval& iv : pillar->intervals)
            f << x0 << ' ' << y0 << ' ' << x0 + p.pillar_size << ' ' << y0 + p.pillar_size << ' '
              << grid_.cellBottom(iv.lo) << ' ' << grid_.cellBottom(iv.hi) << ' '
              << logistic(iv.logodds) << '\n';
    }
    if (!f) THROW_EXCEPTION_FMT("Error writing to target file '%s'", txt.c_str());

    const std::string scene_file = prefix + "_3D.3Dscene";
    mrpt::opengl::COpenGLScene scene;
    auto objs = mrpt::opengl::CSetOfObjects::Create();
    getVisualizationInto(*objs);
    scene.insert(objs);
    if (!scene.saveToFile(scene_file))
        THROW_EXCEPTION_FMT("Error writing to target file '%s'", scene_file.c_str());
}

float CHeightIntervalMap::compute3DMatchingRatio(const mrpt::maps::CMetricMap* otherMap,
                                                 const mrpt::poses::CPose3D& otherMapPose,
                                                 const mrpt::maps::TMatchingRatioParams& mp) const
{
    const auto* pts = dynamic_cast<const mrpt::maps::CPointsMap*>(otherMap);
    if (!pts || pts->empty()) return 0.0f;
    const PillarGrid& g = grid();
    const double threshold = g.params().static_threshold;
    const double d = mp.maxDistForCorr;
    std::size_t matched = 0;
    forEachWorldPoint(*pts,
                      [&](std::size_t, float lx, float ly, float lz)
                      {
                          const auto w =
                              otherMapPose.composePoint(mrpt::math::TPoint3D(lx, ly, lz));
                          const auto idx = g.pillarOf(w.x, w.y);
                          if (!idx) return;
                          const Pillar* pillar = g.findPillar(*idx);
                          if (!pillar) return;
                          for (const Interval& iv : pillar->intervals)
                              if (logistic(iv.logodds) >= threshold &&
                                  w.z >= g.cellBottom(iv.lo) - d && w.z <= g.cellBottom(iv.hi) + d)
                              {
                                  ++matched;
                                  return;
                              }
                      });
    return static_cast<float>(static_cast<double>(matched) / static_cast<double>(pts->size()));
}

// ---------------------------------------------------------------------------------------------
// Serialization (version 1 adds the see-through options; version 0 is still read)
// ---------------------------------------------------------------------------------------------

uint8_t CHeightIntervalMap::serializeGetVersion() const { return 1; }

void CHeightIntervalMap::serializeTo(mrpt::serialization::CArchive& out) const
{
    const Params& p = grid_.params();
    out << p.pillar_size << p.origin_x << p.origin_y << p.height_resolution;
    insertionOptions.writeToStream(out);
    out << genericMapParams;
    const auto pillars = grid_.sortedPillars();
    out << static_cast<uint64_t>(pillars.size());
    for (const auto& [idx, pillar] : pillars)
    {
        out << idx.m << idx.n << pillar->logodds_empty << pillar->seen_top
            << static_cast<uint32_t>(pillar->intervals.size());
        for (const Interval& iv : pillar->intervals) out << iv.lo << iv.hi << iv.logodds;
    }
}

void CHeightIntervalMap::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version)
{
    switch (version)
    {
        case 0:
        case 1:
        {
            Params p;
            in >> p.pillar_size >> p.origin_x >> p.origin_y >> p.height_resolution;
            insertionOptions.readFromStream(in, version);
            in >> genericMapParams;
            PillarGrid g(p);  // validates the geometry
            grid_ = std::move(g);
            syncParams();  // validates the options
            uint64_t n = 0;
            in >> n;
            for (uint64_t k = 0; k < n; ++k)
            {
                PillarIndex idx;
                Pillar pillar;
                uint32_t count = 0;
                in >> idx.m >> idx.n >> pillar.logodds_empty >> pillar.seen_top >> count;
                if (count > grid_.params().max_intervals_per_pillar)
                    THROW_EXCEPTION_FMT(
                        "Corrupt hif map: pillar with %u intervals, above the bound", count);
                pillar.intervals.resize(count);
                for (Interval& iv : pillar.intervals) in >> iv.lo >> iv.hi >> iv.logodds;
                grid_.setPillar(idx, std::move(pillar));
            }
            last_insert_ = {};
        }
        break;
        default:
            MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
    }
}

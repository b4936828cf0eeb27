// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Params.h
 * @brief  The tunable parameters of Height Interval Filtering, with the paper's defaults.
 *
 * Equation numbers refer to "HIF: Height Interval Filtering for Efficient Dynamic Points
 * Removal" (see doc/algorithm.md, which also explains every choice the paper leaves open).
 * The grid itself (pillar size, origin, height resolution) is GridGeometry: it is fixed when a
 * map is created, while these may change between scans.
 *
 * A new parameter is its member below and its line in fields(); .ini files, serialization,
 * validation, equality and hif-clean's summary follow from the table.
 */
#pragma once

#include <array>
#include <cstddef>

#include "hif/FieldTable.h"
#include "hif/GridGeometry.h"

namespace hif
{
/** Parameters of the HIF update and of classification. Probabilities are P(static) =
 *  P(occupied by something that stays), as in the paper. */
struct Params
{
    /** Heights of one pillar in one scan whose gap is at most this are merged into one interval
     *  (Eq. 4 construction; not specified by the paper), metres. */
    double merge_gap = 0.1;
    /** Each scan interval is widened by this much below and above, metres, so that a surface
     *  hit at slightly different heights from scan to scan overlaps itself. */
    double interval_padding = 0.05;

    /** Observation model of the binary Bayes filter (Eq. 6): P_S = alpha, P_D = beta when an
     *  interval is observed; 1 - alpha, 1 - beta otherwise. Paper: alpha > 0.5, beta < 0.5. */
    double alpha = 0.6;
    double beta = 0.45;
    /** Clipping of every probability after an update (Eq. 17-18; paper: [0.1, 0.9]). */
    double p_min = 0.1;
    double p_max = 0.9;
    /** p_empty of a pillar seen for the first time (Eq. 4); 0.5 = no prior knowledge. */
    double p_empty_init = 0.5;

    /** Low-Height Preservation (Eq. 15-16): an interval unobserved by a scan keeps its
     *  probability when it lies entirely below the lowest height the scan saw in the pillar. */
    bool low_height_preservation = true;

    /** High-Height Preservation (ours, not in the paper; false = the paper): an interval
     *  unobserved by a scan also keeps its probability when it lies entirely above the highest
     *  height the scan could see in the pillar: sensor height + distance * tan(top beam
     *  elevation), the top beam's elevation being measured from the scan itself. Without it,
     *  the tops of walls and trees leave the field of view as the sensor approaches and are
     *  wrongly "expected but not seen" (Eq. 13). */
    bool high_height_preservation = true;

    /** Unseen-height prior (ours; false = the paper): a new interval (Eq. 14) above every height
     *  any earlier scan could see in the pillar starts from p_empty_init instead of the pillar's
     *  p_empty, since p_empty (Eq. 8) only speaks for the heights that were in view. */
    bool unseen_height_prior = true;

    /** Range-adaptive intervals (ours; 0 = off, the paper's fixed merge_gap and
     *  interval_padding): the vertical angle between neighbouring beams, degrees. In a pillar
     *  at horizontal distance d from the sensor, heights closer than d * tan(angle) are merged,
     *  and intervals are padded by half of it, so that a surface sampled by consecutive beams
     *  stays one interval at any range. Any value > 0 turns them on; the angle used is the
     *  sensor model's vertical spacing when the map has a model (sensor_from_scans), and this
     *  value only without one (see doc/sensors.md). */
    double beam_spacing_deg = 0.44;

    /** Sensor model from the scans (ours; false = none, the paper): the map estimates its
     *  LiDAR's beams, field of view and resolution from the first scan inserted (SensorModel),
     *  and checks every 50th scan after against it. The model gives the range-adaptive
     *  intervals their beam spacing and the see-through and free-space tests the layout of
     *  their range images; without one, beam_spacing_deg and a 64-beam layout are used. */
    bool sensor_from_scans = true;

    /** See-through misses (ours; 0 = off, the paper): after each scan, every interval of a
     *  pillar within this horizontal distance of the sensor (metres) that the scan did not hit
     *  gets a miss (Eq. 13) when a beam passed through it: in the scan's range image, in the
     *  direction of the pillar's centre and between the interval's bottom and top, some return
     *  lies farther than the pillar by more than see_through_margin and none lies within the
     *  margin of it. Gives "empty" evidence to pillars that no later return falls in (far
     *  cars on open roads, whose vacated pillars are never hit again). At most 2000 pillars
     *  wide (see validateWith()). */
    double see_through_range = 0.0;
    /** Distance, metres, that a return must lie beyond a pillar to count as passing through
     *  it; returns within it of the pillar veto the miss. */
    double see_through_margin = 2.5;

    /** Misses need a beam (ours; false = the paper): evidence of empty space only where a beam
     *  of the scan passed. An interval of a pillar the scan hit, but not at the interval's
     *  heights, gets the Eq. 13 miss only when a beam passed through it: in the scan's range
     *  image, within the pillar's width as seen from the sensor, a return beyond the pillar's
     *  footprint (half its diagonal from its axis) and none within it. And the pillar's
     *  p_empty is lowered (Eq. 8) only when a beam passed through the pillar somewhere between
     *  its lowest content and the top of the view. Where the scan could not have seen
     *  (between two beams of a sparse LiDAR, behind something nearer, where a non-repetitive
     *  pattern did not look this time) the map is kept as it is. */
    bool miss_needs_beam = true;

    /** A surface at a pillar's edge (ours; 0 = off, the paper; needs miss_needs_beam):
     *  distance, metres. An interval's heights at which the scan saw a surface within this
     *  distance of the pillar's edge, in the pillar beside it, get no Eq. 13 miss from the
     *  beams toward the pillar's centre: that surface may go on into the pillar at a place
     *  those beams did not cross. The pillars cut a pole or a trunk that stands astride their
     *  edge in two, and from one side the scan sees only the half in the next pillar while
     *  its beams toward this pillar's centre pass beside the pole; without this, the half
     *  seen from the other side decays (KITTI 08: a quarter of the poles' points). A mover
     *  keeps the interval it left only while it stands within this distance of the edge.
     *  Below half a pillar (validateWith()). */
    double pillar_edge_margin = 0.0;

    /** Ground seen once is kept (ours; 0 = off, the paper; needs miss_needs_beam): a new piece
     *  of a pillar's floor (its lowest interval in the scan) gets the neutral prior 0.5 instead
     *  of p_empty (Eq. 14) where it was seen (not its padding), so that one sighting keeps it,
     *  when every return of the scan in the floor lies on ground: the next beam above returned
     *  farther, at most this slope (degrees) higher or lower, or beyond the pillar and not
     *  lower; and the beams below, one after the other down to the lowest, each returned
     *  nearer, within this slope (plus ground_max_step below the first) of the one above. With a
     *  sparse LiDAR, ground tens of metres away is crossed by a beam in one scan only, and
     *  "needs a second sighting" (p_empty_init < 0.5) removed it; what stands on the ground
     *  (a car's foot, a roof) breaks the run and still needs a second sighting. */
    double ground_max_slope_deg = 0.0;
    /** A step, metres, that the run of ground down to the sensor may take between two beams
     *  (a kerb), for ground_max_slope_deg. */
    double ground_max_step = 0.2;

    /** Free-space test (ours; 0 = off, the paper): how many scans on each side of a scan
     *  (offline; online: before it) may show that its points were not there. A point was not
     *  there at the time of another scan when that scan's beam toward it, from nearly the same
     *  direction (free_space_max_parallax_deg), returned clearly beyond it and no beam around
     *  it returned near it; what counts is only a scan outside the span of scans that saw the
     *  point occupied. A pillar's points of one scan are removed when, above the pillar's
     *  ground (free_space_clearance) and spanning free_space_min_extent in height, at
     *  least free_space_fraction of them were not there at other times: something that
     *  walked through. Needs the scans' range images (FreeSpaceTest); see doc/algorithm.md. */
    std::size_t free_space_window = 0;
    /** How scans are classified, which the free-space test's scans follow (FreeSpaceTest):
     *  online (SLAM), each scan right after its insertion, with the map and the scans of the
     *  past only; offline (false), once every scan is inserted, each with the scans on both
     *  sides of it. The offline defaults (kitti.ini: p_empty_init 0.42, a height first seen
     *  needs a second sighting) remove most of a scan classified before the scans after it
     *  were inserted. */
    bool online = true;
    /** Points farther than this from their sensor are not tested, metres. A person (1.7 m)
     *  still spans 3 rings of a 64-beam sensor (0.4 degrees apart) at 80 m: farther, the
     *  object test (2 entries spanning free_space_min_extent) has too little to go on. */
    double free_space_range = 80.0;
    /** A return counts as near a point (it vetoes, or marks the point occupied) within this
     *  many metres plus free_space_margin_per_m times the point's range; beyond, as clearly
     *  behind it. */
    double free_space_margin = 0.3;
    double free_space_margin_per_m = 0.02;
    /** Points of a scan less than this above their pillar's ground are ground (not tested;
     *  in a pillar shown gone, removed with the rest from half of it up, and below that each
     *  one only where other scans saw through it: a mover's lowest ring at the road's
     *  height), metres. The ground is
     *  the pillar's lowest return in the scan, or the top of the map's floor there (its
     *  lowest static interval) where that lies free_space_min_extent or more below it: with
     *  sparse rings the lowest return is often a mover's own lowest ring. */
    double free_space_clearance = 0.1;
    /** A pillar's tested points must span at least this in height: an object, not ground
     *  texture, metres. */
    double free_space_min_extent = 0.5;
    /** Share of a pillar's judged points (tested points that another scan saw occupied, or
     *  through) that must be shown gone for it to be removed. */
    double free_space_fraction = 0.5;
    /** Only scans that see a point within this angle of the direction it was seen from give
     *  evidence, degrees: from far off the original view, a beam grazes surfaces and passes
     *  through foliage and fences beside the point. */
    double free_space_max_parallax_deg = 10.0;

    /** Minimum range (ours; 0 = off, the paper): points nearer their sensor than this,
     *  metres, are not inserted and are reported dynamic (the vehicle's own returns). */
    double min_range = 0.0;

    /** A point is static when the interval it falls in has P(static) >= this. */
    double static_threshold = 0.5;

    /** Upper bound on intervals per pillar. Touching intervals of equal probability are always
     *  merged (lossless); above this count, the closest neighbours are merged too (lossy). */
    std::size_t max_intervals_per_pillar = 16;

    /** The fields, for loops over them (see FieldTable.h). */
    [[nodiscard]] static const std::array<Field<Params>, 30>& fields();

    /** The paper's method as written: the additions above (HHP, the unseen-height prior,
     *  range-adaptive intervals, the sensor model, misses that need a beam; see-through misses
     *  and the free-space test are off by default) off, offline (as the paper cleans a
     *  sequence). */
    [[nodiscard]] static Params paper();

    /** Throws std::invalid_argument naming the first invalid field and its value. */
    void validate() const;
    /** validate(), and the checks that involve the grid: see_through_range spans at most 2000
     *  pillars, and pillar_edge_margin is under half a pillar. */
    void validateWith(const GridGeometry& geometry) const;

    /** Field-by-field equality (exact). */
    friend bool operator==(const Params& a, const Params& b) { return fieldsEqual(a, b); }
    friend bool operator!=(const Params& a, const Params& b) { return !(a == b); }
};

static_assert(memberCount<Params>() == std::tuple_size_v<std::decay_t<decltype(Params::fields())>>,
              "every member of hif::Params needs its row in Params::fields()");

inline const std::array<Field<Params>, 30>& Params::fields()
{
    using P = Params;
    static const std::array<Field<P>, 30> table{{
        {"merge_gap", &P::merge_gap, Bounds::atLeast(0), 0,
         "Max gap between heights of one interval [m]"},
        {"interval_padding", &P::interval_padding, Bounds::atLeast(0), 0,
         "Widening of scan intervals [m]"},
        {"alpha", &P::alpha, Bounds::open(0.5, 1), 0, "P_S when observed (Eq. 6), in (0.5, 1)"},
        {"beta", &P::beta, Bounds::open(0, 0.5), 0, "P_D when observed (Eq. 6), in (0, 0.5)"},
        {"p_min", &P::p_min, Bounds::open(0, 1), 0, "Lower clipping bound (Eq. 17)"},
        {"p_max", &P::p_max, Bounds::open(0, 1), 0, "Upper clipping bound (Eq. 17)"},
        {"p_empty_init", &P::p_empty_init, Bounds::open(0, 1), 0,
         "p_empty of a new pillar (at least 0.5 with a sensor without rings)"},
        {"low_height_preservation", &P::low_height_preservation, Bounds::any(), 0,
         "LHP (Eq. 15-16)"},
        {"high_height_preservation", &P::high_height_preservation, Bounds::any(), 0,
         "Keep intervals above the field of view (not in the paper)"},
        {"unseen_height_prior", &P::unseen_height_prior, Bounds::any(), 0,
         "New intervals above every seen height start at p_empty_init (not in the paper)"},
        {"beam_spacing_deg", &P::beam_spacing_deg, Bounds::closedOpen(0, 10), 0,
         "Range-adaptive intervals: vertical beam spacing [deg], 0 = off (not in the paper)"},
        {"see_through_range", &P::see_through_range, Bounds::closed(0, 1000), 1,
         "See-through misses within this distance [m], 0 = off (not in the paper)"},
        {"see_through_margin", &P::see_through_margin, Bounds::atLeast(0), 1,
         "A return this far beyond a pillar passed through it [m]"},
        {"free_space_window", &P::free_space_window, Bounds::closed(0, 50), 2,
         "Free-space test: scans on each side that may show a point was not there, 0 = off "
         "(not in the paper)"},
        {"online", &P::online, Bounds::any(), 4,
         "Classified online (right after insertion, the past only) or offline (after every "
         "scan, both sides)"},
        {"free_space_range", &P::free_space_range, Bounds::above(0), 2,
         "Free-space test: points within this range are tested [m]"},
        {"free_space_margin", &P::free_space_margin, Bounds::atLeast(0), 2,
         "Free-space test: a return this near a point is at it [m] (plus the next per metre)"},
        {"free_space_margin_per_m", &P::free_space_margin_per_m, Bounds::closedOpen(0, 1), 2,
         "Free-space test: margin added per metre of range"},
        {"free_space_clearance", &P::free_space_clearance, Bounds::atLeast(0), 2,
         "Free-space test: points this far above their pillar's ground are tested [m]"},
        {"free_space_min_extent", &P::free_space_min_extent, Bounds::atLeast(0), 2,
         "Free-space test: a pillar's tested points span at least this height [m]"},
        {"free_space_fraction", &P::free_space_fraction, Bounds::open(0, 1), 2,
         "Free-space test: share of a pillar's judged points shown gone to remove it"},
        {"free_space_max_parallax_deg", &P::free_space_max_parallax_deg, Bounds::closed(0, 180), 2,
         "Free-space test: evidence only from views within this angle [deg]"},
        {"min_range", &P::min_range, Bounds::closedOpen(0, 100), 2,
         "Points nearer the sensor are not inserted and are dynamic [m], 0 = off"},
        {"miss_needs_beam", &P::miss_needs_beam, Bounds::any(), 3,
         "Eq. 13 misses only where a beam of the scan passed (not in the paper)"},
        {"pillar_edge_margin", &P::pillar_edge_margin, Bounds::atLeast(0), 7,
         "No miss at heights where the scan saw a surface this near the pillar's edge [m], 0 = "
         "off (not in the paper)"},
        {"sensor_from_scans", &P::sensor_from_scans, Bounds::any(), 3,
         "Estimate the LiDAR's beams and resolution from the scans (not in the paper)"},
        {"ground_max_slope_deg", &P::ground_max_slope_deg, Bounds::closedOpen(0, 45), 5,
         "Floors on ground seen once are kept: the ground's max slope [deg], 0 = off (not in "
         "the paper)"},
        {"ground_max_step", &P::ground_max_step, Bounds::atLeast(0), 5,
         "The step the ground may take between two beams (a kerb) [m]"},
        {"static_threshold", &P::static_threshold, Bounds::open(0, 1), 0,
         "Static when P(static) >= this"},
        {"max_intervals_per_pillar", &P::max_intervals_per_pillar, Bounds::atLeast(1), 0,
         "Bound on intervals per pillar"},
    }};
    return table;
}

}  // namespace hif

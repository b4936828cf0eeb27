// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Params.h
 * @brief  All parameters of Height Interval Filtering, with the paper's defaults.
 *
 * Equation numbers refer to "HIF: Height Interval Filtering for Efficient Dynamic Points
 * Removal" (see doc/algorithm.md, which also explains every choice the paper leaves open).
 */
#pragma once

#include <cstddef>
#include <string>

namespace hif
{
/** Parameters of the HIF map. Probabilities are P(static) = P(occupied by something that
 *  stays), as in the paper. Call validate() before use; PillarGrid does it in its constructor. */
struct Params
{
    /** Pillar edge length in x and y, metres (Eq. 1-2; paper: 1 m). */
    double pillar_size = 1.0;
    /** Global grid origin O = (x_o, y_o) on the XY plane, metres (Eq. 1). */
    double origin_x = 0.0;
    double origin_y = 0.0;

    /** Vertical resolution, metres: interval endpoints are snapped to multiples of it, so an
     *  interval is a run of whole height cells [b, t). Not in the paper (which keeps exact
     *  heights); with it, overlap tests are exact and intervals per pillar are bounded. */
    double height_resolution = 0.05;
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

    /** Range-adaptive intervals (ours; 0 = the paper's fixed merge_gap and interval_padding):
     *  the vertical angle between neighbouring beams, degrees (HDL-64E: 0.33 to 0.5, 0.42 on
     *  average; 0.44 measured best on the KITTI clips, see doc/algorithm.md). In a pillar
     *  at horizontal distance d from the sensor, heights closer than d * tan(angle) are merged,
     *  and intervals are padded by half of it, so that a surface sampled by consecutive beams
     *  stays one interval at any range. */
    double beam_spacing_deg = 0.44;

    /** See-through misses (ours; 0 = off, the paper): after each scan, every interval of a
     *  pillar within this horizontal distance of the sensor (metres) that the scan did not hit
     *  gets a miss (Eq. 13) when a beam passed through it: in the scan's range image, in the
     *  direction of the pillar's centre and between the interval's bottom and top, some return
     *  lies farther than the pillar by more than see_through_margin and none lies within the
     *  margin of it. Gives "empty" evidence to pillars that no later return falls in (far
     *  cars on open roads, whose vacated pillars are never hit again). */
    double see_through_range = 0.0;
    /** Distance, metres, that a return must lie beyond a pillar to count as passing through
     *  it; returns within it of the pillar veto the miss. */
    double see_through_margin = 2.5;

    /** A point is static when the interval it falls in has P(static) >= this. */
    double static_threshold = 0.5;

    /** Upper bound on intervals per pillar. Touching intervals of equal probability are always
     *  merged (lossless); above this count, the closest neighbours are merged too (lossy). */
    std::size_t max_intervals_per_pillar = 16;

    /** The paper's method as written: the three options above off. */
    [[nodiscard]] static Params paper();

    /** Throws std::invalid_argument naming the first invalid field and its value. */
    void validate() const;

    /** Field-by-field equality (exact). */
    friend bool operator==(const Params& a, const Params& b);
    friend bool operator!=(const Params& a, const Params& b) { return !(a == b); }
};

}  // namespace hif

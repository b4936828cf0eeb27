// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Params.cpp
 * @brief  Validation of hif::Params.
 */
#include "hif/Params.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace hif
{
namespace
{
template <typename T>
[[noreturn]] void fail(const char* field, T value, const char* requirement)
{
    std::ostringstream os;
    os << "hif::Params: invalid " << field << " = " << value << " (must be " << requirement << ")";
    throw std::invalid_argument(os.str());
}

void requireFinite(const char* field, double v)
{
    if (!std::isfinite(v)) fail(field, v, "a finite number");
}
}  // namespace

void Params::validate() const
{
    requireFinite("pillar_size", pillar_size);
    if (!(pillar_size > 0.0)) fail("pillar_size", pillar_size, "> 0");
    requireFinite("origin_x", origin_x);
    requireFinite("origin_y", origin_y);
    requireFinite("height_resolution", height_resolution);
    if (!(height_resolution > 0.0)) fail("height_resolution", height_resolution, "> 0");
    requireFinite("merge_gap", merge_gap);
    if (!(merge_gap >= 0.0)) fail("merge_gap", merge_gap, ">= 0");
    requireFinite("interval_padding", interval_padding);
    if (!(interval_padding >= 0.0)) fail("interval_padding", interval_padding, ">= 0");
    if (!(alpha > 0.5 && alpha < 1.0)) fail("alpha", alpha, "in (0.5, 1)");
    if (!(beta > 0.0 && beta < 0.5)) fail("beta", beta, "in (0, 0.5)");
    if (!(p_min > 0.0 && p_min < 1.0)) fail("p_min", p_min, "in (0, 1)");
    if (!(p_max > 0.0 && p_max < 1.0)) fail("p_max", p_max, "in (0, 1)");
    if (!(p_min < p_max)) fail("p_min", p_min, "< p_max");
    if (!(p_empty_init >= p_min && p_empty_init <= p_max))
        fail("p_empty_init", p_empty_init, "in [p_min, p_max]");
    requireFinite("beam_spacing_deg", beam_spacing_deg);
    if (!(beam_spacing_deg >= 0.0 && beam_spacing_deg < 10.0))
        fail("beam_spacing_deg", beam_spacing_deg, "in [0, 10)");
    requireFinite("see_through_range", see_through_range);
    if (!(see_through_range >= 0.0 && see_through_range <= 1000.0))
        fail("see_through_range", see_through_range, "in [0, 1000]");
    if (!(see_through_range <= 2000.0 * pillar_size))
        fail("see_through_range", see_through_range, "<= 2000 pillar sizes");
    requireFinite("see_through_margin", see_through_margin);
    if (!(see_through_margin >= 0.0)) fail("see_through_margin", see_through_margin, ">= 0");
    if (!(static_threshold > 0.0 && static_threshold < 1.0))
        fail("static_threshold", static_threshold, "in (0, 1)");
    if (max_intervals_per_pillar < 1)
        fail("max_intervals_per_pillar", max_intervals_per_pillar, ">= 1");
}

Params Params::paper()
{
    Params p;
    p.high_height_preservation = false;
    p.unseen_height_prior = false;
    p.beam_spacing_deg = 0.0;
    return p;
}

bool operator==(const Params& a, const Params& b)
{
    return a.pillar_size == b.pillar_size && a.origin_x == b.origin_x && a.origin_y == b.origin_y &&
           a.height_resolution == b.height_resolution && a.merge_gap == b.merge_gap &&
           a.interval_padding == b.interval_padding && a.alpha == b.alpha && a.beta == b.beta &&
           a.p_min == b.p_min && a.p_max == b.p_max && a.p_empty_init == b.p_empty_init &&
           a.low_height_preservation == b.low_height_preservation &&
           a.high_height_preservation == b.high_height_preservation &&
           a.unseen_height_prior == b.unseen_height_prior &&
           a.beam_spacing_deg == b.beam_spacing_deg && a.see_through_range == b.see_through_range &&
           a.see_through_margin == b.see_through_margin &&
           a.static_threshold == b.static_threshold &&
           a.max_intervals_per_pillar == b.max_intervals_per_pillar;
}

}  // namespace hif

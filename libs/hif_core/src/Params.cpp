// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Params.cpp
 * @brief  Validation of hif::Params beyond each field's bounds, and the paper's settings.
 */
#include "hif/Params.h"

namespace hif
{
void Params::validate() const
{
    constexpr const char* kOwner = "hif::Params";
    validateFields(*this, kOwner);
    if (!(p_min < p_max)) throwInvalid(kOwner, "p_min", p_min, "< p_max");
    if (!(p_empty_init >= p_min && p_empty_init <= p_max))
        throwInvalid(kOwner, "p_empty_init", p_empty_init, "in [p_min, p_max]");
}

void Params::validateWith(const GridGeometry& geometry) const
{
    validate();
    geometry.validate();
    // The see-through misses scan a window of pillars around the sensor.
    if (!(see_through_range <= 2000.0 * geometry.pillar_size))
        throwInvalid("hif::Params", "see_through_range", see_through_range, "<= 2000 pillar sizes");
    if (!(pillar_edge_margin < 0.5 * geometry.pillar_size))
        throwInvalid("hif::Params", "pillar_edge_margin", pillar_edge_margin,
                     "< half the pillar size");
}

Params Params::paper()
{
    Params p;
    p.high_height_preservation = false;
    p.unseen_height_prior = false;
    p.beam_spacing_deg = 0.0;
    p.sensor_from_scans = false;
    p.miss_needs_beam = false;
    p.online = false;  // the paper cleans a sequence offline
    return p;
}

}  // namespace hif

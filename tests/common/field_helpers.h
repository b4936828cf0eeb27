// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   field_helpers.h
 * @brief  Test helper: settings structs (GridGeometry, Params) with fields set away from their
 *         defaults, through the field tables, so that a test over them covers a field added
 *         later without being edited.
 */
#pragma once

#include <gtest/gtest.h>

#include <type_traits>

#include "hif/FieldTable.h"

namespace hif::test
{
/** A valid value other than `v` within `b`. */
inline double otherValue(const Bounds& b, double v)
{
    for (double c : {v * 1.1 + 0.01, v * 0.9 - 0.01, v + 1.0, v - 1.0})
        if (c != v && b.contains(c)) return c;
    ADD_FAILURE() << "no other valid value near " << v;
    return v;
}

/** Sets `field` of `s` to another valid value (bools flipped). */
template <typename S, typename Member>
void changeField(S& s, const Field<S>& field, Member member)
{
    auto& v = s.*member;
    using T = std::decay_t<decltype(v)>;
    if constexpr (std::is_same_v<T, bool>)
        v = !v;
    else if constexpr (std::is_integral_v<T>)
        v = field.bounds.contains(static_cast<double>(v + 1)) ? v + 1 : v - 1;
    else
        v = static_cast<T>(otherValue(field.bounds, static_cast<double>(v)));
}

/** `base` with every field changed: no field of the result equals its default. */
template <typename S>
S everyFieldChanged(S base = S())
{
    forEachField<S>([&](const Field<S>& f, auto member) { changeField(base, f, member); });
    return base;
}

/** Names of the fields where a and b differ. */
template <typename S>
std::string differingFields(const S& a, const S& b)
{
    std::string names;
    forEachField<S>(
        [&](const Field<S>& f, auto member)
        {
            if (!(a.*member == b.*member)) names += std::string(names.empty() ? "" : ", ") + f.name;
        });
    return names;
}

}  // namespace hif::test

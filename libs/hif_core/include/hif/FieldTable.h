// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   FieldTable.h
 * @brief  A table of the fields of a settings struct (GridGeometry, Params): name, member,
 *         allowed values, serialization version and a one-line doc. Validation, equality,
 *         .ini load/save, serialization and JSON are all loops over it, so that a setting is
 *         declared once.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

namespace hif
{
/** Allowed values of a numeric field: from lo to hi, each end open or closed (infinite ends
 *  are open). Doubles must also be finite. */
struct Bounds
{
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = true;
    bool hi_open = true;

    [[nodiscard]] static constexpr Bounds any() { return {}; }
    [[nodiscard]] static constexpr Bounds above(double v) { return {v, kInf, true, true}; }
    [[nodiscard]] static constexpr Bounds atLeast(double v) { return {v, kInf, false, true}; }
    [[nodiscard]] static constexpr Bounds open(double a, double b) { return {a, b, true, true}; }
    [[nodiscard]] static constexpr Bounds closed(double a, double b)
    {
        return {a, b, false, false};
    }
    [[nodiscard]] static constexpr Bounds closedOpen(double a, double b)
    {
        return {a, b, false, true};
    }

    [[nodiscard]] bool contains(double v) const
    {
        return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    }
    /** What a valid value is, as a message ends: "> 0", ">= 1", "in (0.5, 1)", "a finite
     *  number". */
    [[nodiscard]] std::string describe() const;

private:
    static constexpr double kInf = std::numeric_limits<double>::infinity();
};

/** One field of settings struct S. */
template <typename S>
struct Field
{
    /** The member's name: also its .ini key and JSON key. */
    const char* name;
    std::variant<double S::*, bool S::*, std::size_t S::*> member;
    /** Allowed values (numbers only). */
    Bounds bounds;
    /** Serialization version of CHeightIntervalMap that added the field: older files do not
     *  have it, and loading one leaves it at its default. */
    uint8_t since_version;
    /** One line: what it is, with its unit (written as the .ini comment). */
    const char* doc;
};

/** Calls f(field, member_pointer) for every field of S (S::fields(), in table order). */
template <typename S, typename F>
void forEachField(F&& f)
{
    for (const Field<S>& field : S::fields())
        std::visit([&](auto member) { f(field, member); }, field.member);
}

/** Throws std::invalid_argument "<owner>: invalid <name> = <value> (must be <bounds>)" for the
 *  first field of `s` outside its bounds (doubles: or not finite). */
template <typename S>
void validateFields(const S& s, const char* owner);

/** Field-by-field equality (exact). */
template <typename S>
[[nodiscard]] bool fieldsEqual(const S& a, const S& b)
{
    bool equal = true;
    forEachField<S>([&](const Field<S>&, auto member) { equal = equal && a.*member == b.*member; });
    return equal;
}

/** The exception validateFields() throws, for checks across fields. */
[[noreturn]] void throwInvalid(const char* owner, const char* field, double value,
                               const std::string& requirement);

template <typename S>
void validateFields(const S& s, const char* owner)
{
    forEachField<S>(
        [&](const Field<S>& field, auto member)
        {
            const auto v = s.*member;
            if constexpr (!std::is_same_v<decltype(v), const bool>)
            {
                const auto d = static_cast<double>(v);
                const bool finite = d - d == 0.0;  // false for NaN and infinities
                if (!finite) throwInvalid(owner, field.name, d, "a finite number");
                if (!field.bounds.contains(d))
                    throwInvalid(owner, field.name, d, field.bounds.describe());
            }
        });
}

namespace detail
{
/** Converts to any member type, for counting the members brace initialization takes. */
struct AnyMember
{
    template <typename T>
    constexpr operator T() const noexcept  // NOLINT: implicit on purpose
    {
        return T{};
    }
};

template <typename T, typename... A>
constexpr auto bracesTake(int) -> decltype(T{std::declval<A>()...}, true)
{
    return true;
}
template <typename T, typename... A>
constexpr bool bracesTake(...)
{
    return false;
}
template <typename T, std::size_t... I>
constexpr bool bracesTakeCount(std::index_sequence<I...>)
{
    return bracesTake<T, decltype((void)I, AnyMember{})...>(0);
}
}  // namespace detail

/** The number of members of `T`, an aggregate of scalar members (as the settings structs are):
 *  how many values its brace initialization takes. Each settings struct checks at compile time
 *  that its field table has a row for every member, so that none is left out of validation,
 *  equality, the .ini, serialization and JSON. */
template <typename T, std::size_t N = 0>
constexpr std::size_t memberCount()
{
    static_assert(std::is_aggregate_v<T>, "memberCount() counts the members of an aggregate");
    if constexpr (detail::bracesTakeCount<T>(std::make_index_sequence<N + 1>{}))
        return memberCount<T, N + 1>();
    else
        return N;
}

}  // namespace hif

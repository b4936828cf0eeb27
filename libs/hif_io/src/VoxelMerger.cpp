// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   VoxelMerger.cpp
 * @brief  Per-voxel merging with sorted run files and a k-way merge.
 */
#include "hif/io/VoxelMerger.h"

#include <absl/container/flat_hash_map.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <queue>
#include <stdexcept>

#include "hif/io/FileError.h"
#include "hif/io/VoxelKey.h"

namespace hif::io
{
namespace
{
using Key = VoxelKey;

/** A voxel's sums: of the offsets of its points from its corner, and of their intensities. */
struct Sums
{
    double x = 0, y = 0, z = 0, intensity = 0;
    uint32_t points = 0;
    uint32_t last_scan = 0;  ///< the scan that last added to it

    void add(const Sums& o)
    {
        x += o.x;
        y += o.y;
        z += o.z;
        intensity += o.intensity;
        points += o.points;
    }
};

/** A voxel as a run file holds it. */
struct Record
{
    Key key;
    Sums sums;
};
constexpr std::size_t kRecordBytes = 12 + 4 * 8 + 4;

void pack(const Record& r, char* out)
{
    const int32_t key[3] = {r.key.i, r.key.j, r.key.k};
    std::memcpy(out, key, 12);
    const double s[4] = {r.sums.x, r.sums.y, r.sums.z, r.sums.intensity};
    std::memcpy(out + 12, s, 32);
    std::memcpy(out + 44, &r.sums.points, 4);
}

Record unpack(const char* in)
{
    Record r;
    int32_t key[3];
    std::memcpy(key, in, 12);
    r.key = {key[0], key[1], key[2]};
    double s[4];
    std::memcpy(s, in + 12, 32);
    r.sums.x = s[0];
    r.sums.y = s[1];
    r.sums.z = s[2];
    r.sums.intensity = s[3];
    std::memcpy(&r.sums.points, in + 44, 4);
    return r;
}

/** Reads a run file record by record. */
class RunReader
{
public:
    explicit RunReader(const std::string& file) : file_(file), f_(std::fopen(file.c_str(), "rb"))
    {
        if (!f_) throwFileError(file, std::string("cannot be read back: ") + std::strerror(errno));
        std::setvbuf(f_, nullptr, _IOFBF, std::size_t{1} << 18);
    }
    ~RunReader() { std::fclose(f_); }
    RunReader(const RunReader&) = delete;
    RunReader& operator=(const RunReader&) = delete;

    /** The next record, false at the end. */
    bool next(Record& r)
    {
        char buf[kRecordBytes];
        const std::size_t n = std::fread(buf, 1, kRecordBytes, f_);
        if (n == 0 && std::feof(f_)) return false;
        if (n != kRecordBytes)
            throwFileError(file_, "could not be read back (truncated run file of the voxel map)");
        r = unpack(buf);
        return true;
    }

private:
    std::string file_;
    std::FILE* f_;
};
}  // namespace

struct VoxelMerger::Impl
{
    absl::flat_hash_map<Key, Sums> voxels;
    /** Points waiting to be added, in batches: the table is far larger than the caches, and
     *  the slots of a batch are fetched from memory together rather than one after another. */
    struct Pending
    {
        Key key;
        double dx, dy, dz;  ///< from the voxel's corner
        float intensity;
    };
    static constexpr std::size_t kBatch = 32;
    std::array<Pending, kBatch> pending;
    std::size_t pending_count = 0;
    /** The voxel of the last point, while no voxel was added or removed since (consecutive
     *  points of a scan often share one). */
    Key last_key{};
    Sums* last = nullptr;

    /** The records of `keys` (sorted), written to `file` and removed from `voxels`. */
    void writeRun(const std::vector<Key>& keys, const std::string& file)
    {
        last = nullptr;
        std::FILE* f = std::fopen(file.c_str(), "wb");
        if (!f) throwFileError(file, std::string("cannot be created: ") + std::strerror(errno));
        std::vector<char> buf(kRecordBytes * 4096);
        std::size_t used = 0;
        bool ok = true;
        for (const Key& key : keys)
        {
            const auto it = voxels.find(key);
            pack({key, it->second}, buf.data() + used);
            voxels.erase(it);
            used += kRecordBytes;
            if (used == buf.size())
            {
                ok = ok && std::fwrite(buf.data(), 1, used, f) == used;
                used = 0;
            }
        }
        ok = ok && std::fwrite(buf.data(), 1, used, f) == used;
        ok = (std::fclose(f) == 0) && ok;
        if (!ok)
            throwFileError(
                file, std::string("could not be written (disk full?): ") + std::strerror(errno));
    }
};

std::size_t VoxelMerger::voxelsWithin(std::size_t bytes)
{
    // A slot: the key and the sums, and one control byte.
    constexpr std::size_t kSlot = sizeof(std::pair<const Key, Sums>) + 1;
    std::size_t slots = 1;
    while (slots * 2 * kSlot <= bytes) slots *= 2;
    return std::max<std::size_t>(2, (slots - 1) / 8 * 7);
}

VoxelMerger::VoxelMerger(double voxel, std::string spill_prefix, std::size_t max_voxels)
    : voxel_(voxel),
      prefix_(std::move(spill_prefix)),
      max_voxels_(std::max<std::size_t>(max_voxels, 2)),
      impl_(std::make_unique<Impl>())
{
    if (!(voxel > 0) || !std::isfinite(voxel))
        throw std::invalid_argument("VoxelMerger: the voxel size must be positive");
    // The table at its largest from the start: growing it would hold the old and the new one
    // at once, half as much again as the bound (the pages are touched only as voxels come).
    impl_->voxels.reserve(max_voxels_);
}

VoxelMerger::~VoxelMerger()
{
    for (const std::string& run : runs_) std::remove(run.c_str());
}

void VoxelMerger::add(double x, double y, double z, float intensity)
{
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return;
    if (finished_) throw std::logic_error("VoxelMerger::add() after finish()");
    const std::optional<Key> key = voxelKeyOf(x, y, z, voxel_);
    if (!key)
        throw std::runtime_error("a point at (" + std::to_string(x) + ", " + std::to_string(y) +
                                 ", " + std::to_string(z) + ") lies more than 2^31 voxels of " +
                                 std::to_string(voxel_) + " m from the origin: use larger voxels");
    Impl& m = *impl_;
    m.pending[m.pending_count++] = {*key, x - double(key->i) * voxel_, y - double(key->j) * voxel_,
                                    z - double(key->k) * voxel_, intensity};
    ++points_;
    if (m.pending_count == Impl::kBatch) addPending();
}

void VoxelMerger::nextScan()
{
    addPending();
    ++scan_;
}

void VoxelMerger::addPending()
{
    Impl& m = *impl_;
    for (std::size_t k = 0; k < m.pending_count; ++k) m.voxels.prefetch(m.pending[k].key);
    for (std::size_t k = 0; k < m.pending_count; ++k)
    {
        const Impl::Pending& p = m.pending[k];
        bool inserted = false;
        if (!m.last || p.key != m.last_key)
        {
            const auto [it, added] = m.voxels.try_emplace(p.key);
            inserted = added;
            m.last_key = p.key;
            m.last = &it->second;
        }
        Sums& s = *m.last;
        s.x += p.dx;
        s.y += p.dy;
        s.z += p.dz;
        s.intensity += p.intensity;
        ++s.points;
        s.last_scan = scan_;
        if (inserted)
        {
            peak_ = std::max(peak_, m.voxels.size());
            if (m.voxels.size() >= max_voxels_) spill();
        }
    }
    m.pending_count = 0;
}

void VoxelMerger::spill()
{
    auto& voxels = impl_->voxels;
    // The half added to least recently: all voxels last added to before the median scan, or,
    // when that is fewer than half (most of them from the last scans), those of the median scan
    // too. Only their keys are held aside (12 bytes a voxel), sorted.
    std::vector<uint32_t> last;
    last.reserve(voxels.size());
    for (const auto& [key, s] : voxels) last.push_back(s.last_scan);
    auto mid = last.begin() + static_cast<std::ptrdiff_t>(last.size() / 2);
    std::nth_element(last.begin(), mid, last.end());
    const uint32_t cutoff = *mid;
    last = {};
    std::vector<Key> keys;
    for (const auto& [key, s] : voxels)
        if (s.last_scan < cutoff) keys.push_back(key);
    if (keys.size() < voxels.size() / 2)
        for (const auto& [key, s] : voxels)
            if (s.last_scan == cutoff) keys.push_back(key);
    std::sort(keys.begin(), keys.end());
    const std::string file = prefix_ + std::to_string(runs_.size()) + ".part";
    runs_.push_back(file);  // removed by the destructor from here on
    ++spills_;
    impl_->writeRun(keys, file);
}

std::size_t VoxelMerger::finish(const std::function<void(const MergedPoint&)>& sink)
{
    if (finished_) throw std::logic_error("VoxelMerger::finish() twice");
    addPending();
    finished_ = true;
    // The voxels still in memory are one more run, read in the order of their keys.
    auto& voxels = impl_->voxels;
    std::vector<Key> rest;
    rest.reserve(voxels.size());
    for (const auto& [key, s] : voxels) rest.push_back(key);
    std::sort(rest.begin(), rest.end());

    std::vector<std::unique_ptr<RunReader>> readers;
    for (const std::string& run : runs_) readers.push_back(std::make_unique<RunReader>(run));
    const std::size_t memory_run = readers.size();
    std::size_t rest_at = 0;
    const auto next = [&](std::size_t run, Record& r)
    {
        if (run < memory_run) return readers[run]->next(r);
        if (rest_at == rest.size()) return false;
        r.key = rest[rest_at++];
        r.sums = voxels.at(r.key);
        return true;
    };
    // The smallest key at the top; a voxel in several runs comes out of each in turn.
    using Head = std::pair<Record, std::size_t>;
    const auto later = [](const Head& a, const Head& b)
    { return b.first.key < a.first.key || (a.first.key == b.first.key && b.second < a.second); };
    std::priority_queue<Head, std::vector<Head>, decltype(later)> heads(later);
    for (std::size_t run = 0; run <= memory_run; ++run)
    {
        Record r;
        if (next(run, r)) heads.push({r, run});
    }
    std::size_t count = 0;
    while (!heads.empty())
    {
        const Key key = heads.top().first.key;
        Sums s;
        while (!heads.empty() && heads.top().first.key == key)
        {
            const auto [r, run] = heads.top();
            heads.pop();
            s.add(r.sums);
            Record n;
            if (next(run, n)) heads.push({n, run});
        }
        MergedPoint p;
        const double n = s.points;
        p.x = double(key.i) * voxel_ + s.x / n;
        p.y = double(key.j) * voxel_ + s.y / n;
        p.z = double(key.k) * voxel_ + s.z / n;
        p.intensity = static_cast<float>(s.intensity / n);
        p.points = s.points;
        sink(p);
        ++count;
    }
    readers.clear();
    for (const std::string& run : runs_) std::remove(run.c_str());
    runs_.clear();
    impl_->voxels = {};
    impl_->last = nullptr;
    return count;
}

}  // namespace hif::io

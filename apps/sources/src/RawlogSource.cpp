// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   RawlogSource.cpp
 * @brief  Scans of an MRPT rawlog: observations, each scan after its CObservationRobotPose, or
 *         sensory frames.
 */
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <stdexcept>

#include "hif/apps/Cli.h"
#include "hif/apps/FrameComment.h"
#include "hif/apps/ScanSource.h"

namespace hif::apps
{
namespace
{
class RawlogSource : public ScanSource
{
public:
    RawlogSource(std::string file, bool poses_required)
        : file_(std::move(file)), poses_required_(poses_required)
    {
        open();
    }

    bool next(Scan& out) override
    {
        using namespace mrpt::obs;
        if (frame_scans_.next(out)) return counted(true, out);
        auto arch = mrpt::serialization::archiveFrom(*in_);
        for (;;)
        {
            mrpt::serialization::CSerializable::Ptr obj;
            try
            {
                obj = arch.ReadObject();
            }
            catch (const mrpt::serialization::CExceptionEOF&)
            {
                return false;
            }
            catch (const std::exception& e)
            {
                throw std::runtime_error("rawlog '" + file_ + "' is corrupt or truncated after " +
                                         std::to_string(scans_read_) +
                                         " scans: " + innermostMessage(e.what()));
            }
            if (auto comment = std::dynamic_pointer_cast<CObservationComment>(obj))
            {
                if (const auto f = parseKittiFrameComment(comment->text))
                {
                    frame_ = f;
                    continue;
                }
            }
            // Odometry (as kitti2rawlog --odometry writes the trajectory for MRPT's viewers) is
            // not a pose of the scans here: they are placed at their CObservationRobotPose.
            if (obj && IS_CLASS(*obj, CObservationOdometry)) continue;
            if (auto rp = std::dynamic_pointer_cast<CObservationRobotPose>(obj))
            {
                pose_ = rp->pose.mean;
                have_pose_ = true;
                continue;
            }
            if (auto sf = std::dynamic_pointer_cast<CSensoryFrame>(obj))
            {
                // A pose inside the frame places the scans after it.
                const auto first_scan = std::find_if(sf->begin(), sf->end(),
                                                     [](const auto& o) { return o && isScan(*o); });
                const auto first_pose = std::find_if(
                    sf->begin(), sf->end(),
                    [](const auto& o) { return o && IS_CLASS(*o, CObservationRobotPose); });
                if (first_scan != sf->end() && !have_pose_ && first_pose > first_scan &&
                    poses_required_)
                    throwNoPose();
                frame_scans_.assign(*sf, have_pose_ ? pose_ : mrpt::poses::CPose3D(), have_pose_);
                have_pose_ = false;
                if (frame_scans_.next(out)) return counted(true, out);
                continue;
            }
            auto obs = std::dynamic_pointer_cast<CObservation>(obj);
            if (!obs || !isScan(*obs))
            {
                ++skipped_;
                continue;
            }
            if (!have_pose_ && poses_required_) throwNoPose();
            out = {obs, have_pose_ ? pose_ : mrpt::poses::CPose3D(), frame_, have_pose_,
                   std::nullopt};
            have_pose_ = false;  // every scan needs its own pose: never reuse a stale one
            frame_.reset();      // and its own number
            return counted(true, out);
        }
    }

    void rewind() override
    {
        frame_scans_.clear();
        frame_.reset();
        have_pose_ = false;
        scans_read_ = 0;
        skipped_ = 0;
        open();
    }

    [[nodiscard]] std::size_t skippedObjects() const override { return skipped_; }

private:
    void open()
    {
        in_ = std::make_unique<mrpt::io::CFileGZInputStream>();
        if (!in_->open(file_)) throw std::runtime_error("cannot open rawlog '" + file_ + "'");
    }
    /** A scan handed out: counted, and its external points checked. */
    bool counted(bool got, const Scan& out)
    {
        if (got)
            checkExternalPoints(*out.obs,
                                "rawlog '" + file_ + "', scan " + std::to_string(scans_read_));
        scans_read_ += got ? 1 : 0;
        return got;
    }
    [[noreturn]] void throwNoPose() const
    {
        throw std::runtime_error("rawlog '" + file_ + "': scan " + std::to_string(scans_read_) +
                                 " has no pose before it (hif-clean needs a "
                                 "CObservationRobotPose before each scan, as kitti2rawlog "
                                 "writes, or a .simplemap)");
    }

    std::string file_;
    bool poses_required_;
    std::unique_ptr<mrpt::io::CFileGZInputStream> in_;
    FrameScans frame_scans_;
    std::optional<std::size_t> frame_;  ///< from a "kitti frame N" comment, for the next scan
    mrpt::poses::CPose3D pose_;
    bool have_pose_ = false;
    std::size_t scans_read_ = 0;
    std::size_t skipped_ = 0;
};
}  // namespace

std::unique_ptr<ScanSource> openRawlog(const std::string& file, bool poses_required)
{
    return std::make_unique<RawlogSource>(file, poses_required);
}

}  // namespace hif::apps

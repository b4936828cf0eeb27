// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   RunFiles.h
 * @brief  What a run reads and what it writes, checked before anything is written: no output
 *         is an input or another output of the same run (whatever the paths look like:
 *         compared as real paths, hard links included).
 */
#pragma once

#include <string>
#include <vector>

namespace hif::apps
{
class RunFiles
{
public:
    /** A file the run reads, described for messages by `what` (e.g. "the input rawlog"). */
    void input(const std::string& path, const std::string& what);
    /** A folder of which the run reads the files ending in `ext` (e.g. ".label"). */
    void inputFolder(const std::string& dir, const std::string& ext, const std::string& what);
    /** The files of a KITTI sequence folder (SemanticKITTI layout): the .bin files of velodyne/,
     *  the .label files of labels/, poses.txt, calib.txt, times.txt; named "the ... of <what>". */
    void inputKittiSequence(const std::string& dir, const std::string& what);

    /** A file (or, with `folder`, a folder replaced whole) the run writes. Throws
     *  std::runtime_error, naming both, if it is an input, a file of an input folder's kind in
     *  that folder, a folder that holds an input, or the same as, inside or around an output
     *  given before. */
    void output(const std::string& path, const std::string& what, bool folder = false);

private:
    struct Entry
    {
        std::string path, real, what, ext;
        bool folder = false;
    };
    std::vector<Entry> inputs_, outputs_;
};

}  // namespace hif::apps

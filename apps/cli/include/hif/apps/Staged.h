// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Staged.h
 * @brief  Results written aside and put in place only when complete: a run that fails, or is
 *         stopped, leaves the user's earlier results as they were, never a mix of old and new
 *         files; and two runs never write the same results at once.
 */
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hif/apps/Interrupt.h"

namespace hif::apps
{
/** The entries `names` of folder `dir` (files or folders), written into a staging folder beside
 *  `dir` (`.<dir>.partial-<pid>`) and moved into it by commit(). Entries of `dir` that are not
 *  in `names` are never touched. Until commit(), `dir` holds its old entries; after, the new
 *  ones. If commit() is never reached (an error, or SIGINT, SIGTERM, SIGHUP), the staging
 *  folder is removed, and so is `dir` if this run created it and it is still empty. Staging
 *  folders left by runs that were killed (their process is gone) are removed on the way.
 *  While it exists, the object holds a lock on `dir`: a second run into the same folder stops
 *  with a message instead of mixing its results with this one's. */
class StagedFolder
{
public:
    /** Refuses (std::runtime_error naming it and `flag`) if one of `names` exists in `dir` and
     *  `overwrite` is false, if `dir` is a file or a dangling symbolic link, or if another run
     *  is writing into it; creates `dir` (if needed) and the staging folder. */
    StagedFolder(const std::string& dir, std::vector<std::string> names, bool overwrite,
                 const std::string& flag);
    ~StagedFolder();
    StagedFolder(const StagedFolder&) = delete;
    StagedFolder& operator=(const StagedFolder&) = delete;

    /** The folder to write the entries into. */
    [[nodiscard]] const std::string& path() const { return staging_; }
    /** Moves the new entries into `dir`, replacing the old ones (without `overwrite`, refusing
     *  to replace one that appeared meanwhile). */
    void commit();

private:
    /** Removes what a run that did not commit made (staging folder, lock, created folder). */
    void abandon();

    std::string dir_, staging_;
    std::vector<std::string> names_;
    bool overwrite_;
    std::string flag_;
    bool committed_ = false;
    bool created_dir_ = false;
    int lock_fd_ = -1;
    std::optional<RemoveOnInterrupt> remove_dir_, remove_staging_;
};

/** One file written beside itself as `.<name>.partial-<pid>.<ext>` and renamed over `file` by
 *  commit(); removed if commit() is never reached (an error, or SIGINT, SIGTERM, SIGHUP).
 *  Partial files of `file` left by runs that were killed are removed on the way. */
class StagedFile
{
public:
    /** Refuses (std::runtime_error naming the file, and `what` names it: the option that gave
     *  it) if `file` exists and `overwrite` (--overwrite) is false, if it is a folder, or if the
     *  folder it goes in does not exist. */
    StagedFile(const std::string& file, bool overwrite, const std::string& what);
    ~StagedFile();
    StagedFile(const StagedFile&) = delete;
    StagedFile& operator=(const StagedFile&) = delete;

    /** The file to write. */
    [[nodiscard]] const std::string& path() const { return partial_; }
    /** Renames the file into place (without `overwrite`, refusing to replace a file that
     *  appeared meanwhile). */
    void commit();

private:
    std::string file_, partial_;
    bool overwrite_;
    bool committed_ = false;
    std::optional<RemoveOnInterrupt> remove_partial_;
};

}  // namespace hif::apps

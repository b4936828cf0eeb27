// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Staged.h
 * @brief  Results written aside and put in place only when complete: a run that fails leaves
 *         the user's earlier results as they were, never a mix of old and new files.
 */
#pragma once

#include <string>
#include <vector>

namespace hif::apps
{
/** The entries `names` of folder `dir` (files or folders), written into a staging folder beside
 *  `dir` and moved into it by commit(). Entries of `dir` that are not in `names` are never
 *  touched. Until commit(), `dir` holds its old entries; after, the new ones. If commit() is
 *  never reached (an error), the staging folder is removed. */
class StagedFolder
{
public:
    /** Refuses (std::runtime_error naming it and `flag`) if one of `names` exists in `dir` and
     *  `overwrite` is false; creates the staging folder. */
    StagedFolder(const std::string& dir, std::vector<std::string> names, bool overwrite,
                 const std::string& flag);
    ~StagedFolder();
    StagedFolder(const StagedFolder&) = delete;
    StagedFolder& operator=(const StagedFolder&) = delete;

    /** The folder to write the entries into. */
    [[nodiscard]] const std::string& path() const { return staging_; }
    /** Moves the new entries into `dir` (created if needed), replacing the old ones. */
    void commit();

private:
    std::string dir_, staging_;
    std::vector<std::string> names_;
    bool committed_ = false;
};

/** One file written beside itself as `.<name>.partial-<pid>.<ext>` and renamed over `file` by
 *  commit(); removed if commit() is never reached. */
class StagedFile
{
public:
    /** Refuses (std::runtime_error) if `file` exists and `overwrite` is false. */
    StagedFile(const std::string& file, bool overwrite, const std::string& flag);
    ~StagedFile();
    StagedFile(const StagedFile&) = delete;
    StagedFile& operator=(const StagedFile&) = delete;

    /** The file to write. */
    [[nodiscard]] const std::string& path() const { return partial_; }
    void commit();

private:
    std::string file_, partial_;
    bool committed_ = false;
};

}  // namespace hif::apps

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Staged.cpp
 * @brief  Staging folders and files.
 */
#include "hif/apps/Staged.h"

#include <unistd.h>

#include <filesystem>
#include <stdexcept>

#include "hif/apps/Cli.h"

namespace fs = std::filesystem;

namespace hif::apps
{
namespace
{
std::string pidSuffix() { return "-" + std::to_string(getpid()); }

void renameOrThrow(const fs::path& from, const fs::path& to)
{
    std::error_code ec;
    fs::rename(from, to, ec);
    if (ec)
        throw std::runtime_error("cannot move '" + from.string() + "' to '" + to.string() +
                                 "': " + ec.message());
}
}  // namespace

StagedFolder::StagedFolder(const std::string& dir, std::vector<std::string> names, bool overwrite,
                           const std::string& flag)
    : dir_(cleanDir(dir)), names_(std::move(names))
{
    if (fs::exists(dir_) && !fs::is_directory(dir_))
        throw std::runtime_error("'" + dir_ + "' exists and is not a folder");
    for (const std::string& n : names_) refuseToOverwrite(dir_ + "/" + n, overwrite, flag);
    const fs::path p = fs::absolute(dir_);
    staging_ =
        (p.parent_path() / ("." + p.filename().string() + ".partial" + pidSuffix())).string();
    fs::remove_all(staging_);
    makeDirs(staging_);
}

StagedFolder::~StagedFolder()
{
    if (committed_) return;
    std::error_code ec;
    fs::remove_all(staging_, ec);  // a failed run leaves nothing behind
}

void StagedFolder::commit()
{
    makeDirs(dir_);
    // The old entries go aside first, then the new ones in; the aside copies are dropped last.
    const fs::path aside = fs::path(dir_) / (".old" + pidSuffix());
    std::error_code ec;
    fs::remove_all(aside, ec);
    makeDirs(aside.string());
    for (const std::string& n : names_)
        if (fs::exists(fs::path(dir_) / n)) renameOrThrow(fs::path(dir_) / n, aside / n);
    for (const std::string& n : names_)
        if (fs::exists(fs::path(staging_) / n))
            renameOrThrow(fs::path(staging_) / n, fs::path(dir_) / n);
    committed_ = true;
    fs::remove_all(aside, ec);
    fs::remove_all(staging_, ec);
}

StagedFile::StagedFile(const std::string& file, bool overwrite, const std::string& flag)
    : file_(file)
{
    // Beside it, hidden, with the same extension (which may say the format).
    const fs::path p(file);
    partial_ = (p.parent_path() /
                ("." + p.stem().string() + ".partial" + pidSuffix() + p.extension().string()))
                   .string();
    refuseToOverwrite(file_, overwrite, flag);
}

StagedFile::~StagedFile()
{
    if (committed_) return;
    std::error_code ec;
    fs::remove(partial_, ec);
}

void StagedFile::commit()
{
    renameOrThrow(partial_, file_);
    committed_ = true;
}

}  // namespace hif::apps

// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Staged.cpp
 * @brief  Staging folders and files, their locks, and the partial results of stopped runs.
 */
#include "hif/apps/Staged.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "hif/apps/Cli.h"

namespace fs = std::filesystem;

namespace hif::apps
{
namespace
{
/** The flag every app takes to replace earlier results. */
const std::string kOverwriteFlag = "--overwrite";

std::string pidSuffix() { return "-" + std::to_string(getpid()); }

bool processAlive(long pid)
{
    if (pid <= 0) return false;
    return kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

/** Removes the entries of `dir` named `<prefix><pid><suffix>` whose process is gone: what a run
 *  killed before it could clean up (kill -9, a crash, a power cut) left behind. */
void removeStale(const fs::path& dir, const std::string& prefix, const std::string& suffix)
{
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    {
        const std::string name = it->path().filename().string();
        if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
            name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
            continue;
        const std::string digits =
            name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
        if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
            continue;
        const long pid = std::stol(digits);
        if (pid == getpid() || processAlive(pid)) continue;
        std::error_code rm;
        if (fs::remove_all(it->path(), rm) > 0 && !rm)
            std::cerr << "note: removed '" << it->path().string()
                      << "', left by a run that was stopped (process " << pid << " is gone)\n";
    }
}

[[noreturn]] void throwAppeared(const fs::path& p, const std::string& flag)
{
    throw std::runtime_error("'" + p.string() +
                             "' appeared while this run was writing it (another program?): it "
                             "was not replaced, and this run's result is not kept; pass " +
                             flag + " to replace it");
}

/** Renames `from` to `to`; unless `replace`, fails if `to` exists (atomically where the file
 *  system can). */
void moveInto(const fs::path& from, const fs::path& to, bool replace, const std::string& flag)
{
    int rc = 0;
    if (replace)
        rc = std::rename(from.c_str(), to.c_str());
    else
    {
        rc = renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE);
        if (rc != 0 && (errno == EINVAL || errno == ENOSYS))
        {
            // A file system without the no-replace rename: check, then rename.
            std::error_code ec;
            if (fs::symlink_status(to, ec).type() != fs::file_type::not_found)
            {
                errno = EEXIST;
                rc = -1;
            }
            else
                rc = std::rename(from.c_str(), to.c_str());
        }
    }
    if (rc == 0) return;
    if (errno == EEXIST || errno == ENOTEMPTY) throwAppeared(to, flag);
    throw std::runtime_error("cannot move '" + from.string() + "' to '" + to.string() +
                             "': " + std::strerror(errno));
}

bool existsOrIsALink(const fs::path& p)
{
    std::error_code ec;
    return fs::symlink_status(p, ec).type() != fs::file_type::not_found;
}

void refuseDanglingLink(const fs::path& p, const std::string& flag)
{
    std::error_code ec;
    if (fs::is_symlink(p, ec) && !fs::exists(p, ec))
        throw std::runtime_error(flag + " '" + p.string() + "' is a symbolic link to '" +
                                 fs::read_symlink(p, ec).string() + "', which does not exist");
}
}  // namespace

StagedFolder::StagedFolder(const std::string& dir, std::vector<std::string> names, bool overwrite,
                           const std::string& flag)
    : dir_(cleanDir(dir)), names_(std::move(names)), overwrite_(overwrite), flag_(flag)
{
    refuseDanglingLink(dir_, "the output folder");
    if (fs::exists(dir_) && !fs::is_directory(dir_))
        throw std::runtime_error("'" + dir_ + "' exists and is not a folder");
    std::error_code ec;
    created_dir_ = fs::create_directories(dir_, ec);
    if (ec || !fs::is_directory(dir_))
        throw std::runtime_error("cannot create folder '" + dir_ + "': " + ec.message());
    if (created_dir_) remove_dir_.emplace(dir_, /*only_if_empty=*/true);
    try
    {
        // One run at a time per output folder: the lock goes with the process, however it ends.
        lock_fd_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (lock_fd_ < 0)
            throw std::runtime_error("cannot open folder '" + dir_ + "': " + std::strerror(errno));
        if (flock(lock_fd_, LOCK_EX | LOCK_NB) != 0)
            throw std::runtime_error(
                "'" + dir_ +
                "' is being written by another run right now; wait for it to end, or write "
                "elsewhere");
        // Staged beside the real folder (not beside a link to it): the moves stay renames.
        const fs::path real = fs::canonical(dir_);
        const std::string stem = "." + real.filename().string() + ".partial-";
        removeStale(real.parent_path(), stem, "");
        removeStale(real, ".old-", "");
        for (const std::string& n : names_) refuseToOverwrite(dir_ + "/" + n, overwrite_, flag_);
        staging_ = (real.parent_path() / (stem + std::to_string(getpid()))).string();
        fs::remove_all(staging_);
        remove_staging_.emplace(staging_);
        makeDirs(staging_);
    }
    catch (...)
    {
        abandon();
        throw;
    }
}

StagedFolder::~StagedFolder() { abandon(); }

void StagedFolder::abandon()
{
    std::error_code ec;
    if (!committed_ && !staging_.empty()) fs::remove_all(staging_, ec);  // nothing left behind
    if (lock_fd_ >= 0) ::close(lock_fd_);
    lock_fd_ = -1;
    if (!committed_ && created_dir_ && fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
    created_dir_ = false;
    remove_staging_.reset();
    remove_dir_.reset();
}

void StagedFolder::commit()
{
    if (!overwrite_)
        for (const std::string& n : names_)
            if (existsOrIsALink(fs::path(staging_) / n) && existsOrIsALink(fs::path(dir_) / n))
                throwAppeared(fs::path(dir_) / n, flag_);
    // The old entries go aside first, then the new ones in; the aside copies are dropped last.
    const fs::path aside = fs::path(dir_) / (".old" + pidSuffix());
    std::error_code ec;
    fs::remove_all(aside, ec);
    makeDirs(aside.string());
    for (const std::string& n : names_)
        if (existsOrIsALink(fs::path(dir_) / n))
            moveInto(fs::path(dir_) / n, aside / n, true, flag_);
    for (const std::string& n : names_)
        if (existsOrIsALink(fs::path(staging_) / n))
            moveInto(fs::path(staging_) / n, fs::path(dir_) / n, overwrite_, flag_);
    committed_ = true;
    fs::remove_all(aside, ec);
    fs::remove_all(staging_, ec);
}

StagedFile::StagedFile(const std::string& file, bool overwrite, const std::string& what)
    : file_(file), overwrite_(overwrite)
{
    const fs::path p(file);
    std::error_code ec;
    if (fs::is_directory(p, ec))
        throw std::runtime_error(what + " '" + file + "' is a folder (a file name was expected)");
    const fs::path parent = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    if (!fs::is_directory(parent, ec))
        throw std::runtime_error(
            what + " '" + file + "': the folder '" + parent.string() +
            (fs::exists(parent, ec) ? "' is not a folder" : "' does not exist"));
    refuseToOverwrite(file_, overwrite, kOverwriteFlag);
    // Beside it, hidden, with the same extension (which may say the format).
    const std::string stem = "." + p.stem().string() + ".partial-";
    removeStale(parent, stem, p.extension().string());
    partial_ = (parent / (stem + std::to_string(getpid()) + p.extension().string())).string();
    remove_partial_.emplace(partial_);
}

StagedFile::~StagedFile()
{
    if (committed_) return;
    std::error_code ec;
    fs::remove(partial_, ec);
}

void StagedFile::commit()
{
    moveInto(partial_, file_, overwrite_, kOverwriteFlag);
    committed_ = true;
}

}  // namespace hif::apps

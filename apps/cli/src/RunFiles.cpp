// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   RunFiles.cpp
 * @brief  Inputs and outputs of a run, compared as real paths.
 */
#include "hif/apps/RunFiles.h"

#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace hif::apps
{
namespace
{
/** The path with every symbolic link of its existing part resolved, absolute, normalized. */
std::string realPath(const std::string& path)
{
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(fs::absolute(path), ec);
    return (ec ? fs::absolute(path).lexically_normal() : p).string();
}

bool samePath(const std::string& a_real, const std::string& b_real)
{
    if (a_real == b_real) return true;
    std::error_code ec;
    return fs::exists(a_real, ec) && fs::exists(b_real, ec) && fs::equivalent(a_real, b_real, ec);
}

/** `inner` lies somewhere below folder `outer` (both real paths). */
bool liesIn(const std::string& inner, const std::string& outer)
{
    return inner.size() > outer.size() + 1 && inner.compare(0, outer.size(), outer) == 0 &&
           (outer.back() == '/' || inner[outer.size()] == '/');
}

/** "'<path>' (<what>)", how an output is named first. */
std::string named(const std::string& what, const std::string& path)
{
    return "'" + path + "' (" + what + ")";
}

/** How the other path of a conflict is named: by what it is, and by its path when the user
 *  wrote it differently (a link, another spelling). */
std::string other(const std::string& what, const std::string& path, const std::string& mine)
{
    return path == mine ? what : what + " '" + path + "'";
}
}  // namespace

void RunFiles::input(const std::string& path, const std::string& what)
{
    inputs_.push_back({path, realPath(path), what, "", false});
}

void RunFiles::inputFolder(const std::string& dir, const std::string& ext, const std::string& what)
{
    inputs_.push_back({dir, realPath(dir), what, ext, true});
}

void RunFiles::inputKittiSequence(const std::string& dir, const std::string& what)
{
    const fs::path d(dir);
    inputFolder((d / "velodyne").string(), ".bin", "the scans of " + what);
    inputFolder((d / "labels").string(), ".label", "the labels of " + what);
    for (const char* f : {"poses.txt", "calib.txt", "times.txt"})
        input((d / f).string(), std::string("the ") + f + " of " + what);
}

void RunFiles::output(const std::string& path, const std::string& what, bool folder)
{
    const std::string real = realPath(path);
    const std::string me = named(what, path);
    const std::string never =
        ": an output is never an input of the same run, with or without "
        "--overwrite";
    for (const Entry& in : inputs_)
    {
        const std::string it = other(in.what, in.path, path);
        if (samePath(real, in.real))
            throw std::runtime_error(me + " is " + (in.folder ? "the folder of " : "") + it +
                                     never);
        if (in.folder && fs::path(real).parent_path().string() == in.real &&
            fs::path(real).extension().string() == in.ext)
            throw std::runtime_error(me + " would be one of the " + in.ext + " files of " +
                                     in.what + " '" + in.path + "'" + never);
        if (folder && liesIn(in.real, real))
            throw std::runtime_error(me + ", a folder this run replaces whole, holds " + in.what +
                                     " '" + in.path + "'" + never);
    }
    for (const Entry& out : outputs_)
    {
        if (samePath(real, out.real))
            throw std::runtime_error(me + " is also " + other(out.what, out.path, path) +
                                     ": two outputs of one run cannot be the same file");
        if ((out.folder && liesIn(real, out.real)) || (folder && liesIn(out.real, real)))
            throw std::runtime_error(me + " and " + out.what + " '" + out.path +
                                     "' lie one inside the other: two outputs of one run cannot");
    }
    outputs_.push_back({path, real, what, "", folder});
}

}  // namespace hif::apps

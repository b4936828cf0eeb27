// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CloudWriter.cpp
 * @brief  Streaming binary PLY/PCD writer.
 */
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <iomanip>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <utility>

#include "hif/io/CloudFiles.h"
#include "hif/io/FileError.h"

namespace hif::io
{
namespace
{
bool endsWith(const std::string& s, const std::string& suffix)
{
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/** An open file descriptor, closed when it goes. */
struct Fd
{
    int fd = -1;
    ~Fd()
    {
        if (fd >= 0) ::close(fd);
    }
};

void writeAll(int fd, const char* p, std::size_t n, const std::string& file)
{
    while (n > 0)
    {
        const ssize_t w = ::write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0)
            throwFileError(
                file, std::string("could not be written (disk full?): ") + std::strerror(errno));
        p += w;
        n -= static_cast<std::size_t>(w);
    }
}

/** Writes `header`, then `length` bytes of file `from` starting at `offset`, into `file`: the
 *  copy done by the kernel (copy_file_range) where it can, else through a large buffer. */
void writeHeaderAndCopy(const std::string& file, const std::string& header, const std::string& from,
                        off_t offset, std::size_t length)
{
    Fd in{::open(from.c_str(), O_RDONLY | O_CLOEXEC)};
    if (in.fd < 0) throwFileError(from, std::string("cannot be read: ") + std::strerror(errno));
    Fd out{::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644)};
    if (out.fd < 0) throwFileError(file, std::string("cannot be created: ") + std::strerror(errno));
    writeAll(out.fd, header.data(), header.size(), file);
    bool kernel_copy = true;
    std::vector<char> buf;
    while (length > 0)
    {
        ssize_t n = 0;
        if (kernel_copy)
        {
            n = ::copy_file_range(in.fd, &offset, out.fd, nullptr, length, 0);
            // Not supported here (another file system, an old kernel): copy through memory.
            if (n < 0 &&
                (errno == EXDEV || errno == ENOSYS || errno == EINVAL || errno == EOPNOTSUPP))
            {
                kernel_copy = false;
                continue;
            }
        }
        else
        {
            buf.resize(std::min(length, std::size_t{1} << 22));
            n = ::pread(in.fd, buf.data(), buf.size(), offset);
            if (n > 0)
            {
                writeAll(out.fd, buf.data(), static_cast<std::size_t>(n), file);
                offset += n;
            }
        }
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
            throwFileError(file, "could not be written (" + from + " ended early or " +
                                     std::strerror(errno) + ")");
        length -= static_cast<std::size_t>(n);
    }
    if (::close(std::exchange(out.fd, -1)) != 0)
        throwFileError(file,
                       std::string("could not be written (disk full?): ") + std::strerror(errno));
}
}  // namespace

/** The body's writes, on a thread of their own: the caller fills one buffer while the other is
 *  written (copying it into the kernel costs as much as making the points). One write at a
 *  time; its failure is kept for the caller's next flush() or wait(). */
class CloudWriter::BackgroundWrites
{
public:
    explicit BackgroundWrites(std::size_t buffer_bytes)
        : buffer_(buffer_bytes), thread_([this] { loop(); })
    {
    }
    ~BackgroundWrites()
    {
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        cv_.notify_all();
        thread_.join();
    }
    BackgroundWrites(const BackgroundWrites&) = delete;
    BackgroundWrites& operator=(const BackgroundWrites&) = delete;

    /** Writes the first `bytes` of `buffer` to `file`, and gives `buffer` an empty one of the
     *  same size (once the write before is done). */
    void write(std::FILE* file, std::vector<char>& buffer, std::size_t bytes)
    {
        std::unique_lock<std::mutex> lock(mutex_);
        cv_.wait(lock, [this] { return !pending_; });
        buffer_.swap(buffer);
        file_ = file;
        bytes_ = bytes;
        pending_ = true;
        lock.unlock();
        cv_.notify_all();
    }
    /** Why a write failed, if one did (said once); with `wait`, once the write under way is
     *  done. */
    [[nodiscard]] std::string failure(bool wait)
    {
        std::unique_lock<std::mutex> lock(mutex_);
        if (wait) cv_.wait(lock, [this] { return !pending_; });
        return std::exchange(error_, std::string());
    }

private:
    void loop()
    {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;)
        {
            cv_.wait(lock, [this] { return pending_ || stop_; });
            if (!pending_) return;  // stopped
            lock.unlock();
            const bool ok = std::fwrite(buffer_.data(), 1, bytes_, file_) == bytes_;
            const int err = errno;
            lock.lock();
            if (!ok && error_.empty()) error_ = std::strerror(err);
            pending_ = false;
            cv_.notify_all();
        }
    }

    std::vector<char> buffer_;  ///< being written, or the spare
    std::FILE* file_ = nullptr;
    std::size_t bytes_ = 0;
    bool pending_ = false, stop_ = false;
    std::string error_;
    std::mutex mutex_;
    std::condition_variable cv_;
    std::thread thread_;
};

CloudWriter::CloudWriter(std::vector<std::string> files, PointFields fields)
    : files_(std::move(files))
{
    if (files_.empty()) throw std::invalid_argument("CloudWriter: no output file");
    for (const std::string& file : files_)
        if (!endsWith(file, ".pcd") && !endsWith(file, ".ply"))
            throwFileError(file, "has an unknown point-cloud extension (use .ply or .pcd)");
    setFields(fields);
    buf_.resize(kBufferBytes);
}

void CloudWriter::setFields(const PointFields& fields)
{
    if (count_ > 0 || closed_)
        throw std::logic_error("CloudWriter::setFields() after the first point");
    for (const std::string& file : files_)
        if (fields.colour && !endsWith(file, ".ply"))
            throwFileError(file, "cannot hold coloured points (write a .ply)");
    fields_ = fields;
}

CloudWriter::~CloudWriter()
{
    writes_.reset();  // a write under way ends first
    if (f_)
    {
        std::fclose(f_);
        std::remove(body_file_.c_str());
    }
}

void CloudWriter::expectCount(std::size_t count)
{
    if (count_ > 0 || closed_)
        throw std::logic_error("CloudWriter::expectCount() after the first point");
    expected_ = count;
}

void CloudWriter::open()
{
    // With a count expected, the body goes straight into the first file after the room its
    // header will take; otherwise into "<first file>.part", copied behind each header.
    if (expected_)
    {
        body_file_ = files_.front();
        body_offset_ = header(files_.front(), *expected_).size();
    }
    else
    {
        body_file_ = files_.front() + ".part";
        body_offset_ = 0;
    }
    f_ = std::fopen(body_file_.c_str(), "w+b");  // read back if the coordinates widen
    if (!f_) throwFileError(body_file_, std::string("cannot be created: ") + std::strerror(errno));
    if (body_offset_ > 0 && std::fseek(f_, static_cast<long>(body_offset_), SEEK_SET) != 0)
        throwFileError(body_file_, std::string("cannot be written: ") + std::strerror(errno));
}

void CloudWriter::flush()
{
    if (!f_) open();
    if (used_ > 0)
    {
        if (!writes_) writes_ = std::make_unique<BackgroundWrites>(kBufferBytes);
        writes_->write(f_, buf_, used_);
        used_ = 0;
    }
    throwIfAWriteFailed(false);
}

void CloudWriter::throwIfAWriteFailed(bool wait)
{
    if (!writes_) return;
    const std::string error = writes_->failure(wait);
    if (!error.empty()) throwFileError(body_file_, "could not be written (disk full?): " + error);
}

std::string CloudWriter::viewpointText() const
{
    if (viewpoint_.matrix() == Eigen::Matrix4d::Identity()) return "0 0 0 1 0 0 0";
    const Eigen::Quaterniond q(viewpoint_.linear());
    const Eigen::Vector3d& t = viewpoint_.translation();
    std::ostringstream s;
    s << std::setprecision(17) << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.w() << ' '
      << q.x() << ' ' << q.y() << ' ' << q.z();
    return s.str();
}

std::size_t CloudWriter::recordBytes() const { return (double_ ? 24 : 12) + fields_.tailBytes(); }

std::string CloudWriter::header(const std::string& file, std::size_t count) const
{
    const std::string n = std::to_string(count);
    const std::string ply_type = double_ ? "double" : "float";
    // The fields after x y z: (PLY type, name, PCD size, PCD type).
    struct Field
    {
        const char *ply, *name, *size, *type;
    };
    std::vector<Field> tail;
    if (fields_.intensity) tail.push_back({"float", "intensity", "4", "F"});
    if (fields_.colour)
        for (const char* c : {"red", "green", "blue"}) tail.push_back({"uchar", c, "1", "U"});
    if (fields_.label) tail.push_back({"uchar", "class", "1", "U"});
    if (fields_.scan) tail.push_back({"uint", "scan", "4", "U"});
    if (fields_.time) tail.push_back({"double", "time", "8", "F"});
    if (fields_.points) tail.push_back({"uint", "points", "4", "U"});
    if (endsWith(file, ".ply"))
    {
        std::string h =
            "ply\nformat binary_little_endian 1.0\ncomment written by hif\nelement vertex " + n +
            "\nproperty " + ply_type + " x\nproperty " + ply_type + " y\nproperty " + ply_type +
            " z\n";
        for (const Field& f : tail) h += std::string("property ") + f.ply + " " + f.name + "\n";
        return h + "end_header\n";
    }
    std::string names = "x y z", sizes = double_ ? "8 8 8" : "4 4 4", types = "F F F",
                counts = "1 1 1";
    for (const Field& f : tail)
    {
        names += std::string(" ") + f.name;
        sizes += std::string(" ") + f.size;
        types += std::string(" ") + f.type;
        counts += " 1";
    }
    return "# .PCD v0.7 - Point Cloud Data file format (written by hif)\nVERSION 0.7\nFIELDS " +
           names + "\nSIZE " + sizes + "\nTYPE " + types + "\nCOUNT " + counts + "\nWIDTH " + n +
           "\nHEIGHT 1\nVIEWPOINT " + viewpointText() + "\nPOINTS " + n + "\nDATA binary\n";
}

void CloudWriter::promote()
{
    // The records so far, read back (they are in buf_, or in the body file and buf_), widened,
    // and written again where a float64 body starts; rare (once a file, at most) and linear.
    std::vector<char> old;
    if (f_)
    {
        flush();
        throwIfAWriteFailed(true);
        const std::size_t bytes = count_ * recordBytes();
        old.resize(bytes);
        if (std::fflush(f_) != 0 ||
            std::fseek(f_, static_cast<long>(body_offset_), SEEK_SET) != 0 ||
            std::fread(old.data(), 1, bytes, f_) != bytes)
            throwFileError(body_file_,
                           std::string("could not be read back: ") + std::strerror(errno));
        std::fclose(std::exchange(f_, nullptr));
        std::remove(body_file_.c_str());
    }
    else
        old.assign(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(used_));
    const std::size_t n = count_, rest = fields_.tailBytes();
    const std::size_t from = 12 + rest;
    double_ = true;
    count_ = 0;
    used_ = 0;
    for (std::size_t k = 0; k < n; ++k)
    {
        float xyz[3];
        std::memcpy(xyz, old.data() + k * from, 12);
        char v[24 + kMaxTail];
        const double wide[3] = {xyz[0], xyz[1], xyz[2]};
        std::memcpy(v, wide, 24);
        std::memcpy(v + 24, old.data() + k * from + 12, rest);
        append(v, 24 + rest);
    }
}

void CloudWriter::close()
{
    if (closed_) return;
    flush();  // with no point, the files still get their headers
    throwIfAWriteFailed(true);
    writes_.reset();
    const bool failed = std::fclose(f_) != 0;
    f_ = nullptr;
    closed_ = true;
    if (failed)
        throwFileError(body_file_,
                       std::string("could not be closed (disk full?): ") + std::strerror(errno));

    const std::size_t bytes = count_ * recordBytes();
    std::size_t first = 0;  // the files still to write
    if (expected_)
    {
        const std::string h = header(files_.front(), count_);
        if (h.size() == body_offset_)
        {
            // The room left was right: the header goes in front of the body, and the first file
            // is complete.
            Fd fd{::open(body_file_.c_str(), O_WRONLY | O_CLOEXEC)};
            if (fd.fd < 0 || ::pwrite(fd.fd, h.data(), h.size(), 0) != ssize_t(h.size()) ||
                ::close(std::exchange(fd.fd, -1)) != 0)
                throwFileError(body_file_,
                               std::string("could not be written: ") + std::strerror(errno));
            first = 1;
        }
        else
        {
            // Another count of digits than expected: the body is moved behind the right header.
            const std::string part = files_.front() + ".part";
            if (std::rename(body_file_.c_str(), part.c_str()) != 0)
                throwFileError(body_file_,
                               std::string("cannot be renamed: ") + std::strerror(errno));
            body_file_ = part;
        }
    }
    for (std::size_t k = first; k < files_.size(); ++k)
        writeHeaderAndCopy(files_[k], header(files_[k], count_), body_file_,
                           static_cast<off_t>(body_offset_), bytes);
    if (first == 0) std::remove(body_file_.c_str());
}

}  // namespace hif::io

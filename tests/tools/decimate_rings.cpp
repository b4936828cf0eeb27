// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   decimate_rings.cpp
 * @brief  Test tool: a copy of a KITTI sequence with every k-th ring of each scan only (and the
 *         labels of those points), to stand for a sparser LiDAR: every 2nd of the HDL-64E's
 *         rings is about an HDL-32E's spacing, every 4th a VLP-16's. The rings kept are those
 *         whose number (0 the first of a scan) is `phase` modulo k (default 0).
 *
 *   hif_decimate_rings <sequence folder> <output folder> <k> [phase]
 */
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"
#include "hif/io/Rings.h"

namespace fs = std::filesystem;

int main(int argc, char** argv)
{
    try
    {
        if (argc != 4 && argc != 5)
            throw std::runtime_error("usage: hif_decimate_rings <sequence> <output> <k> [phase]");
        const hif::io::KittiSequence seq(argv[1]);
        const fs::path out(argv[2]);
        // A whole number, or -1 (refused below).
        const auto number = [](const char* text)
        {
            char* end = nullptr;
            const long v = std::strtol(text, &end, 10);
            return end != text && *end == '\0' && v >= 0 && v <= 64 ? static_cast<int>(v) : -1;
        };
        const int k = number(argv[3]);
        if (k < 1) throw std::runtime_error("k must be a whole number in [1, 64]");
        const int phase = argc == 5 ? number(argv[4]) : 0;
        if (phase < 0 || phase >= k)
            throw std::runtime_error("phase must be a whole number in [0, k)");
        if (fs::exists(out)) throw std::runtime_error("'" + out.string() + "' exists");
        fs::create_directories(out / "velodyne");
        if (seq.hasLabels()) fs::create_directories(out / "labels");
        for (const char* f : {"calib.txt", "poses.txt", "times.txt"})
            fs::copy_file(fs::path(seq.dir()) / f, out / f);
        std::size_t kept = 0, total = 0;
        for (std::size_t i = 0; i < seq.size(); ++i)
        {
            const hif::io::Cloud scan = seq.readScan(i);
            const std::vector<uint32_t> ring = hif::io::ringOfEachPoint(scan);
            const bool labelled = seq.hasLabels() && fs::exists(seq.labelFile(i));
            const std::vector<uint32_t> labels =
                labelled ? hif::io::readLabels(seq.labelFile(i)) : std::vector<uint32_t>{};
            if (labelled && labels.size() != scan.size())
                throw std::runtime_error("'" + seq.labelFile(i) + "' does not match its scan");
            std::vector<float> pts;
            std::vector<uint32_t> lab;
            for (std::size_t p = 0; p < scan.size(); ++p)
            {
                if (ring[p] % static_cast<uint32_t>(k) != static_cast<uint32_t>(phase)) continue;
                pts.insert(pts.end(), {scan.x[p], scan.y[p], scan.z[p], scan.intensity[p]});
                if (labelled) lab.push_back(labels[p]);
            }
            kept += pts.size() / 4;
            total += scan.size();
            const std::string name = hif::io::frameName(i);
            std::ofstream bin(out / "velodyne" / (name + ".bin"), std::ios::binary);
            bin.write(reinterpret_cast<const char*>(pts.data()),
                      static_cast<std::streamsize>(pts.size() * sizeof(float)));
            bin.close();
            if (!bin)
                throw std::runtime_error("cannot write '" + (out / "velodyne").string() + "'");
            if (labelled) hif::io::writeLabels((out / "labels" / (name + ".label")).string(), lab);
        }
        std::cout << "[hif_decimate_rings] every " << k << " ring(s) from ring " << phase << " of "
                  << seq.size() << " scans: " << kept << " of " << total << " points\n";
        return 0;
    }
    catch (const std::exception& e)
    {
        std::cerr << "[hif_decimate_rings] error: " << e.what() << "\n";
        return 1;
    }
}

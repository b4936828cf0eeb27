// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Evaluate.h
 * @brief  hif-eval's work as a job: point-level scores of moving-object predictions against
 *         SemanticKITTI labels, with the protocol of the dynamic-points-removal benchmark
 *         (labels 0 and 1 excluded, classes 252-259 dynamic): SA, DA, AA, HA per scan and in
 *         total, DA per moving class, and SA and DA per range band when the scans are given.
 *         The app is its command line; the tests run the job in process.
 */
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <utility>

#include "hif/io/Breakdown.h"

namespace hif::jobs
{
/** What to score and what to write; the flags of hif-eval, which the job's messages name. */
struct EvaluateOptions
{
    std::string labels;                      ///< --labels: the ground truth folder
    std::string predictions;                 ///< --predictions
    std::string scans;                       ///< --scans, for ranges and pictures (optional)
    double ego_radius = 3.0;                 ///< --ego-radius, metres
    std::optional<std::string> png;          ///< --png
    std::optional<std::string> classes_ply;  ///< --classes-ply
    std::optional<std::string> json;         ///< --json
    bool overwrite = false;                  ///< --overwrite
    bool per_scan = true;                    ///< a line per scan (--quiet: false)
    bool objects = false;                    ///< --objects: a line per moving object
};

/** What was scored. */
struct EvaluateResult
{
    std::size_t scans = 0;  ///< scored: predictions with a label file
    hif::io::Scores total;
};

/** Checks the folders and the files to write (never an input, never replaced unasked), scores
 *  every prediction that has a label file, prints the tables on `log` and writes what was asked
 *  for. Throws std::runtime_error naming the flag or the file and the problem. */
class Evaluate
{
public:
    /** What the job's lines and its app's errors start with. */
    static constexpr const char* kTag = "[hif-eval]";

    explicit Evaluate(EvaluateOptions options) : options_(std::move(options)) {}
    EvaluateResult run(std::ostream& log) const;

private:
    EvaluateOptions options_;
};

}  // namespace hif::jobs

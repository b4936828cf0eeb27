// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   hif-eval/main.cpp
 * @brief  hif-eval: point-level scores of moving-object predictions against SemanticKITTI
 *         labels; the work is hif::jobs::Evaluate (apps/jobs), its flags
 *         hif::jobs::EvaluateCommandLine.
 */
#include "hif/apps/Cli.h"
#include "hif/jobs/EvaluateCommandLine.h"

int main(int argc, char** argv)
{
    return hif::apps::cliMain<hif::jobs::EvaluateCommandLine>(argc, argv);
}

#pragma once
// `geohybrid biaxial FILE.prm`: a REDF sample sheared in biaxial compression at several
// confining stresses, and the macroscopic parameters read from the curves. The campaign itself,
// which `calibrate` shares: biaxial_input.h (its parameters) and biaxial_campaign.h (its run).
#include "apps/biaxial_campaign.h"
#include "apps/biaxial_input.h"

#include <string>

namespace geohybrid::apps
{
class Summary; // run_directory.h

int run_biaxial_command(const std::string &input_file, bool resume);

/// Writes the macroscopic parameters of a campaign into a summary, under the keys of the
/// biaxial summary contract (peak_friction_angle_deg, ..., porosity); shared with `calibrate`.
void set_biaxial_results(Summary &summary, const dem::BiaxialParameters &parameters, double porosity);
} // namespace geohybrid::apps

#pragma once
// A biaxial campaign run (`geohybrid biaxial`, and each iteration of `geohybrid calibrate`): one
// REDF sample, made at the lowest confining stress or read from the sample file, and one test per
// confining stress on a copy of it consolidated to that stress. The tests run side by side.
#include "apps/biaxial_input.h"
#include "dem/laboratory/sample_file.h"

#include <optional>
#include <vector>

namespace geohybrid::apps
{
/// The sample held by the campaign's sample file, if there is one. Throws, naming the parameter
/// and the file, if the file cannot be read or holds a sample made with other settings: its tests
/// would not be those of this input.
std::optional<dem::StoredSample> read_campaign_sample(const BiaxialCampaign &campaign);

/// Runs the campaign: one REDF sample, made at the lowest confining stress (or read from the
/// sample file), and one test per confining stress on a copy of it consolidated to that stress.
/// The tests run concurrently when there are threads for it; the curves do not depend on how.
std::vector<dem::BiaxialCurve> run_biaxial_campaign(const BiaxialCampaign &campaign, bool show_progress);

/// Mean initial porosity of the samples of a campaign.
double mean_initial_porosity(const std::vector<dem::BiaxialCurve> &curves);
} // namespace geohybrid::apps

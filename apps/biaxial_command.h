#pragma once
// `geohybrid biaxial FILE.prm`: a REDF sample sheared in biaxial compression at several
// confining stresses, and the macroscopic parameters read from the curves.
#include "dem/laboratory/biaxial_test.h"
#include "dem/laboratory/sample_preparation.h"

#include <deal.II/base/parameter_handler.h>

#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::apps
{
class Summary; // run_directory.h

void declare_biaxial_parameters(dealii::ParameterHandler &prm);
int run_biaxial_command(const std::string &input_file, bool resume);

/// What a biaxial campaign needs, read from the parameters (shared with `calibrate`).
struct BiaxialCampaign
{
  dem::RedfSpec sample;                ///< target_stress: the campaign uses the lowest confining stress
  dem::BiaxialSpec test;               ///< confining_stress is set per confinement
  std::vector<double> confining_stresses;
  /// The REDF sample's file: read if it exists (it must hold the sample `sample` describes),
  /// written after making the sample otherwise; empty = the sample is not kept.
  std::filesystem::path sample_file;
};
/// Reads the Sample, Particle contact, Wall contact and Test subsections. Throws naming `where`.
BiaxialCampaign parse_biaxial_campaign(dealii::ParameterHandler &prm, const std::string &where);

/// Mean initial porosity of the samples of a campaign.
double mean_initial_porosity(const std::vector<dem::BiaxialCurve> &curves);

/// Writes the macroscopic parameters of a campaign into a summary, under the keys of the
/// biaxial summary contract (peak_friction_angle_deg, ..., porosity); shared with `calibrate`.
void set_biaxial_results(Summary &summary, const dem::BiaxialParameters &parameters, double porosity);

/// Runs the campaign: one REDF sample, made at the lowest confining stress (or read from the
/// sample file), and one test per confining stress on a copy of it consolidated to that stress.
/// The tests run concurrently when there are threads for it; the curves do not depend on how.
std::vector<dem::BiaxialCurve> run_biaxial_campaign(const BiaxialCampaign &campaign, bool show_progress);
} // namespace geohybrid::apps

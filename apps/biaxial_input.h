#pragma once
// The input of a biaxial campaign, which `geohybrid biaxial` runs once and `geohybrid calibrate`
// once per iteration: the sample (REDF), the particles' and the walls' contacts, the confining
// stresses and the test.
#include "dem/laboratory/biaxial_test.h"
#include "dem/laboratory/sample_preparation.h"

#include <deal.II/base/parameter_handler.h>

#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::apps
{
/// Declares the entries of `geohybrid biaxial` (`calibrate` adds its own).
void declare_biaxial_parameters(dealii::ParameterHandler &prm);

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
} // namespace geohybrid::apps

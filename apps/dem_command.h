#pragma once
// `geohybrid dem FILE.prm`: the general DEM scene runner.
#include <deal.II/base/parameter_handler.h>

#include <string>

namespace geohybrid::apps
{
void declare_dem_parameters(dealii::ParameterHandler &prm);
/// Parses `input_file` (.prm or .json) and runs the scene it describes. Returns the exit code.
int run_dem_command(const std::string &input_file);
} // namespace geohybrid::apps

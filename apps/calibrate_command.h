#pragma once
// `geohybrid calibrate FILE.prm`: contact micro-parameters (friction, kn, ks/kn) adjusted by
// repeated biaxial campaigns until the sample's peak friction angle, Young modulus and,
// optionally, Poisson ratio meet their targets; the result is written as a .prm fragment.
#include <deal.II/base/parameter_handler.h>

#include <string>

namespace geohybrid::apps
{
void declare_calibrate_parameters(dealii::ParameterHandler &prm);
int run_calibrate_command(const std::string &input_file, bool resume);
} // namespace geohybrid::apps

#pragma once
// `geohybrid dem FILE.prm [--resume]`: the general DEM scene runner.
#include <deal.II/base/parameter_handler.h>

#include <string>

namespace geohybrid::apps
{
void declare_dem_parameters(dealii::ParameterHandler &prm);
/// Parses `input_file` (.prm or .json) and runs the scene it describes. Returns the exit code.
///
/// With `resume`, the run continues from OUTPUT/checkpoint.h5 instead of starting at t = 0: the
/// system is built and checked from the input as usual, then takes the checkpoint's state (the
/// walls included: their position, velocity, control and contact law come from the checkpoint,
/// while the particle contact law and the Simulation settings come from the input, so that e.g.
/// the end time can be raised). The output files are continued as a straight run to the end time
/// would have written them: time_series.csv and particle_history.csv keep their rows up to the
/// checkpoint (later ones, written before a crash, are dropped) and particles.h5/.xdmf its
/// snapshots up to the checkpoint; a row or snapshot that an earlier run wrote only because it
/// ended at the checkpoint time, off the output interval, is dropped too. A missing CSV or .h5
/// file is started anew. Throws if the checkpoint is missing, damaged or does not fit the input,
/// or if the end time is before the checkpoint time, before any output file is touched.
int run_dem_command(const std::string &input_file, bool resume);
} // namespace geohybrid::apps

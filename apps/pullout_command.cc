// `geohybrid pullout`: the pull-out test of the reference paper (sections 4.3-4.5), in the mode
// the input asks for. The command reads the input once (pullout_input.cc: the entries and their
// checks) and hands it to its mode: dem, the tank filled with particles (pullout_dem_mode.cc);
// fem, the same test with a deal.II continuum for the soil (pullout_fem_mode.cc); hybrid,
// particles round the sheet and the continuum elsewhere (pullout_hybrid_mode.cc). All write the
// same files through apps/pullout_output.h, plus parameters.prm and summary.json (written last).
// In dem mode, also the soil's fields at 'Output/field outputs at' (pullout_field_output.h):
// pullout_fields.h5/.xdmf, grain_displacements_u*mm.csv/.png, force_network_u*mm.csv/.png,
// surface_uplift.csv/.png.
//
// Every mode's summary.json holds `parameters_hash`, the hash of the resolved input without its
// run-control entries (apps/parameters_hash.h); `--print-parameters-hash` (check_pullout_input)
// reads and checks an input as a run does, each mode stopping before its first file.
#include "pullout_command.h"

#include "parameters_hash.h"
#include "pullout_dem_mode.h"
#include "pullout_fem_mode.h"
#include "pullout_hybrid_mode.h"
#include "pullout_input.h"
#include "run_directory.h"

#include <stdexcept>

namespace geohybrid::apps
{
using dealii::ParameterHandler;

namespace
{
/// The input of FILE with `overrides`, read and checked as every run reads it, then run; with
/// `hash`, each mode stops before its first file is written, and *hash gets the input's hash.
int read_and_run(const std::string &input_file, bool resume, MPI_Comm communicator, const ParameterOverrides &overrides,
                 std::string *hash)
{
  ParameterHandler prm;
  declare_pullout_parameters(prm);
  parse_input_file(prm, input_file);
  for (const auto &[path, value] : overrides)
    set_parameter(prm, path, value);
  const std::string where = "input file '" + input_file + "'";
  const std::string mode = prm.get("mode");
  if (resume && mode == "fem")
    throw std::invalid_argument(where + ": --resume continues a run of 'mode' = dem or hybrid only (fem mode writes "
                                "no checkpoints): run it again without --resume");
  // Hybrid mode fills its particle box from the whole tank's Filling: checked as in dem mode.
  const PullOutInput in = parse_pullout(prm, where, mode != "fem");
  const bool check_only = hash != nullptr;
  const int status = mode == "hybrid" ? run_pullout_hybrid_mode(prm, in, where, resume, communicator, check_only)
                     : mode == "dem"  ? run_pullout_dem_mode(prm, in, where, resume, communicator, check_only)
                                      : run_pullout_fem_mode(prm, in, where, communicator, check_only);
  if (hash)
    *hash = pullout_parameters_hash(prm);
  return status;
}
} // namespace

int run_pullout_command(const std::string &input_file, bool resume, const ParameterOverrides &overrides)
{
  return run_pullout_command(input_file, resume, MPI_COMM_WORLD, overrides);
}

int run_pullout_command(const std::string &input_file, bool resume, MPI_Comm communicator,
                        const ParameterOverrides &overrides)
{
  return read_and_run(input_file, resume, communicator, overrides, nullptr);
}

std::string check_pullout_input(const std::string &input_file, MPI_Comm communicator, const ParameterOverrides &overrides)
{
  std::string hash;
  read_and_run(input_file, false, communicator, overrides, &hash);
  return hash;
}
} // namespace geohybrid::apps

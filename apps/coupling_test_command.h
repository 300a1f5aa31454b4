#pragma once
// `geohybrid coupling-test FILE.prm` (issue 6): the coupling's benchmarks for one method, so that
// users compare the methods with measured figures. It runs the patch test (ghost forces under a
// uniform strain), a long wave through the band or the interface (the energy reflected) and an
// undamped coupled run (the energy drift), all from apps/coupling_benchmarks/coupling_benchmarks.h (methods 1
// and 2 on the overlapping patch, method 3 on a lattice standing on the continuum), and writes summary.json,
// parameters.prm, energy_history.csv and wave_reflection.csv.
#include "apps/coupling_benchmarks/coupling_benchmarks.h"
#include "apps/coupling_benchmarks/standing_lattice.h"

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace geohybrid::apps
{
void declare_coupling_test_parameters(dealii::ParameterHandler &prm);

/// What the input file asks for, read and checked.
struct CouplingTestInput
{
  std::string output_directory;
  std::string method_name; ///< coupling::name_of(method), whichever spelling the input used
  coupling::CouplingMethod method;
  coupling::benchmarks::PatchGeometry patch; ///< of the patch test and the energy run
  coupling::benchmarks::PlaneStrain strain;        ///< as the input gives it
  /// What the patch test applies: `strain`, with its shear left out for the non-overlapping
  /// interface (its set-up cannot load the disc-edge tangential springs; coupling/README.md).
  coupling::benchmarks::PlaneStrain patch_strain;
  /// Methods 1 and 2: the patch test along the lattice's rows, where the weights are exact
  /// (coupling_benchmarks.h): `strain` scaled to 'strain size along the rows', on the
  /// commensurate layout nearest the input's band width and cell size.
  coupling::benchmarks::PlaneStrain row_patch_strain;
  coupling::benchmarks::RowPatchLayout row_patch_layout;
  coupling::benchmarks::StripSpec strip;     ///< of the wave
  unsigned int n_energy_steps = 10000;
  /// Method 1: the wave and the energy run again with the continuum at each of these particle
  /// steps (multi-rate, coupling/coupled_stepper.h), the particles at the lockstep's step over it.
  std::vector<unsigned int> continuum_step_ratios;
};

/// Reads the declared entries of `prm` (already parsed) and checks what the patterns cannot.
/// Throws std::invalid_argument naming `where` (the input file) and the entry.
CouplingTestInput parse_coupling_test(dealii::ParameterHandler &prm, const std::string &where);

/// Parses `input_file`, runs the three benchmarks, then (only if all of them ran) writes the
/// output directory. `resume` is refused: the run has no checkpoint (it lasts seconds).
int run_coupling_test_command(const std::string &input_file, bool resume);
} // namespace geohybrid::apps

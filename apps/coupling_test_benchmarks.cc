// `geohybrid coupling-test`'s three benchmarks for the chosen method, and what each figure means
// for it (coupling_test_benchmarks.h).
#include "coupling_test_benchmarks.h"

#include <type_traits>
#include <variant>

namespace geohybrid::apps
{
namespace bench = coupling::benchmarks;

namespace
{
/// Methods 1 and 2: the overlapping patch and the strip with a band (coupling_benchmarks.h).
BenchmarkFigures band_figures(const CouplingTestInput &in, const BenchmarkRunning &running)
{
  BenchmarkFigures f;
  running("patch test", [&] {
    const bench::PatchTestResult patch = bench::patch_test(in.method, in.patch_strain, in.patch);
    f.ghost_discs = patch.ghost.particles_outside_band;
    f.ghost_nodes = patch.ghost.continuum_nodes;
    f.n_particles = patch.n_particles;
    f.n_cells = patch.n_cells;
  });
  running("patch test along the rows", [&] {
    f.row_patch = bench::row_patch_test(in.method, in.row_patch_strain, bench::PatchContinuumStress::lattice, in.patch,
                                        in.row_patch_layout);
  });
  running("wave", [&] { f.wave = bench::strip_crossing(in.method, in.strip, in.patch); });
  running("energy run", [&] { f.energy = bench::energy_record(in.method, in.n_energy_steps, 0.0, in.patch); });
  for (const unsigned int ratio : in.continuum_step_ratios)
    running("multi-rate wave and energy run", [&] {
      BenchmarkFigures::MultiRateFigures m;
      m.ratio = ratio;
      bench::StripSpec strip = in.strip;
      strip.continuum_step_ratio = ratio;
      m.wave = bench::strip_crossing(in.method, strip, in.patch);
      m.energy = bench::energy_record(in.method, in.n_energy_steps, f.energy.time_step / ratio, in.patch,
                                      coupling::MultiRate{ratio});
      f.multi_rate.push_back(m);
    });
  f.ghost_definition =
    "patch test along the lattice's rows (the band's normal +y; cells commensurate with the lattice, the band's edges "
    "on cell sides: the layout where the energy weights are exact, coupling_benchmarks.h) under the uniform strain "
    "row_patch_strain_*, the continuum carrying the strained lattice's own stress on the mesh strained with it: the "
    "largest force on an interior untied disc (relative to |sigma| d) or residual at an interior continuum node, "
    "f_ext - f_int + sum_p N_I(X_p) F_p (relative to |sigma| times the cell height). Under shear the band's edge row "
    "is left a moment, row_patch_disc_moment_relative (relative to |sigma| d^2). The same measure across the rows "
    "(the band's normal +x, the closed-form moduli, strain patch_strain_*) is ghost_force_across_rows_relative "
    "(ghost_force_untied_discs_relative, ghost_force_continuum_nodes_relative): a quadrature error of order d / w, "
    "not removable with Q1 cells on the hexagonal lattice (coupling/README.md)";
  f.wave_definition =
    "a Gaussian velocity pulse crossing the band of a 6-row strip: the energy of the difference from a run of the "
    "particles alone (no band), over the particle-only region's discs once the pulse is half the strip length into "
    "the continuum, over the incident (right-going, half the initial) energy";
  f.energy_definition =
    "undamped coupled run of the patch, a pulse crossing the band: mean of (E(t) - E(0)) / E(0) over the last "
    "quarter of the steps minus its mean over the first quarter, sampled every 10 steps";
  return f;
}

/// Method 3: the lattice standing on the continuum (standing_lattice.h, interface_benchmark.cc).
BenchmarkFigures interface_figures(const coupling::InterfaceCoupling &interface, const CouplingTestInput &in,
                                   const BenchmarkRunning &running)
{
  BenchmarkFigures f;
  running("patch test", [&] {
    const bench::InterfacePatchTestResult patch = bench::interface_patch_test(interface, in.patch_strain, in.patch);
    f.ghost_discs = patch.bottom_discs;
    f.ghost_nodes = patch.interface_nodes;
    f.n_particles = patch.n_particles;
    f.n_cells = patch.n_cells;
  });
  running("wave", [&] { f.wave = bench::interface_strip_crossing(interface, in.strip, in.patch); });
  running("energy run",
          [&] { f.energy = bench::interface_energy_record(interface, in.strip, in.n_energy_steps, 0.0, in.patch); });
  f.ghost_definition =
    "patch test of 14 x 9 discs standing on 14 x 6 cells of one spacing under the uniform strain patch_strain_* (the "
    "input's eps_xx and eps_yy; its eps_xy left out: a disc-edge contact formed at the strained state starts with an "
    "unloaded tangential spring): the largest force on a bottom-row disc or residual f_ext - f_int at an interface "
    "node, more than 1.5 spacings from the free sides, relative to |sigma| d. With the matched interface springs "
    "it is lambda eps_xx / |sigma| in closed form (one normal spring per disc has no Poisson coupling), round-off "
    "for a uniaxial eps_yy";
  f.wave_definition =
    "a Gaussian pulse of downward velocity starting half the strip length above the interface of a strip 6 columns "
    "wide standing on the continuum: the energy of the difference from a run of the lattice continued below the "
    "interface, over all the discs once the pulse is half the strip length into the continuum, over the incident "
    "(downward, half the initial) energy";
  f.energy_definition =
    "undamped coupled run of the wave's strip and pulse (it crosses the interface and reflects at the continuum's "
    "free bottom as a tension that opens it): mean of (E(t) - E(0)) / E(0) over the last quarter of the steps minus "
    "its mean over the first quarter, sampled every 10 steps; E includes the interface springs' energy and their "
    "friction work";
  return f;
}
} // namespace

BenchmarkFigures run_benchmarks(const CouplingTestInput &in, const BenchmarkRunning &running)
{
  // Each method's scenarios, chosen by the variant's alternative (a new alternative without its
  // scenarios does not compile).
  return std::visit(
    [&](const auto &method) {
      if constexpr (std::is_same_v<std::decay_t<decltype(method)>, coupling::InterfaceCoupling>)
        return interface_figures(method, in, running);
      else
        return band_figures(in, running);
    },
    in.method);
}
} // namespace geohybrid::apps

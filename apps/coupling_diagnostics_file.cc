#include "coupling_diagnostics_file.h"

#include "coupling/hybrid_pullout.h"
#include "dem/io/checked_output.h"
#include "dem/measurements.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace geohybrid::apps
{
DiagnosticsFile::DiagnosticsFile(const std::filesystem::path &directory)
  : path_(directory / "coupling_diagnostics.csv")
  , file_(path_)
{
  file_ << "time_s,head_displacement_m,head_tension_N_per_m,particles_unbalanced_ratio,"
           "continuum_out_of_balance_ratio,coupling_force_on_particles_x_N_per_m,"
           "coupling_force_on_particles_y_N_per_m,coupling_force_on_continuum_x_N_per_m,"
           "coupling_force_on_continuum_y_N_per_m,coupling_force_imbalance_N_per_m,particle_energy_J_per_m,"
           "particle_kinetic_J_per_m,continuum_kinetic_J_per_m,coupling_energy_J_per_m,crossing_tension_N_per_m,"
           "particle_boundary_work_J_per_m,continuum_internal_work_J_per_m,continuum_damping_work_J_per_m,"
           "continuum_gravity_work_J_per_m,coupling_work_on_continuum_J_per_m,continuum_sheet_truss_work_J_per_m,"
           "continuum_sheet_interface_work_J_per_m,energy_balance_error\n";
  flush();
  file_.precision(10);
}

void DiagnosticsFile::add(const dem::PullPoint &point, coupling::HybridPullOut &hybrid)
{
  const coupling::CouplingDiagnostics d = hybrid.stepper().diagnostics();
  const coupling::CouplingForceSums &f = d.forces;
  const double imbalance = (f.on_particles + f.on_continuum).norm();
  const double largest = std::max(f.on_particles.norm(), f.on_continuum.norm());
  largest_imbalance_ = std::max(largest_imbalance_, imbalance);
  largest_force_ = std::max(largest_force_, largest);
  const coupling::SheetCrossing *crossing = hybrid.stepper().sheet_crossing();
  // The balance over the pull, from its first point (the coupled settling before it is not in it).
  if (!start_)
    start_ = d;
  balance_error_ = coupling::energy_balance_error(*start_, d);
  largest_balance_error_ = std::max(largest_balance_error_, std::abs(balance_error_));
  const fem::ExplicitEnergyLedger &c = d.continuum_ledger, &c0 = start_->continuum_ledger;
  const fem::SheetEnergyLedger &s = d.continuum_sheet_ledger, &s0 = start_->continuum_sheet_ledger;
  const std::array<double, n_columns> row{{hybrid.stepper().time(),
                                          point.head_displacement,
                                          point.head_tension,
                                          dem::unbalanced_force_ratio(hybrid.particle_system()),
                                          hybrid.continuum().out_of_balance_ratio(),
                                          f.on_particles.x(),
                                          f.on_particles.y(),
                                          f.on_continuum.x(),
                                          f.on_continuum.y(),
                                          imbalance,
                                          d.particle_energy,
                                          d.particle_kinetic,
                                          d.continuum_kinetic,
                                          d.coupling_energy,
                                          crossing ? crossing->tension() : 0.0,
                                          d.particle_budget.boundary_work - start_->particle_budget.boundary_work,
                                          c.internal_work - c0.internal_work,
                                          c.damping_work - c0.damping_work,
                                          c.gravity_work - c0.gravity_work,
                                          c.added_force_work - c0.added_force_work,
                                          s.truss_work - s0.truss_work,
                                          s.interface_work - s0.interface_work,
                                          balance_error_}};
  rows_.insert(rows_.end(), row.begin(), row.end());
  write_row(row.data());
  flush();
}

void DiagnosticsFile::store(dem::CommandState &command) const
{
  command.reals["diagnostics_rows"] = rows_;
  command.reals["diagnostics_extremes"] = {largest_imbalance_, largest_force_, balance_error_,
                                           largest_balance_error_};
}

void DiagnosticsFile::restore(const dem::CommandState &saved)
{
  rows_ = saved.real("diagnostics_rows");
  if (rows_.size() % n_columns != 0)
    throw std::runtime_error("checkpoint of 'pullout': the stored coupling diagnostics' rows are incomplete");
  const std::vector<double> &e = saved.real("diagnostics_extremes", 4);
  largest_imbalance_ = e[0];
  largest_force_ = e[1];
  balance_error_ = e[2];
  largest_balance_error_ = e[3];
  for (std::size_t r = 0; r < n_rows(); ++r)
    write_row(&rows_[r * n_columns]);
  flush();
}

void DiagnosticsFile::finish(Summary &summary)
{
  flush();
  summary.set("coupling_force_imbalance_max_N_per_m", largest_imbalance_);
  summary.set("coupling_force_max_N_per_m", largest_force_);
  summary.set("energy_balance_error_relative", balance_error_);
  summary.set("energy_balance_error_max_relative", largest_balance_error_);
  summary.set("energy_balance_error_relative_definition",
              "over the pull, from its first point: the change of the coupled system's energy (the particles' "
              "stored + dissipated - the walls' and the clamp's work, the continuum's kinetic energy + internal "
              "work + damping work - gravity work, the coupling's stored energy) over the largest change of "
              "those terms (coupling::energy_balance_error); at the last point, and the largest |value| over the "
              "points (max). With the sheet crossing into the continuum, its part in the continuum is in it "
              "(kinetic energy, truss and interface work, damping: fem::SheetEnergyLedger)");
}

void DiagnosticsFile::flush() { dem::flush_checked(file_, path_); }

void DiagnosticsFile::write_row(const double *row)
{
  for (std::size_t k = 0; k < n_columns; ++k)
    file_ << (k > 0 ? "," : "") << row[k];
  file_ << '\n';
}
} // namespace geohybrid::apps

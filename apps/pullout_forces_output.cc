#include "pullout_forces_output.h"

#include "dem/io/checked_output.h"

#include <iomanip>
#include <locale>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
std::vector<double> budget_terms(const dem::EnergyBudget &e)
{
  return {e.kinetic, e.local_damping_dissipated, e.friction_dissipated + e.interface_friction_dissipated,
          e.boundary_work};
}
} // namespace

PullForcesOutput::PullForcesOutput(const std::filesystem::path &directory, double mu,
                                   const dem::EnergyBudget &energy_at_start)
  : file_(directory / "pullout_forces.csv"), mu_(mu), start_(energy_at_start), out_(file_)
{
  out_.imbue(std::locale::classic());
  out_ << std::setprecision(10);
  out_ << "head_displacement_m,head_tension_kN_per_m,interface_friction_kN_per_m,interface_normal_kN_per_m,"
          "node_wall_kN_per_m,sheet_inertia_kN_per_m,sheet_damping_kN_per_m,normal_force_kN_per_m,"
          "mobilised_friction,soil_kinetic_energy_J_per_m,local_damping_dissipated_J_per_m,"
          "friction_dissipated_J_per_m,clamp_work_J_per_m\n";
  dem::flush_checked(out_, file_);
}

PullForcesOutput::PullForcesOutput(const std::filesystem::path &directory, double mu, const dem::CommandState &saved)
  : PullForcesOutput(directory, mu, dem::EnergyBudget{})
{
  const std::vector<double> &start = saved.real("forces_energy_at_start", 4);
  start_.kinetic = start[0];
  start_.local_damping_dissipated = start[1];
  start_.friction_dissipated = start[2];
  start_.boundary_work = start[3];
  const std::vector<double> &rows = saved.real("forces_rows");
  if (rows.size() % n_columns != 0)
    throw std::runtime_error("checkpoint of 'pullout': the stored rows of pullout_forces.csv are incomplete");
  for (std::size_t k = 0; k < rows.size(); k += n_columns)
    write_row(&rows[k]);
  rows_ = rows;
}

void PullForcesOutput::store(dem::CommandState &command) const
{
  command.reals["forces_energy_at_start"] = budget_terms(start_);
  command.reals["forces_rows"] = rows_;
}

void PullForcesOutput::add_point(const dem::PullPoint &point, const dem::DemSystem &system)
{
  const dem::HeadTensionParts &p = point.parts;
  const dem::EnergyBudget e = system.energy();
  const std::vector<double> now = budget_terms(e), start = budget_terms(start_);
  const double limit = mu_ * p.elastic_normal_force;
  const double row[n_columns] = {point.head_displacement,
                                 point.head_tension / 1e3,
                                 p.interface_friction / 1e3,
                                 p.interface_normal / 1e3,
                                 p.node_wall / 1e3,
                                 p.inertia / 1e3,
                                 p.damping / 1e3,
                                 p.elastic_normal_force / 1e3,
                                 limit > 0.0 ? p.tangential_force / limit : 0.0,
                                 now[0],
                                 now[1] - start[1],
                                 now[2] - start[2],
                                 now[3] - start[3]};
  rows_.insert(rows_.end(), row, row + n_columns);
  write_row(row);
}

void PullForcesOutput::write_row(const double *row)
{
  for (std::size_t k = 0; k < n_columns; ++k)
    out_ << row[k] << (k + 1 < n_columns ? ',' : '\n');
  dem::flush_checked(out_, file_);
}

void PullForcesOutput::finish()
{
  dem::flush_checked(out_, file_);
}
} // namespace geohybrid::apps

#include "coupling/hybrid_checkpoint.h"

#include <stdexcept>

namespace geohybrid::coupling
{
namespace
{
std::vector<double> ledger_numbers(const fem::ExplicitEnergyLedger &l)
{
  return {l.kinetic, l.initial_kinetic, l.internal_work, l.damping_work, l.gravity_work, l.load_work, l.added_force_work};
}

fem::ExplicitEnergyLedger ledger_from(const std::vector<double> &v)
{
  fem::ExplicitEnergyLedger l;
  l.kinetic = v[0];
  l.initial_kinetic = v[1];
  l.internal_work = v[2];
  l.damping_work = v[3];
  l.gravity_work = v[4];
  l.load_work = v[5];
  l.added_force_work = v[6];
  return l;
}

std::vector<double> sheet_ledger_numbers(const fem::SheetEnergyLedger &l)
{
  return {l.kinetic, l.initial_kinetic, l.truss_work, l.interface_work, l.damping_work, l.load_work, l.clamp_work};
}

fem::SheetEnergyLedger sheet_ledger_from(const std::vector<double> &v)
{
  fem::SheetEnergyLedger l;
  l.kinetic = v[0];
  l.initial_kinetic = v[1];
  l.truss_work = v[2];
  l.interface_work = v[3];
  l.damping_work = v[4];
  l.load_work = v[5];
  l.clamp_work = v[6];
  return l;
}
} // namespace

void store_continuum_state(const fem::ExplicitSolverState &s, dem::CommandState &c)
{
  c.reals["continuum_clock"] = {s.time, s.previous_step, s.time_step};
  c.counts["continuum_n_steps"] = {s.n_steps};
  c.reals["continuum_velocity"] = s.velocity;
  c.reals["continuum_displacement"] = s.displacement;
  c.reals["continuum_internal_force"] = s.internal_force;
  c.reals["continuum_external_force"] = s.external_force;
  c.reals["continuum_added_force"] = s.added_force;
  c.reals["continuum_material_points"] = s.material_points;
  c.reals["continuum_ledger"] = ledger_numbers(s.ledger);
  c.counts["continuum_has_sheet"] = {s.has_sheet ? 1u : 0u};
  if (!s.has_sheet)
    return;
  const fem::EmbeddedSheetState &t = s.sheet;
  c.reals["continuum_sheet_displacement"] = t.displacement;
  c.reals["continuum_sheet_velocity"] = t.velocity;
  c.reals["continuum_sheet_truss_force"] = t.truss_force;
  c.reals["continuum_sheet_interface_force"] = t.interface_force;
  c.reals["continuum_sheet_node_load"] = t.node_load;
  c.reals["continuum_sheet_shear_stress"] = t.shear_stress;
  c.reals["continuum_sheet_normal_stress"] = t.normal_stress;
  c.reals["continuum_sheet_arc_length"] = t.arc_length;
  c.counts["continuum_sheet_segment"].assign(t.segment.begin(), t.segment.end());
  c.reals["continuum_sheet_ledger"] = sheet_ledger_numbers(t.ledger);
  c.counts["continuum_sheet_advanced"] = {t.advanced ? 1u : 0u};
}

fem::ExplicitSolverState restore_continuum_state(const dem::CommandState &c)
{
  fem::ExplicitSolverState s;
  const std::vector<double> &clock = c.real("continuum_clock", 3);
  s.time = clock[0];
  s.previous_step = clock[1];
  s.time_step = clock[2];
  s.n_steps = c.count("continuum_n_steps", 1)[0];
  s.velocity = c.real("continuum_velocity");
  const std::size_t n = s.velocity.size();
  s.displacement = c.real("continuum_displacement", n);
  s.internal_force = c.real("continuum_internal_force", n);
  s.external_force = c.real("continuum_external_force", n);
  s.added_force = c.real("continuum_added_force", n);
  s.material_points = c.real("continuum_material_points");
  s.ledger = ledger_from(c.real("continuum_ledger", 7));
  s.has_sheet = c.count("continuum_has_sheet", 1)[0] != 0;
  if (!s.has_sheet)
    return s;
  fem::EmbeddedSheetState &t = s.sheet;
  t.displacement = c.real("continuum_sheet_displacement");
  const std::size_t n_nodes = t.displacement.size() / 2;
  t.velocity = c.real("continuum_sheet_velocity", 2 * n_nodes);
  t.truss_force = c.real("continuum_sheet_truss_force", 2 * n_nodes);
  t.interface_force = c.real("continuum_sheet_interface_force", 2 * n_nodes);
  t.node_load = c.real("continuum_sheet_node_load", 2 * n_nodes);
  t.shear_stress = c.real("continuum_sheet_shear_stress", n_nodes);
  t.normal_stress = c.real("continuum_sheet_normal_stress", n_nodes);
  t.arc_length = c.real("continuum_sheet_arc_length", n_nodes);
  const std::vector<std::uint64_t> &segment = c.count("continuum_sheet_segment", n_nodes);
  t.segment.assign(segment.begin(), segment.end());
  t.ledger = sheet_ledger_from(c.real("continuum_sheet_ledger", 7));
  t.advanced = c.count("continuum_sheet_advanced", 1)[0] != 0;
  return s;
}

void store_window_phase(const CoupledStepper &stepper, dem::CommandState &command)
{
  if (stepper.continuum_step_ratio() > 1)
    command.counts["coupled_window_phase"] = {stepper.window_phase()};
}

void restore_window_phase(const dem::CommandState &command, CoupledStepper &stepper)
{
  if (command.counts.find("coupled_window_phase") == command.counts.end())
    {
      if (stepper.continuum_step_ratio() > 1)
        throw std::invalid_argument("the checkpoint holds no multi-rate window: it was written in lockstep");
      return;
    }
  stepper.restore_window_phase(static_cast<unsigned int>(command.count("coupled_window_phase", 1)[0]));
}
} // namespace geohybrid::coupling

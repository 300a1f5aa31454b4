// The explicit solver's state as plain numbers (ExplicitSolverState, explicit_solver.h): what a
// checkpoint keeps to continue a run bit for bit.
#include "explicit_solver.h"

#include <stdexcept>
#include <string>

namespace geohybrid::fem
{
namespace
{
constexpr unsigned int numbers_per_material_point = 26;

void put_symmetric(std::vector<double> &out, const dealii::SymmetricTensor<2, 3> &t)
{
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      out.push_back(t[i][j]);
}

dealii::SymmetricTensor<2, 3> get_symmetric(const double *&in)
{
  dealii::SymmetricTensor<2, 3> t;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      t[i][j] = *in++;
  return t;
}
} // namespace

ExplicitSolverState ExplicitSolver::export_state() const
{
  ExplicitSolverState s;
  s.time = time_;
  s.previous_step = previous_step_;
  s.time_step = time_step_;
  s.n_steps = n_steps_;
  const auto owned = [](const Vector &v) {
    std::vector<double> out(v.locally_owned_size());
    for (unsigned int i = 0; i < v.locally_owned_size(); ++i)
      out[i] = v.local_element(i);
    return out;
  };
  s.velocity = owned(velocity_);
  s.displacement = owned(displacement_);
  s.internal_force = owned(internal_force_);
  s.external_force = owned(external_force_);
  s.added_force = owned(added_force_);
  for (const MaterialPoint *p : cells_.points)
    {
      put_symmetric(s.material_points, p->stress);
      put_symmetric(s.material_points, p->plastic_strain);
      put_symmetric(s.material_points, p->trial_stress);
      put_symmetric(s.material_points, p->trial_plastic_strain);
      s.material_points.push_back(static_cast<double>(static_cast<int>(p->region)));
      s.material_points.push_back(static_cast<double>(static_cast<int>(p->trial_region)));
    }
  s.ledger = ledger_;
  s.has_sheet = sheet_ != nullptr;
  if (sheet_)
    s.sheet = sheet_->export_state();
  return s;
}

void ExplicitSolver::restore_state(const ExplicitSolverState &s)
{
  const unsigned int n = velocity_.locally_owned_size();
  const std::size_t n_points = cells_.points.size();
  for (const std::vector<double> *v : {&s.velocity, &s.displacement, &s.internal_force, &s.external_force, &s.added_force})
    if (v->size() != n)
      throw std::invalid_argument("explicit solver: a saved state of " + std::to_string(v->size()) +
                                  " DoFs does not fit this solver's " + std::to_string(n));
  if (s.material_points.size() != numbers_per_material_point * n_points)
    throw std::invalid_argument("explicit solver: a saved state of " +
                                std::to_string(s.material_points.size() / numbers_per_material_point) +
                                " material points does not fit this solver's " + std::to_string(n_points));
  if (s.has_sheet != (sheet_ != nullptr))
    throw std::invalid_argument(std::string("explicit solver: a saved state ") + (s.has_sheet ? "with" : "without") +
                                " a sheet does not fit this solver");
  if (!(s.time_step > 0.0) || s.time_step > stable_time_step())
    throw std::invalid_argument("explicit solver: the saved time step is not stable here");
  time_ = s.time;
  previous_step_ = s.previous_step;
  time_step_ = s.time_step;
  n_steps_ = static_cast<unsigned int>(s.n_steps);
  const auto restore = [n](const std::vector<double> &in, Vector &v) {
    for (unsigned int i = 0; i < n; ++i)
      v.local_element(i) = in[i];
  };
  restore(s.velocity, velocity_);
  restore(s.displacement, displacement_);
  restore(s.internal_force, internal_force_);
  restore(s.external_force, external_force_);
  restore(s.added_force, added_force_);
  displacement_.update_ghost_values();
  const double *in = s.material_points.data();
  for (MaterialPoint *p : cells_.points)
    {
      p->stress = get_symmetric(in);
      p->plastic_strain = get_symmetric(in);
      p->trial_stress = get_symmetric(in);
      p->trial_plastic_strain = get_symmetric(in);
      p->region = static_cast<ReturnRegion>(static_cast<int>(*in++));
      p->trial_region = static_cast<ReturnRegion>(static_cast<int>(*in++));
    }
  ledger_ = s.ledger;
  if (sheet_)
    sheet_->restore_state(s.sheet);
}
} // namespace geohybrid::fem

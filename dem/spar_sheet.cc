#include "spar_sheet.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace geohybrid::dem
{
namespace
{
void require(bool condition, const std::string &where, const std::string &name, double value, const std::string &what)
{
  if (!condition)
    {
      std::ostringstream message;
      message << where << ": parameter '" << name << "' = " << value << " " << what;
      throw std::invalid_argument(message.str());
    }
}
} // namespace

ContactParameters default_interface_parameters()
{
  ContactParameters c;
  c.friction_angle_deg = 25.6; // soil-geosynthetic, calibrated on the run-out with H = 0.40 m
  return c;
}

void SheetParameters::validate(const std::string &where) const
{
  require(axial_stiffness > 0.0 && std::isfinite(axial_stiffness), where, "axial stiffness J", axial_stiffness,
          "must be positive [N/m]");
  require(thickness > 0.0 && std::isfinite(thickness), where, "thickness", thickness, "must be positive [m]");
  require(areal_mass > 0.0 && std::isfinite(areal_mass), where, "areal mass", areal_mass,
          "must be positive [kg/m^2]");
  require(mass_scaling >= 1.0 && std::isfinite(mass_scaling), where, "mass scaling", mass_scaling,
          "must be at least 1 [-]");
  interface.validate(where + ", interface");
}

SparSheet::SparSheet(std::string name, const std::vector<Vec2> &nodes, const SheetParameters &parameters)
  : name_(std::move(name)), parameters_(parameters)
{
  const std::string where = "sheet '" + name_ + "'";
  parameters_.validate(where);
  interface_law_ = LinearContactLaw(parameters_.interface);
  if (nodes.size() < 2)
    throw std::invalid_argument(where + ": parameter 'nodes' has " + std::to_string(nodes.size()) +
                                " node(s); a sheet needs at least 2");
  for (std::size_t k = 0; k < nodes.size(); ++k)
    if (!std::isfinite(nodes[k].x()) || !std::isfinite(nodes[k].y()))
      throw std::invalid_argument(where + ": parameter 'nodes': node " + std::to_string(k) +
                                  " has a non-finite coordinate");
  const std::size_t n = nodes.size();
  rest_length.resize(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k)
    {
      rest_length[k] = (nodes[k + 1] - nodes[k]).norm();
      if (!(rest_length[k] > 0.0))
        throw std::invalid_argument(where + ": parameter 'nodes': segment " + std::to_string(k) + " (nodes " +
                                    std::to_string(k) + " and " + std::to_string(k + 1) +
                                    ") has zero length; consecutive nodes must be distinct");
    }
  tension.assign(n - 1, 0.0);
  x.resize(n);
  y.resize(n);
  for (std::size_t k = 0; k < n; ++k)
    {
      x[k] = nodes[k].x();
      y[k] = nodes[k].y();
    }
  for (auto *v : {&vx, &vy, &fx, &fy, &damping_fx, &damping_fy, &reaction_x, &reaction_y, &load_x, &load_y})
    v->assign(n, 0.0);
  gravitational_mass.resize(n);
  for (std::size_t k = 0; k < n; ++k)
    {
      const double left = k > 0 ? rest_length[k - 1] : 0.0, right = k + 1 < n ? rest_length[k] : 0.0;
      gravitational_mass[k] = parameters_.areal_mass * 0.5 * (left + right);
    }
  mass.resize(n);
  inverse_mass.resize(n);
  set_mass_scaling(parameters_.mass_scaling);
}

double SparSheet::segment_length(std::size_t k) const
{
  const double dx = x[k + 1] - x[k], dy = y[k + 1] - y[k];
  return std::sqrt(dx * dx + dy * dy);
}

void SparSheet::prescribe_velocity(std::size_t k, const Vec2 &v)
{
  if (k >= n_nodes())
    throw std::out_of_range("sheet '" + name_ + "': node " + std::to_string(k) + " does not exist");
  inverse_mass[k] = 0.0;
  vx[k] = v.x();
  vy[k] = v.y();
}

void SparSheet::release(std::size_t k)
{
  if (k >= n_nodes())
    throw std::out_of_range("sheet '" + name_ + "': node " + std::to_string(k) + " does not exist");
  inverse_mass[k] = 1.0 / mass[k];
  reaction_x[k] = reaction_y[k] = 0.0;
}

void SparSheet::set_load(std::size_t k, const Vec2 &load)
{
  if (k >= n_nodes())
    throw std::out_of_range("sheet '" + name_ + "': node " + std::to_string(k) + " does not exist");
  if (!std::isfinite(load.x()) || !std::isfinite(load.y()))
    throw std::invalid_argument("sheet '" + name_ + "': the load on node " + std::to_string(k) + " is not finite");
  load_x[k] = load.x();
  load_y[k] = load.y();
}

void SparSheet::keep_first_nodes(std::size_t n_kept)
{
  if (n_kept < 2 || n_kept > n_nodes())
    throw std::invalid_argument("sheet '" + name_ + "': cannot keep " + std::to_string(n_kept) + " of its " +
                                std::to_string(n_nodes()) + " nodes (at least 2)");
  for (auto *v : {&x, &y, &vx, &vy, &fx, &fy, &mass, &inverse_mass, &gravitational_mass, &damping_fx, &damping_fy,
                  &reaction_x, &reaction_y, &load_x, &load_y})
    v->resize(n_kept);
  rest_length.resize(n_kept - 1);
  tension.resize(n_kept - 1);
}

void SparSheet::set_mass_scaling(double factor)
{
  require(factor >= 1.0 && std::isfinite(factor), "sheet '" + name_ + "'", "mass scaling", factor,
          "must be at least 1 [-]");
  parameters_.mass_scaling = factor;
  for (std::size_t k = 0; k < n_nodes(); ++k)
    {
      const bool kinematic = mass[k] > 0.0 && inverse_mass[k] == 0.0; // (mass is 0 before the first call)
      mass[k] = factor * gravitational_mass[k];
      inverse_mass[k] = kinematic ? 0.0 : 1.0 / mass[k];
    }
}

namespace
{
/// Stiffness a free node of `sheet` can meet: its segments' J / l0 plus the stiffest contact.
double node_stiffness(const SparSheet &sheet, std::size_t k, double contact_stiffness)
{
  return sheet.chain().node_stiffness(sheet.rest_length.data(), sheet.n_nodes(), k, contact_stiffness);
}
} // namespace

double SparSheet::critical_time_step(double contact_stiffness) const
{
  // A uniform chain of masses m and springs k is stable for dt < 2 / omega_max = sqrt(m / k);
  // sqrt(m / (sum of the stiffnesses on the node)) is below it (by sqrt(2) in the chain) and
  // also covers end nodes and nodes pressed by contacts.
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n_nodes(); ++k)
    if (inverse_mass[k] > 0.0)
      dt = std::min(dt, std::sqrt(mass[k] / node_stiffness(*this, k, contact_stiffness)));
  return dt;
}

double SparSheet::required_mass_scaling(double dt, double contact_stiffness) const
{
  double factor = 1.0;
  for (std::size_t k = 0; k < n_nodes(); ++k)
    if (inverse_mass[k] > 0.0)
      factor = std::max(factor, dt * dt * node_stiffness(*this, k, contact_stiffness) / gravitational_mass[k]);
  return factor;
}

void SparSheet::start_forces(const Vec2 &gravity)
{
  // + 0.0 turns -0.0 into +0.0, as for bodies (DemSystem::compute_pair_forces).
  for (std::size_t k = 0; k < n_nodes(); ++k)
    {
      fx[k] = gravitational_mass[k] * gravity.x() + load_x[k] + 0.0;
      fy[k] = gravitational_mass[k] * gravity.y() + load_y[k] + 0.0;
    }
}

void SparSheet::add_axial_forces()
{
  const geosynthetic::TensionOnlyChain law = chain();
  for (std::size_t k = 0; k < n_segments(); ++k)
    {
      const double dx = x[k + 1] - x[k], dy = y[k + 1] - y[k];
      const double length = std::sqrt(dx * dx + dy * dy), l0 = rest_length[k];
      if (!law.is_taut(length, l0)) // slack (or folded onto itself): no compression, no bending
        {
          tension[k] = 0.0;
          continue;
        }
      const double T = law.tension(length, l0);
      tension[k] = T;
      const double tx = T * dx / length, ty = T * dy / length;
      fx[k] += tx;
      fy[k] += ty;
      fx[k + 1] -= tx;
      fy[k + 1] -= ty;
    }
}

SparSheet::StepWork SparSheet::kick_and_drift(double dt)
{
  const double half = 0.5 * dt;
  StepWork work;
  for (std::size_t k = 0; k < n_nodes(); ++k)
    {
      const double vx0 = vx[k], vy0 = vy[k];
      vx[k] += half * (fx[k] + damping_fx[k]) * inverse_mass[k];
      vy[k] += half * (fy[k] + damping_fy[k]) * inverse_mass[k];
      // Work of the damping force during the half kick, exact for a constant force.
      work.damping += 0.5 * half * (damping_fx[k] * (vx0 + vx[k]) + damping_fy[k] * (vy0 + vy[k]));
      x[k] += dt * vx[k];
      y[k] += dt * vy[k];
      if (inverse_mass[k] > 0.0) // a kinematic node's load is held by its clamp
        work.boundary += dt * (load_x[k] * vx[k] + load_y[k] * vy[k]);
    }
  return work;
}

SparSheet::StepWork SparSheet::damp_and_kick(double dt, double alpha, const Vec2 &gravity)
{
  const double half = 0.5 * dt;
  StepWork work;
  const auto damping = [alpha](double force, double velocity) {
    return -alpha * std::abs(force) * static_cast<double>((velocity > 0.0) - (velocity < 0.0));
  };
  for (std::size_t k = 0; k < n_nodes(); ++k)
    {
      if (inverse_mass[k] == 0.0)
        {
          // The clamp holds the node: its reaction balances every force on it, weight and load
          // included. Power into the rest of the system: minus the force the system applies on
          // the node (all but weight and load) times its velocity, i.e. (reaction + m g + load) . v.
          const double rx = -fx[k], ry = -fy[k];
          const double ex = gravitational_mass[k] * gravity.x() + load_x[k];
          const double ey = gravitational_mass[k] * gravity.y() + load_y[k];
          work.boundary += 0.5 * dt * ((reaction_x[k] + rx + 2.0 * ex) * vx[k] + (reaction_y[k] + ry + 2.0 * ey) * vy[k]);
          reaction_x[k] = rx;
          reaction_y[k] = ry;
          damping_fx[k] = damping_fy[k] = 0.0;
          continue;
        }
      damping_fx[k] = damping(fx[k], vx[k]);
      damping_fy[k] = damping(fy[k], vy[k]);
      const double vx0 = vx[k], vy0 = vy[k];
      vx[k] += half * (fx[k] + damping_fx[k]) * inverse_mass[k];
      vy[k] += half * (fy[k] + damping_fy[k]) * inverse_mass[k];
      work.damping += 0.5 * half * (damping_fx[k] * (vx0 + vx[k]) + damping_fy[k] * (vy0 + vy[k]));
    }
  return work;
}

double SparSheet::kinetic_energy() const
{
  double e = 0.0;
  for (std::size_t k = 0; k < n_nodes(); ++k)
    if (inverse_mass[k] > 0.0)
      e += 0.5 * mass[k] * (vx[k] * vx[k] + vy[k] * vy[k]);
  return e;
}

double SparSheet::gravitational_energy(const Vec2 &gravity) const
{
  double e = 0.0;
  for (std::size_t k = 0; k < n_nodes(); ++k)
    if (inverse_mass[k] > 0.0)
      e -= gravitational_mass[k] * (gravity.x() * x[k] + gravity.y() * y[k]);
  return e;
}

double SparSheet::elastic_energy() const
{
  const geosynthetic::TensionOnlyChain law = chain();
  double e = 0.0;
  for (std::size_t k = 0; k < n_segments(); ++k) // + 0.0 for a slack one: e >= +0.0, no bit changes
    e += law.elastic_energy(segment_length(k), rest_length[k]);
  return e;
}

std::vector<Vec2> subdivide_polyline(const std::vector<Vec2> &corners, double max_segment_length)
{
  if (!(max_segment_length > 0.0))
    throw std::invalid_argument("subdivide_polyline: the segment length must be positive");
  if (corners.size() < 2)
    throw std::invalid_argument("subdivide_polyline: a polyline needs at least two corners");
  std::vector<Vec2> nodes{corners.front()};
  for (std::size_t c = 0; c + 1 < corners.size(); ++c)
    {
      const Vec2 a = corners[c], b = corners[c + 1];
      const double length = (b - a).norm();
      if (!(length > 0.0))
        throw std::invalid_argument("subdivide_polyline: corners " + std::to_string(c) + " and " +
                                    std::to_string(c + 1) + " coincide");
      const auto n = static_cast<std::size_t>(std::max(1.0, std::ceil(length / max_segment_length - 1e-9)));
      for (std::size_t i = 1; i < n; ++i)
        nodes.push_back(a + (static_cast<double>(i) / static_cast<double>(n)) * (b - a));
      nodes.push_back(b);
    }
  return nodes;
}
} // namespace geohybrid::dem

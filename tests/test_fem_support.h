#pragma once
// Shared set-up for the tests of the continuum solver: meshes, soils and load functions.
#include "fem/pullout_problem.h"
#include "fem/quasi_static_solver.h"

#include <deal.II/grid/grid_generator.h>

#include <cmath>

namespace geohybrid::fem::testing
{
using dealii::Point;
using Mesh = dealii::parallel::distributed::Triangulation<dim>;

// Boundary ids of a colorized rectangle.
inline constexpr dealii::types::boundary_id left = 0, right = 1, bottom = 2, top = 3;

inline SoilModel elastic_soil(double E = 50e6, double nu = 0.3)
{
  SoilParameters p;
  p.kind = SoilModelKind::linear_elastic;
  p.young_modulus = E;
  p.poisson_ratio = nu;
  return SoilModel(p);
}

inline SoilModel mohr_coulomb_soil(double phi, double c, double psi, double E = 20e6, double nu = 0.3)
{
  SoilParameters p;
  p.kind = SoilModelKind::mohr_coulomb;
  p.young_modulus = E;
  p.poisson_ratio = nu;
  p.strength = {phi, c, psi};
  return SoilModel(p);
}

inline void make_rectangle(Mesh &mesh, unsigned int nx, unsigned int ny, const Point<dim> &p1, const Point<dim> &p2)
{
  dealii::GridGenerator::subdivided_hyper_rectangle(mesh, {nx, ny}, p1, p2, true);
}

/// A deterministic pseudo-random number in [-1, 1] from a vertex position: the same on every rank.
inline double hash(const Point<dim> &p)
{
  const double s = std::sin(12.9898 * p[0] + 78.233 * p[1]) * 43758.5453;
  return 2.0 * (s - std::floor(s)) - 1.0;
}

/// u(x, t) = t (u0 + G x): a linear displacement field, growing with the pseudo-time.
class LinearDisplacement : public dealii::Function<dim>
{
public:
  LinearDisplacement() : dealii::Function<dim>(dim) {}
  double value(const Point<dim> &x, unsigned int c) const override
  {
    const double u0[2] = {1e-3, -2e-3};
    const double G[2][2] = {{2e-3, -1e-3}, {3e-3, -4e-3}};
    return get_time() * (u0[c] + G[c][0] * x[0] + G[c][1] * x[1]);
  }
};

/// f(t) = a + b t, a constant in space (a pressure or a displacement component).
class LinearInTime : public dealii::Function<dim>
{
public:
  LinearInTime(double a, double b, unsigned int n_components = 1, unsigned int component = 0)
    : dealii::Function<dim>(n_components), a_(a), b_(b), component_(component) {}
  double value(const Point<dim> &, unsigned int c) const override
  {
    return c == component_ ? a_ + b_ * get_time() : 0.0;
  }

private:
  double a_, b_;
  unsigned int component_;
};

inline double max_abs_difference(const dealii::PETScWrappers::MPI::Vector &a, const dealii::PETScWrappers::MPI::Vector &b,
                          const dealii::IndexSet &owned)
{
  double m = 0.0;
  for (const auto i : owned)
    m = std::max(m, std::abs(a[i] - b[i]));
  return dealii::Utilities::MPI::max(m, MPI_COMM_WORLD);
}

inline QuasiStaticSettings exact_settings(unsigned int degree)
{
  QuasiStaticSettings s;
  s.element_degree = degree;
  s.newton.relative_tolerance = 1e-12;
  s.linear_solver.relative_tolerance = 1e-13;
  s.stepping.increment = 1.0;
  return s;
}
/// A 2 m x 1 m layer of soil (density 2000 kg/m^3) on a fixed base between smooth walls.
struct Layer
{
  double width = 2.0, height = 1.0, density = 2000.0, g = 9.81, E = 20e6, nu = 0.3, phi = 30.0;
  double unit_weight() const { return density * g; }
  BoundaryConditions supports() const
  {
    BoundaryConditions bc;
    bc.displacements = {{left, true, false, nullptr}, {right, true, false, nullptr}, {bottom, true, true, nullptr}};
    return bc;
  }
  GeostaticStress geostatic() const
  {
    GeostaticStress g0;
    g0.surface_elevation = height;
    g0.unit_weight = unit_weight();
    g0.k0 = 1 - std::sin(phi * pi / 180.0);
    return g0;
  }
  QuasiStaticSettings settings(unsigned int degree) const
  {
    QuasiStaticSettings s;
    s.element_degree = degree;
    s.density = density;
    s.newton.relative_tolerance = 1e-12;
    s.linear_solver.relative_tolerance = 1e-13;
    s.stepping.increment = 0.5;
    return s;
  }
};

/// A load of `pressure` on the top face for x < `width`.
class StripPressure : public dealii::Function<dim>
{
public:
  StripPressure(double pressure, double width) : dealii::Function<dim>(1), pressure_(pressure), width_(width) {}
  double value(const Point<dim> &x, unsigned int) const override { return x[0] < width_ ? pressure_ : 0.0; }

private:
  double pressure_, width_;
};

/// The layer's mesh: `nx_q1` x nx_q1 / 2 Q1 cells, or half as many Q2 cells (the same nodes).
inline void make_layer_mesh(Mesh &mesh, const Layer &layer, unsigned int degree, unsigned int nx_q1)
{
  const unsigned int nx = degree == 1 ? nx_q1 : nx_q1 / 2;
  make_rectangle(mesh, nx, nx / 2, Point<dim>(0, 0), Point<dim>(layer.width, layer.height));
}

/// The layer's supports with `pressure` on the top face over x < 0.5 m [Pa].
inline BoundaryConditions strip_loaded_layer(const Layer &layer, double pressure)
{
  BoundaryConditions bc = layer.supports();
  bc.pressures = {{top, std::make_shared<StripPressure>(pressure, 0.5)}};
  return bc;
}

/// A 0.6 m x 0.4 m tank of 12 x 8 cells, elastic soil (E = 20 MPa, nu = 0.3, K0 = nu / (1 - nu))
/// of 15.2 kN/m^3 under 30 kPa, the sheet over the whole length (L = 0.6 m, from the front wall
/// to the back wall) at H = 0.225 m, in the middle of a row of cells. With smooth walls at both of
/// its ends, the vertical equilibrium of the soil above the sheet gives a mean normal stress of
/// sigma_v = q + gamma H over its length however the shear redistributes it, so the limit is
/// exactly 2 sigma_v tan(delta) L (a sheet ending inside the soil would not have that property).
inline PulloutProblemParameters small_pullout_tank(double pull_rate)
{
  PulloutProblemParameters p;
  p.sheet_length = 0.6;
  p.sheet_depth = 0.225;
  p.sheet_node_spacing = 0.025;
  p.soil.kind = SoilModelKind::linear_elastic;
  p.soil.young_modulus = 20e6;
  p.soil.poisson_ratio = 0.3;
  p.soil_density = 15.2e3 / 9.81;
  p.surcharge = 30e3;
  p.pull_rate = pull_rate;
  p.final_displacement = 0.012;
  p.output_interval = 0.5e-3;
  return p;
}

/// A wrap-around in a 0.8 m x 0.6 m tank of elastic soil (E = 20 MPa, nu = 0.3, K0 = nu / (1 -
/// nu)) of 15.2 kN/m^3 under 30 kPa, 50 mm cells: lower part L = 0.425 m at H = 0.375 m, return
/// D1 = 0.15 m, upper part B = 0.2 m at H - D1 = 0.225 m, each through the middle of a row (the
/// return of a column) of cells, nodes every 25 mm, pulled 30 mm.
inline PulloutProblemParameters small_wrap_around_tank(double pull_rate)
{
  PulloutProblemParameters p = small_pullout_tank(pull_rate);
  p.sheet_length = 0.425;
  p.sheet_depth = 0.375;
  p.wrap_around = true;
  p.return_height = 0.15;
  p.upper_length = 0.2;
  p.final_displacement = 0.03;
  return p;
}
} // namespace geohybrid::fem::testing

#pragma once
// The geosynthetic sheet in the continuum: a chain of tension-only 2-node truss elements (the
// same spar model as the DEM sheet, dem/spar_sheet.h, Chareyre & Villard 2005):
//
//   T = J (l - l0) / l0   when l > l0,   T = 0   when l <= l0 (no compression, no bending),
//
// J the tensile stiffness per metre of width [N/m], l the current and l0 the rest length of a
// segment, per metre of width like everything in fem/ (conventions.h). The law is
// geosynthetic::TensionOnlyChain's (geosynthetic/tension_only_chain.h), the DEM sheet's too; this
// truss computes T from the strain l / l0 - 1 (tension_at_strain). The current length uses
// the nodes' displaced positions, as the DEM sheet does, so a sheet that rotates does not stretch.
//
// The sheet's parameters are those of the DEM sheet (J, areal mass, mass scaling, interface
// friction angle 25.6 degrees and cohesion), in a value type of fem/ (fem/ must not include dem/;
// apps/ fills both from one input file). The interface to the soil is sheet_interface.h.
#include "fem/conventions.h"
#include "geosynthetic/tension_only_chain.h"

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace geohybrid::fem
{
/// Zero-thickness Mohr-Coulomb interface between each face of the sheet and the soil:
/// tau <= c_i + sigma_n tan(delta), sigma_n the soil's compressive stress normal to the sheet;
/// penalty stiffnesses tie the sheet to the soil below that limit.
struct SheetInterfaceParameters
{
  double friction_angle_deg = 25.6; ///< delta, soil-geosynthetic (reference paper, section 4.3) [deg]
  double cohesion = 0.0;            ///< c_i, the adhesion [Pa]
  double normal_stiffness = 1e8;    ///< k_n per face, a penalty [Pa/m]
  double shear_stiffness = 1e8;     ///< k_s per face, the elastic slip before sliding [Pa/m]
};

struct TrussSheetParameters
{
  double axial_stiffness = 2.104e6; ///< J per metre of width [N/m]; default GT230 (Table 2)
  double areal_mass = 0.62;         ///< mass per unit area [kg/m^2]; default GT230
  double mass_scaling = 1.0;        ///< factor on the nodes' inertial mass, >= 1 [-]
  SheetInterfaceParameters interface;

  /// Throws std::invalid_argument naming `where` and the parameter.
  void validate(const std::string &where) const;
};

class TrussSheet
{
public:
  using Force = dealii::Tensor<1, dim>;

  /// A sheet through `nodes` (at least two, consecutive nodes distinct), unstretched. Throws
  /// std::invalid_argument naming `where` and the parameter for bad input.
  TrussSheet(const std::vector<dealii::Point<dim>> &nodes, const TrussSheetParameters &parameters,
             const std::string &where = "sheet");

  const TrussSheetParameters &parameters() const { return parameters_; }
  /// The tension-only law of its segments, with its J.
  geosynthetic::TensionOnlyChain chain() const { return {parameters_.axial_stiffness}; }
  std::size_t n_nodes() const { return nodes_.size(); }
  std::size_t n_segments() const { return rest_lengths_.size(); }
  const dealii::Point<dim> &node(std::size_t k) const { return nodes_[k]; } ///< reference position [m]
  double rest_length(std::size_t s) const { return rest_lengths_[s]; }      ///< l0 [m]
  /// Half the rest length of each segment at node k: the sheet's length that node stands for [m].
  double tributary_length(std::size_t k) const;
  /// The unit tangent at node k (mean of its segments' directions in the reference state).
  Force tangent(std::size_t k) const;
  /// Inertial mass of node k: areal mass times tributary length times mass scaling [kg/m].
  double node_mass(std::size_t k) const;
  /// The stiffness node k meets: `other_stiffness` plus J / l0 of its segments [N/m^2].
  double node_stiffness(std::size_t k, double other_stiffness) const
  {
    return chain().node_stiffness(rest_lengths_.data(), n_nodes(), k, other_stiffness);
  }

  /// T of every segment for the node displacements `u` [N/m] (zero when slack).
  std::vector<double> axial_forces(const std::vector<Force> &u) const;
  /// The force the segments exert on each node for displacements `u` [N/m].
  std::vector<Force> nodal_forces(const std::vector<Force> &u) const;
  /// The consistent tangent of segment s for displacements `u`: K = (J / l0) e x e + (T / l)
  /// (I - e x e), e the current unit direction, so that the resisting forces of its nodes change
  /// by [K -K; -K K] [du_s; du_s+1]. Zero when slack (l < l0): a slack segment carries nothing
  /// and resists nothing. At l = l0 exactly (the unstretched start) it is the taut one, J / l0
  /// along the segment [N/m^2].
  dealii::Tensor<2, dim> segment_stiffness(const std::vector<Force> &u, std::size_t s) const;

private:
  std::vector<dealii::Point<dim>> nodes_;
  std::vector<double> rest_lengths_;
  TrussSheetParameters parameters_;
};
} // namespace geohybrid::fem

#include "interface_wall.h"

#include "dem/contact_frame.h"
#include "dem/contact_list.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace geohybrid::coupling
{
InterfaceWall::InterfaceWall(const InterfaceCoupling &parameters, const dem::ParticleSet &particles,
                             const fem::ExplicitSolver &continuum, double skin)
  : law_((parameters.validate(), parameters.contact)), skin_(skin)
{
  const std::string where = "interface coupling: ";
  const fem::DisplacementSpace &space = continuum.space();
  if (dealii::Utilities::MPI::n_mpi_processes(space.communicator()) != 1)
    throw std::invalid_argument(where + "the coupling runs on one MPI rank only (for now)");
  if (space.degree() != 1)
    throw std::invalid_argument(where + "the interface edges must be straight: Q1 cells only ('element degree' 1)");
  if (!(skin > 0.0))
    throw std::invalid_argument(where + "the skin must be positive");

  // The edges: boundary faces with the id, their two vertices as nodes (deduplicated by x DoF).
  // For Q1, cell DoF i is the shape function of vertex system_to_component_index(i).second.
  const auto &fe = space.fe();
  const auto &partitioner = *continuum.displacement().get_partitioner();
  std::vector<dealii::types::global_dof_index> dofs(fe.n_dofs_per_cell());
  std::map<unsigned int, std::uint32_t> node_of_x_dof;
  std::map<std::uint32_t, std::uint32_t> edge_starting_at;
  for (const auto &cell : space.dof_handler().active_cell_iterators())
    for (unsigned int f = 0; f < dealii::GeometryInfo<fem::dim>::faces_per_cell; ++f)
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == parameters.boundary_id)
        {
          cell->get_dof_indices(dofs);
          std::uint32_t ends[2];
          for (unsigned int v = 0; v < 2; ++v)
            {
              const unsigned int vertex = dealii::GeometryInfo<fem::dim>::face_to_cell_vertices(f, v);
              InterfaceNode node;
              for (unsigned int i = 0; i < dofs.size(); ++i)
                {
                  const auto [component, scalar] = fe.system_to_component_index(i);
                  if (scalar != vertex)
                    continue;
                  (component == 0 ? node.x_dof : node.y_dof) = partitioner.global_to_local(dofs[i]);
                }
              node.reference = Vec2(cell->vertex(vertex)[0], cell->vertex(vertex)[1]);
              node.inverse_mass = continuum.is_constrained(node.x_dof) ? 0.0 : 1.0 / continuum.lumped_mass().local_element(node.x_dof);
              const auto [it, added] = node_of_x_dof.emplace(node.x_dof, static_cast<std::uint32_t>(nodes_.size()));
              if (added)
                nodes_.push_back(node);
              ends[v] = it->second;
            }
          // Outward: perp(end - start) points away from the cell's centre.
          const Vec2 centre(cell->center()[0], cell->center()[1]);
          const Vec2 a = nodes_[ends[0]].reference, b = nodes_[ends[1]].reference;
          InterfaceEdge edge;
          const bool outward = dem::perp(b - a).dot(0.5 * (a + b) - centre) > 0.0;
          edge.start = outward ? ends[0] : ends[1];
          edge.end = outward ? ends[1] : ends[0];
          edge_starting_at[edge.start] = static_cast<std::uint32_t>(edges_.size());
          edges_.push_back(edge);
        }
  if (edges_.empty())
    {
      std::ostringstream message;
      message << where << "the mesh has no boundary face with 'boundary id' " << parameters.boundary_id;
      throw std::invalid_argument(message.str());
    }
  for (std::size_t e = 0; e < edges_.size(); ++e)
    {
      const auto next = edge_starting_at.find(edges_[e].end);
      if (next != edge_starting_at.end())
        {
          edges_[e].end_shared = true;
          edges_[next->second].previous = static_cast<std::int64_t>(e);
        }
    }

  // Bins over the interface's box widened by the reach of a disc.
  smallest_radius_ = std::numeric_limits<double>::max();
  for (std::size_t d = 0; d < particles.n_discs_total(); ++d)
    {
      largest_radius_ = std::max(largest_radius_, particles.disc_radius[d]);
      smallest_radius_ = std::min(smallest_radius_, particles.disc_radius[d]);
    }
  if (particles.n_discs_total() == 0)
    throw std::invalid_argument(where + "there are no particles");
  node_allowance_ = largest_radius_;
  const double reach = largest_radius_ + skin_ + node_allowance_;
  Vec2 lower = nodes_[0].reference, upper = nodes_[0].reference;
  for (const InterfaceNode &n : nodes_)
    {
      lower = lower.cwiseMin(n.reference);
      upper = upper.cwiseMax(n.reference);
    }
  grid_origin_ = lower - Vec2(reach, reach);
  bin_size_ = 2.0 * reach;
  n_bins_x_ = static_cast<unsigned int>(std::ceil((upper.x() - lower.x() + 2.0 * reach) / bin_size_)) + 1;
  n_bins_y_ = static_cast<unsigned int>(std::ceil((upper.y() - lower.y() + 2.0 * reach) / bin_size_)) + 1;
  std::vector<std::vector<std::uint32_t>> bins(std::size_t(n_bins_x_) * n_bins_y_);
  for (std::size_t e = 0; e < edges_.size(); ++e)
    {
      const Vec2 a = nodes_[edges_[e].start].reference, b = nodes_[edges_[e].end].reference;
      const Vec2 low = a.cwiseMin(b) - Vec2(reach, reach) - grid_origin_, high = a.cwiseMax(b) + Vec2(reach, reach) - grid_origin_;
      const auto bin = [this](double coordinate, unsigned int n) {
        return std::min(n - 1, static_cast<unsigned int>(std::max(0.0, std::floor(coordinate / bin_size_))));
      };
      for (unsigned int j = bin(low.y(), n_bins_y_); j <= bin(high.y(), n_bins_y_); ++j)
        for (unsigned int i = bin(low.x(), n_bins_x_); i <= bin(high.x(), n_bins_x_); ++i)
          bins[std::size_t(j) * n_bins_x_ + i].push_back(static_cast<std::uint32_t>(e));
    }
  bin_first_edge_.assign(1, 0);
  for (const auto &bin : bins)
    {
      bin_edges_.insert(bin_edges_.end(), bin.begin(), bin.end()); // edges ascending in each bin
      bin_first_edge_.push_back(static_cast<std::uint32_t>(bin_edges_.size()));
    }

  // Room for every disc within reach of the interface on each of a few edges: no allocation while
  // the contacts stay of that order.
  const std::size_t capacity = 4 * particles.n_discs_total() + 64;
  for (auto *v : {&candidate_disc_, &candidate_edge_, &previous_disc_, &previous_edge_})
    v->reserve(capacity);
  candidate_state_.reserve(capacity);
  previous_state_.reserve(capacity);
  disc_x_at_rebuild_.resize(particles.n_discs_total());
  disc_y_at_rebuild_.resize(particles.n_discs_total());
  node_displacement_at_rebuild_.resize(nodes_.size());
}

bool InterfaceWall::candidates_stale(const dem::ParticleSet &p, const fem::ExplicitSolver::Vector &u) const
{
  // A disc-edge distance changes by at most the disc's move plus the largest node move.
  double disc_move2 = 0.0, node_move2 = 0.0;
  for (std::size_t d = 0; d < p.n_discs_total(); ++d)
    disc_move2 = std::max(disc_move2, std::pow(p.disc_x[d] - disc_x_at_rebuild_[d], 2) +
                                        std::pow(p.disc_y[d] - disc_y_at_rebuild_[d], 2));
  for (std::size_t n = 0; n < nodes_.size(); ++n)
    node_move2 = std::max(node_move2, (Vec2(u.local_element(nodes_[n].x_dof), u.local_element(nodes_[n].y_dof)) -
                                       node_displacement_at_rebuild_[n]).squaredNorm());
  return std::sqrt(disc_move2) + std::sqrt(node_move2) > skin_;
}

void InterfaceWall::rebuild_candidates(const dem::ParticleSet &p, const fem::ExplicitSolver::Vector &u)
{
  for (std::size_t n = 0; n < nodes_.size(); ++n)
    {
      node_displacement_at_rebuild_[n] = Vec2(u.local_element(nodes_[n].x_dof), u.local_element(nodes_[n].y_dof));
      if (node_displacement_at_rebuild_[n].norm() > node_allowance_)
        {
          std::ostringstream message;
          message << "interface coupling: the interface node at (" << nodes_[n].reference.x() << ", "
                  << nodes_[n].reference.y() << ") m moved " << node_displacement_at_rebuild_[n].norm()
                  << " m, more than a disc radius: the interface assumes small strain";
          throw std::runtime_error(message.str());
        }
    }
  std::swap(previous_disc_, candidate_disc_);
  std::swap(previous_edge_, candidate_edge_);
  std::swap(previous_state_, candidate_state_);
  candidate_disc_.clear();
  candidate_edge_.clear();
  candidate_state_.clear();
  std::size_t old = 0; // the previous list is sorted by (disc, edge), as the new one is made
  for (std::uint32_t d = 0; d < p.n_discs_total(); ++d)
    {
      disc_x_at_rebuild_[d] = p.disc_x[d];
      disc_y_at_rebuild_[d] = p.disc_y[d];
      const Vec2 centre(p.disc_x[d], p.disc_y[d]);
      const double i = std::floor((centre.x() - grid_origin_.x()) / bin_size_),
                   j = std::floor((centre.y() - grid_origin_.y()) / bin_size_);
      if (i < 0.0 || j < 0.0 || i >= n_bins_x_ || j >= n_bins_y_)
        continue;
      const std::size_t bin = static_cast<std::size_t>(j) * n_bins_x_ + static_cast<std::size_t>(i);
      for (std::uint32_t k = bin_first_edge_[bin]; k < bin_first_edge_[bin + 1]; ++k)
        {
          const std::uint32_t e = bin_edges_[k];
          Vec2 closest;
          const double distance =
            dem::closest_point_on_segment(centre, node_position(u, edges_[e].start), node_position(u, edges_[e].end), closest);
          if (distance >= p.disc_radius[d] + skin_)
            continue;
          while (old < previous_disc_.size() &&
                 (previous_disc_[old] < d || (previous_disc_[old] == d && previous_edge_[old] < e)))
            ++old;
          const bool kept = old < previous_disc_.size() && previous_disc_[old] == d && previous_edge_[old] == e;
          candidate_disc_.push_back(d);
          candidate_edge_.push_back(e);
          candidate_state_.push_back(kept ? previous_state_[old] : dem::ContactState{});
        }
    }
  // A touching contact dropped from the list (it cannot be: it lies within the skin) would lose
  // its spring energy silently; the criterion above guarantees it does not happen.
  rebuild_needed_ = false;
  ++n_rebuilds_;
}

void InterfaceWall::apply(dem::ParticleSet &p, fem::ExplicitSolver &continuum, const TieTiming &timing,
                          CouplingForceSums &sums)
{
  const double drift_time = timing.drift_time;
  const auto &u = continuum.displacement();
  const auto &v = continuum.velocity();
  if (rebuild_needed_ || candidates_stale(p, u))
    rebuild_candidates(p, u);
  elastic_energy_ = 0.0;
  n_touching_ = 0;
  for (std::size_t q = 0; q < candidate_disc_.size(); ++q)
    {
      const std::uint32_t d = candidate_disc_[q], b = p.disc_body[d];
      const InterfaceEdge &edge = edges_[candidate_edge_[q]];
      dem::ContactState &state = candidate_state_[q];
      const Vec2 centre(p.disc_x[d], p.disc_y[d]);
      const Vec2 a = node_position(u, edge.start), ab = node_position(u, edge.end) - a;
      const double raw = (centre - a).dot(ab) / ab.squaredNorm();
      // Who owns a contact at a shared node: see the header.
      bool owned = raw >= 0.0 ? (raw < 1.0 || !edge.end_shared) : edge.previous < 0;
      if (raw < 0.0 && edge.previous >= 0)
        {
          const InterfaceEdge &before = edges_[static_cast<std::size_t>(edge.previous)];
          const Vec2 a0 = node_position(u, before.start), ab0 = node_position(u, before.end) - a0;
          owned = (centre - a0).dot(ab0) / ab0.squaredNorm() >= 1.0; // a convex corner
        }
      const double xi = std::clamp(raw, 0.0, 1.0);
      const Vec2 closest = a + xi * ab;
      const double distance = (closest - centre).norm();
      const double overlap = owned ? p.disc_radius[d] - distance : std::min(0.0, p.disc_radius[d] - distance);
      if (overlap <= 0.0 && !state.touching)
        continue;
      const Vec2 normal = dem::ContactFrame::normal_towards(centre, closest, distance,
                                                            [&]() -> Vec2 { return -dem::perp(ab).normalized(); });
      // The contact point of a disc still apart (a contact that held forces) is on its surface.
      const dem::ContactFrame contact =
        dem::ContactFrame::of_disc(p, d, normal, std::max(overlap, 0.0)).with_overlap(overlap);
      const InterfaceNode &na = nodes_[edge.start], &nb = nodes_[edge.end];
      const double shape_a = 1.0 - xi, shape_b = xi;
      const Vec2 v_edge = shape_a * Vec2(v.local_element(na.x_dof), v.local_element(na.y_dof)) +
                          shape_b * Vec2(v.local_element(nb.x_dof), v.local_element(nb.y_dof));
      const double inverse_mass_sum =
        p.inverse_mass[b] + shape_a * shape_a * na.inverse_mass + shape_b * shape_b * nb.inverse_mass;
      const dem::ContactForce f = law_.evaluate(contact.kinematics(v_edge, inverse_mass_sum, drift_time), state);
      dissipated_ += f.friction_work + f.viscous_work;
      if (!state.touching)
        continue;
      elastic_energy_ += law_.elastic_energy(f.elastic_normal, f.tangential_force);
      ++n_touching_;
      const Vec2 force = contact.force_on_i(f); // on the disc
      p.fx[b] += force.x();
      p.fy[b] += force.y();
      p.torque[b] += dem::cross(contact.lever(), force);
      sums.on_particles += force;
      continuum.add_external_force(na.x_dof, -shape_a * force.x());
      continuum.add_external_force(na.y_dof, -shape_a * force.y());
      continuum.add_external_force(nb.x_dof, -shape_b * force.x());
      continuum.add_external_force(nb.y_dof, -shape_b * force.y());
      sums.on_continuum -= shape_a * force + shape_b * force;
    }
}

double InterfaceWall::squared_frequency_bound(const dem::ParticleSet &p, const fem::ExplicitSolver & /*continuum*/) const
{
  // One contact's stiffness couples the disc's contact point and the edge's nodes through
  // g = (1, -N_A, -N_B) (the gap's dependence on them), K_c = (kn n n^T + ks t t^T) (x) g g^T, whose
  // 2 x 2 blocks have norm max(kn, ks). Block Gershgorin on M^-1 K (each node has one lumped mass
  // for x and y): node I's row sum is sum_c max(kn, ks) N_I (1 + N_A + N_B) / M_I = 2 max(kn, ks)
  // sum_c N_I / M_I. The discs touching the two edges at I are at least s = 1.8 r_min apart along
  // them (discs overlapping each other by under a tenth of a radius), and N_I is a hat of height 1
  // and base L_before + L_after, so sum_c N_I <= 1 + (L_before + L_after) / (2 s) (a Riemann sum of
  // a unimodal function). A disc's row: at most two interface contacts (straight or concave
  // interface), each 2 max(kn / m, ks (1/m + r^2 / I)) (the contact point's mobility: tangentially
  // the disc turns too).
  const double kn = law_.normal_stiffness(), ks = law_.shear_stiffness(), k = std::max(kn, ks);
  std::vector<double> adjacent_length(nodes_.size(), 0.0);
  for (const InterfaceEdge &e : edges_)
    {
      const double length = (nodes_[e.end].reference - nodes_[e.start].reference).norm();
      adjacent_length[e.start] += length;
      adjacent_length[e.end] += length;
    }
  double largest = 0.0;
  const double spacing = 1.8 * smallest_radius_;
  for (std::size_t n = 0; n < nodes_.size(); ++n)
    largest = std::max(largest, 2.0 * k * (1.0 + adjacent_length[n] / (2.0 * spacing)) * nodes_[n].inverse_mass);
  for (std::size_t d = 0; d < p.n_discs_total(); ++d)
    {
      const std::uint32_t b = p.disc_body[d];
      const double lever2 = std::pow(std::hypot(p.disc_offset_x[d], p.disc_offset_y[d]) + p.disc_radius[d], 2);
      const double mobility = std::max(kn * p.inverse_mass[b], ks * (p.inverse_mass[b] + lever2 * p.inverse_inertia[b]));
      largest = std::max(largest, 2.0 * 2.0 * mobility);
    }
  return largest;
}
} // namespace geohybrid::coupling

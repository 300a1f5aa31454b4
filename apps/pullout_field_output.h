#pragma once
// The soil's fields during `geohybrid pullout` (the paper's Figures 10-12), written at chosen
// head displacements ('Output/field outputs at'):
//
//   pullout_fields.h5, .xdmf               a SnapshotWriter snapshot at the start of the pull and at
//                                          each chosen displacement: grains with their velocities,
//                                          the contact-force network, the sheet (open in ParaView)
//   grain_displacements_u<D>mm.csv, .png   every grain: body_id, x0_m, y0_m (start of the pull),
//                                          x_m, y_m, dx_m, dy_m, vx_m_per_s, vy_m_per_s; arrows
//                                          magnified as the plot's title says (Figure 10)
//   force_network_u<D>mm.csv, .png         every touching disc-disc contact: x_m, y_m (disc i),
//                                          dx_m, dy_m (to disc j), normal_force_N_per_m; lines
//                                          coloured by their force (Figure 12)
//   surface_uplift.csv, .png               the soil surface at the start (the highest grain of
//                                          each strip two discs wide): body_id, x_m, surface_y_m, its
//                                          uplift at each chosen displacement, uplift_m_at_<D>mm
//                                          (Figure 11), written by finish()
//
// D is the chosen head displacement in mm.
#include "dem/dem_system.h"
#include "dem/io/checkpoint.h"
#include "dem/io/snapshot_writer.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace geohybrid::apps
{
class PullOutFieldOutput
{
public:
  /// `at`: head displacements [m], ascending; `width`: the tank's inner length; `strip`: the
  /// width of the surface strips [m].
  PullOutFieldOutput(const std::filesystem::path &directory, std::vector<double> at, double width, double strip);
  /// A resumed run: the grains' positions at the start of the pull, the fields written and the
  /// uplift profiles from `saved` (store()); `system` is the restored one (the same bodies).
  /// pullout_fields.h5 keeps its snapshots up to the system's time and is continued.
  PullOutFieldOutput(const std::filesystem::path &directory, std::vector<double> at, double width, double strip,
                     const dem::CommandState &saved, const dem::DemSystem &system);
  /// Keeps what a resumed run needs in `command` (for a checkpoint).
  void store(dem::CommandState &command) const;
  /// Call at every recorded point of the pull, the start (0) first: writes the fields of each
  /// chosen displacement once the pull has reached it.
  void record(double head_displacement, const dem::DemSystem &system);
  /// Writes the surface uplift profile.
  void finish();

private:
  void find_surface();
  void write_fields(const std::string &tag, const dem::DemSystem &system);

  std::filesystem::path directory_;
  std::vector<double> at_;
  double width_, strip_;
  std::size_t next_ = 0;
  std::optional<dem::ParticleSet> start_;
  dem::SnapshotWriter snapshots_;
  std::vector<std::string> uplift_tags_;
  std::vector<std::vector<double>> uplift_; ///< per chosen displacement, per surface point [m]
  std::vector<std::int64_t> surface_id_;
  std::vector<double> surface_x_, surface_y_;
};
} // namespace geohybrid::apps

#pragma once
// Snapshots of a DemSystem for ParaView: one HDF5 file holding every snapshot, and an XDMF (version 3)
// file describing it, rewritten after each snapshot so that it is always valid.
//
// HDF5 layout (datasets are row-major; "n" = number of discs, "m" = touching pair contacts,
// "w" = touching wall contacts; z = 0 everywhere):
//
//   /snapshot_NNNNNN                         attributes: time [s] (double), step (uint64),
//                                            n_discs, n_bodies, n_contacts, n_wall_contacts (uint64)
//     particles/position        n x 3  double  disc centre [m]
//     particles/connectivity    n      int64   0 .. n-1 (the Polyvertex topology)
//     particles/radius          n      double  [m]
//     particles/velocity        n x 3  double  body velocity + omega x (disc centre - body centre) [m/s]
//     particles/cluster_id      n      int64   ParticleSet::body_id of the owning body
//     particles/rotation        n      double  rotation of the owning body [rad]
//     contacts/points           2m x 3 double  line k goes from disc i (point 2k) to disc j (2k+1)
//     contacts/connectivity     m x 2  int64   (2k, 2k+1)
//     contacts/normal_force     m      double  elastic normal force kn * overlap [N/m]
//     contacts/tangential_force m      double  Ft along t on the i side [N/m]
//     contacts/force_magnitude  m      double  |(force_x, force_y)| on disc i, dashpot included [N/m]
//     contacts/bonded           m      int32   1 if the contact is bonded
//     sheets/position           N x 3  double  sheet nodes, all sheets one after the other [m]
//     sheets/velocity           N x 3  double  [m/s]
//     sheets/sheet_index        N      int32   index of the node's sheet in DemSystem::sheets()
//     sheets/connectivity       S x 2  int64   segment k joins nodes (i, i + 1) of one sheet
//     sheets/tension            S      double  axial force of the segment [N/m]
//     sheets/strain             S      double  (l - l0) / l0, negative when slack [-]
//     sheet_contacts/...        the contact datasets, lines from the disc centre to the contact's
//                               point on the sheet's centre line, plus wall_index (int32) holding
//                               the sheet's index
//     wall_contacts/...         same datasets with w lines from the disc centre to the closest
//                               point of the wall, plus wall_index (int32); written last
//
// Snapshot attributes also give n_sheet_nodes, n_sheet_segments, n_sheet_contacts (uint64; absent
// in files written before sheets existed, read as 0).
//
// Contacts are those with ContactState::touching, in the order of the contact lists.
// Datasets of an empty set have a zero first dimension; the XDMF file then leaves out the grid,
// since ParaView does not read empty grids.
//
// The HDF5 file is opened only while write() runs, so that a reader (ParaView) can open it between
// snapshots. Not thread-safe: call write() from one thread, between DemSystem::step() calls.
#include "dem/dem_system.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::dem
{
class SnapshotWriter
{
public:
  /// Creates (truncates) DIRECTORY/BASENAME.h5 and DIRECTORY/BASENAME.xdmf; creates DIRECTORY if
  /// needed. Throws std::runtime_error naming the file if it cannot.
  SnapshotWriter(const std::filesystem::path &directory, const std::string &basename = "particles");

  /// Continues the files of an earlier run (resuming from a checkpoint): reopens
  /// DIRECTORY/BASENAME.h5, keeps its snapshots in order while they are complete and their time
  /// is <= keep_until_time, removes the first one that is not and all after it (HDF5 does not give
  /// their space back; h5repack does), and rewrites the .xdmf to list the kept ones exactly as
  /// write() listed them; write() then appends after them. A missing .h5 is
  /// created empty, as by the constructor. Throws std::runtime_error naming the file if it exists
  /// but cannot be reopened (e.g. damaged by a crash while a snapshot was written).
  static SnapshotWriter resume(const std::filesystem::path &directory, const std::string &basename,
                               double keep_until_time);

  /// Appends one snapshot of the system at its current time and rewrites the .xdmf so that it is
  /// always valid (ParaView can open it while the run goes on). Throws std::runtime_error naming
  /// the file on failure.
  void write(const DemSystem &system);

  std::size_t n_snapshots() const { return xdmf_entries_.size(); }

  const std::filesystem::path &h5_path() const { return h5_path_; }
  const std::filesystem::path &xdmf_path() const { return xdmf_path_; }

private:
  SnapshotWriter(const std::filesystem::path &directory, const std::string &basename, bool create);
  void create_empty_files();
  void write_xdmf() const;

  std::filesystem::path h5_path_, xdmf_path_;
  std::string h5_name_;                    ///< file name of the .h5 as the .xdmf refers to it
  std::vector<std::string> xdmf_entries_;  ///< one <Grid> per snapshot
};
} // namespace geohybrid::dem

#pragma once
// The XDMF text of one snapshot: a <Grid> whose data items point into the HDF5 file
// (snapshot_writer.h gives the layout). Everything it needs is in the snapshot's attributes, so a
// resumed writer rebuilds the entries of the snapshots it keeps from the file alone. Helpers of
// SnapshotWriter, not part of its interface.
#include <cstdint>
#include <string>

namespace geohybrid::dem::snapshot_detail
{
/// The sizes of one snapshot, stored as its attributes.
struct SnapshotCounts
{
  std::uint64_t n_discs = 0, n_contacts = 0, n_wall_contacts = 0;
  std::uint64_t n_sheet_nodes = 0, n_sheet_segments = 0, n_sheet_contacts = 0;
};

/// The <Grid> of the snapshot `name` at `time` in the .xdmf, its datasets in the file `h5_name`.
std::string xdmf_entry(const std::string &h5_name, const std::string &name, double time, const SnapshotCounts &n);
} // namespace geohybrid::dem::snapshot_detail

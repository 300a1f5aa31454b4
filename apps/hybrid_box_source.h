#pragma once
// Where hybrid mode's particle box comes from: its own fill (the default), or a dem-mode fill of
// the same tank ('Hybrid/particles from' = that run's filled_tank.h5), the box's region cut out of
// it (dem/laboratory/tank_cut.h). Cut, the hybrid pulls the very grains pure DEM pulled round the
// sheet, and the two curves differ by what the continuum and the coupling do, not by a packing's
// scatter: the comparison of issue 26's "T_max within 3 %" made seed by seed.
#include "coupling/particle_box.h"
#include "dem/laboratory/pullout_tank.h"

#include <deal.II/base/parameter_handler.h>

#include <filesystem>
#include <string>

namespace geohybrid::apps
{
/// The entries a dem run's filled tank does not depend on, which may differ between it and the
/// hybrid run that cuts its box from it: the mode, subsections Hybrid, Continuum, Pull and Output,
/// and the run-control entries.
const std::vector<std::string> &entries_a_filled_tank_leaves_free();

/// The particle box of `box` cut from the filled tank in `file` (a dem-mode pull-out's
/// filled_tank.h5, or its checkpoint.h5 before the pull). Refuses (std::invalid_argument naming
/// `where`, 'Hybrid/particles from' and `file`) a file that cannot be read or is not a filled
/// dem-mode tank, and one whose input differs from `prm` in an entry the fill depends on (each
/// named with both values).
dem::PullOutTank box_cut_from_filled_tank(const std::filesystem::path &file, const dealii::ParameterHandler &prm,
                                          const dem::PullOutTankSpec &tank, const coupling::ParticleBox &box,
                                          const std::string &where);
} // namespace geohybrid::apps

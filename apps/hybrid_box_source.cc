#include "hybrid_box_source.h"

#include "parameters_hash.h"
#include "pullout_command.h"
#include "resume_check.h"

#include "dem/io/checkpoint.h"
#include "dem/laboratory/tank_cut.h"
#include "dem/laboratory/tank_filling.h"

#include <stdexcept>

namespace geohybrid::apps
{
const std::vector<std::string> &entries_a_filled_tank_leaves_free()
{
  static const std::vector<std::string> entries = [] {
    std::vector<std::string> e = pullout_run_control_entries();
    e.insert(e.end(), {"mode", "Hybrid/", "Continuum/", "Pull/", "Output/"});
    return e;
  }();
  return entries;
}

dem::PullOutTank box_cut_from_filled_tank(const std::filesystem::path &file, const dealii::ParameterHandler &prm,
                                          const dem::PullOutTankSpec &tank, const coupling::ParticleBox &box,
                                          const std::string &where)
{
  const std::string entry = where + ": parameter 'Hybrid/particles from' = '" + file.string() + "'";
  dem::CommandState saved;
  dem::DemSystemState state;
  try
    {
      state = dem::read_checkpoint(file, saved);
    }
  catch (const std::exception &e)
    {
      throw std::invalid_argument(entry + ": cannot read a filled tank there: " + e.what());
    }
  const std::optional<dem::PullProgress> progress = dem::restore_pull_progress(saved);
  // A dem run's input leaves 'mode' at its default: a hybrid run's filled_box.h5 is a box already.
  if (const auto input = saved.texts.find(checkpoint_input_key);
      input != saved.texts.end() && input->second.find("\nmode = ") != std::string::npos &&
      input->second.find("\nmode = dem\n") == std::string::npos)
    throw std::invalid_argument(entry + ": not a dem-mode run's tank; give a 'mode = dem' run's filled_tank.h5");
  dealii::ParameterHandler defaults;
  declare_pullout_parameters(defaults);
  const std::optional<std::string> differing =
    differing_entries(saved, prm, defaults, entries_a_filled_tank_leaves_free());
  if (!differing)
    throw std::invalid_argument(entry + ": the file keeps no input to check against (written by an older version)");
  if (!differing->empty())
    throw std::invalid_argument(entry + ": that tank was filled with another input: " + *differing +
                                " (the fill depends on all but the mode, Hybrid, Continuum, Pull, Output and the "
                                "run-control entries)");
  if (progress && progress->n_steps > 0)
    throw std::invalid_argument(entry + ": that tank has been pulled " + std::to_string(progress->n_steps) +
                                " steps; give the dem run's filled_tank.h5");
  const dem::PullOutTank filled =
    dem::restore_pullout_tank(std::move(state), dem::tank_settling_settings(tank.resolved_filling()), saved);
  return dem::cut_pull_out_tank(filled, tank.geometry.tank_length, box.box_tank, dem::Vec2(box.x0, box.y0), entry);
}
} // namespace geohybrid::apps

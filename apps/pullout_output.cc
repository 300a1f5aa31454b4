#include "pullout_output.h"

#include "apps/interrupt.h"
#include "apps/plot.h"
#include "dem/io/checked_output.h"

#include <algorithm>
#include <iostream>
#include <iomanip>
#include <locale>
#include <sstream>
#include <stdexcept>

namespace geohybrid::apps
{
PulloutOutput::PulloutOutput(const std::filesystem::path &directory, double sheet_width, std::vector<double> profiles_at)
  : directory_(directory), sheet_width_(sheet_width), profiles_at_(std::move(profiles_at)),
    curve_(directory / "pullout_curve.csv"), per_sheet_(directory / "pullout_curve_sheet.csv"),
    displacements_(directory / "sheet_displacements.csv"), profiles_(directory / "sheet_tension.csv")
{
  std::sort(profiles_at_.begin(), profiles_at_.end());
  for (std::ofstream *f : {&curve_, &per_sheet_, &displacements_, &profiles_})
    {
      f->imbue(std::locale::classic());
      *f << std::setprecision(10);
    }
  curve_ << "head_displacement_m,head_tension_kN_per_m\n";
  per_sheet_ << "head_displacement_m,head_tension_kN\n";
  displacements_ << "head_displacement_m,beginning_displacement_m,middle_displacement_m,end_displacement_m\n";
  profiles_ << "head_displacement_m,node,arc_length_m,x_m,y_m,tension_kN_per_m\n";
  flush();
}

void PulloutOutput::flush()
{
  // Flushed at every point, so that the files of a run killed or interrupted hold every row
  // recorded; a failed write (a full disk) stops the run naming the file, not later at its end.
  const std::pair<std::ofstream *, const char *> files[] = {{&curve_, "pullout_curve.csv"},
                                                            {&per_sheet_, "pullout_curve_sheet.csv"},
                                                            {&displacements_, "sheet_displacements.csv"},
                                                            {&profiles_, "sheet_tension.csv"}};
  for (const auto &[file, name] : files)
    dem::flush_checked(*file, directory_ / name);
}

PulloutOutput::PulloutOutput(const std::filesystem::path &directory, double sheet_width, std::vector<double> profiles_at,
                             const dem::CommandState &saved)
  : PulloutOutput(directory, sheet_width, std::move(profiles_at))
{
  const std::vector<double> &points = saved.real("curve_points");
  const std::vector<double> &profiles = saved.real("profile_rows");
  if (points.size() % 5 != 0 || profiles.size() % 6 != 0)
    throw std::runtime_error("checkpoint of 'pullout': the stored curve rows are incomplete");
  for (std::size_t k = 0; k < points.size(); k += 5)
    add_point(points[k], points[k + 1], {{points[k + 2], points[k + 3], points[k + 4]}});
  for (std::size_t k = 0; k < profiles.size(); k += 6)
    write_profile_row(&profiles[k]);
  profile_rows_ = profiles;
  next_profile_ = static_cast<std::size_t>(saved.count("next_profile", 1)[0]);
  flush();
}

void PulloutOutput::store(dem::CommandState &command) const
{
  command.reals["curve_points"] = points_;
  command.reals["profile_rows"] = profile_rows_;
  command.counts["next_profile"] = {next_profile_};
}

void PulloutOutput::add_point(double u, double T, const std::array<double, 3> &moved)
{
  const double row[5] = {u, T, moved[0], moved[1], moved[2]};
  points_.insert(points_.end(), row, row + 5);
  write_point(row);
  flush();
}

void PulloutOutput::write_point(const double *row)
{
  const double u = row[0], T = row[1];
  curve_ << u << ',' << T / 1e3 << '\n';
  per_sheet_ << u << ',' << T * sheet_width_ / 1e3 << '\n';
  displacements_ << u << ',' << row[2] << ',' << row[3] << ',' << row[4] << '\n';
  if (T > T_max_)
    {
      T_max_ = T;
      u_at_T_max_ = u;
    }
}

void PulloutOutput::write_profile_row(const double *r)
{
  profiles_ << r[0] << ',' << static_cast<std::size_t>(r[1]) << ',' << r[2] << ',' << r[3] << ',' << r[4] << ','
            << r[5] / 1e3 << '\n';
}

bool PulloutOutput::profile_due(double u) const
{
  return next_profile_ < profiles_at_.size() && u >= profiles_at_[next_profile_] - 1e-12;
}

void PulloutOutput::add_profile(double u, const std::vector<SheetTensionRow> &rows)
{
  for (; profile_due(u); ++next_profile_)
    for (const SheetTensionRow &r : rows)
      {
        const double row[6] = {u, static_cast<double>(r.segment), r.arc_length, r.x, r.y, r.tension};
        profile_rows_.insert(profile_rows_.end(), row, row + 6);
        write_profile_row(row);
      }
  flush();
}

void PulloutOutput::finish(const std::string &label, const CurveReferences &references, double final_displacement)
{
  flush();
  std::vector<PlotSeries> series{{directory_ / "pullout_curve.csv", 1, 2,
                                  references.demonstration.empty() ? label : label + ", demonstration", 1e3, 1.0}};
  if (const auto &full = references.full_size)
    {
      const std::filesystem::path file = directory_ / "reference_curve.csv";
      std::ofstream f(file);
      f << "head_displacement_m,head_tension_kN_per_m\n";
      for (const std::array<double, 2> &row : full->mean_curve)
        f << number(row[0]) << ',' << number(row[1]) << '\n';
      dem::close_checked(f, file);
      series.push_back({file, 1, 2,
                        "full size, mean of " + std::to_string(full->seeds.size()) + " seeds (" +
                          full->directory.string() + "), T_max " + number(full->T_max.mean, 4) + " kN/m",
                        1e3, 1.0, "lines lw 2 dt 1", {}});
    }
  if (const auto &T = references.experimental_T_max)
    {
      const std::filesystem::path line = directory_ / "experimental_T_max.csv";
      std::ofstream f(line);
      f << "head_displacement_m,T_max_kN_per_m\n0," << number(*T / 1e3) << '\n'
        << number(std::max(final_displacement, references.full_size ? references.full_size->mean_curve.back()[0] : 0.0))
        << ',' << number(*T / 1e3) << '\n';
      dem::close_checked(f, line);
      series.push_back({line, 1, 2, "experiment, T_max", 1e3, 1.0});
    }
  const std::string title = references.demonstration.empty()
                              ? std::string("Pull-out, head tension")
                              : "DEMONSTRATION, not a result: " + references.demonstration;
  plot_png(directory_ / "pullout_curve.png", title, {{"head displacement [mm]", "head tension [kN/m]", series}});
}

void PulloutOutput::fill_summary(Summary &summary, const std::string &mode, const std::string &anchorage,
                                 const CurveReferences &references) const
{
  const std::optional<double> &experimental_T_max = references.experimental_T_max;
  summary.set("command", "pullout");
  summary.set("mode", mode);
  summary.set("anchorage", anchorage);
  summary.set("T_max_kN_per_m", T_max_ / 1e3);
  summary.set("T_max_kN_for_sheet_width", T_max_ * sheet_width_ / 1e3);
  summary.set("head_displacement_at_T_max_m", u_at_T_max_);
  if (experimental_T_max)
    {
      summary.set("experimental_T_max_kN_per_m", *experimental_T_max / 1e3);
      summary.set("T_max_difference_percent", 100.0 * (T_max_ / *experimental_T_max - 1.0));
    }
  if (!references.demonstration.empty())
    summary.set("demonstration", references.demonstration);
  if (const auto &full = references.full_size)
    {
      summary.set("full_size_runs", full->directory.string());
      summary.set("full_size_n_seeds", static_cast<double>(full->seeds.size()));
      summary.set("full_size_T_max_kN_per_m", full->T_max.mean);
      summary.set("full_size_T_max_std_kN_per_m", full->T_max.std);
      summary.set("full_size_T_max_of_mean_curve_kN_per_m", full->T_max_of_mean_curve);
    }
}

dem::PullOutTank fill_with_progress(const dem::PullOutTankSpec &spec, const std::string &what)
{
  const std::string doing = "filling " + what;
  ProgressReport progress(doing, 1.0);
  dem::PullOutTank filled = dem::fill_pull_out_tank(spec, [&](double f) {
    progress.update(f);
    throw_if_interrupted(doing); // a partial fill cannot be resumed
  });
  progress.finish();
  return filled;
}

std::string fill_steps_per_layer(const dem::FilledTank &filled)
{
  std::ostringstream text;
  text << "fill steps per layer (growth + settling)";
  for (const dem::TankLayer &layer : filled.layers)
    text << ' ' << layer.n_growth_steps << '+' << layer.n_settling_steps << (layer.from_cache ? " (kept lift)" : "");
  text << ", lowest growth friction per layer";
  for (const dem::TankLayer &layer : filled.layers)
    text << ' ' << number(layer.growth_friction_deg, 3);
  text << " deg";
  return text.str();
}

void add_dem_sheet_point(PulloutOutput &output, const dem::PullOutTank &tank, const dem::SparSheet &sheet,
                         const dem::PullPoint &point, const dem::Vec2 &origin)
{
  const std::size_t middle = (tank.first_node_inside + tank.lower_part_end) / 2;
  const auto moved = [&](std::size_t k) { return sheet.x[k] - tank.initial_nodes[k].x(); };
  output.add_point(point.head_displacement, point.head_tension,
                   {{moved(tank.first_node_inside), moved(middle), moved(tank.lower_part_end)}});
  if (!output.profile_due(point.head_displacement))
    return;
  std::vector<SheetTensionRow> rows;
  for (std::size_t k = 0; k < sheet.n_segments(); ++k)
    rows.push_back({k, 0.5 * (tank.arc_length[k] + tank.arc_length[k + 1]),
                    origin.x() + 0.5 * (sheet.x[k] + sheet.x[k + 1]), origin.y() + 0.5 * (sheet.y[k] + sheet.y[k + 1]),
                    sheet.tension[k]});
  output.add_profile(point.head_displacement, rows);
}

void set_dem_sheet_summary(Summary &summary, const dem::SparSheet &sheet, double sheet_level, double cover_as_laid,
                           double gamma_H, const dem::SheetLevelStress &before, double one_face_friction)
{
  summary.set("n_sheet_nodes", static_cast<double>(sheet.n_nodes()));
  summary.set("sheet_level_m", sheet_level);
  summary.set("H_as_laid_m", cover_as_laid);
  summary.set("gamma_H_Pa", gamma_H);
  summary.set("sigma_v_top_face_Pa", before.top_face);
  summary.set("sigma_v_bottom_face_Pa", before.bottom_face);
  summary.set("sigma_v_love_weber_above_Pa", before.love_weber_above);
  summary.set("sigma_v_over_gamma_H", before.top_face / gamma_H);
  summary.set("one_face_friction_kN_per_m", one_face_friction / 1e3);
}
bool pull_with_checkpoints(dem::PullOut &pull, const std::function<void(const dem::PullPoint &)> &record,
                           const std::function<void()> &save_checkpoint, double checkpoint_interval,
                           std::uint64_t stop_after, const std::filesystem::path &checkpoint_file)
{
  WallClockInterval checkpoint_due(checkpoint_interval);
  std::uint64_t steps_now = 0;
  while (!pull.finished())
    {
      if (pull.step())
        record(pull.last_point());
      ++steps_now;
      // A signal (interrupt.h): the step is done, its point recorded; the checkpoint is the
      // periodic one, written whatever the interval, so that --resume goes on bit for bit.
      if (const int signal = interrupt_signal(); signal != 0 && !pull.finished())
        {
          save_checkpoint();
          std::cerr << '\n';
          throw Interrupted(signal,
                            "at " + number(1e3 * pull.head_displacement(), 4) + " mm of the pull (" +
                              std::to_string(steps_now) + " steps of this run): the checkpoint " +
                              checkpoint_file.string() + " and the curve files so far are written, no summary.json",
                            true);
        }
      const bool stop = stop_after > 0 && steps_now >= stop_after && !pull.finished();
      if (checkpoint_due.due() || stop)
        save_checkpoint();
      if (stop)
        {
          std::cerr << '\n';
          std::cout << "geohybrid pullout: stopped after " << steps_now << " steps as 'stop after steps' asks, at "
                    << number(1e3 * pull.head_displacement(), 4) << " mm; continue with --resume (checkpoint "
                    << checkpoint_file.string() << ")" << std::endl;
          return false;
        }
    }
  return true;
}
} // namespace geohybrid::apps

#include "pullout_output.h"

#include "apps/plot.h"

#include <algorithm>
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
  for (std::ofstream *f : {&curve_, &per_sheet_, &displacements_, &profiles_})
    if (!*f)
      throw std::runtime_error("cannot write the results in " + directory.string());
}

void PulloutOutput::add_point(double u, double T, const std::array<double, 3> &moved)
{
  curve_ << u << ',' << T / 1e3 << '\n';
  per_sheet_ << u << ',' << T * sheet_width_ / 1e3 << '\n';
  displacements_ << u << ',' << moved[0] << ',' << moved[1] << ',' << moved[2] << '\n';
  if (T > T_max_)
    {
      T_max_ = T;
      u_at_T_max_ = u;
    }
}

bool PulloutOutput::profile_due(double u) const
{
  return next_profile_ < profiles_at_.size() && u >= profiles_at_[next_profile_] - 1e-12;
}

void PulloutOutput::add_profile(double u, const std::vector<SheetTensionRow> &rows)
{
  for (; profile_due(u); ++next_profile_)
    for (const SheetTensionRow &r : rows)
      profiles_ << u << ',' << r.segment << ',' << r.arc_length << ',' << r.x << ',' << r.y << ',' << r.tension / 1e3
                << '\n';
}

void PulloutOutput::finish(const std::string &label, const std::optional<double> &experimental_T_max,
                           double final_displacement)
{
  for (std::ofstream *f : {&curve_, &per_sheet_, &displacements_, &profiles_})
    if (!f->flush())
      throw std::runtime_error("cannot write the results in " + directory_.string());
  std::vector<PlotSeries> series{{directory_ / "pullout_curve.csv", 1, 2, label, 1e3, 1.0}};
  if (experimental_T_max)
    {
      const std::filesystem::path line = directory_ / "experimental_T_max.csv";
      std::ofstream f(line);
      f << "head_displacement_m,T_max_kN_per_m\n0," << number(*experimental_T_max / 1e3) << '\n'
        << number(final_displacement) << ',' << number(*experimental_T_max / 1e3) << '\n';
      series.push_back({line, 1, 2, "experiment, T_max", 1e3, 1.0});
    }
  plot_png(directory_ / "pullout_curve.png", "Pull-out, head tension",
           {{"head displacement [mm]", "head tension [kN/m]", series}});
}

void PulloutOutput::fill_summary(Summary &summary, const std::string &mode, const std::string &anchorage,
                                 const std::optional<double> &experimental_T_max) const
{
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
}
} // namespace geohybrid::apps

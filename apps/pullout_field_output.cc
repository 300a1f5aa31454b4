#include "pullout_field_output.h"

#include "plot.h"

#include "dem/io/checked_output.h"
#include "dem/laboratory/pullout_fields.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <locale>
#include <sstream>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
std::string millimetres(double metres)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << std::setprecision(6) << 1e3 * metres;
  return s.str();
}
} // namespace

PullOutFieldOutput::PullOutFieldOutput(const std::filesystem::path &directory, std::vector<double> at, double width,
                                       double strip)
  : directory_(directory), at_(std::move(at)), width_(width), strip_(strip), snapshots_(directory, "pullout_fields")
{
  std::sort(at_.begin(), at_.end());
}

PullOutFieldOutput::PullOutFieldOutput(const std::filesystem::path &directory, std::vector<double> at, double width,
                                       double strip, const dem::CommandState &saved, const dem::DemSystem &system)
  : directory_(directory), at_(std::move(at)), width_(width), strip_(strip),
    // Half a step of slack: times are compared as written.
    snapshots_(dem::SnapshotWriter::resume(directory, "pullout_fields", system.time() + 0.5 * system.time_step()))
{
  std::sort(at_.begin(), at_.end());
  next_ = static_cast<std::size_t>(saved.count("fields_written", 1)[0]);
  if (next_ > at_.size())
    throw std::runtime_error("checkpoint of 'pullout': more field outputs written than 'Output/field outputs at' asks");
  if (saved.counts.count("fields_started") && saved.count("fields_started", 1)[0] != 0)
    {
      // Only the positions are read from the start (grain_displacements, surface_uplift); the
      // bodies and their sizes are those of the system now.
      dem::ParticleSet start = system.particles();
      const std::size_t nb = start.n_bodies(), nd = start.n_discs_total();
      const std::vector<double> &x = saved.real("fields_start_x", nb), &y = saved.real("fields_start_y", nb);
      const std::vector<double> &dx = saved.real("fields_start_disc_x", nd), &dy = saved.real("fields_start_disc_y", nd);
      std::copy(x.begin(), x.end(), start.x.begin());
      std::copy(y.begin(), y.end(), start.y.begin());
      std::copy(dx.begin(), dx.end(), start.disc_x.begin());
      std::copy(dy.begin(), dy.end(), start.disc_y.begin());
      start_ = std::move(start);
      find_surface();
    }
  const std::vector<double> &uplift = saved.real("fields_uplift");
  const std::size_t n_surface = surface_x_.size();
  if (uplift.size() != next_ * n_surface)
    throw std::runtime_error("checkpoint of 'pullout': the stored uplift profiles do not fit the surface");
  for (std::size_t k = 0; k < next_; ++k)
    {
      uplift_.emplace_back(uplift.begin() + k * n_surface, uplift.begin() + (k + 1) * n_surface);
      uplift_tags_.push_back(millimetres(at_[k]));
    }
}

void PullOutFieldOutput::store(dem::CommandState &command) const
{
  command.counts["fields_written"] = {next_};
  command.counts["fields_started"] = {start_ ? 1u : 0u};
  if (start_)
    {
      const dem::ParticleSet &p = *start_;
      command.reals["fields_start_x"].assign(p.x.begin(), p.x.end());
      command.reals["fields_start_y"].assign(p.y.begin(), p.y.end());
      command.reals["fields_start_disc_x"].assign(p.disc_x.begin(), p.disc_x.end());
      command.reals["fields_start_disc_y"].assign(p.disc_y.begin(), p.disc_y.end());
    }
  std::vector<double> &uplift = command.reals["fields_uplift"];
  uplift.clear();
  for (const std::vector<double> &u : uplift_)
    uplift.insert(uplift.end(), u.begin(), u.end());
}

void PullOutFieldOutput::find_surface()
{
  surface_id_.clear();
  surface_x_.clear();
  surface_y_.clear();
  for (const dem::SurfacePoint &s : dem::surface_uplift(*start_, *start_, width_, strip_))
    {
      surface_id_.push_back(s.body_id);
      surface_x_.push_back(s.x0);
      surface_y_.push_back(s.top0);
    }
}

void PullOutFieldOutput::record(double head_displacement, const dem::DemSystem &system)
{
  if (!start_)
    {
      start_ = system.particles();
      snapshots_.write(system);
      find_surface();
    }
  while (next_ < at_.size() && head_displacement >= at_[next_] - 1e-12)
    {
      write_fields(millimetres(at_[next_]), system);
      ++next_;
    }
}

void PullOutFieldOutput::write_fields(const std::string &tag, const dem::DemSystem &system)
{
  snapshots_.write(system);
  const dem::ParticleSet &now = system.particles();

  // Figure 10: the grains' displacements since the start of the pull.
  const std::filesystem::path grains = directory_ / ("grain_displacements_u" + tag + "mm.csv");
  std::ofstream g(grains);
  g << "body_id,x0_m,y0_m,x_m,y_m,dx_m,dy_m,vx_m_per_s,vy_m_per_s\n" << std::setprecision(12);
  double largest = 0.0;
  for (const dem::GrainDisplacement &d : dem::grain_displacements(*start_, now))
    {
      g << d.body_id << ',' << d.x0 << ',' << d.y0 << ',' << d.x << ',' << d.y << ',' << d.dx << ',' << d.dy << ','
        << d.vx << ',' << d.vy << '\n';
      largest = std::max(largest, std::hypot(d.dx, d.dy));
    }
  dem::close_checked(g, grains);
  // Arrows magnified so that the longest is 5 % of the tank.
  const double magnify = largest > 0.0 ? 0.05 * width_ / largest : 1.0;
  std::ostringstream title;
  title << "Grain displacements at a head displacement of " << tag << " mm (arrows x " << std::setprecision(3)
        << magnify << ")";
  plot_png(grains.string().substr(0, grains.string().size() - 4) + ".png", title.str(),
           {{"x [m]", "y [m]",
             {{grains, 2, 3, "displacement", 1.0, 1.0, "vectors head size screen 0.004,20 lw 1", {6, 7}, {magnify, magnify}}},
             "set size ratio -1"}});

  // Figure 12: the contact-force network, line width in proportion to the force.
  const std::filesystem::path forces = directory_ / ("force_network_u" + tag + "mm.csv");
  std::ofstream f(forces);
  f << "x_m,y_m,dx_m,dy_m,normal_force_N_per_m\n" << std::setprecision(12);
  double strongest = 0.0;
  for (const dem::ForceChain &c : dem::contact_force_network(system))
    {
      f << c.x1 << ',' << c.y1 << ',' << c.x2 - c.x1 << ',' << c.y2 - c.y1 << ',' << c.normal_force << '\n';
      strongest = std::max(strongest, c.normal_force);
    }
  dem::close_checked(f, forces);
  std::ostringstream force_title;
  force_title << "Contact normal forces [N/m] at a head displacement of " << tag << " mm (largest "
              << std::setprecision(3) << strongest << " N/m)";
  plot_png(forces.string().substr(0, forces.string().size() - 4) + ".png", force_title.str(),
           {{"x [m]", "y [m]",
             {{forces, 1, 2, "normal force", 1.0, 1.0, "vectors nohead lw 2 lc palette", {3, 4, 5}, {1.0, 1.0, 1.0}}},
             "set size ratio -1\nset palette defined (0 'grey90', 1 'orange', 2 'red', 3 'black')"}});

  // Figure 11: the uplift of the surface grains.
  std::vector<double> uplift;
  for (const dem::SurfacePoint &s : dem::surface_uplift(*start_, now, width_, strip_))
    uplift.push_back(s.uplift);
  uplift_.push_back(uplift);
  uplift_tags_.push_back(tag);
}

void PullOutFieldOutput::finish()
{
  if (surface_x_.empty())
    return;
  const std::filesystem::path file = directory_ / "surface_uplift.csv";
  std::ofstream out(file);
  out << "body_id,x_m,surface_y_m";
  for (const std::string &tag : uplift_tags_)
    out << ",uplift_m_at_" << tag << "mm";
  out << '\n' << std::setprecision(12);
  for (std::size_t k = 0; k < surface_x_.size(); ++k)
    {
      out << surface_id_[k] << ',' << surface_x_[k] << ',' << surface_y_[k];
      for (const std::vector<double> &u : uplift_)
        out << ',' << u[k];
      out << '\n';
    }
  dem::close_checked(out, file);
  std::vector<PlotSeries> series;
  for (std::size_t k = 0; k < uplift_tags_.size(); ++k)
    series.push_back({file, 2, static_cast<int>(4 + k), "head displacement " + uplift_tags_[k] + " mm", 1e3, 1e3});
  if (!series.empty())
    plot_png(directory_ / "surface_uplift.png", "Uplift of the soil surface",
             {{"x [mm]", "vertical displacement of the surface grains [mm]", series}});
}
} // namespace geohybrid::apps

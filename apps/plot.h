#pragma once
// PNG plots of CSV results through gnuplot (Debian package gnuplot-nox). The gnuplot script is
// kept beside the PNG so a user can restyle the figure.
#include <filesystem>
#include <string>
#include <vector>

namespace geohybrid::apps
{
struct PlotSeries
{
  std::filesystem::path csv;  ///< comma-separated, one header line
  int x_column, y_column;     ///< 1-based
  std::string label;
  double x_scale = 1.0, y_scale = 1.0; ///< e.g. 1e-3 to plot Pa as kPa
};

struct PlotPanel
{
  std::string x_label, y_label;
  std::vector<PlotSeries> series;
};

/// Writes PNG.gp and runs gnuplot to make PNG with the panels stacked vertically. Returns false
/// (and says why on stderr) if gnuplot is not installed or fails; the results stay valid.
bool plot_png(const std::filesystem::path &png, const std::string &title, const std::vector<PlotPanel> &panels);
} // namespace geohybrid::apps

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
  std::string style = "lines lw 2";    ///< gnuplot's 'with' clause
  /// Further columns after x and y, each scaled by y_scale (e.g. the upper bound of a band for
  /// 'filledcurves', or dx, dy for 'vectors', then scaled as x and y: see scale_extra_as_x_y).
  std::vector<int> extra_columns = {};
  bool scale_extra_as_x_y = false; ///< extra columns scaled x, y, x, y, ... instead of all by y_scale
};

struct PlotPanel
{
  std::string x_label, y_label;
  std::vector<PlotSeries> series;
  std::string settings = ""; ///< gnuplot commands before the panel's plot (e.g. "set size ratio -1")
};

/// Writes PNG.gp and runs gnuplot to make PNG with the panels stacked vertically. Returns false
/// (and says why on stderr) if gnuplot is not installed or fails; the results stay valid.
bool plot_png(const std::filesystem::path &png, const std::string &title, const std::vector<PlotPanel> &panels);
} // namespace geohybrid::apps

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
  /// Further columns after x and y (e.g. the upper bound of a band for 'filledcurves', or dx, dy
  /// and a line width for 'vectors'), each scaled by its extra_scales entry, y_scale if none.
  std::vector<int> extra_columns = {};
  std::vector<double> extra_scales = {};
  /// gnuplot's 'every' clause, to plot some rows of a file ("::2::5": the third to the sixth row
  /// after the header); empty: every row.
  std::string every = "";
};

struct PlotPanel
{
  std::string x_label, y_label;
  std::vector<PlotSeries> series;
  std::string settings = ""; ///< gnuplot commands before the panel's plot (e.g. "set size ratio -1")
};

/// Writes PNG.gp and runs gnuplot to make PNG with the panels stacked vertically. Returns false
/// (and says why on stderr) if gnuplot is not installed or fails; the results stay valid. Throws
/// std::runtime_error naming PNG.gp if it cannot be written, or naming PNG if gnuplot left it cut
/// short (a full disk: dem/io/checked_output.h).
bool plot_png(const std::filesystem::path &png, const std::string &title, const std::vector<PlotPanel> &panels);
} // namespace geohybrid::apps

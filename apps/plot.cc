#include "plot.h"

#include "dem/io/checked_output.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
/// `text` as a gnuplot single-quoted string: a quote inside is doubled (a title or a path with an
/// apostrophe would otherwise end the string and break the script).
std::string quoted(const std::string &text)
{
  std::string q = "'";
  for (const char c : text)
    q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

/// Whether `png` is a whole PNG file: its signature first and its IEND chunk last (the chunk's
/// type and its fixed CRC). gnuplot exits 0 when the disk fills under its PNG: cairo's failed
/// writes are not its errors, and the file is left cut short.
bool png_is_complete(const std::filesystem::path &png)
{
  std::ifstream f(png, std::ios::binary);
  char head[8] = {}, tail[8] = {};
  if (!f.read(head, 8))
    return false;
  f.seekg(-8, std::ios::end);
  if (!f.read(tail, 8))
    return false;
  const char signature[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};
  const char iend[8] = {'I', 'E', 'N', 'D', '\xae', '\x42', '\x60', '\x82'};
  return std::equal(head, head + 8, signature) && std::equal(tail, tail + 8, iend);
}
} // namespace

bool plot_png(const std::filesystem::path &png, const std::string &title, const std::vector<PlotPanel> &panels)
{
  const std::filesystem::path script = png.string() + ".gp";
  {
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 900," << 420 * panels.size() << " font ',11'\n"
       << "set output " << quoted(png.string()) << "\n"
       // Titles, labels and paths as written: no subscripts from their underscores.
       << "set termoption noenhanced\n"
       << "set datafile separator ','\nset key autotitle columnhead\nset grid\n"
       << "set multiplot layout " << panels.size() << ",1 title " << quoted(title) << "\n";
    for (const PlotPanel &panel : panels)
      {
        gp << panel.settings << (panel.settings.empty() ? "" : "\n") << "set xlabel " << quoted(panel.x_label)
           << "\nset ylabel " << quoted(panel.y_label) << "\nplot ";
        for (std::size_t k = 0; k < panel.series.size(); ++k)
          {
            const PlotSeries &s = panel.series[k];
            gp << (k ? ", " : "") << quoted(s.csv.string()) << (s.every.empty() ? "" : " every " + s.every)
               << " using ($" << s.x_column << "*" << s.x_scale << "):($"
               << s.y_column << "*" << s.y_scale << ")";
            for (std::size_t e = 0; e < s.extra_columns.size(); ++e)
              gp << ":($" << s.extra_columns[e] << "*" << (e < s.extra_scales.size() ? s.extra_scales[e] : s.y_scale) << ")";
            gp << " with " << s.style << " title " << quoted(s.label);
          }
        gp << "\n";
        if (!panel.settings.empty())
          gp << "reset\nset datafile separator ','\nset key autotitle columnhead\nset grid\n";
      }
    gp << "unset multiplot\n";
    // A script cut short by a full disk would only make gnuplot fail, with a note that the
    // results are complete: the disk's failure is the run's.
    dem::close_checked(gp, script);
  }
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0)
    {
      std::cerr << "note: gnuplot is not installed; " << script.string() << " can make " << png.string()
                << " later (apt-get install gnuplot-nox)\n";
      return false;
    }
  const std::string command = "gnuplot '" + script.string() + "' 2> '" + script.string() + ".log'";
  const int status = std::system(command.c_str());
  // A PNG begun and cut short is a write that failed (a full disk), whatever gnuplot said: the
  // run stops there, as for a CSV, rather than ending with a broken figure beside its summary.
  if (std::filesystem::exists(png) && !png_is_complete(png))
    throw std::runtime_error(dem::write_failure_message(png));
  if (status != 0)
    {
      std::cerr << "note: gnuplot failed on " << script.string() << " (see its .log); the CSV results are complete\n";
      return false;
    }
  std::filesystem::remove(script.string() + ".log");
  return true;
}
} // namespace geohybrid::apps

// `geohybrid biaxial`: the calibration test of the reference paper (section 4.2). One sample is
// made by REDF at the lowest confining stress (or read from 'Sample/sample file', where it is
// saved otherwise: making it is the costly part). For each confining stress a copy of it is
// consolidated isotropically to that stress, as a triaxial sample is before shearing, then
// compressed by the top wall at a speed giving a small inertial number while the lateral walls
// hold the confining stress. The tests run concurrently. Outputs:
//   biaxial_<sigma>kPa.csv  axial strain, deviatoric stress, volumetric strain, wall stresses
//   biaxial.png             deviator and volumetric strain against axial strain
//   summary.json            peak/residual friction angle, cohesion, E, E50, Poisson ratio, psi
//   continuum_soil.prm      the plane-strain Mohr-Coulomb continuum with the same response, a
//                           'subsection Continuum' fragment for pull-outs in mode = fem
#include "biaxial_command.h"

#include "plot.h"
#include "run_directory.h"

#include "dem/io/checked_output.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace geohybrid::apps
{
using dealii::ParameterHandler;

void set_biaxial_results(Summary &summary, const dem::BiaxialParameters &r, double porosity)
{
  summary.set("peak_friction_angle_deg", r.peak_friction_angle_deg);
  summary.set("residual_friction_angle_deg", r.residual_friction_angle_deg);
  summary.set("cohesion_Pa", r.cohesion);
  summary.set("young_modulus_Pa", r.young_modulus);
  summary.set("young_modulus_50_Pa", r.young_modulus_50);
  summary.set("poisson_ratio", r.poisson_ratio);
  summary.set("dilatancy_angle_deg", r.dilatancy_angle_deg);
  summary.set("porosity", porosity);
}

/// The continuum soil with the biaxial response of this DEM soil (dem::continuum_equivalent), as a
/// 'subsection Continuum' fragment that a pull-out input includes after its own, so that its fem
/// mode runs the same soil as its dem mode. Returns the reason when there is no such continuum
/// (nothing written then), or an empty string.
std::string write_continuum_fragment(const std::filesystem::path &file, const dem::BiaxialParameters &r,
                                     const std::string &input_file)
{
  const dem::ContinuumEquivalent c = dem::continuum_equivalent(r);
  if (!c.invalid_reason.empty())
    return c.invalid_reason;
  if (c.poisson_ratio > 0.49) // the largest 'Continuum/Poisson ratio' geohybrid pullout takes
    return "its plane-strain Poisson ratio " + number(c.poisson_ratio, 4) + " is above 0.49";
  // Whole or absent (dem::write_whole_file): a pull-out's input includes this file, and a cut one
  // would read as a continuum of default entries.
  std::ostringstream f;
  f << "# The continuum soil with the biaxial response of the DEM soil of `geohybrid biaxial " << input_file << "`:\n"
    << "# plane strain, E = E_2D (1 - nu^2) and nu = nu_2D / (1 + nu_2D) from the biaxial's E_2D = "
    << number(r.young_modulus, 6) << " Pa and nu_2D = " << number(r.poisson_ratio, 4) << ",\n"
    << "# the peak friction angle and cohesion of the Mohr-Coulomb fit over the confinements, the dilatancy\n"
    << "# angle at the peak dilation rate (dem/laboratory/biaxial_test.h, continuum_equivalent). For a pull-out's\n"
    << "# mode = fem: a line 'include " << file.filename().string()
    << "' (path relative to the working directory) after its subsection Continuum.\n"
    << "subsection Continuum\n"
    << "  set soil model = Mohr-Coulomb\n"
    << "  set Young modulus = " << number(c.young_modulus) << "\n"
    << "  set Poisson ratio = " << number(c.poisson_ratio) << "\n"
    << "  set friction angle = " << number(c.friction_angle_deg) << "\n"
    << "  set cohesion = " << number(c.cohesion) << "\n"
    << "  set dilatancy angle = " << number(c.dilatancy_angle_deg) << "\n"
    << "end\n";
  dem::write_whole_file(file, f.str());
  return "";
}

int run_biaxial_command(const std::string &input_file, bool resume)
{
  if (resume)
    throw std::invalid_argument("geohybrid biaxial: --resume is not supported; a campaign takes minutes, rerun it");
  ParameterHandler prm;
  declare_biaxial_parameters(prm);
  parse_input_file(prm, input_file);
  const std::string where = "input file '" + input_file + "'";
  const BiaxialCampaign campaign = parse_biaxial_campaign(prm, where);
  try // a sample file that cannot serve stops the run before any output
    {
      read_campaign_sample(campaign);
    }
  catch (const std::invalid_argument &e)
    {
      throw std::invalid_argument(where + ": " + e.what());
    }
  catch (const std::runtime_error &e)
    {
      throw std::runtime_error(where + ": " + e.what());
    }

  const std::filesystem::path out = prepare_output_directory(prm.get("output directory"), false);
  write_resolved_parameters(prm, out);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<dem::BiaxialCurve> curves = run_biaxial_campaign(campaign, true);
  const double wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  PlotPanel deviator{"axial strain [%]", "deviatoric stress [kPa]", {}};
  PlotPanel volume{"axial strain [%]", "volumetric strain [%] (compression > 0)", {}};
  for (const dem::BiaxialCurve &c : curves)
    {
      const std::string tag = std::to_string(static_cast<int>(std::lround(c.confining_stress / 1e3))) + "kPa";
      const std::filesystem::path csv = out / ("biaxial_" + tag + ".csv");
      std::ofstream f(csv);
      f << std::setprecision(10)
        << "axial_strain,deviatoric_stress_Pa,volumetric_strain,lateral_strain,axial_stress_Pa,lateral_stress_Pa\n";
      for (const dem::BiaxialPoint &p : c.points)
        f << p.axial_strain << ',' << p.deviatoric_stress << ',' << p.volumetric_strain << ',' << p.lateral_strain
          << ',' << p.axial_stress << ',' << p.lateral_stress << '\n';
      dem::close_checked(f, csv);
      deviator.series.push_back({csv, 1, 2, "sigma_0 = " + tag, 100.0, 1e-3});
      volume.series.push_back({csv, 1, 3, "sigma_0 = " + tag, 100.0, 100.0});
    }
  plot_png(out / "biaxial.png", "Biaxial compression (one REDF sample)", {deviator, volume});

  const dem::BiaxialParameters r = dem::analyse_biaxial_curves(curves);
  const std::string no_continuum = write_continuum_fragment(out / "continuum_soil.prm", r, input_file);
  Summary summary;
  summary.set("command", "biaxial");
  summary.set("continuum_fragment", no_continuum.empty() ? "continuum_soil.prm" : "not written: " + no_continuum);
  const double porosity = mean_initial_porosity(curves);
  double inertial = 0.0;
  for (const dem::BiaxialCurve &c : curves)
    inertial = std::max(inertial, c.inertial_number);
  set_biaxial_results(summary, r, porosity);
  summary.set("max_inertial_number", inertial);
  summary.set("n_particles", static_cast<double>(campaign.sample.n_particles));
  summary.set("sample_file", campaign.sample_file.string());
  summary.set("wall_time_s", wall_time);
  // The paper's sand 1 (triaxial tests at INSA, section 4.2): phi' = 38.4 deg, E = 20 MPa.
  summary.set("reference_friction_angle_deg", 38.4);
  summary.set("reference_young_modulus_Pa", 20e6);
  summary.write(out / "summary.json");
  std::cout << std::setprecision(4) << "geohybrid biaxial: peak friction angle " << r.peak_friction_angle_deg
            << " deg (paper's sand 1: 38.4), residual " << r.residual_friction_angle_deg << " deg, cohesion "
            << r.cohesion << " Pa, E " << r.young_modulus / 1e6 << " MPa (paper: 20), E50 " << r.young_modulus_50 / 1e6
            << " MPa, nu " << r.poisson_ratio << ", psi " << r.dilatancy_angle_deg << " deg; porosity " << porosity
            << "; " << wall_time << " s\nresults in " << out.string() << " (summary.json, biaxial.png, biaxial_*.csv"
            << (no_continuum.empty() ? ", continuum_soil.prm)\n" : ")\nno continuum_soil.prm: " + no_continuum + "\n");
  return 0;
}
} // namespace geohybrid::apps

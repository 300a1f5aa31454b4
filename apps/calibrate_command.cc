// `geohybrid calibrate`: the calibration of the reference paper (section 4.2) done by the
// program instead of by hand. The paper fitted kn to the tangent elastic modulus, chose ks/kn for
// the Poisson ratio and fitted the contact friction to the peak of the triaxial curves; here each
// iteration is one biaxial campaign (the input's Sample and Test) run with the current guess, and
// dem::calibrate_micro_parameters turns what it measured into the next guess.
//
// Which sample each campaign shears ('Calibration/sample'):
//   reuse   one REDF sample per confining stress, made once with the starting parameters, given
//           each guess's contact laws and brought back to equilibrium
//           (dem/laboratory/sample_reuse.h). One fabric for every iteration, so the response varies
//           smoothly with the parameters: on a 200-cluster sample a 1 % change of kn moved phi' by
//           0.5 to 1 deg and E by 1 % this way, against 1.3 deg and 40 % with a new sample (which
//           is another random assembly).
//   remake  a new REDF sample per iteration, made with the guess's parameters, exactly what
//           `geohybrid biaxial` does with them; the scatter between samples then adds to the
//           measurement, which is fine on large samples only.
//
// Outputs, in the output directory:
//   calibration.csv      one row per iteration: the micro-parameters, what they gave, the errors
//   calibrated_soil.prm  a 'subsection Particle contact' fragment, to include in later inputs
//   summary.json         written last, only when the targets are met
#include "calibrate_command.h"

#include "biaxial_command.h"
#include "run_directory.h"

#include "dem/io/checked_output.h"
#include "dem/laboratory/calibration.h"
#include "dem/laboratory/sample_reuse.h"
#include "dem/measurements.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <unistd.h>

namespace geohybrid::apps
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_calibrate_parameters(ParameterHandler &prm)
{
  declare_biaxial_parameters(prm);
  // Redeclared: a calibration's results do not belong with those of a single biaxial run.
  prm.declare_entry("output directory", "output/calibrate", Patterns::Anything(),
                    "Directory for all results, created if needed, relative to the working directory");

  prm.enter_subsection("Calibration");
  prm.declare_entry("target friction angle", "", Patterns::Anything(),
                    "Peak friction angle phi' to reach (Mohr-Coulomb fit of the peaks over the confining "
                    "stresses); required [deg]");
  prm.declare_entry("target Young modulus", "", Patterns::Anything(),
                    "Initial tangent Young modulus E to reach (as 'young_modulus_Pa' of geohybrid biaxial, "
                    "averaged over the confining stresses); required [Pa]");
  prm.declare_entry("target Poisson ratio", "", Patterns::Anything(),
                    "Initial Poisson ratio to reach by adjusting ks/kn; empty or negative = not targeted, "
                    "ks/kn stays as given in 'Particle contact' [-]");
  prm.declare_entry("friction angle tolerance", "0.5", Patterns::Double(),
                    "Accepted |phi' - target|, positive [deg]");
  prm.declare_entry("Young modulus tolerance", "0.05", Patterns::Double(),
                    "Accepted |E - target| / target, positive [-]");
  prm.declare_entry("Poisson ratio tolerance", "0.02", Patterns::Double(),
                    "Accepted |nu - target|, positive [-]");
  prm.declare_entry("sample", "reuse", Patterns::Selection("reuse|remake"),
                    "reuse: one REDF sample per confining stress, made with the starting parameters and given each "
                    "iteration's contact laws (one fabric: smooth response, and REDF runs once); remake: a new REDF "
                    "sample per iteration, as geohybrid biaxial makes (sample-to-sample scatter adds to the "
                    "measurements) [-]");
  prm.declare_entry("maximum iterations", "12", Patterns::Integer(1, 1000),
                    "Biaxial campaigns at most; the calibration fails if the targets are not met by then [-]");
  prm.declare_entry("scale wall stiffness", "true", Patterns::Bool(),
                    "Whether the biaxial walls' kn and ks follow the particles' kn (keeping the input's ratio), "
                    "so that the compliance of the wall contacts does not bias E as kn changes [-]");
  prm.declare_entry("fragment file", "calibrated_soil.prm", Patterns::Anything(),
                    "Name of the .prm fragment with the calibrated 'Particle contact' subsection, written in "
                    "the output directory [-]");
  prm.leave_subsection();
}

namespace
{
/// A number entry of the Calibration subsection that may be left empty.
std::optional<double> optional_number(ParameterHandler &prm, const std::string &entry, const std::string &where)
{
  const std::string text = prm.get(entry);
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos)
    return std::nullopt;
  std::istringstream in(text.substr(first));
  in.imbue(std::locale::classic());
  double value;
  if (!(in >> value) || !(in >> std::ws).eof() || !std::isfinite(value))
    throw std::invalid_argument(where + ": 'Calibration/" + entry + "' = '" + text + "' is not a number");
  return value;
}

/// With its sign always shown, for errors.
std::string signed_number(double value, int digits) { return (value >= 0.0 ? "+" : "") + number(value, digits); }

/// The value an input file holding number(value) gives back: what the fragment will carry.
double as_written(double value) { return std::stod(number(value)); }

struct CalibrationInput
{
  dem::CalibrationTargets targets;
  bool scale_wall_stiffness = true;
  bool reuse_sample = true;
  std::string fragment_file;
};

CalibrationInput parse_calibration(ParameterHandler &prm, const std::string &where)
{
  CalibrationInput c;
  dem::CalibrationTargets &t = c.targets;
  prm.enter_subsection("Calibration");
  const auto required = [&](const std::string &entry, const std::string &what) {
    const std::optional<double> value = optional_number(prm, entry, where);
    if (!value)
      throw std::invalid_argument(where + ": 'Calibration/" + entry + "' is missing: give the " + what);
    return *value;
  };
  const auto positive = [&](const std::string &entry, double value, const std::string &unit) {
    if (!(value > 0.0))
      throw std::invalid_argument(where + ": 'Calibration/" + entry + "' = " + number(value) + " must be positive" +
                                  unit);
    return value;
  };
  t.friction_angle_deg = required("target friction angle", "peak friction angle to reach [deg]");
  if (!(t.friction_angle_deg > 0.0 && t.friction_angle_deg < 90.0))
    throw std::invalid_argument(where + ": 'Calibration/target friction angle' = " + number(t.friction_angle_deg) +
                                " must lie between 0 and 90 deg");
  t.young_modulus = positive("target Young modulus", required("target Young modulus", "Young modulus to reach [Pa]"),
                             " [Pa]");
  const std::optional<double> nu = optional_number(prm, "target Poisson ratio", where);
  if (nu && *nu >= 0.0)
    {
      if (!(*nu < 1.0))
        throw std::invalid_argument(where + ": 'Calibration/target Poisson ratio' = " + number(*nu) +
                                    " must be below 1 for a 2D medium (leave it empty not to target it)");
      t.poisson_ratio = *nu;
    }
  t.friction_angle_tolerance_deg = positive("friction angle tolerance", prm.get_double("friction angle tolerance"), " [deg]");
  t.young_modulus_tolerance = positive("Young modulus tolerance", prm.get_double("Young modulus tolerance"), " [-]");
  t.poisson_ratio_tolerance = positive("Poisson ratio tolerance", prm.get_double("Poisson ratio tolerance"), " [-]");
  t.max_iterations = static_cast<std::size_t>(prm.get_integer("maximum iterations"));
  c.scale_wall_stiffness = prm.get_bool("scale wall stiffness");
  c.reuse_sample = prm.get("sample") == "reuse";
  c.fragment_file = prm.get("fragment file");
  prm.leave_subsection();
  if (c.fragment_file.empty() || c.fragment_file.find('/') != std::string::npos || c.fragment_file == "." ||
      c.fragment_file == "..")
    throw std::invalid_argument(where + ": 'Calibration/fragment file' = '" + c.fragment_file +
                                "' must be a plain file name (it is written in the output directory)");
  if (c.fragment_file == "summary.json" || c.fragment_file == "calibration.csv" || c.fragment_file == "parameters.prm")
    throw std::invalid_argument(where + ": 'Calibration/fragment file' = '" + c.fragment_file +
                                "' is the name of another output of the run");
  return c;
}

/// The biaxial campaign of the input with the contact parameters of `micro`.
BiaxialCampaign with_micro_parameters(const BiaxialCampaign &input, const dem::MicroParameters &micro,
                                      bool scale_wall_stiffness)
{
  BiaxialCampaign c = input;
  dem::ContactParameters &particle = c.sample.particle_contact;
  // The campaign runs with exactly the values the fragment will hold, so an input including the
  // fragment reproduces the last campaign bit for bit.
  particle.friction_angle_deg = as_written(micro.friction_angle_deg);
  particle.normal_stiffness = as_written(micro.normal_stiffness);
  particle.shear_stiffness = as_written(micro.stiffness_ratio * micro.normal_stiffness);
  if (scale_wall_stiffness)
    {
      const double factor = particle.normal_stiffness / input.sample.particle_contact.normal_stiffness;
      c.sample.wall_contact.normal_stiffness = as_written(input.sample.wall_contact.normal_stiffness * factor);
      c.sample.wall_contact.shear_stiffness = as_written(input.sample.wall_contact.shear_stiffness * factor);
    }
  return c;
}

/// A REDF sample at one confining stress, kept to be sheared with many contact laws.
struct PreparedSample
{
  dem::RedfSample sample;
  double confining_stress;
  double mean_diameter; ///< of a disc of the mean particle area, for the inertial number
};

std::string label_of(double confining_stress)
{
  return "biaxial " + std::to_string(static_cast<int>(std::lround(confining_stress / 1e3))) + " kPa";
}

std::vector<PreparedSample> prepare_samples(const BiaxialCampaign &campaign, bool show_progress)
{
  std::vector<PreparedSample> samples;
  for (const double sigma_0 : campaign.confining_stresses)
    {
      dem::RedfSpec spec = campaign.sample;
      spec.target_stress = sigma_0;
      ProgressReport progress(label_of(sigma_0) + ", REDF sample", 1.0);
      dem::RedfSample sample = dem::make_redf_sample(
        spec, show_progress ? std::function<void(double)>([&](double f) { progress.update(f); }) : std::function<void(double)>());
      if (show_progress)
        progress.finish();
      const dem::ParticleSet &p = sample.system.particles();
      const double mean_diameter = 2.0 * std::sqrt(dem::total_solid_area(p) / (dem::pi * p.n_bodies()));
      samples.push_back({std::move(sample), sigma_0, mean_diameter});
    }
  return samples;
}

/// The biaxial tests of `campaign` (its contact laws and Test) on copies of the prepared samples.
std::vector<dem::BiaxialCurve> shear_prepared_samples(const std::vector<PreparedSample> &samples,
                                                      const BiaxialCampaign &campaign, bool show_progress)
{
  std::vector<dem::BiaxialCurve> curves;
  for (const PreparedSample &prepared : samples)
    {
      dem::DemSystem system = prepared.sample.system;
      const dem::RectangularBox &box = prepared.sample.box;
      dem::change_contact_laws(system, box, campaign.sample.particle_contact, campaign.sample.wall_contact,
                               prepared.confining_stress);
      dem::BiaxialSpec test = campaign.test;
      test.confining_stress = prepared.confining_stress;
      const std::string label = label_of(prepared.confining_stress);
      ProgressReport progress(label + ", compression", 1.0);
      dem::BiaxialCurve curve = dem::run_biaxial_test(
        system, box, test, prepared.mean_diameter, campaign.sample.density,
        show_progress ? std::function<void(double)>([&](double f) { progress.update(f); }) : std::function<void(double)>());
      if (show_progress)
        progress.finish();
      if (curve.inertial_number > 1e-3)
        std::cerr << "warning: " << label << ": inertial number " << curve.inertial_number
                  << " is above 1e-3; the test is not quasi-static (lower 'top wall speed' or 'inertial number')\n";
      curves.push_back(std::move(curve));
    }
  return curves;
}

std::string confinements_kpa(const BiaxialCampaign &campaign)
{
  std::string text;
  for (const double sigma_0 : campaign.confining_stresses)
    text += (text.empty() ? "" : ", ") + number(sigma_0 / 1e3, 6);
  return text + " kPa";
}
} // namespace

int run_calibrate_command(const std::string &input_file, bool resume)
{
  if (resume)
    throw std::invalid_argument("geohybrid calibrate: --resume is not supported; rerun the calibration (the "
                                "iterations so far are in calibration.csv: start from the last row)");
  ParameterHandler prm;
  declare_calibrate_parameters(prm);
  parse_input_file(prm, input_file);
  const std::string where = "input file '" + input_file + "'";
  const BiaxialCampaign campaign = parse_biaxial_campaign(prm, where);
  const CalibrationInput input = parse_calibration(prm, where);
  const dem::CalibrationTargets &targets = input.targets;
  const dem::ContactParameters &start_contact = campaign.sample.particle_contact;
  dem::MicroParameters start;
  start.friction_angle_deg = start_contact.friction_angle_deg;
  start.normal_stiffness = start_contact.normal_stiffness;
  start.stiffness_ratio = start_contact.shear_stiffness / start_contact.normal_stiffness;
  if (!(start.stiffness_ratio > 0.0))
    throw std::invalid_argument(where + ": 'Particle contact/shear stiffness' must be positive for a calibration "
                                "(it is the starting ks/kn)");

  const std::filesystem::path out = prepare_output_directory(prm.get("output directory"), false);
  // A fragment from an earlier run must not pass for the result of this one.
  std::filesystem::remove(out / input.fragment_file);
  write_resolved_parameters(prm, out);
  std::ofstream csv(out / "calibration.csv");
  csv << "iteration,friction_angle_deg,normal_stiffness_N_per_m_per_m,stiffness_ratio,peak_friction_angle_deg,"
         "young_modulus_Pa,poisson_ratio,friction_angle_error_deg,young_modulus_relative_error,poisson_ratio_error,"
         "converged,campaign_wall_time_s\n";
  dem::flush_checked(csv, out / "calibration.csv");

  std::cout << "geohybrid calibrate: targets phi' = " << number(targets.friction_angle_deg, 4) << " +/- "
            << number(targets.friction_angle_tolerance_deg, 3) << " deg, E = " << number(targets.young_modulus / 1e6, 4)
            << " MPa +/- " << number(100.0 * targets.young_modulus_tolerance, 3) << " %, nu "
            << (targets.poisson_ratio ? "= " + number(*targets.poisson_ratio, 3) + " +/- " +
                                          number(targets.poisson_ratio_tolerance, 3)
                                      : std::string("not targeted"))
            << "; " << campaign.sample.n_particles << " particles at " << confinements_kpa(campaign) << std::endl;

  // What the model keeps of the last campaign, for the summary.
  dem::BiaxialParameters last_parameters;
  double last_porosity = 0.0, last_wall_time = 0.0;
  std::size_t n_campaigns = 0;
  const bool show_progress = isatty(fileno(stderr)) != 0; // in a log, the iteration lines suffice
  std::vector<PreparedSample> prepared;
  if (input.reuse_sample)
    {
      const auto start_time = std::chrono::steady_clock::now();
      prepared = prepare_samples(with_micro_parameters(campaign, start, input.scale_wall_stiffness), show_progress);
      std::cout << "calibrate: REDF samples made with the starting parameters (porosity "
                << number(prepared.front().sample.result.porosity, 4) << "); "
                << number(std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count(), 3)
                << " s" << std::endl;
    }
  const dem::BiaxialModel model = [&](const dem::MicroParameters &micro) {
    ++n_campaigns;
    const auto start_time = std::chrono::steady_clock::now();
    std::vector<dem::BiaxialCurve> curves;
    try
      {
        const BiaxialCampaign guess = with_micro_parameters(campaign, micro, input.scale_wall_stiffness);
        curves = input.reuse_sample ? shear_prepared_samples(prepared, guess, show_progress)
                                    : run_biaxial_campaign(guess, show_progress);
      }
    catch (const std::exception &e)
      {
        throw std::runtime_error("calibration iteration " + std::to_string(n_campaigns) + " (friction angle " +
                                 number(micro.friction_angle_deg, 6) + " deg, kn " + number(micro.normal_stiffness, 6) +
                                 " N/m/m, ks/kn " + number(micro.stiffness_ratio, 6) + "): " + e.what());
      }
    last_wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    last_parameters = dem::analyse_biaxial_curves(curves);
    last_porosity = mean_initial_porosity(curves);
    dem::MacroResponse m;
    m.friction_angle_deg = last_parameters.peak_friction_angle_deg;
    m.young_modulus = last_parameters.young_modulus;
    m.poisson_ratio = last_parameters.poisson_ratio;
    return m;
  };
  const auto report = [&](const dem::CalibrationIteration &it) {
    const dem::MicroParameters &p = it.micro;
    const dem::MacroResponse &m = it.macro;
    csv << std::setprecision(12) << it.index << ',' << p.friction_angle_deg << ',' << p.normal_stiffness << ','
        << p.stiffness_ratio << ',' << m.friction_angle_deg << ',' << m.young_modulus << ',' << m.poisson_ratio << ','
        << it.friction_angle_error_deg << ',' << it.young_modulus_error << ','
        << (targets.poisson_ratio ? number(it.poisson_ratio_error) : std::string()) << ',' << (it.converged ? 1 : 0)
        << ',' << last_wall_time << '\n';
    // At each iteration (a campaign takes minutes): a full disk stops the calibration here.
    dem::flush_checked(csv, out / "calibration.csv");
    std::cout << "calibrate: iteration " << it.index << ": friction " << number(p.friction_angle_deg, 4) << " deg, kn "
              << number(p.normal_stiffness, 4) << " N/m/m, ks/kn " << number(p.stiffness_ratio, 3) << " -> phi' "
              << number(m.friction_angle_deg, 4) << " deg (" << signed_number(it.friction_angle_error_deg, 2) << "), E "
              << number(m.young_modulus / 1e6, 4) << " MPa (" << signed_number(100.0 * it.young_modulus_error, 2)
              << " %), nu " << number(m.poisson_ratio, 3)
              << (targets.poisson_ratio ? " (" + signed_number(it.poisson_ratio_error, 2) + ")" : std::string())
              << (it.converged ? ", targets met" : "") << "; " << number(last_wall_time, 3) << " s" << std::endl;
  };

  const auto start_time = std::chrono::steady_clock::now();
  const dem::CalibrationResult result = dem::calibrate_micro_parameters(start, targets, model, report);
  const double wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  dem::close_checked(csv, out / "calibration.csv");
  if (!result.converged)
    throw std::runtime_error(where + ": calibration failed: " + result.failure + " (every iteration is in " +
                             (out / "calibration.csv").string() + ")");

  const dem::CalibrationIteration &final_iteration = result.iterations.back();
  const BiaxialCampaign calibrated = with_micro_parameters(campaign, final_iteration.micro, input.scale_wall_stiffness);
  const dem::ContactParameters &particle = calibrated.sample.particle_contact;
  const dem::MacroResponse &achieved = final_iteration.macro;
  const std::filesystem::path fragment = out / input.fragment_file;
  {
    // Whole or absent (dem::write_whole_file): an input that includes an empty or cut fragment
    // would read the contact laws' defaults without a word.
    std::ostringstream f;
    f << "# Soil contact micro-parameters calibrated by `geohybrid calibrate " << input_file << "` in "
      << result.iterations.size() << " biaxial campaigns.\n"
      << "# Targets:  peak friction angle " << number(targets.friction_angle_deg, 6) << " +/- "
      << number(targets.friction_angle_tolerance_deg, 4) << " deg, Young modulus " << number(targets.young_modulus, 6)
      << " Pa +/- " << number(100.0 * targets.young_modulus_tolerance, 4) << " %, Poisson ratio "
      << (targets.poisson_ratio ? number(*targets.poisson_ratio, 4) + " +/- " + number(targets.poisson_ratio_tolerance, 4)
                                : std::string("not targeted"))
      << "\n# Achieved: peak friction angle " << number(achieved.friction_angle_deg, 6) << " deg, Young modulus "
      << number(achieved.young_modulus, 6) << " Pa, Poisson ratio " << number(achieved.poisson_ratio, 4) << "\n"
      << "# on " << (input.reuse_sample ? "one REDF sample (made with the starting parameters, reused by every iteration)"
                                         : "a new REDF sample per iteration")
      << " of " << campaign.sample.n_particles << " particles,\n# porosity " << number(last_porosity, 4) << ", seed "
      << campaign.sample.seed << ", confining stresses " << confinements_kpa(campaign) << ", walls kn = "
      << number(calibrated.sample.wall_contact.normal_stiffness) << ", ks = "
      << number(calibrated.sample.wall_contact.shear_stiffness) << " N/m/m.\n"
      << "# The values hold for samples of that porosity; a new REDF sample is another random assembly, whose\n"
      << "# scatter (check it with geohybrid biaxial) shrinks with its size. Include this file at the top level\n"
      << "# of an input file (a line 'include " << input.fragment_file << "', path relative to the working directory).\n"
      << "subsection Particle contact\n"
      << "  set normal stiffness = " << number(particle.normal_stiffness) << "\n"
      << "  set shear stiffness = " << number(particle.shear_stiffness) << "\n"
      << "  set friction angle = " << number(particle.friction_angle_deg) << "\n"
      << "  set shear strength = " << number(particle.shear_strength) << "\n"
      << "  set tensile strength = " << number(particle.tensile_strength) << "\n"
      << "  set restitution coefficient = " << number(particle.restitution) << "\n"
      << "  set bond new contacts = " << (particle.bond_new_contacts ? "true" : "false") << "\n"
      << "end\n";
    dem::write_whole_file(fragment, f.str());
  }

  Summary summary;
  summary.set("command", "calibrate");
  summary.set("converged", 1.0);
  summary.set("iterations", static_cast<double>(result.iterations.size()));
  summary.set("contact_friction_angle_deg", particle.friction_angle_deg);
  summary.set("normal_stiffness_N_per_m_per_m", particle.normal_stiffness);
  summary.set("shear_stiffness_N_per_m_per_m", particle.shear_stiffness);
  summary.set("stiffness_ratio", particle.shear_stiffness / particle.normal_stiffness);
  set_biaxial_results(summary, last_parameters, last_porosity); // the last campaign: the achieved values
  summary.set("target_friction_angle_deg", targets.friction_angle_deg);
  summary.set("target_young_modulus_Pa", targets.young_modulus);
  summary.set("target_poisson_ratio", targets.poisson_ratio ? *targets.poisson_ratio : std::nan(""));
  summary.set("friction_angle_tolerance_deg", targets.friction_angle_tolerance_deg);
  summary.set("young_modulus_tolerance", targets.young_modulus_tolerance);
  summary.set("poisson_ratio_tolerance", targets.poisson_ratio_tolerance);
  summary.set("fragment_file", input.fragment_file);
  summary.set("sample", input.reuse_sample ? "reuse" : "remake");
  summary.set("n_particles", static_cast<double>(campaign.sample.n_particles));
  summary.set("wall_time_s", wall_time);
  summary.write(out / "summary.json");
  std::cout << "geohybrid calibrate: targets met after " << result.iterations.size()
            << (result.iterations.size() == 1 ? " iteration" : " iterations") << ": friction angle "
            << number(particle.friction_angle_deg, 6) << " deg, kn " << number(particle.normal_stiffness, 6)
            << " N/m/m, ks " << number(particle.shear_stiffness, 6) << " N/m/m; " << number(wall_time, 4)
            << " s\nresults in " << out.string() << " (" << input.fragment_file
            << ", calibration.csv, summary.json)\n";
  return 0;
}
} // namespace geohybrid::apps

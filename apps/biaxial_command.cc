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

#include "contact_parameters.h"
#include "plot.h"
#include "run_directory.h"

#include "dem/io/checked_output.h"
#include "dem/laboratory/sample_file.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <numeric>
#include <optional>
#include <thread>

namespace geohybrid::apps
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_biaxial_parameters(ParameterHandler &prm)
{
  prm.declare_entry("output directory", "output/biaxial", Patterns::Anything(),
                    "Directory for all results, created if needed, relative to the working directory");
  prm.declare_entry("threads", "2", Patterns::Integer(1, 256), "Number of threads [-]");

  prm.enter_subsection("Sample");
  prm.declare_entry("number of particles", "4000", Patterns::Integer(1), "Particles in the sample [-]");
  prm.declare_entry("width", "0.2", Patterns::Double(1e-6), "Width of the sample [m]");
  prm.declare_entry("height", "0.4", Patterns::Double(1e-6), "Height of the sample [m]");
  prm.declare_entry("shape", "two-disc cluster", Patterns::Selection("disc|two-disc cluster"),
                    "Particle shape; the paper uses clusters of two discs of diameters d and 0.9 d");
  prm.declare_entry("size ratio", "0.5", Patterns::Double(0.05, 1.0),
                    "Smallest over largest particle size (uniform distribution); the sizes are scaled so "
                    "the particles fill the sample at the target porosity [-]");
  prm.declare_entry("size distribution", "uniform", Patterns::Anything(),
                    "'uniform' (radii uniform between 'size ratio' and 1) or size classes as relative "
                    "size : area fraction pairs, e.g. '1.0:0.3, 0.75:0.4, 0.5:0.3' (fractions of the solid "
                    "area, i.e. of the mass, summing to 1; sizes relative, scaled to fill the sample) [-]");
  prm.declare_entry("cluster diameter ratio", "0.9", Patterns::Double(0.1, 1.0),
                    "Small over large disc diameter in a cluster [-]");
  prm.declare_entry("cluster centre spacing", "0.95", Patterns::Double(0.01, 0.95),
                    "Distance between a cluster's disc centres over the large diameter; 0.95 = touching [-]");
  prm.declare_entry("density", "2650", Patterns::Double(1e-9), "Solid density [kg/m^3]");
  prm.declare_entry("target porosity", "0.2", Patterns::Double(0.0, 1.0), "2D porosity of the sample (Table 5) [-]");
  prm.declare_entry("porosity tolerance", "0.005", Patterns::Double(1e-6, 0.1), "Accepted porosity error [-]");
  prm.declare_entry("initial growth friction", "-1", Patterns::Double(-1.0, 89.0),
                    "Friction angle at the start of REDF growth; -1 = the material's [deg]");
  prm.declare_entry("seed", "1", Patterns::Integer(0), "Seed of the random sample [-]");
  prm.declare_entry("sample file", "", Patterns::Anything(),
                    "HDF5 file of the REDF sample, relative to the working directory: read if it exists (it must "
                    "have been made with the same Sample, Particle contact and Wall contact settings and the same "
                    "lowest confining stress, or the run stops and says what differs), otherwise made and written "
                    "there; empty = make the sample and do not keep it");
  prm.leave_subsection();

  prm.enter_subsection("Particle contact");
  dem::ContactParameters table5;
  table5.normal_stiffness = 7e7;
  table5.shear_stiffness = 3.5e7;
  table5.friction_angle_deg = 10.0;
  declare_contact_parameters(prm, table5);
  prm.leave_subsection();
  prm.enter_subsection("Wall contact");
  dem::ContactParameters frictionless = table5;
  frictionless.friction_angle_deg = 0.0; // "The four walls were non frictional"
  declare_contact_parameters(prm, frictionless);
  prm.leave_subsection();

  prm.enter_subsection("Test");
  prm.declare_entry("confining stresses", "10e3, 20e3, 50e3", Patterns::List(Patterns::Double(1.0), 1),
                    "Lateral stresses sigma_0, one test each (the paper's triaxial tests: 10, 20, 50 kPa) [Pa]");
  prm.declare_entry("top wall speed", "auto", Patterns::Anything(),
                    "Speed V of the top wall, positive, or 'auto' to choose it from the inertial number [m/s]");
  prm.declare_entry("inertial number", "2e-4", Patterns::Double(1e-8, 1.0),
                    "Target inertial number I = strain rate x d x sqrt(rho / sigma_0) when the top wall speed "
                    "is 'auto'; a warning above 1e-3. The paper's sample is still rate-sensitive below it: "
                    "from 2.5e-4 to 5e-4 its deviator grows 12-36 % (bench/RESULTS.md) [-]");
  prm.declare_entry("final axial strain", "0.1", Patterns::Double(1e-4, 0.45), "End of the test [-]");
  prm.declare_entry("record interval", "0.001", Patterns::Double(1e-6, 0.1),
                    "Axial strain between recorded points [-]");
  prm.leave_subsection();
}

BiaxialCampaign parse_biaxial_campaign(ParameterHandler &prm, const std::string &where)
{
  BiaxialCampaign c;
  dem::RedfSpec &s = c.sample;
  s.n_threads = prm.get_integer("threads");
  prm.enter_subsection("Sample");
  s.n_particles = static_cast<std::size_t>(prm.get_integer("number of particles"));
  s.width = prm.get_double("width");
  s.height = prm.get_double("height");
  s.shape = prm.get("shape") == "disc" ? dem::ParticleShape::disc : dem::ParticleShape::two_disc_cluster;
  const std::string sizes = prm.get("size distribution");
  if (sizes == "uniform")
    s.size_distribution = dem::SizeDistribution::uniform(prm.get_double("size ratio"));
  else
    try
      {
        std::vector<dem::SizeDistribution::SizeClass> classes;
        for (const std::string &item : dealii::Utilities::split_string_list(sizes, ','))
          {
            const std::vector<std::string> pair = dealii::Utilities::split_string_list(item, ':');
            double number[2] = {0.0, 0.0};
            std::size_t used[2] = {0, 0};
            for (std::size_t i = 0; i < 2 && pair.size() == 2; ++i)
              try
                {
                  number[i] = std::stod(pair[i], &used[i]);
                }
              catch (const std::exception &)
                {
                }
            if (pair.size() != 2 || used[0] != pair[0].size() || used[1] != pair[1].size())
              throw std::invalid_argument("'" + item + "' is not a 'size : fraction' pair of numbers");
            classes.push_back({number[0], number[1]});
          }
        s.size_distribution = dem::SizeDistribution::fractions(classes);
      }
    catch (const std::exception &e)
      {
        throw std::invalid_argument(where + ": 'Sample/size distribution' = '" + sizes + "': " + e.what());
      }
  s.cluster_diameter_ratio = prm.get_double("cluster diameter ratio");
  s.cluster_spacing = prm.get_double("cluster centre spacing");
  s.density = prm.get_double("density");
  s.target_porosity = prm.get_double("target porosity");
  s.porosity_tolerance = prm.get_double("porosity tolerance");
  s.initial_growth_friction_deg = prm.get_double("initial growth friction");
  s.seed = static_cast<std::uint64_t>(prm.get_integer("seed"));
  c.sample_file = prm.get("sample file");
  prm.leave_subsection();
  if (!(s.target_porosity >= 0.05 && s.target_porosity <= 0.8))
    throw std::invalid_argument(where + ": 'Sample/target porosity' = " + std::to_string(s.target_porosity) +
                                " cannot be reached by a 2D assembly; use a value in [0.05, 0.8]");
  prm.enter_subsection("Particle contact");
  s.particle_contact = parse_contact_parameters(prm, where + ", subsection 'Particle contact'");
  prm.leave_subsection();
  prm.enter_subsection("Wall contact");
  s.wall_contact = parse_contact_parameters(prm, where + ", subsection 'Wall contact'");
  prm.leave_subsection();
  prm.enter_subsection("Test");
  for (const std::string &item : dealii::Utilities::split_string_list(prm.get("confining stresses"), ','))
    c.confining_stresses.push_back(dealii::Utilities::string_to_double(item));
  if (c.confining_stresses.empty())
    throw std::invalid_argument(where + ": 'Test/confining stresses' is empty; give at least one stress in Pa");
  const std::string speed = prm.get("top wall speed");
  if (speed != "auto")
    {
      try
        {
          c.test.top_wall_speed = std::stod(speed);
        }
      catch (const std::exception &)
        {
          c.test.top_wall_speed = -1.0;
        }
      if (!(c.test.top_wall_speed > 0.0))
        throw std::invalid_argument(where + ": 'Test/top wall speed' = '" + speed +
                                    "' must be a positive speed in m/s, or 'auto'");
    }
  c.test.target_inertial_number = prm.get_double("inertial number");
  c.test.final_axial_strain = prm.get_double("final axial strain");
  // A very short test (a check) accelerates the top wall over half of it at most.
  c.test.ramp_strain = std::min(c.test.ramp_strain, 0.5 * c.test.final_axial_strain);
  c.test.record_interval = prm.get_double("record interval");
  prm.leave_subsection();
  if (c.test.record_interval * 10.0 > c.test.final_axial_strain)
    throw std::invalid_argument(where + ": 'Test/record interval' must be at most a tenth of 'final axial strain'");
  return c;
}

namespace
{
std::string kpa_label(double stress) { return std::to_string(static_cast<int>(std::lround(stress / 1e3))) + " kPa"; }

double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// What the campaign's sample is made from: REDF at the lowest confining stress.
dem::RedfSpec sample_spec(const BiaxialCampaign &campaign)
{
  dem::RedfSpec spec = campaign.sample;
  spec.target_stress = *std::min_element(campaign.confining_stresses.begin(), campaign.confining_stresses.end());
  return spec;
}

/// The sample held by the campaign's sample file, if there is one. Throws, naming the parameter
/// and the file, if the file cannot be read or holds a sample made with other settings: its tests
/// would not be those of this input.
std::optional<dem::StoredSample> read_campaign_sample(const BiaxialCampaign &campaign)
{
  const std::filesystem::path &file = campaign.sample_file;
  if (file.empty() || !std::filesystem::exists(file))
    return std::nullopt;
  if (campaign.confining_stresses.empty())
    throw std::invalid_argument("biaxial campaign: no confining stress");
  std::optional<dem::StoredSample> stored;
  try
    {
      stored = dem::read_sample_file(file);
    }
  catch (const std::runtime_error &e)
    {
      throw std::runtime_error(std::string("'Sample/sample file': ") + e.what());
    }
  const std::vector<std::string> differences = dem::sample_spec_differences(stored->spec, sample_spec(campaign));
  if (!differences.empty())
    {
      std::string list;
      for (const std::string &d : differences)
        list += (list.empty() ? "" : "; ") + d +
                (d.rfind("target_stress", 0) == 0 ? " (the lowest of 'Test/confining stresses')" : "");
      throw std::invalid_argument("'Sample/sample file' = '" + file.string() +
                                  "' holds a sample made with other settings than this input's (" + list +
                                  "); remove the file to make a new sample there, or name another file");
    }
  return stored;
}

/// The campaign's sample: read from the sample file if it exists, made by REDF otherwise (and
/// written to the sample file if one is named).
dem::StoredSample campaign_sample(const BiaxialCampaign &campaign, bool show_progress)
{
  const dem::RedfSpec spec = sample_spec(campaign);
  const std::filesystem::path &file = campaign.sample_file;
  if (std::optional<dem::StoredSample> stored = read_campaign_sample(campaign))
    {
      if (show_progress)
        std::cerr << "biaxial: REDF sample read from " << file.string() << " (porosity " << stored->result.porosity
                  << ", " << kpa_label(spec.target_stress) << ")\n";
      return std::move(*stored);
    }
  const auto start = std::chrono::steady_clock::now();
  ProgressReport progress("biaxial: REDF sample at " + kpa_label(spec.target_stress), 1.0);
  const dem::RedfSample sample =
    dem::make_redf_sample(spec, show_progress ? std::function<void(double)>([&](double f) { progress.update(f); })
                                              : std::function<void(double)>());
  if (show_progress)
    progress.finish();
  dem::StoredSample stored = dem::store_sample(sample, spec);
  if (!file.empty())
    dem::write_sample_file(stored, file);
  if (show_progress)
    std::cerr << "biaxial: REDF sample made in " << seconds_since(start) << " s (" << sample.result.n_steps
              << " steps, porosity " << sample.result.porosity << ")"
              << (file.empty() ? std::string() : ", saved to " + file.string()) << "\n";
  return stored;
}

/// One test on its own copy of the sample.
dem::BiaxialCurve run_one_test(const BiaxialCampaign &campaign, const dem::StoredSample &sample, double sigma_0,
                               int n_threads, const std::function<void(double)> &progress,
                               const std::function<int()> &thread_budget)
{
  dem::RedfSample copy = dem::restore_sample(sample, n_threads);
  // Mean particle size for the inertial number: the diameter of a disc of the mean area.
  const dem::ParticleSet &p = copy.system.particles();
  const double mean_diameter = 2.0 * std::sqrt(dem::total_solid_area(p) / (dem::pi * p.n_bodies()));
  dem::BiaxialSpec test = campaign.test;
  test.confining_stress = sigma_0;
  return dem::run_biaxial_test(copy.system, copy.box, test, mean_diameter, sample.spec.density, progress,
                               thread_budget);
}
} // namespace

std::vector<dem::BiaxialCurve> run_biaxial_campaign(const BiaxialCampaign &campaign, bool show_progress)
{
  if (campaign.confining_stresses.empty())
    throw std::invalid_argument("biaxial campaign: no confining stress");
  const dem::StoredSample sample = campaign_sample(campaign, show_progress);

  // The tests run side by side, each on its own copy of the sample: with n threads and k tests,
  // min(n, k) at a time on n / min(n, k) threads each. A few thousand particles keep two threads
  // of one system waiting for each other at every step; two systems on a thread each do not.
  // When no test is left to start, a worker that finishes gives its threads to those still
  // running (each test may use n / (workers still busy) threads): with 2 threads and the three
  // default confinements, the 10 kPa test runs on one thread, the 20 and 50 kPa tests one after
  // the other on the other, and the 50 kPa test ends on both.
  // The curves do not depend on this: a DemSystem gives the same numbers on any thread count,
  // and one moved to another thread count mid-run continues bit for bit.
  const std::size_t n_tests = campaign.confining_stresses.size();
  const int n_threads = std::max(1, campaign.sample.n_threads);
  const std::size_t n_workers = std::min<std::size_t>(static_cast<std::size_t>(n_threads), n_tests);
  const int threads_per_test = n_threads / static_cast<int>(n_workers);
  // Longest first: at a given inertial number the strain rate grows with sqrt(sigma_0), so the
  // lowest confinement takes the most steps.
  std::vector<std::size_t> order(n_tests);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return campaign.confining_stresses[a] < campaign.confining_stresses[b];
  });

  std::vector<dem::BiaxialCurve> curves(n_tests);
  std::vector<std::exception_ptr> errors(n_tests);
  std::vector<double> done(n_tests, 0.0);
  std::mutex progress_mutex;
  ProgressReport progress("biaxial: " + std::to_string(n_tests) + " tests, " + std::to_string(n_workers) +
                            " at a time on " + std::to_string(threads_per_test) + " thread(s) each",
                          1.0);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::atomic<int> busy_workers{static_cast<int>(n_workers)};
  const std::function<int()> thread_budget = [&] { return std::max(threads_per_test, n_threads / busy_workers.load()); };
  const auto start = std::chrono::steady_clock::now();
  const auto worker = [&] {
    for (std::size_t k = next++; k < n_tests && !failed; k = next++)
      {
        const std::size_t test = order[k];
        const auto report = [&, test](double fraction) {
          const std::lock_guard<std::mutex> lock(progress_mutex);
          done[test] = fraction;
          progress.update(std::accumulate(done.begin(), done.end(), 0.0) / n_tests);
        };
        try
          {
            curves[test] = run_one_test(campaign, sample, campaign.confining_stresses[test], threads_per_test,
                                        show_progress ? std::function<void(double)>(report)
                                                      : std::function<void(double)>(),
                                        thread_budget);
          }
        catch (...)
          {
            errors[test] = std::current_exception();
            failed = true;
          }
      }
    --busy_workers; // no test left to start: the tests still running may take this thread
  };
  std::vector<std::thread> helpers;
  for (std::size_t w = 1; w < n_workers; ++w)
    helpers.emplace_back(worker);
  worker();
  for (std::thread &t : helpers)
    t.join();
  for (const std::exception_ptr &e : errors)
    if (e)
      std::rethrow_exception(e);
  if (show_progress)
    {
      progress.finish();
      std::cerr << "biaxial: consolidation and compression of the " << n_tests << " tests took " << seconds_since(start)
                << " s\n";
      for (const dem::BiaxialCurve &curve : curves)
        std::cerr << "biaxial: " << kpa_label(curve.confining_stress) << ": " << curve.consolidation_steps
                  << " consolidation and " << curve.compression_steps << " compression steps, ended on "
                  << curve.final_threads << " thread(s)\n";
    }
  for (const dem::BiaxialCurve &curve : curves)
    if (curve.inertial_number > 1e-3)
      std::cerr << "warning: biaxial " << kpa_label(curve.confining_stress) << ": inertial number "
                << curve.inertial_number << " is above 1e-3; the test is not quasi-static (lower 'top wall speed' "
                << "or 'inertial number')\n";
  return curves;
}

double mean_initial_porosity(const std::vector<dem::BiaxialCurve> &curves)
{
  double porosity = 0.0;
  for (const dem::BiaxialCurve &c : curves)
    porosity += c.initial_porosity / static_cast<double>(curves.size());
  return porosity;
}

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
  std::ofstream f(file);
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
  dem::close_checked(f, file);
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

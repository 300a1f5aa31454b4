#include "biaxial_campaign.h"

#include "run_directory.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <functional>
#include <iostream>
#include <mutex>
#include <numeric>
#include <thread>

namespace geohybrid::apps
{
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
} // namespace

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

namespace
{
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
} // namespace geohybrid::apps

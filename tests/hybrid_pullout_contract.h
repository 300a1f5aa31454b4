#pragma once
// The output contract of `geohybrid pullout` with 'mode = hybrid' on the small hybrid input
// (small_hybrid_pullout_input.h, no extra lines), checked on a finished run's directory. One run
// serves it and the SIGTERM test's straight run (test_app_interrupt.cc): the same input, so the
// contract costs no run of its own.
#include "apps/pullout_command.h"
#include "pullout_forces_check.h"
#include "text_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace geohybrid::testing
{
/// The number a flat summary.json gives `key` (NaN if it has none).
inline double summary_number(const std::string &json, const std::string &key)
{
  const auto at = json.find("\"" + key + "\": ");
  if (at == std::string::npos)
    return std::nan("");
  return std::stod(json.substr(at + key.size() + 4));
}

/// The files in `out` of the run of `input`, and summary.json with the hybrid's keys.
inline void expect_hybrid_pullout_contract(const std::filesystem::path &out, const std::string &input)
{
  namespace fs = std::filesystem;
  const std::vector<std::string> curve = lines_of(out / "pullout_curve.csv");
  ASSERT_EQ(curve.size(), 1u + 6u); // header, the start and five intervals of 0.2 mm
  EXPECT_EQ(curve[0], "head_displacement_m,head_tension_kN_per_m");
  EXPECT_EQ(lines_of(out / "pullout_curve_sheet.csv").size(), curve.size());
  const std::vector<std::string> moves = lines_of(out / "sheet_displacements.csv");
  ASSERT_EQ(moves.size(), curve.size());
  EXPECT_EQ(moves[0], "head_displacement_m,beginning_displacement_m,middle_displacement_m,end_displacement_m");
  const std::vector<std::string> profiles = lines_of(out / "sheet_tension.csv");
  EXPECT_GT(profiles.size(), 2u * 25u); // two profiles of a row per segment (0.25 m of 1 cm segments)
  EXPECT_TRUE(fs::exists(out / "pullout_curve.png"));
  EXPECT_TRUE(fs::exists(out / "parameters.prm"));
  expect_pullout_forces_add_up(out); // as in dem mode (test_app_pullout.cc)
  // The coupling's diagnostics at each point of the curve.
  const std::vector<std::string> diagnostics = lines_of(out / "coupling_diagnostics.csv");
  ASSERT_EQ(diagnostics.size(), curve.size());
  EXPECT_EQ(diagnostics[0].rfind("time_s,head_displacement_m,head_tension_N_per_m,particles_unbalanced_ratio,", 0), 0u)
    << diagnostics[0];

  const std::string summary = read_text(out / "summary.json");
  EXPECT_NE(summary.find("\"mode\": \"hybrid\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"parameters_hash\": \"" + geohybrid::apps::check_pullout_input(input) + "\""),
            std::string::npos)
    << summary;
  EXPECT_NE(summary.find("\"coupling_method\": \"multipliers\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"DEM_region\": ["), std::string::npos) << summary;
  // The box [0.1, 0.4] x [0.05, 0.15] m of the 0.4 m x 0.2 m tank: 3/8 of 4,000 grains.
  EXPECT_NEAR(summary_number(summary, "n_particles"), 1500.0, 100.0) << summary;
  EXPECT_EQ(summary_number(summary, "n_particles_full_tank"), 4000.0);
  EXPECT_GT(summary_number(summary, "n_cells"), 0.0);
  EXPECT_GT(summary_number(summary, "band_width_m"), 0.0);
  EXPECT_LT(summary_number(summary, "band_width_m"), 0.05);
  EXPECT_GT(summary_number(summary, "T_max_kN_per_m"), 0.0);
  const double dt = summary_number(summary, "time_step_s"), dt_particles = summary_number(summary, "particle_time_step_s");
  EXPECT_GT(dt, 0.0);
  EXPECT_LE(dt, dt_particles * (1.0 + 1e-12));
  EXPECT_GT(summary_number(summary, "n_settling_steps"), 0.0);
  // The box's top was loaded by the 0.05 m of soil above it before the coupling (gamma 15.2
  // kN/m^3: 760 Pa), the lid released within 1 % of it.
  EXPECT_NEAR(summary_number(summary, "overburden_Pa"), 15.2e3 * 0.05, 1e-6) << summary;
  EXPECT_NEAR(summary_number(summary, "overburden_reached_Pa"), 15.2e3 * 0.05, 0.01 * 15.2e3 * 0.05);
  // The coupling forces on the two sides cancel to round-off at every point of the pull (the
  // multipliers act as -lambda on a particle and N_I lambda on the nodes, sum_I N_I = 1).
  const double largest = summary_number(summary, "coupling_force_max_N_per_m");
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(summary_number(summary, "coupling_force_imbalance_max_N_per_m"), 1e-10 * largest) << summary;
  // The coupled system's energy balance over the pull (the particles' budget booked from the
  // coupling on, the continuum's work ledger, the coupling's stored energy): measured 1.0e-4 at the
  // end, 1.9e-4 at most, of the clamp's work (0.13 J/m); 1.34 when the particles' dissipation was
  // not booked. The csv has its terms.
  std::cout << "energy balance over the pull: " << summary_number(summary, "energy_balance_error_relative")
            << " at the end, largest " << summary_number(summary, "energy_balance_error_max_relative") << std::endl;
  EXPECT_LT(summary_number(summary, "energy_balance_error_max_relative"), 1e-3) << summary;
  EXPECT_NE(diagnostics[0].find(",continuum_internal_work_J_per_m,continuum_damping_work_J_per_m,"
                                "continuum_gravity_work_J_per_m,coupling_work_on_continuum_J_per_m,continuum_sheet_truss_work_J_per_m,"
                                "continuum_sheet_interface_work_J_per_m,energy_balance_error"),
            std::string::npos)
    << diagnostics[0];
  // 1 mm at 5 mm/s: at least 0.2 s of coupled steps, and not much more (the start's ramp).
  const double pulled_for = summary_number(summary, "n_pull_steps") * dt;
  EXPECT_GE(pulled_for, 0.2 * (1.0 - 1e-9));
  EXPECT_LT(pulled_for, 0.3);
  // At 5 mm/s the pull is quasi-static: the watch, which keeps the grains in the box and weighs
  // their kinetic energy against the clamp's work, has nothing to say.
  EXPECT_NE(summary.find("\"warnings\": []"), std::string::npos) << summary;
  EXPECT_GT(summary_number(summary, "fill_wall_time_s"), 0.0);
  EXPECT_GE(summary_number(summary, "wall_time_s"), summary_number(summary, "fill_wall_time_s"));
  // Where the time went (issue 26): the set-up's settlings within it, the coupled steps' parts
  // each taken and within the pull's wall time, the pull after the set-up.
  const double set_up = summary_number(summary, "set_up_wall_time_s"), pull = summary_number(summary, "pull_wall_time_s");
  EXPECT_GT(summary_number(summary, "coupled_settling_wall_time_s"), 0.0);
  EXPECT_LE(summary_number(summary, "box_settling_wall_time_s") + summary_number(summary, "coupled_settling_wall_time_s"),
            set_up - summary_number(summary, "fill_wall_time_s"));
  double parts = 0.0;
  for (const char *part : {"pull_continuum_wall_time_s", "pull_coupling_wall_time_s", "pull_particles_wall_time_s"})
    {
      EXPECT_GT(summary_number(summary, part), 0.0) << part;
      parts += summary_number(summary, part);
    }
  EXPECT_GE(summary_number(summary, "pull_band_drive_wall_time_s"), 0.0);
  parts += summary_number(summary, "pull_band_drive_wall_time_s");
  EXPECT_LE(parts, pull);
  EXPECT_LE(set_up + pull, summary_number(summary, "wall_time_s") * (1.0 + 1e-9));
  for (const char *key : {"experimental_T_max_kN_per_m", "T_max_difference_percent", "gamma_H_Pa",
                          "sigma_v_top_face_Pa", "n_sheet_nodes"})
    EXPECT_NE(summary.find(std::string("\"") + key + "\""), std::string::npos) << key;
}
} // namespace geohybrid::testing

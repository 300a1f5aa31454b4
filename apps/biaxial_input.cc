#include "biaxial_input.h"

#include "contact_parameters.h"

#include <algorithm>
#include <exception>
#include <stdexcept>

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
} // namespace geohybrid::apps

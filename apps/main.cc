// geohybrid: one executable, one subcommand per kind of run.
//
//   geohybrid dem FILE.prm                 a DEM scene (deposition, impacts, any walls)
//   geohybrid COMMAND --print-parameters   every parameter of COMMAND with default, unit, doc
//
// Input files are read with deal.II's ParameterHandler (.prm or .json). Errors in the input stop
// the run before anything is written, with a message naming the file and the parameter.
#include "apps/dem_command.h"

#include <deal.II/base/parameter_handler.h>

#include <cstring>
#include <functional>
#include <iostream>
#include <map>

namespace
{
struct Command
{
  const char *summary;
  std::function<void(dealii::ParameterHandler &)> declare;
  std::function<int(const std::string &)> run;
};

const std::map<std::string, Command> &commands()
{
  static const std::map<std::string, Command> table{
    {"dem", {"run a DEM scene: deposition of discs or clusters in a box, or particles from CSV",
             geohybrid::apps::declare_dem_parameters, geohybrid::apps::run_dem_command}},
  };
  return table;
}

void print_usage(std::ostream &out)
{
  out << "geohybrid: 2D DEM of soil coupled with a deal.II continuum, for geosynthetic anchorages\n\n"
         "usage: geohybrid COMMAND FILE.prm|FILE.json\n"
         "       geohybrid COMMAND --print-parameters   (every parameter, default, unit and meaning)\n"
         "       geohybrid --help\n\ncommands:\n";
  for (const auto &[name, command] : commands())
    out << "  " << name << std::string(12 - std::min<std::size_t>(11, name.size()), ' ') << command.summary << '\n';
}
} // namespace

int main(int argc, char **argv)
{
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h"))
    {
      print_usage(std::cout);
      return argc < 2 ? 1 : 0;
    }
  const auto found = commands().find(argv[1]);
  if (found == commands().end())
    {
      std::cerr << "geohybrid: unknown command '" << argv[1] << "'\n\n";
      print_usage(std::cerr);
      return 2;
    }
  if (argc != 3)
    {
      std::cerr << "geohybrid " << argv[1] << ": expected one input file or --print-parameters\n";
      return 2;
    }
  try
    {
      if (!std::strcmp(argv[2], "--print-parameters"))
        {
          dealii::ParameterHandler prm;
          found->second.declare(prm);
          prm.print_parameters(std::cout, dealii::ParameterHandler::OutputStyle::PRM);
          return 0;
        }
      return found->second.run(argv[2]);
    }
  catch (const std::exception &e)
    {
      std::cerr << "geohybrid " << argv[1] << ": error: " << e.what() << '\n';
      return 1;
    }
}

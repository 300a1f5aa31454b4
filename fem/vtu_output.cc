#include "vtu_output.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/data_out.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <vector>

namespace geohybrid::fem
{
namespace
{
/// Writes `file` with `write`; throws std::runtime_error naming it if it cannot be opened or a
/// write fails (deal.II's writers throw ExcIO at the first failed write; the flush catches the
/// failure of what its buffer still holds).
void write_checked(const std::string &file, const std::function<void(std::ostream &)> &write)
{
  const std::string failure = "cannot write " + file + " (is the disk full, or the directory not writable?)";
  std::ofstream out(file);
  if (!out)
    throw std::runtime_error(failure);
  try
    {
      write(out);
    }
  catch (const dealii::ExceptionBase &)
    {
      throw std::runtime_error(failure);
    }
  out.flush();
  if (!out)
    throw std::runtime_error(failure);
}
} // namespace

std::string write_soil_vtu(const DisplacementSpace &space, const dealii::PETScWrappers::MPI::Vector &displacement,
                           MaterialPointHistory &material_points, const std::string &directory,
                           const std::string &basename, unsigned int step)
{
  const auto &mesh = space.mesh();
  const unsigned int n_cells = mesh.n_active_cells();
  dealii::Vector<float> sigma_xx(n_cells), sigma_yy(n_cells), sigma_xy(n_cells), sigma_zz(n_cells),
    mean_pressure(n_cells), deviatoric_stress(n_cells), plastic_shear_strain(n_cells), yielded(n_cells),
    rank(n_cells);
  material_points.for_each_cell([&](const auto &cell, auto &points) {
    const unsigned int c = cell->active_cell_index();
    for (const auto &p : points)
      {
        const auto &s = p->stress;
        sigma_xx(c) += s[0][0];
        sigma_yy(c) += s[1][1];
        sigma_xy(c) += s[0][1];
        sigma_zz(c) += s[2][2];
        mean_pressure(c) += -dealii::trace(s) / 3.0;
        // q = sqrt(3 J2), the von Mises measure of the deviator, as in triaxial testing.
        deviatoric_stress(c) += std::sqrt(1.5) * dealii::deviator(s).norm();
        // sqrt(2/3 e:e) of the plastic strain deviator: the usual equivalent plastic strain.
        plastic_shear_strain(c) += std::sqrt(2.0 / 3.0) * dealii::deviator(p->plastic_strain).norm();
        yielded(c) += p->region == ReturnRegion::elastic ? 0.0 : 1.0;
      }
    const float n = points.size();
    for (auto *v : {&sigma_xx, &sigma_yy, &sigma_xy, &sigma_zz, &mean_pressure, &deviatoric_stress,
                    &plastic_shear_strain, &yielded})
      (*v)(c) /= n;
    rank(c) = mesh.locally_owned_subdomain();
  });

  dealii::DataOut<dim> data_out;
  data_out.attach_dof_handler(space.dof_handler());
  const std::vector<std::string> names(dim, "displacement");
  const std::vector<dealii::DataComponentInterpretation::DataComponentInterpretation> interpretation(
    dim, dealii::DataComponentInterpretation::component_is_part_of_vector);
  data_out.add_data_vector(displacement, names, dealii::DataOut<dim>::type_dof_data, interpretation);
  data_out.add_data_vector(sigma_xx, "sigma_xx");
  data_out.add_data_vector(sigma_yy, "sigma_yy");
  data_out.add_data_vector(sigma_xy, "sigma_xy");
  data_out.add_data_vector(sigma_zz, "sigma_zz");
  data_out.add_data_vector(mean_pressure, "mean_pressure");
  data_out.add_data_vector(deviatoric_stress, "deviatoric_stress");
  data_out.add_data_vector(plastic_shear_strain, "plastic_shear_strain");
  data_out.add_data_vector(yielded, "yielded_fraction");
  data_out.add_data_vector(rank, "mpi_rank");
  // Curved cells (Q2 mapping) are subdivided so that ParaView shows their curvature.
  data_out.build_patches(space.mapping(), space.degree(), dealii::DataOut<dim>::curved_inner_cells);
  // Each rank its piece, rank 0 the record listing them: the files and names of deal.II's
  // write_vtu_with_pvtu_record (one file per rank), but through streams checked here, so that a
  // failed write (a full disk) stops the run with one error naming the file, not deal.II's ExcIO
  // and its stack trace.
  const unsigned int this_rank = dealii::Utilities::MPI::this_mpi_process(space.communicator());
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(space.communicator());
  const std::string stem = basename + "_" + dealii::Utilities::int_to_string(step, 4);
  const auto piece = [&](unsigned int r) { return stem + "." + dealii::Utilities::int_to_string(r) + ".vtu"; };
  write_checked(directory + "/" + piece(this_rank), [&](std::ostream &out) { data_out.write_vtu(out); });
  const std::string record = stem + ".pvtu";
  if (this_rank == 0)
    {
      std::vector<std::string> pieces;
      for (unsigned int r = 0; r < n_ranks; ++r)
        pieces.push_back(piece(r));
      write_checked(directory + "/" + record, [&](std::ostream &out) { data_out.write_pvtu_record(out, pieces); });
    }
  return record;
}
} // namespace geohybrid::fem

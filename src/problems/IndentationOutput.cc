// ParaView output of IndentationProblem: deformed mesh (Eulerian mapping), displacement,
// cell-averaged Cauchy stress, von Mises stress, equivalent plastic strain and the nodal contact
// fields (pressure, status, friction traction); the pile-up files of the top surface.
// Units: um, GPa.
#include "analysis/PileUp.h"
#include "case/CaseFile.h"
#include "fem/FiniteStrainElement.h"
#include "output/OutputFile.h"
#include "output/ParaViewFiles.h"
#include "output/PythonScripts.h"
#include "problems/IndentationProblem.h"

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q_eulerian.h>
#include <deal.II/numerics/data_out.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <numbers>

namespace indentsim::problems
{
  using namespace dealii;
  using fem::GhostedVector;
  using fem::to_thread_readable;
  namespace pileup = analysis::pileup;

  namespace
  {
    // The axisymmetric section's top edge from (R, u_r, u_z) to the next, revolved about the
    // axis into the quadrilaterals of the surface the pile-up analysis reads (analysis/PileUp.h):
    // 2 degrees per sector, fine enough that the revolved rings stand for the circles.
    void revolve_edge(const std::array<double, 3> &a, const std::array<double, 3> &b,
                      std::vector<pileup::SurfaceQuad> &surface)
    {
      constexpr unsigned int n_sectors = 180;
      const auto             corner = [](const std::array<double, 3> &p, const double angle) {
        const double c = std::cos(angle), s = std::sin(angle);
        return pileup::SurfaceNode{p[0] * c, p[0] * s, p[1] * c, p[1] * s, p[2]};
      };
      for (unsigned int k = 0; k < n_sectors; ++k)
        {
          const double t0 = 2 * std::numbers::pi * k / n_sectors;
          const double t1 = 2 * std::numbers::pi * (k + 1) / n_sectors;
          surface.push_back({corner(a, t0), corner(b, t0), corner(b, t1), corner(a, t1)});
        }
    }
  } // namespace

  template <int dim>
  void IndentationProblem<dim>::compute_cell_fields(Vector<float>              &von_mises,
                                                    Vector<float>              &plastic_strain,
                                                    std::vector<Vector<float>> &cauchy)
  {
    for_each_cell_stress([&](const auto &cell, const std::vector<Tensor<2, 3>> &sigma,
                             const std::span<const double> state) {
      const unsigned int index = cell->active_cell_index();
      Tensor<2, 3>       mean;
      double             mises = 0, eps_p = 0;
      const unsigned int n_q_points = history_.n_q_points(), n_state = history_.n_state();
      for (unsigned int q = 0; q < n_q_points; ++q)
        {
          mean += sigma[q] / n_q_points;
          const Tensor<2, 3> s = sigma[q] - trace(sigma[q]) / 3. * unit_symmetric_tensor<3>();
          mises += std::sqrt(1.5 * scalar_product(s, s)) / n_q_points;
          eps_p += material_->equivalent_plastic_strain(state.subspan(q * n_state, n_state)) /
                   n_q_points;
        }
      von_mises[index] = mises;
      plastic_strain[index] = eps_p;
      unsigned int k = 0; // (xx, xy, xz, yy, yz, zz) or (rr, r theta, rz, theta theta, ...)
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          cauchy[k++][index] = mean[i][j];
    });
  }

  template <int dim>
  void IndentationProblem<dim>::write_vtu(const unsigned int index)
  {
    const unsigned int n_cells_local = solid_.triangulation.n_active_cells();
    Vector<float> von_mises(n_cells_local), plastic_strain(n_cells_local), subdomain(n_cells_local);
    std::vector<Vector<float>> cauchy(6, Vector<float>(n_cells_local));
    compute_cell_fields(von_mises, plastic_strain, cauchy);
    for (const auto &cell : solid_.triangulation.active_cell_iterators())
      subdomain[cell->active_cell_index()] = solid_.triangulation.locally_owned_subdomain();

    // Nodal contact fields on a scalar Q1 field: pressure p [GPa], status (0 open, 1 stick,
    // 2 slip) and the magnitude of the friction traction |t| [GPa], all nominal (per reference
    // area).
    DoFHandler<dim> scalar_dofs(solid_.triangulation);
    const FE_Q<dim> fe_scalar(1);
    scalar_dofs.distribute_dofs(fe_scalar);
    const IndexSet owned = scalar_dofs.locally_owned_dofs();
    const IndexSet relevant = DoFTools::extract_locally_relevant_dofs(scalar_dofs);
    const auto nodal_field = [&](const std::function<double(const contact::ContactNode &)> &value) {
      PETScWrappers::MPI::Vector                field(owned, communicator_);
      std::map<types::global_dof_index, double> value_by_dof; // vector dof x -> value
      for (const auto &node : contact_->nodes())
        value_by_dof[node.dofs[0]] = value(node);
      for (const auto &cell : solid_.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const typename DoFHandler<dim>::active_cell_iterator scalar_cell(
                &solid_.triangulation, cell->level(), cell->index(), &scalar_dofs);
            for (const unsigned int v : cell->vertex_indices())
              {
                const auto it = value_by_dof.find(cell->vertex_dof_index(v, 0));
                const auto dof = scalar_cell->vertex_dof_index(v, 0);
                if (it != value_by_dof.end() && owned.is_element(dof))
                  field(dof) = it->second;
              }
          }
      field.compress(VectorOperation::insert);
      PETScWrappers::MPI::Vector ghosted(owned, relevant, communicator_);
      ghosted = field;
      // DataOut works on threads: it reads thread-readable copies, not the PETSc vectors.
      return to_thread_readable(ghosted, owned, relevant, communicator_);
    };
    const GhostedVector pressure_readable =
        nodal_field([](const contact::ContactNode &node) { return node.pressure; });
    const GhostedVector status_readable = nodal_field(
        [](const contact::ContactNode &node) { return static_cast<double>(node.status); });
    const GhostedVector traction_readable =
        nodal_field([](const contact::ContactNode &node) { return node.traction.norm(); });
    const GhostedVector u =
        to_thread_readable(solution_, solid_.locally_owned, solid_.locally_relevant, communicator_);

    // The axisymmetric section is written in its (r, z) plane: x is r, y is z; its tensor
    // components are (r, theta, z).
    DataOut<dim> data_out;
    data_out.attach_dof_handler(solid_.dof_handler);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector_field(
        dim, DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(u, std::vector<std::string>(dim, "displacement_um"),
                             DataOut<dim>::type_dof_data, vector_field);
    data_out.add_data_vector(scalar_dofs, pressure_readable, "contact_pressure_GPa");
    data_out.add_data_vector(scalar_dofs, status_readable, "contact_status");
    data_out.add_data_vector(scalar_dofs, traction_readable, "friction_traction_GPa");
    const char        *names_3d[6] = {"cauchy_xx_GPa", "cauchy_xy_GPa", "cauchy_xz_GPa",
                                      "cauchy_yy_GPa", "cauchy_yz_GPa", "cauchy_zz_GPa"};
    const char        *names_axisymmetric[6] = {"cauchy_rr_GPa",     "cauchy_rtheta_GPa",
                                                "cauchy_rz_GPa",     "cauchy_thetatheta_GPa",
                                                "cauchy_thetaz_GPa", "cauchy_zz_GPa"};
    const char *const *names = dim == 3 ? names_3d : names_axisymmetric;
    for (unsigned int k = 0; k < 6; ++k)
      data_out.add_data_vector(cauchy[k], names[k]);
    data_out.add_data_vector(von_mises, "von_mises_GPa");
    data_out.add_data_vector(plastic_strain, "equivalent_plastic_strain");
    data_out.add_data_vector(subdomain, "mpi_rank");

    // The geometry is written in the deformed configuration.
    const MappingQEulerian<dim, GhostedVector> deformed(1, solid_.dof_handler, u);
    data_out.build_patches(deformed, 1);
    const std::string pvtu = output::write_vtu_with_pvtu_record(
        data_out, output_directory_, io::output_files::paraview_basename, index, 4, communicator_);
    // PVD time = output index: depth is not monotonic over load and unload.
    vtu_records_.emplace_back(index, pvtu);
    output::write_pvd(output_directory_ + "/" + io::output_files::paraview_basename + ".pvd",
                      vtu_records_, communicator_);
    scalar_dofs.clear();
  }

  template <int dim>
  std::vector<pileup::SurfaceQuad> IndentationProblem<dim>::gather_top_surface() const
  {
    // 3D: per face, 4 corners in cyclic order x (X, Y, u_x, u_y, u_z). deal.II numbers a face's
    // vertices lexicographically, 0 (0,0), 1 (1,0), 2 (0,1), 3 (1,1): cyclic is 0, 1, 3, 2.
    // Axisymmetric: per top edge, its 2 vertices x (R, u_r, u_z).
    constexpr unsigned int                n_corners = dim == 3 ? 4 : 2, n_values = dim == 3 ? 5 : 3;
    constexpr std::array<unsigned int, 4> cyclic = {0, 1, 3, 2};
    std::vector<double>                   local;
    for (const auto &cell : solid_.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && face->boundary_id() == mesh::boundary::top)
            for (unsigned int k = 0; k < n_corners; ++k)
              {
                const unsigned int v = dim == 3 ? cyclic[k] : k;
                for (unsigned int d = 0; d + 1 < dim; ++d)
                  local.push_back(face->vertex(v)[d]);
                for (unsigned int d = 0; d < dim; ++d)
                  local.push_back(solution_(face->vertex_dof_index(v, d)));
              }
    const std::vector<std::vector<double>> gathered =
        Utilities::MPI::gather(communicator_, local, 0);

    std::vector<pileup::SurfaceQuad> surface;
    for (const std::vector<double> &values : gathered)
      for (std::size_t i = 0; i + n_corners * n_values <= values.size(); i += n_corners * n_values)
        {
          const double *c = &values[i];
          if constexpr (dim == 3)
            {
              pileup::SurfaceQuad quad;
              for (unsigned int v = 0; v < 4; ++v, c += n_values)
                quad[v] = {c[0], c[1], c[2], c[3], c[4]};
              surface.push_back(quad);
            }
          else
            revolve_edge({{c[0], c[1], c[2]}}, {{c[3], c[4], c[5]}}, surface);
        }
    return mesh_info_.quarter ? pileup::mirror_quarter(surface) : surface;
  }

  template <int dim>
  void IndentationProblem<dim>::write_pileup(const std::vector<SurfaceSnapshot> &snapshots,
                                             const double                        contact_radius)
  {
    namespace files = io::output_files;
    pileup_results_.clear();
    for (const SurfaceSnapshot &snapshot : snapshots)
      {
        pileup::PileUpParameters parameters;
        parameters.depth = snapshot.depth;
        parameters.contact_radius = contact_radius;
        // The revolved axisymmetric surface has sectors far narrower than its elements near the
        // axis: its map is sampled at half the contact-element size instead.
        if (mesh_info_.axisymmetric)
          parameters.grid_spacing =
              std::max(0.5 * mesh_info_.contact_element_size, 3 * contact_radius / 200);
        // Only a crystal or a pyramid can break the axial symmetry besides the square mesh.
        parameters.sources.anisotropic_material = case_.material.model == io::ModelKind::crystal;
        parameters.sources.non_axisymmetric_indenter =
            case_.indenter.shape == io::IndenterShape::vickers ||
            case_.indenter.shape == io::IndenterShape::berkovich;
        pileup_results_.push_back(pileup::analyse(snapshot.surface, snapshot.stage, parameters));
        const pileup::PileUpResult &result = pileup_results_.back();
        output::write_file(output_directory_ + "/" +
                               (snapshot.stage == "max_depth" ? files::pileup_max_depth_csv
                                                              : files::pileup_unloaded_csv),
                           [&](std::ostream &out) { pileup::write_grid_csv(out, result.grid); });
        pcout_ << std::defaultfloat << std::setprecision(4) << "Pile-up (" << result.stage
               << ", depth " << result.depth << " um): max height " << result.max_pileup
               << " um at r = " << result.max_pileup_radius << " um, azimuth "
               << result.max_pileup_azimuth_deg << " deg; analysis radius "
               << result.analysis_radius << " um; fold: " << pileup::describe_fold(result.spectrum)
               << std::endl;
      }
    if (pileup_results_.empty())
      return;
    // The unloaded stage (the residual impression, what experiments measure) is the top level;
    // without unloading, the maximum-depth stage.
    output::write_file(output_directory_ + "/" + files::pileup_json, [&](std::ostream &out) {
      pileup::write_json(out, pileup_results_, pileup_results_.back());
    });
    output::write_file(
        output_directory_ + "/" + files::pileup_profiles_csv,
        [&](std::ostream &out) { pileup::write_profiles_csv(out, pileup_results_); });

    // The maps and profiles as PNG files; a missing Python or matplotlib leaves a warning only.
    output::draw_plot("plot_pileup.py", {output_directory_},
                      "of the pile-up in " + output_directory_, std::cerr);
  }
  template class IndentationProblem<2>;
  template class IndentationProblem<3>;
} // namespace indentsim::problems

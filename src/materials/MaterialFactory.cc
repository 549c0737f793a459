#include "materials/MaterialFactory.h"
#include "case/DamageProfile.h"
#include "materials/CrystalPlasticity.h"
#include "materials/J2Plasticity.h"
#include "materials/LayeredMaterial.h"
#include "materials/NeoHookean.h"
#include "materials/crystal/Orientation.h"
#include "materials/crystal/SlipSystems.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace indentsim::materials
{
  namespace
  {
    // One extended Voce law per slip family: the family's block where the case file gives one,
    // the common parameters otherwise; the latent ratio q or the matrix between families.
    FamilyVoceHardening crystal_hardening(const io::MaterialParameters &p,
                                          const SlipSystems            &systems)
    {
      const ExtendedVoceHardening common{p.tau0, p.tau1,    p.theta0,        p.theta1,
                                         p.q,    p.tau_irr, p.softening_slip};
      if (p.family_hardening.empty() && p.latent_matrix.empty())
        return FamilyVoceHardening(common);
      std::vector<ExtendedVoceHardening> laws(systems.families.size(), common);
      for (const io::FamilyHardening &block : p.family_hardening)
        {
          const auto found =
              std::find(systems.families.begin(), systems.families.end(), block.family);
          if (found == systems.families.end())
            throw std::invalid_argument("material.hardening.\"" + block.family +
                                        "\": not one of the slip families");
          laws[found - systems.families.begin()] = {block.tau0,          block.tau1, block.theta0,
                                                    block.theta1,        p.q,        block.tau_irr,
                                                    block.softening_slip};
        }
      return FamilyVoceHardening(laws, systems.family, p.q, p.latent_matrix);
    }

    std::unique_ptr<MaterialModel>
    create_homogeneous_material(const io::MaterialParameters &parameters)
    {
      if (parameters.model == io::ModelKind::neo_hookean)
        return std::make_unique<NeoHookean>(parameters.young_modulus, parameters.poisson_ratio);

      if (parameters.model == io::ModelKind::j2)
        {
          YieldStressMeasure measure;
          if (parameters.yield_stress_measure == io::YieldStressMeasure::cauchy)
            measure = YieldStressMeasure::cauchy;
          else if (parameters.yield_stress_measure == io::YieldStressMeasure::kirchhoff)
            measure = YieldStressMeasure::kirchhoff;
          else
            throw std::invalid_argument("material.yield_stress_measure = \"" +
                                        to_string(parameters.yield_stress_measure) +
                                        "\" is not supported; allowed: cauchy, kirchhoff");
          return std::make_unique<J2Plasticity>(parameters.young_modulus, parameters.poisson_ratio,
                                                create_hardening_law(parameters), measure);
        }

      if (parameters.model == io::ModelKind::crystal)
        {
          const auto       &p = parameters;
          const SlipSystems systems =
              slip_systems(to_string(p.lattice), p.slip_families, p.c_over_a);
          return std::make_unique<CrystalPlasticity>(
              systems,
              p.lattice == io::Lattice::hcp
                  ? LatticeElasticity::hexagonal(p.C11, p.C12, p.C13, p.C33, p.C44)
                  : LatticeElasticity::cubic(p.C11, p.C12, p.C44),
              crystal_hardening(p, systems), p.yield_exponent_n);
        }

      throw std::invalid_argument("material.model = \"" + to_string(parameters.model) +
                                  "\" is not supported; allowed: neo_hookean, j2, crystal");
    }
  } // namespace

  std::unique_ptr<MaterialModel> create_material(const io::MaterialParameters &parameters)
  {
    // A depth-graded specimen (layers or a damage profile): each slab's material as the case
    // validator read it, the material block itself below them.
    const std::vector<io::DepthSlab> slabs = io::depth_slabs(parameters, "material");
    if (slabs.empty())
      return create_homogeneous_material(parameters);
    std::vector<std::unique_ptr<MaterialModel>> layers;
    std::vector<double>                         thicknesses;
    for (const io::DepthSlab &slab : slabs)
      {
        layers.push_back(create_homogeneous_material(slab.material));
        thicknesses.push_back(slab.thickness);
      }
    return std::make_unique<LayeredMaterial>(std::move(layers), std::move(thicknesses),
                                             create_homogeneous_material(parameters));
  }

  IsotropicHardening create_hardening_law(const io::MaterialParameters &parameters)
  {
    const auto &p = parameters;
    if (p.hardening_law == io::HardeningLaw::linear)
      return IsotropicHardening::linear(p.yield_stress, p.hardening_modulus);
    if (p.hardening_law == io::HardeningLaw::power)
      return IsotropicHardening::power(p.yield_stress, p.young_modulus, p.hardening_exponent);
    if (p.hardening_law == io::HardeningLaw::voce)
      return IsotropicHardening::voce(p.yield_stress, p.hardening_saturation, p.hardening_rate,
                                      p.hardening_modulus);
    if (p.hardening_law == io::HardeningLaw::table)
      return IsotropicHardening::table(p.hardening_plastic_strain, p.hardening_stress);
    throw std::invalid_argument("material.hardening.law = \"" + to_string(p.hardening_law) +
                                "\" is not supported; allowed: linear, power, voce, table");
  }

  namespace
  {
    std::string indices_text(const std::vector<double> &indices)
    {
      std::ostringstream text;
      text << '[';
      for (std::size_t i = 0; i < indices.size(); ++i)
        text << (i == 0 ? "" : ", ") << indices[i];
      text << ']';
      return text.str();
    }

    // The indices of material.orientation.<key> as a crystal-frame vector (SlipSystems.h's
    // frames): cubic [hkl] as they are (the plane (hkl) has the normal [hkl]); hcp planes (hkl)
    // = (h k -(h+k) l) through the reciprocal basis, directions [UVW] = U a1 + V a2 + W c, whose
    // Miller-Bravais form is [uvtw] = [(2U - V)/3, (2V - U)/3, -(u + v), W].
    std::array<double, 3> crystal_vector(const io::MaterialParameters &material,
                                         const std::string &key, const bool plane)
    {
      const auto                &o = material.orientation;
      const std::vector<double> &indices = plane ? o.surface_normal : o.reference_direction;
      const bool                 hcp = material.lattice == io::Lattice::hcp;
      const std::string          shown = key + " " + indices_text(indices) + ": ";
      const std::string          letters = plane ? "[h, k, l]" : "[u, v, w]";
      if (indices.size() == 4 && !hcp)
        throw std::invalid_argument(shown + "four Miller-Bravais indices are for hcp only; give " +
                                    letters);
      if (indices.size() != 3 && indices.size() != 4)
        throw std::invalid_argument(shown + "expected 3 indices " + letters +
                                    (hcp ? " or 4 Miller-Bravais indices" : ""));
      if (!hcp)
        return {{indices[0], indices[1], indices[2]}};
      if (std::all_of(indices.begin(), indices.end(), [](const double i) { return i == 0; }))
        throw std::invalid_argument(shown + "names no " + (plane ? "plane" : "direction") +
                                    " (all indices 0)");

      std::array<double, 4> four;
      if (indices.size() == 4)
        {
          const double third = -(indices[0] + indices[1]);
          if (std::abs(indices[2] - third) > 1e-9 * (1 + std::abs(third)))
            {
              std::ostringstream message;
              message << shown << "the third Miller-Bravais index must be "
                      << (plane ? "i = -(h + k) = " : "t = -(u + v) = ") << third << ", not "
                      << indices[2];
              throw std::invalid_argument(message.str());
            }
          four = {{indices[0], indices[1], indices[2], indices[3]}};
        }
      else if (plane)
        four = {{indices[0], indices[1], -(indices[0] + indices[1]), indices[2]}};
      else
        {
          const double u = (2 * indices[0] - indices[1]) / 3, v = (2 * indices[1] - indices[0]) / 3;
          four = {{u, v, -(u + v), indices[2]}};
        }
      const dealii::Tensor<1, 3> vector = plane
                                              ? miller_bravais_plane_normal(four, material.c_over_a)
                                              : miller_bravais_direction(four, material.c_over_a);
      return {{vector[0], vector[1], vector[2]}};
    }
  } // namespace

  dealii::Tensor<2, 3> create_orientation(const io::MaterialParameters &material)
  {
    const io::OrientationParameters &orientation = material.orientation;
    if (orientation.kind == io::OrientationKind::euler_bunge_deg)
      return bunge_rotation(orientation.euler_bunge_deg);
    if (orientation.kind != io::OrientationKind::surface_normal)
      throw std::invalid_argument("material.orientation: kind \"" + to_string(orientation.kind) +
                                  "\" is not supported; allowed: euler_bunge_deg, surface_normal");
    const std::array<double, 3> normal = crystal_vector(material, "surface_normal", true);
    const std::array<double, 3> reference = crystal_vector(material, "reference_direction", false);
    if (material.lattice != io::Lattice::hcp)
      return rotation_from_surface_normal(normal, reference);
    try
      {
        return rotation_from_surface_normal(normal, reference);
      }
    catch (const std::invalid_argument &)
      {
        // Non-zero vectors (crystal_vector): the reference direction is out of the plane. The
        // message in the case file's indices, not the crystal-frame vectors.
        throw std::invalid_argument(
            "reference_direction " + indices_text(orientation.reference_direction) +
            " does not lie in the plane surface_normal " +
            indices_text(orientation.surface_normal) +
            " (hcp: u h + v k + t i + w l = 0 in Miller-Bravais indices, e.g. [2, -1, -1, 0] "
            "in (0, 0, 0, 1))");
      }
  }
} // namespace indentsim::materials

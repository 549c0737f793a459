// The material of the specimen (material.*): the model, its parameters and the crystal
// orientation. Units: stresses and moduli in GPa, angles in degrees.
#pragma once

#include "case/Choice.h"

#include <array>
#include <string>
#include <vector>

namespace indentsim::io
{
  enum class ModelKind
  {
    neo_hookean,
    j2,
    crystal
  };
  template <>
  struct ChoiceWords<ModelKind>
  {
    static constexpr std::array<ChoiceWord<ModelKind>, 3> words = {
        {{ModelKind::neo_hookean, "neo_hookean"},
         {ModelKind::j2, "j2"},
         {ModelKind::crystal, "crystal"}}};
  };

  // The stress that enters the Mises yield function of J2 (eq. 4).
  enum class YieldStressMeasure
  {
    cauchy,
    kirchhoff
  };
  template <>
  struct ChoiceWords<YieldStressMeasure>
  {
    static constexpr std::array<ChoiceWord<YieldStressMeasure>, 2> words = {
        {{YieldStressMeasure::cauchy, "cauchy"}, {YieldStressMeasure::kirchhoff, "kirchhoff"}}};
  };

  // The isotropic hardening law of J2 (material.hardening.law; materials/IsotropicHardening.h).
  enum class HardeningLaw
  {
    linear,
    power,
    voce,
    table
  };
  template <>
  struct ChoiceWords<HardeningLaw>
  {
    static constexpr std::array<ChoiceWord<HardeningLaw>, 4> words = {
        {{HardeningLaw::linear, "linear"},
         {HardeningLaw::power, "power"},
         {HardeningLaw::voce, "voce"},
         {HardeningLaw::table, "table"}}};
  };

  // The crystal lattice (materials/crystal/SlipSystems.h: its slip families and frame).
  enum class Lattice
  {
    fcc,
    bcc,
    hcp
  };
  template <>
  struct ChoiceWords<Lattice>
  {
    static constexpr std::array<ChoiceWord<Lattice>, 3> words = {
        {{Lattice::fcc, "fcc"}, {Lattice::bcc, "bcc"}, {Lattice::hcp, "hcp"}}};
  };

  // Which form of material.orientation the case file gave.
  enum class OrientationKind
  {
    euler_bunge_deg,
    surface_normal
  };
  template <>
  struct ChoiceWords<OrientationKind>
  {
    static constexpr std::array<ChoiceWord<OrientationKind>, 2> words = {
        {{OrientationKind::euler_bunge_deg, "euler_bunge_deg"},
         {OrientationKind::surface_normal, "surface_normal"}}};
  };

  // Crystal orientation (material.orientation). Bunge convention, passive: the rotation matrix
  // g = R_z(phi2) R_x(Phi) R_z(phi1) maps sample components to crystal components,
  // v_crystal = g v_sample. Alternatively the crystal direction [hkl] along the sample z axis
  // (the indented plane's normal) and the crystal direction [uvw] along the sample x axis.
  struct OrientationParameters
  {
    Choice<OrientationKind> kind = OrientationKind::euler_bunge_deg;
    std::array<double, 3>   euler_bunge_deg = {{0., 0., 0.}}; // (phi1, Phi, phi2) [deg]
    // Miller indices: cubic [hkl], [uvw]; hcp three-index (hkl), [UVW] or four-index
    // Miller-Bravais (hkil), [uvtw] (crystal/SlipSystems.h converts them).
    std::vector<double> surface_normal = {0., 0., 1.};      // the indented plane
    std::vector<double> reference_direction = {1., 0., 0.}; // the direction along sample x

    bool operator==(const OrientationParameters &) const = default;
  };

  // One slip family's own extended Voce and irradiation parameters
  // (material.hardening."{112}<111>": {...}); the keys a block leaves out take the common values
  // (material.hardening.tau0, ...) when read.
  struct FamilyHardening
  {
    std::string family;                // a name of SlipSystems.h, one of slip_families
    double      tau0 = 0;              // [GPa]
    double      tau1 = 0;              // [GPa]
    double      theta0 = 0;            // [GPa]
    double      theta1 = 0;            // [GPa]
    double      tau_irr = 0;           // tau_irr,0 [GPa]
    double      softening_slip = 0.05; // gamma_0 [-] (the common default)
    double      barrier_strength = 0;  // alpha of the dispersed-barrier law [-]

    bool operator==(const FamilyHardening &) const = default;
  };

  // One layer of a depth-graded material (material.layers), from the surface down: its
  // thickness and the material keys it gives its own values, as flow YAML. The layer's material
  // is the material block as resolved (every key written out, as in resolved_case.yaml) with
  // these keys replaced (case/MaterialLayers.h).
  struct MaterialLayer
  {
    double      thickness = 0; // [um], >= 0
    std::string overrides;     // e.g. "{yield_stress: 0.6}"

    bool operator==(const MaterialLayer &) const = default;
  };

  // How the damage of a damage profile raises the strength (material.damage_profile.law).
  enum class DamageLaw
  {
    saturation,       // j2: Delta sigma_y = Delta sigma_sat (1 - exp(-d/d0))^p
    table,            // j2: Delta sigma_y piecewise linear in d
    dispersed_barrier // crystal: tau_irr,0 = alpha mu b sqrt(N(d) D), N = N_sat (1 - exp(-d/d0))
  };
  template <>
  struct ChoiceWords<DamageLaw>
  {
    static constexpr std::array<ChoiceWord<DamageLaw>, 3> words = {
        {{DamageLaw::saturation, "saturation"},
         {DamageLaw::table, "table"},
         {DamageLaw::dispersed_barrier, "dispersed_barrier"}}};
  };

  // A damage profile (material.damage_profile): the damage d [dpa] against the depth below the
  // original surface, and the law that turns it into strength (case/DamageProfile.h). Empty
  // depth: no profile.
  struct DamageProfileParameters
  {
    std::string         file;               // CSV read into the two lists below ("": inline)
    std::vector<double> depth;              // [um], from >= 0, strictly increasing
    std::vector<double> dpa;                // d [dpa] >= 0, one per depth
    double              resolution = 0.005; // the sampling slabs' thickness [um]
    Choice<DamageLaw>   law = DamageLaw::saturation;
    double              saturation_increment = 0.0; // Delta sigma_sat [GPa] (saturation)
    double              saturation_dose = 0.1;      // d0 [dpa] (saturation, dispersed_barrier)
    double              exponent = 1.0;             // p [-] (saturation)
    std::vector<double> table_dpa;                  // d_i [dpa] (table)
    std::vector<double> table_delta_yield_stress;   // Delta sigma_y,i [GPa] (table)
    // dispersed_barrier (placeholders of the schema's ranges otherwise: the form needs them).
    double shear_modulus = 1.0;      // mu [GPa]
    double burgers_vector = 1.0;     // b [um]
    double defect_size = 1.0;        // D, the defects' diameter [um]
    double saturation_density = 1.0; // N_sat [1/um^3]

    bool given() const { return !depth.empty() || !file.empty(); }
    bool operator==(const DamageProfileParameters &) const = default;
  };

  // The depth of the last layer's bottom below the original surface: the layers' total
  // thickness [um] (0 without layers).
  inline double layered_depth(const std::vector<MaterialLayer> &layers)
  {
    double depth = 0;
    for (const MaterialLayer &layer : layers)
      depth += layer.thickness;
    return depth;
  }

  struct MaterialParameters
  {
    Choice<ModelKind>          model = ModelKind::j2;
    double                     young_modulus = 69.0;    // E [GPa]
    double                     poisson_ratio = 0.26;    // nu [-], -1 < nu < 0.5
    double                     yield_stress = 0.305;    // sigma_y0 [GPa]
    double                     hardening_modulus = 0.5; // H [GPa], linear isotropic hardening
    Choice<YieldStressMeasure> yield_stress_measure = YieldStressMeasure::cauchy;

    // The J2 hardening law (material.hardening.law and its keys); linear uses
    // hardening_modulus, voce adds it as its linear term.
    Choice<HardeningLaw> hardening_law = HardeningLaw::linear;
    double               hardening_exponent = 0.0;   // n (power), 0 <= n < 1
    double               hardening_saturation = 0.0; // Q [GPa] (voce)
    double               hardening_rate = 1.0;       // b [-] (voce); a placeholder unless voce
    std::vector<double>  hardening_plastic_strain;   // table: eps_p,i [-]
    std::vector<double>  hardening_stress;           // table: true stress sigma_i [GPa]
    std::string          hardening_file; // table: CSV read into the two lists above ("": inline)

    // Crystal plasticity (model: crystal), the paper's section 2.2 and Table 2.
    Choice<Lattice> lattice = Lattice::fcc; // fcc: {111}<110>, 12 slip systems
    // The slip families (SlipSystems.h names); empty: the lattice's default ones.
    std::vector<std::string> slip_families;
    double                   c_over_a = 0.0;                      // hcp: c/a [-]; 0: not given
    double                   C11 = 106.7, C12 = 60.4, C44 = 28.3; // elastic constants [GPa]
    double                   C13 = 0.0, C33 = 0.0; // hcp's further constants [GPa]; 0: not given
    double                   tau0 = 0.12;          // initial critical resolved shear stress [GPa]
    double                   tau1 = 0.02;          // Voce back-extrapolated increment [GPa]
    double                   theta0 = 0.1;         // initial hardening rate [GPa]
    double                   theta1 = 0.006;       // asymptotic hardening rate [GPa]
    double                   q = 1.4;              // latent hardening ratio [-]
    double                   tau_irr = 0.0; // the irradiation defects' initial critical shear [GPa]
    double                   softening_slip = 0.05; // gamma_0, the slip that sweeps them out [-]
    double barrier_strength = 0.0; // alpha of the dispersed-barrier law (damage_profile) [-]
    std::vector<FamilyHardening> family_hardening; // blocks given per family, in file order
    // Latent ratios q_fg between families f and g (rows and columns in slip_families order);
    // empty: q for every pair of distinct systems.
    std::vector<std::vector<double>> latent_matrix;
    double yield_exponent_n = 10; // n of the regularized Schmid law (exponent 2n), eq. 14
    OrientationParameters orientation;
    // Layers from the surface down; below the last one the parameters above hold (the
    // substrate). Empty: a homogeneous specimen.
    std::vector<MaterialLayer> layers;
    // A depth-graded material from a damage profile (excludes layers).
    DamageProfileParameters damage_profile;

    bool operator==(const MaterialParameters &) const = default;
  };
} // namespace indentsim::io

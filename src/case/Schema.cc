// The case-file schema table (see Schema.h). Each entry: the path, where the value is stored,
// the unit, what the reader expects, the admissible range with the validator's message, the
// resolved case's comment and the reference's description.
#include "case/Schema.h"
#include "case/SchemaBuilder.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace indentsim::io
{
  using namespace schema_builder;

  namespace
  {
    // Successive halvings of a load increment beyond this leave increments of 1e-9 of the
    // original: more would only hide a model problem.
    constexpr double max_cutbacks = 30;

    // n <= 50 keeps (tau / tau_c)^(2n) of eq. 14 finite for every ratio tau / tau_c < 1000 that a
    // trial state may reach ((10^3)^100 = 10^300 < 1.8e308); the paper uses n = 10.
    constexpr double max_yield_exponent = 50;

    // The tensile cube has elements_per_side^3 cells; beyond this it would not fit in memory
    // (and n^3 would overflow the orientation count).
    constexpr double max_elements_per_side = 200;

    // Upper bounds of the count keys: far above any useful value, low enough that a typo (an
    // extra digit or two) is named at once instead of exhausting memory or time. The memory a
    // mesh needs is estimated and checked against the machine before a run
    // (output/MemoryEstimate.h); 512 contact elements on the default refined region need
    // about 40 M cells.
    constexpr double max_steps = 100000;
    constexpr double max_iterations = 1000;

    using C = Case;
    using M = MaterialParameters;
    using OP = OrientationParameters;
    using I = IndenterParameters;
    using S = SpecimenParameters;
    using L = LoadingParameters;
    using PU = PartialUnloads;
    using DP = DamageProfileParameters;
    using CP = ContactParameters;
    using SP = SolverParameters;
    using OU = OutputParameters;

    // specimen.contact_elements: auto designs the refined region (mesh/MeshDesign.h).
    bool explicit_mesh(const Case &c)
    {
      return !c.specimen.automatic_mesh();
    }
    bool automatic_mesh(const Case &c)
    {
      return c.specimen.automatic_mesh();
    }
    bool graded_automatic_mesh(const Case &c)
    {
      return automatic_mesh(c) && (!c.material.layers.empty() || c.material.damage_profile.given());
    }
    bool linear_hardening(const Case &c)
    {
      return c.material.hardening_law == HardeningLaw::linear;
    }
    bool nonlinear_hardening(const Case &c)
    {
      return !linear_hardening(c);
    }
    bool power_hardening(const Case &c)
    {
      return c.material.hardening_law == HardeningLaw::power;
    }
    bool geometric_spacing(const Case &c)
    {
      return c.loading.spacing == Spacing::geometric;
    }
    bool partial_unloads_given(const Case &c)
    {
      return c.loading.partial_unloads.enabled();
    }
    bool voce_hardening(const Case &c)
    {
      return c.material.hardening_law == HardeningLaw::voce;
    }
    bool inline_hardening_table(const Case &c)
    {
      return c.material.hardening_law == HardeningLaw::table && c.material.hardening_file.empty();
    }
    bool hardening_table(const Case &c)
    {
      return c.material.hardening_law == HardeningLaw::table;
    }
    bool hardening_table_file(const Case &c)
    {
      return c.material.hardening_law == HardeningLaw::table && !c.material.hardening_file.empty();
    }

    bool hexagonal(const Case &c)
    {
      return c.material.lattice == Lattice::hcp;
    }
    bool not_fcc(const Case &c)
    {
      return c.material.lattice != Lattice::fcc;
    }

    bool family_hardening_given(const Case &c)
    {
      return !c.material.family_hardening.empty();
    }
    // A crystal with irradiation defects (material.hardening.tau_irr or a dispersed-barrier
    // damage profile, in the common block or a family's).
    bool crystal_irradiation(const Case &c)
    {
      const MaterialParameters &m = c.material;
      bool                      given = m.tau_irr > 0 || m.barrier_strength > 0;
      for (const FamilyHardening &block : m.family_hardening)
        given = given || block.tau_irr > 0 || block.barrier_strength > 0;
      return m.model == ModelKind::crystal && given;
    }
    bool latent_matrix_given(const Case &c)
    {
      return !c.material.latent_matrix.empty();
    }
    // An alternative spelling of a key that the resolved case writes under another path.
    bool never_written(const Case &)
    {
      return false;
    }
    bool layers_given(const Case &c)
    {
      return !c.material.layers.empty();
    }
    bool damage_profile_given(const Case &c)
    {
      return c.material.damage_profile.given();
    }
    bool inline_damage_profile(const Case &c)
    {
      return damage_profile_given(c) && c.material.damage_profile.file.empty();
    }
    bool damage_profile_file(const Case &c)
    {
      return !c.material.damage_profile.file.empty();
    }
    bool damage_law_is(const Case &c, const DamageLaw law)
    {
      return damage_profile_given(c) && c.material.damage_profile.law == law;
    }
    bool saturation_damage_law(const Case &c)
    {
      return damage_law_is(c, DamageLaw::saturation);
    }
    bool saturating_damage_law(const Case &c)
    {
      return saturation_damage_law(c) || damage_law_is(c, DamageLaw::dispersed_barrier);
    }
    bool table_damage_law(const Case &c)
    {
      return damage_law_is(c, DamageLaw::table);
    }
    bool barrier_damage_law(const Case &c)
    {
      return damage_law_is(c, DamageLaw::dispersed_barrier);
    }
    bool orientation_by_normal(const Case &c)
    {
      return c.material.orientation.kind == OrientationKind::surface_normal;
    }
    bool orientation_by_angles(const Case &c)
    {
      return !orientation_by_normal(c);
    }

    std::vector<Key> top_level_keys()
    {
      using D = Declare;
      return {
          D::at<&C::test>("test")
              .expect("the kind of test")
              .required()
              .comment("indentation | tensile")
              .describe("the kind of test: indentation of a block, or the tensile test of a cube"),
          D::at<&C::compare_j2>("compare_j2")
              .comment("tensile: also run J2 (young_modulus...) on the same mesh")
              .describe("`tensile` only: repeat the run with J2 (`young_modulus`, `poisson_ratio`, "
                        "`yield_stress`, `hardening_modulus`) on the same cube; command line "
                        "`--compare-j2` sets it"),
      };
    }

    std::vector<Key> material_keys()
    {
      using D = Declare;
      return {
          D::at<&C::material, &M::model>("material.model")
              .expect("the material model")
              .required()
              .comment("neo_hookean | j2 | crystal")
              .describe("hyperelastic neo-Hookean, finite-strain J2 plasticity, or crystal "
                        "plasticity"),
          D::at<&C::material, &M::young_modulus>("material.young_modulus")
              .unit("GPa")
              .expect("E in GPa")
              .range(above(0), "Young's modulus E must be > 0 GPa")
              .comment("E [GPa]")
              .describe("Young's modulus E (neo_hookean, j2)"),
          D::at<&C::material, &M::poisson_ratio>("material.poisson_ratio")
              .expect("nu")
              .range(between(-1, false, 0.5, false),
                     "Poisson's ratio must satisfy -1 < nu < 0.5 (0.5 is incompressible, which a "
                     "displacement formulation cannot represent)")
              .comment("nu [-], -1 < nu < 0.5")
              .describe("Poisson's ratio ν (neo_hookean, j2)"),
          D::at<&C::material, &M::yield_stress>("material.yield_stress")
              .unit("GPa")
              .expect("sigma_y0 in GPa")
              .range(above(0), "the initial yield stress sigma_y0 must be > 0 GPa")
              .comment("sigma_y0 [GPa] (j2)")
              .describe("initial yield stress σy0 (j2)"),
          D::at<&C::material, &M::hardening_modulus>("material.hardening_modulus")
              .unit("GPa")
              .expect("H in GPa")
              .range(at_least(0),
                     "the hardening modulus H must be >= 0 GPa (0: perfect plasticity)")
              .written_if(&linear_hardening)
              .comment("H [GPa], linear isotropic hardening (j2)")
              .describe("linear isotropic hardening modulus H, σy = σy0 + H εp; 0: perfect "
                        "plasticity (j2; or `hardening: {law: linear, modulus: H}`, never both)"),
          D::at<&C::material, &M::yield_stress_measure>("material.yield_stress_measure")
              .expect("a stress measure")
              .comment("cauchy | kirchhoff: stress in the Mises yield function (j2)")
              .describe("the stress in the Mises yield function, eq. 4 (j2)"),
          D::at<&C::material, &M::lattice>("material.lattice")
              .expect("a lattice")
              .comment("fcc | bcc | hcp (crystal)")
              .describe("the crystal lattice: `fcc` ({111}⟨110⟩ slip), `bcc`, `hcp` with the slip "
                        "families of `slip_families`; the crystal frames in the user guide "
                        "(crystal)"),
          D::at<&C::material, &M::slip_families>("material.slip_families")
              .entries("slip family names", "a slip family")
              .written_if(&not_fcc)
              .default_is("bcc: [\"{110}<111>\"]; hcp: [basal, prismatic, pyramidal_ca]")
              .allowed_is("bcc: {110}<111>, {112}<111>, {123}<111>; hcp: basal, prismatic, "
                          "pyramidal_a, pyramidal_ca, pyramidal_ca2; each once")
              .comment("slip families (crystal)")
              .describe("the slip families of the lattice, each once; quote the bcc names "
                        "(YAML reads `{` as a map): `[\"{110}<111>\", \"{112}<111>\"]` (crystal)"),
          D::at<&C::material, &M::c_over_a>("material.c_over_a")
              .expect("the ratio c/a")
              .written_if(&hexagonal)
              .default_is("– (required for hcp)")
              .allowed_is("> 0 (hcp only)")
              .comment("c/a of the hexagonal cell (hcp)")
              .describe("c/a of the hexagonal lattice, e.g. 1.593 (Zr), 1.587 (Ti) (hcp)"),
          D::at<&C::material, &M::C11>("material.elastic.C11")
              .unit("GPa")
              .expect("C11 in GPa")
              .comment("[GPa]")
              .describe("cubic stiffness in the lattice frame; positive definite with C12, C44: "
                        "C11 − C12 > 0, C11 + 2 C12 > 0 (crystal)"),
          D::at<&C::material, &M::C12>("material.elastic.C12")
              .unit("GPa")
              .expect("C12 in GPa")
              .comment("[GPa]")
              .describe("cubic stiffness in the lattice frame (crystal)"),
          D::at<&C::material, &M::C44>("material.elastic.C44")
              .unit("GPa")
              .expect("C44 in GPa")
              .allowed_is("> 0; checked with C11 and C12 (positive definite)")
              .comment("[GPa]")
              .describe("cubic shear stiffness in the lattice frame; hcp: the shear stiffness on "
                        "planes containing c (crystal)"),
          D::at<&C::material, &M::C13>("material.elastic.C13")
              .unit("GPa")
              .expect("C13 in GPa")
              .written_if(&hexagonal)
              .default_is("– (required for hcp)")
              .allowed_is("positive definite with C11, C12, C33, C44 (hcp only)")
              .comment("[GPa]")
              .describe("hexagonal stiffness, c along z: C13 couples the basal and c directions "
                        "(hcp)"),
          D::at<&C::material, &M::C33>("material.elastic.C33")
              .unit("GPa")
              .expect("C33 in GPa")
              .written_if(&hexagonal)
              .default_is("– (required for hcp)")
              .allowed_is("positive definite with C11, C12, C13, C44 (hcp only)")
              .comment("[GPa]")
              .describe("hexagonal stiffness along c (hcp); C66 = (C11 − C12)/2"),
          D::at<&C::material, &M::hardening_law>("material.hardening.law")
              .expect("a hardening law")
              .written_if(&nonlinear_hardening)
              .default_is("`linear` with `hardening_modulus`")
              .comment("j2: linear | power | voce | table")
              .describe("the J2 hardening law σy(εp) (j2; see the user guide): `linear` needs "
                        "`modulus`; `power` σy0 (1 + E εp/σy0)^n needs `exponent`; `voce` "
                        "σy0 + Q (1 − exp(−b εp)) + H εp needs `saturation`, `rate` (`modulus` "
                        "optional); `table` needs `plastic_strain` and `stress`, or `file`"),
          D::at<&C::material, &M::hardening_modulus>("material.hardening.modulus")
              .unit("GPa")
              .expect("H in GPa")
              .range(at_least(0),
                     "the hardening modulus H must be >= 0 GPa (0: perfect plasticity)")
              .written_if(&voce_hardening)
              .default_is("– (linear: required; voce: 0)")
              .comment("H [GPa], linear term")
              .describe("H: the slope of `law: linear` (the same as `hardening_modulus`), the "
                        "linear term of `law: voce` (default 0) (j2)"),
          D::at<&C::material, &M::hardening_exponent>("material.hardening.exponent")
              .expect("the power-law exponent n")
              .range(between(0, true, 1, false),
                     "the power-law exponent n must satisfy 0 <= n < 1 (0: perfect plasticity)")
              .written_if(&power_hardening)
              .default_is("– (required for power)")
              .comment("n [-], 0 <= n < 1")
              .describe("n of `law: power`, σy = σy0 (1 + E εp/σy0)^n with E = `young_modulus` "
                        "(Dao et al. 2001); 0: perfect plasticity (j2)"),
          D::at<&C::material, &M::hardening_saturation>("material.hardening.saturation")
              .unit("GPa")
              .expect("Q in GPa")
              .range(finite_at_least(0), "the Voce saturation Q must be a finite stress >= 0 GPa")
              .written_if(&voce_hardening)
              .default_is("– (required for voce)")
              .comment("Q [GPa]")
              .describe("Q of `law: voce`: σy tends to σy0 + Q (+ H εp) (j2)"),
          D::at<&C::material, &M::hardening_rate>("material.hardening.rate")
              .expect("the Voce rate b")
              .range(finite_above(0), "the Voce rate b must be finite and > 0 (dimensionless)")
              .written_if(&voce_hardening)
              .default_is("– (required for voce)")
              .comment("b [-]")
              .describe("b of `law: voce`: the saturation is reached at εp of a few 1/b; the "
                        "initial slope is Q b + H (j2)"),
          D::at<&C::material, &M::hardening_plastic_strain>("material.hardening.plastic_strain")
              .entries("plastic strains", "a plastic strain")
              .range(finite_at_least(0), "the plastic strains must be finite and >= 0")
              .fingerprinted_if(&hardening_table)
              .written_if(&inline_hardening_table)
              .default_is("– (table)")
              .allowed_is("from 0, strictly increasing, ≥ 2 points")
              .comment("eps_p [-], from 0, increasing")
              .describe("`law: table`: the equivalent plastic strains εp of the points, from 0 "
                        "and strictly increasing (j2)"),
          D::at<&C::material, &M::hardening_stress>("material.hardening.stress")
              .unit("GPa")
              .entries("true stresses in GPa", "a stress in GPa")
              .range(finite_above(0), "the stresses must be finite and > 0 GPa")
              .fingerprinted_if(&hardening_table)
              .written_if(&inline_hardening_table)
              .default_is("– (table)")
              .allowed_is("> 0, non-decreasing, the first = `yield_stress`")
              .comment("true stress [GPa], the first = yield_stress")
              .describe("`law: table`: the true (Cauchy) stress at each plastic strain; "
                        "non-decreasing; the first is the initial yield stress and must equal "
                        "`yield_stress`; piecewise linear between the points, beyond the last "
                        "continued with the last segment's slope (j2)"),
          D::at<&C::material, &M::hardening_file>("material.hardening.file")
              .unit("path")
              .expect("the path of a CSV hardening table")
              .relative_to_case_file()
              .not_a_result() // the fingerprint takes its content: the two lists above
              .written_if(&hardening_table_file)
              .default_is("– (table)")
              .comment("table: CSV plastic_strain,true_stress_GPa")
              .describe("`law: table` from a CSV file instead of the two lists, relative to the "
                        "case file's directory: a header `plastic_strain,true_stress_GPa` (or "
                        "`..._MPa`), then one point per line (j2)"),
          D::at<&C::material, &M::tau0>("material.hardening.tau0")
              .unit("GPa")
              .expect("tau0 in GPa")
              .range(above(0), "the initial critical resolved shear stress tau0 must be > 0 GPa")
              .comment("initial critical shear [GPa]")
              .describe("initial critical resolved shear stress τ0 (crystal)"),
          D::at<&C::material, &M::tau1>("material.hardening.tau1")
              .unit("GPa")
              .expect("tau1 in GPa")
              .range(at_least(0), "must be >= 0 GPa")
              .comment("[GPa]")
              .describe(
                  "Voce saturation increment τ1; > 0 when `theta0` > 0 (the Voce law τc = τ0 + "
                  "(τ1 + θ1 Γ)(1 − exp(−θ0 Γ/τ1)) divides by τ1) (crystal)"),
          D::at<&C::material, &M::theta0>("material.hardening.theta0")
              .unit("GPa")
              .expect("theta0 in GPa")
              .range(at_least(0), "must be >= 0 GPa")
              .comment("initial hardening rate [GPa]")
              .describe("initial hardening rate θ0 (crystal)"),
          D::at<&C::material, &M::theta1>("material.hardening.theta1")
              .unit("GPa")
              .expect("theta1 in GPa")
              .range(at_least(0), "must be >= 0 GPa")
              .comment("asymptotic hardening rate [GPa]")
              .describe("asymptotic hardening rate θ1 (crystal)"),
          D::at<&C::material, &M::q>("material.hardening.q")
              .expect("the latent hardening ratio q")
              .range(at_least(0),
                     "the latent hardening ratio q must be >= 0 (1: isotropic hardening)")
              .comment("latent hardening ratio [-]")
              .describe("latent hardening ratio q, h_rs = q for r ≠ s, 1 for r = s (1: "
                        "isotropic hardening); or `latent_hardening: {q: ...}`, never both "
                        "(crystal)"),
          D::at<&C::material, &M::tau_irr>("material.hardening.tau_irr")
              .unit("GPa")
              .expect("tau_irr in GPa")
              .range(finite_at_least(0), "the irradiation term tau_irr must be finite and >= 0 GPa")
              .written_if(&crystal_irradiation)
              .comment("irradiation defects' initial critical shear [GPa]")
              .describe("τirr,0: the critical shear that irradiation defects add, swept out by "
                        "slip, τc = τc(Γ) + τirr,0 exp(−Γ/γ0); 0: none. Set per layer, or by a "
                        "`damage_profile` (crystal)"),
          D::at<&C::material, &M::softening_slip>("material.hardening.softening_slip")
              .expect("the softening slip gamma_0")
              .range(finite_above(0), "the softening slip gamma_0 must be finite and > 0")
              .written_if(&crystal_irradiation)
              .comment("gamma_0 of tau_irr exp(-Gamma/gamma_0) [-]")
              .describe("γ0: the total slip Γ over which the irradiation term decays by 1/e "
                        "(crystal)"),
          D::at<&C::material, &M::barrier_strength>("material.hardening.barrier_strength")
              .expect("the barrier strength alpha")
              .range(finite_at_least(0), "the barrier strength alpha must be finite and >= 0")
              .written_if(&crystal_irradiation)
              .comment("alpha of the dispersed-barrier law [-]")
              .describe("α of the damage law `form: dispersed_barrier`, τirr,0 = α μ b √(N D), "
                        "typically 0.1–0.5 for dislocation loops; per family where they differ "
                        "(crystal)"),
          D::at<&C::material, &M::family_hardening>("material.hardening.<family>")
              .written_if(&family_hardening_given)
              .default_is("– (every family: the keys above)")
              .allowed_is("a family of `slip_families`, each once; keys `tau0`, `tau1`, "
                          "`theta0`, `theta1`, `tau_irr`, `softening_slip`, `barrier_strength` "
                          "as above")
              .comment("[GPa]")
              .describe("one slip family's own Voce parameters, e.g. `\"{112}<111>\": {tau0: "
                        "0.42, tau1: 0.1, theta0: 1, theta1: 0.01}`; the keys a block leaves out "
                        "take the values above, families without a block take them all (crystal)"),
          D::at<&C::material, &M::q>("material.latent_hardening.q")
              .expect("the latent hardening ratio q")
              .written_if(&never_written)
              .default_is("`hardening.q`")
              .allowed_is("≥ 0")
              .comment("latent hardening ratio [-]")
              .describe("the latent hardening ratio q, the same as `hardening.q` (give one); the "
                        "resolved case writes it as `hardening.q` (crystal)"),
          D::at<&C::material, &M::latent_matrix>("material.latent_hardening.matrix")
              .written_if(&latent_matrix_given)
              .default_is("– (q for every pair)")
              .allowed_is("n×n numbers ≥ 0, n the number of `slip_families`")
              .comment("q_fg between families, in slip_families order [-]")
              .describe("latent ratios q_fg between the families f and g, rows and columns in "
                        "the order of `slip_families`: h_rs = q_f(r)f(s) for r ≠ s, 1 for r = s; "
                        "replaces q (crystal)"),
          D::at<&C::material, &M::yield_exponent_n>("material.yield_exponent_n")
              .expect("the exponent n of eq. 14")
              .range(between(1, true, max_yield_exponent, true),
                     "n (exponent 2n in eq. 14) must satisfy 1 <= n <= " +
                         format_number(max_yield_exponent) +
                         " (a real number; larger n makes (tau/tau_c)^(2n) overflow)")
              .comment("n, exponent 2n of eq. 14 (crystal)")
              .describe("real exponent 2n of the regularized Schmid law (eq. 14); larger n would "
                        "overflow (τ/τc)^2n (crystal)"),
          D::at<&C::material, &M::orientation, &OP::euler_bunge_deg>(
              "material.orientation.euler_bunge_deg")
              .unit("deg")
              .entries("[phi1, Phi, phi2] in degrees", "degrees")
              .written_if(&orientation_by_angles)
              .comment("(phi1, Phi, phi2) [deg]")
              .describe("Bunge Euler angles (φ1, Φ, φ2); **or** the next two keys, never both "
                        "(crystal)"),
          D::at<&C::material, &M::orientation, &OP::surface_normal>(
              "material.orientation.surface_normal")
              .entries("[h, k, l], or [h, k, i, l] for hcp", "a Miller index")
              .written_if(&orientation_by_normal)
              .default_is("–")
              .allowed_is("3 numbers, not all 0; hcp also 4 with i = −(h + k)")
              .comment("indented plane (hkl) or (hkil), normal along sample z")
              .describe("the indented plane, whose normal lies along sample z: cubic (hkl), "
                        "the normal is the direction [hkl]; hcp (hkl) or Miller–Bravais (hkil); "
                        "needs `reference_direction` (crystal)"),
          D::at<&C::material, &M::orientation, &OP::reference_direction>(
              "material.orientation.reference_direction")
              .entries("[u, v, w], or [u, v, t, w] for hcp", "a Miller index")
              .written_if(&orientation_by_normal)
              .default_is("–")
              .allowed_is("3 numbers, not all 0; hcp also 4 with t = −(u + v); in the plane")
              .comment("crystal direction [uvw] or [uvtw] along sample x")
              .describe("the crystal direction along sample x, in the indented plane (not "
                        "guessed): cubic [uvw]; hcp [uvw] = u a1 + v a2 + w c or Miller–Bravais "
                        "[uvtw] (crystal)"),
          D::at<&C::material, &M::layers>("material.layers")
              .written_if(&layers_given)
              .default_is("– (homogeneous)")
              .allowed_is("a list of maps, each `thickness` (µm, ≥ 0) and keys of `material` "
                          "other than `model`, `lattice`, `slip_families`, `c_over_a`, "
                          "`orientation`, `hardening.law` and `layers`")
              .comment("from the surface down [um, GPa]")
              .describe("a depth-graded specimen (indentation): layers from the surface down, "
                        "e.g. `[{thickness: 1.5, yield_stress: 0.6}]`; each layer is the "
                        "material block with the keys it gives replaced (nested maps key by "
                        "key), the material block itself holds below the last layer (the "
                        "substrate). A quadrature point takes the layer of its depth below the "
                        "undeformed surface"),
          D::at<&C::material, &M::damage_profile, &DP::file>("material.damage_profile.file")
              .unit("path")
              .expect("the path of a CSV damage profile")
              .relative_to_case_file()
              .not_a_result() // the fingerprint takes its content: the two lists below
              .written_if(&damage_profile_file)
              .default_is("– (homogeneous)")
              .comment("CSV: depth with its unit, dpa")
              .describe("a depth-graded specimen from a damage profile (indentation; not with "
                        "`layers`): a CSV relative to the case file's directory with a depth "
                        "column whose name carries its unit (`depth_um`, `depth_nm`, "
                        "`depth (nm)`) and a `dpa` column, from the surface down (user guide, "
                        "\"Damage profiles\"); or the two lists below; `law` turns the dose into "
                        "strength"),
          D::at<&C::material, &M::damage_profile, &DP::depth>("material.damage_profile.depth")
              .unit("um")
              .entries("depths in um", "a depth in um")
              .range(finite_at_least(0), "the depths must be finite and >= 0 um")
              .fingerprinted_if(&damage_profile_given)
              .written_if(&inline_damage_profile)
              .default_is("–")
              .allowed_is("≥ 0, strictly increasing, ≥ 2 points")
              .comment("depth below the original surface [um]")
              .describe("the profile inline: depths below the undeformed surface, strictly "
                        "increasing; above the first the first dose holds, below the last the "
                        "substrate"),
          D::at<&C::material, &M::damage_profile, &DP::dpa>("material.damage_profile.dpa")
              .unit("dpa")
              .entries("doses in dpa", "a dose in dpa")
              .range(finite_at_least(0), "the doses must be finite and >= 0 dpa")
              .fingerprinted_if(&damage_profile_given)
              .written_if(&inline_damage_profile)
              .default_is("–")
              .allowed_is("≥ 0, one per depth, some > 0")
              .comment("damage [dpa]")
              .describe("the damage (displacements per atom) at each depth; linear in between"),
          D::at<&C::material, &M::damage_profile, &DP::resolution>(
              "material.damage_profile.resolution")
              .unit("um")
              .expect("the sampling thickness in um")
              .range(finite_above(0), "the resolution must be finite and > 0 um")
              .written_if(&damage_profile_given)
              .comment("sampling slab thickness [um]")
              .describe("the profile is sampled in slabs of this thickness: a quadrature point "
                        "takes the strength at its slab's centre (so within half of it of its "
                        "own depth)"),
          D::at<&C::material, &M::damage_profile, &DP::law>("material.damage_profile.law.form")
              .expect("a dose-to-strength law")
              .written_if(&damage_profile_given)
              .default_is("– (required with a profile)")
              .comment("saturation | table (j2) | dispersed_barrier (crystal)")
              .describe("how the dose d raises the strength: `saturation` Δσy = Δσsat (1 − "
                        "exp(−d/d0))^p and `table` (j2, added to `yield_stress`); "
                        "`dispersed_barrier` τirr,0 = α μ b √(N D), N = Nsat (1 − exp(−d/d0)) "
                        "(crystal, the irradiation term of `hardening.tau_irr`)"),
          D::at<&C::material, &M::damage_profile, &DP::saturation_increment>(
              "material.damage_profile.law.saturation_increment")
              .unit("GPa")
              .expect("Delta sigma_sat in GPa")
              .range(finite_at_least(0), "Delta sigma_sat must be finite and >= 0 GPa")
              .written_if(&saturation_damage_law)
              .comment("Delta sigma_sat [GPa]")
              .describe("Δσsat of `form: saturation`: the yield stress increment at high dose "
                        "(j2)"),
          D::at<&C::material, &M::damage_profile, &DP::saturation_dose>(
              "material.damage_profile.law.saturation_dose")
              .unit("dpa")
              .expect("d0 in dpa")
              .range(finite_above(0), "the saturation dose d0 must be finite and > 0 dpa")
              .written_if(&saturating_damage_law)
              .comment("d0 [dpa]")
              .describe("d0 of `saturation` and `dispersed_barrier`: the dose scale of the "
                        "saturation"),
          D::at<&C::material, &M::damage_profile, &DP::exponent>(
              "material.damage_profile.law.exponent")
              .expect("the exponent p")
              .range(finite_above(0), "the exponent p must be finite and > 0")
              .written_if(&saturation_damage_law)
              .comment("p [-]")
              .describe("p of `form: saturation` (0.5: the dispersed-barrier square root at low "
                        "dose)"),
          D::at<&C::material, &M::damage_profile, &DP::table_dpa>("material.damage_profile.law.dpa")
              .unit("dpa")
              .entries("doses in dpa", "a dose in dpa")
              .range(finite_at_least(0), "the doses must be finite and >= 0 dpa")
              .written_if(&table_damage_law)
              .default_is("– (table)")
              .allowed_is("from 0, strictly increasing, ≥ 2 points")
              .comment("d_i [dpa]")
              .describe("`form: table`: the doses of the points, from 0, strictly increasing; "
                        "beyond the last the last increment holds (j2)"),
          D::at<&C::material, &M::damage_profile, &DP::table_delta_yield_stress>(
              "material.damage_profile.law.delta_yield_stress")
              .unit("GPa")
              .entries("yield stress increments in GPa", "an increment in GPa")
              .range(finite_at_least(0), "the increments must be finite and >= 0 GPa")
              .written_if(&table_damage_law)
              .default_is("– (table)")
              .allowed_is("≥ 0, the first 0, one per dose")
              .comment("Delta sigma_y,i [GPa]")
              .describe("`form: table`: the yield stress increment at each dose, piecewise "
                        "linear (j2)"),
          D::at<&C::material, &M::damage_profile, &DP::shear_modulus>(
              "material.damage_profile.law.shear_modulus")
              .unit("GPa")
              .expect("mu in GPa")
              .range(finite_above(0), "the shear modulus mu must be finite and > 0 GPa")
              .written_if(&barrier_damage_law)
              .default_is("– (dispersed_barrier)")
              .comment("mu [GPa]")
              .describe("μ of `form: dispersed_barrier` (crystal)"),
          D::at<&C::material, &M::damage_profile, &DP::burgers_vector>(
              "material.damage_profile.law.burgers_vector")
              .unit("um")
              .expect("b in um")
              .range(finite_above(0), "the Burgers vector b must be finite and > 0 um")
              .written_if(&barrier_damage_law)
              .default_is("– (dispersed_barrier)")
              .comment("b [um]")
              .describe("b of `form: dispersed_barrier`, e.g. 2.74e-4 µm for W (crystal)"),
          D::at<&C::material, &M::damage_profile, &DP::defect_size>(
              "material.damage_profile.law.defect_size")
              .unit("um")
              .expect("D in um")
              .range(finite_above(0), "the defect size D must be finite and > 0 um")
              .written_if(&barrier_damage_law)
              .default_is("– (dispersed_barrier)")
              .comment("D, defect diameter [um]")
              .describe("D of `form: dispersed_barrier`: the mean diameter of the defects "
                        "(dislocation loops) (crystal)"),
          D::at<&C::material, &M::damage_profile, &DP::saturation_density>(
              "material.damage_profile.law.saturation_density")
              .unit("1/um^3")
              .expect("N_sat in 1/um^3")
              .range(finite_above(0),
                     "the saturation density N_sat must be finite and > 0 per um^3")
              .written_if(&barrier_damage_law)
              .default_is("– (dispersed_barrier)")
              .comment("N_sat [1/um^3]")
              .describe("Nsat of `form: dispersed_barrier`: the defect density at high dose "
                        "(1e23 m⁻³ = 1e5 µm⁻³) (crystal)"),
      };
    }

    std::vector<Key> indenter_keys()
    {
      using D = Declare;
      return {
          D::at<&C::indenter, &I::shape>("indenter.shape")
              .expect("an indenter shape")
              .comment("rounded_cone | sphere | cone | vickers | berkovich | flat_punch | "
                       "profile_table")
              .describe("the rigid indenter (see the indenter shapes in the user guide)"),
          D::at<&C::indenter, &I::a>("indenter.a")
              .expect("the slope parameter a")
              .range(above(0), "the slope parameter a (tan of the cone half-angle) must be > 0")
              .comment("rounded_cone (eq. 16): slope [-], half-angle atan(a)")
              .describe("slope parameter of eq. 16, cone half-angle atan(a) (rounded_cone)"),
          D::at<&C::indenter, &I::delta>("indenter.delta")
              .unit("um")
              .expect("the tip rounding delta in um")
              .range(at_least(0), "the tip rounding delta must be >= 0 um (0: sharp cone)")
              .comment("tip rounding [um], tip radius a^2*delta")
              .describe("tip rounding δ, tip radius a²δ; 0 = sharp cone (rounded_cone)"),
          D::at<&C::indenter, &I::radius>("indenter.radius")
              .unit("um")
              .expect("the radius in um")
              .range(finite_above(0),
                     "the radius of the sphere or of the flat punch must be > 0 um")
              .comment("sphere, flat_punch: radius [um]")
              .describe("the sphere's radius (sphere), the punch's radius (flat_punch)"),
          D::at<&C::indenter, &I::half_angle_deg>("indenter.half_angle_deg")
              .unit("deg")
              .expect("the cone half-angle in degrees")
              .range(between(0, false, 90, false),
                     "the cone half-angle (between flank and axis) must satisfy 0 < alpha < 90 deg "
                     "(70.3: the area function 24.5 h^2 of the Vickers and Berkovich pyramids)")
              .comment("cone: half-angle flank-axis [deg]")
              .describe("angle α between flank and axis (cone; 70.3°: the area function 24.5 h² of "
                        "the pyramids)"),
          D::at<&C::indenter, &I::tip_radius>("indenter.tip_radius")
              .unit("um")
              .expect("the tip radius in um")
              .range(finite_at_least(0),
                     "the tip radius of the cone or pyramid must be >= 0 um (0: sharp)")
              .comment("cone, vickers, berkovich: tip and edge radius [um], 0: sharp cone")
              .describe(
                  "radius of the rounded tip and edges; 0 = sharp (cone, vickers, berkovich)"),
          D::at<&C::indenter, &I::rotation_deg>("indenter.rotation_deg")
              .unit("deg")
              .expect("an angle in degrees")
              .range(finite(),
                     "the rotation about the indentation axis must be a finite angle in degrees")
              .comment("vickers, berkovich: about +z, ccw from above [deg]; 0: a face towards +x")
              .describe("angle about +z, counterclockwise seen from above; at 0 face 0 faces +x "
                        "(vickers: faces towards ±x, ±y, edges along x = ±y; berkovich: an edge "
                        "along −x) (vickers, berkovich)"),
          D::at<&C::indenter, &I::edge_radius>("indenter.edge_radius")
              .unit("um")
              .expect("the edge radius in um")
              .allowed_is("0 ≤ x ≤ `radius`")
              .comment("flat_punch: rim rounding [um], 0: sharp")
              .describe("rounding of the rim; 0 = sharp (flat_punch)"),
          D::at<&C::indenter, &I::file>("indenter.file")
              .unit("path")
              .expect("the path of a CSV profile table")
              .relative_to_case_file()
              .comment("profile_table: CSV r_um,z_um or depth_um,area_um2")
              .describe("CSV table, relative to the case file's directory (the resolved case lists "
                        "the absolute path); header `r_um,z_um` or `depth_um,area_um2`; required "
                        "for (and read only by) profile_table"),
      };
    }

    std::vector<Key> specimen_keys()
    {
      using D = Declare;
      return {
          D::at<&C::specimen, &S::size>("specimen.size")
              .unit("um")
              .range(above(0), "every edge length must be > 0 um")
              .comment("full block edge lengths [um]")
              .default_is("[360, 360, 180]; with `contact_elements: auto` designed: half-width "
                          "and depth 160 a_d (a_d the predicted contact radius)")
              .describe("edge lengths of the full block"),
          D::at<&C::specimen, &S::refined_region>("specimen.refined_region")
              .unit("um")
              .written_if(&explicit_mesh)
              .range(above(0), "every edge length must be > 0 um")
              .allowed_is("3 numbers > 0, ≤ `size`")
              .comment("refined block under the tip [um]")
              .describe("the refined block under the tip (the paper's mesh: uniform elements "
                        "of edge refined_region_x / contact_elements; contact nodes exist on "
                        "its top face only); not given with `contact_elements: auto`, which "
                        "designs it"),
          D::at<&C::specimen, &S::contact_elements>("specimen.contact_elements")
              .range({4, true, double(max_contact_elements), true, 4},
                     "N must be a multiple of 4 with 4 <= N <= " +
                         std::to_string(max_contact_elements) +
                         " (4, 8, 12, 16, ...) so that the mesh can be built: the 2:1 "
                         "coarsening around the refined region needs N/2 even, and with "
                         "symmetry: quarter the modelled N/2 x N/2 faces must be even as well; a "
                         "multiple of 4 satisfies both (the upper bound keeps a typo from "
                         "exhausting memory: 48 resolves the paper's indent)")
              .or_word("auto")
              .comment("N: N x N faces across the refined top face; auto: graded mesh")
              .describe("N: N×N faces across the refined top face, on the paper's mesh (a "
                        "uniform refined block, graded outside). `auto`: a mesh graded toward "
                        "the tip, designed from the indenter's area function at the maximum "
                        "depth (force control: from `max_force` with the hardness 3σ_y, at "
                        "most `max_depth`): elements of edge ρ/n at the distance ρ from the "
                        "tip, so the contact radius spans about n elements from max_depth/8 to "
                        "max_depth; `size` (if not given) and `refined_region` (never given) "
                        "are designed, and the resolved case lists them (user guide, "
                        "\"Automatic meshes\")"),
          D::at<&C::specimen, &S::elements_per_radius>("specimen.elements_per_radius")
              .written_if(&automatic_mesh)
              .range(between(2, true, 64, true),
                     "n must satisfy 2 <= n <= 64 (elements of edge rho/n at the distance rho "
                     "from the tip; the cells grow as n^2 in axisymmetric mode and n^3 in 3D)")
              .or_word("auto")
              .comment("n: elements of edge rho/n at the distance rho from the tip; auto: "
                       "10 axisymmetric, 6 in 3D")
              .describe("with `contact_elements: auto` only: n, the automatic mesh's elements "
                        "per distance from the tip (edge ρ/n at the distance ρ, within three "
                        "contact radii; ρ/(n/2) beyond). `auto`: 10 in axisymmetric mode, 6 in "
                        "3D. A larger n refines the whole design, for convergence studies "
                        "(user guide, \"Automatic meshes\")"),
          D::at<&C::specimen, &S::surface_refinement>("specimen.surface_refinement")
              .written_if(&automatic_mesh)
              .range(between(1, true, 8, true),
                     "allowed: auto, 1, 2, 4 or 8 (the top face's cells within the contact "
                     "nodes' reach are that many times smaller than the design's edge)")
              .or_word("auto")
              .allowed_is("1, 2, 4 or 8, or `auto`")
              .comment("1 | 2 | 4 | 8: top-face cells under the contact this many times "
                       "smaller; auto: 2 axisymmetric, 1 in 3D")
              .describe("with `contact_elements: auto` only: the top face's cells within the "
                        "contact nodes' reach are this many times smaller than the edge ρ/n "
                        "the design gives them (1, 2, 4 or 8), so the contact edge passes nodes "
                        "that much closer together and the force's ripple as it passes them "
                        "shrinks; each node entering the contact costs Newton iterations. "
                        "`auto`: 2 in axisymmetric mode, 1 in 3D (user guide, \"Automatic "
                        "meshes\")"),
          D::at<&C::specimen, &S::elements_across_layers>("specimen.elements_across_layers")
              .written_if(&graded_automatic_mesh)
              .range(between(1, true, 16, true),
                     "the elements across the thinnest layer must satisfy 1 <= m <= 16 (the "
                     "cells across the layers grow as m^2 in axisymmetric mode and m^3 in 3D)")
              .comment("elements across the thinnest layer or the damage peak")
              .describe("with `contact_elements: auto` and `material.layers` or "
                        "`damage_profile` only: the elements across the thinnest layer (or the "
                        "damage peak's width at half maximum) near the indent; fewer make a 3D "
                        "design affordable at the cost of resolving the layer's boundary "
                        "(user guide, \"Automatic meshes\")"),
          D::at<&C::specimen, &S::symmetry>("specimen.symmetry")
              .expect("a symmetry")
              .comment("full | quarter (x >= 0, y >= 0) | axisymmetric (r, z)")
              .describe(
                  "`quarter`: x ≥ 0, y ≥ 0 with symmetry planes x = 0, y = 0; for `crystal` "
                  "only if x = 0 and y = 0 are cubic mirror planes (e.g. (001), or (011) with "
                  "[100] along x; not (111)); only for an indenter with these mirror planes "
                  "(every axisymmetric shape, `vickers` at a `rotation_deg` that is a "
                  "multiple of 45, never `berkovich`). `axisymmetric`: the 2D (r, z) section "
                  "of a cylinder of radius size_x/2 and height size_z (size_y unused), refined "
                  "for r ≤ refined_region_x/2, z ≥ −refined_region_z, with u_r = 0 on the axis; "
                  "forces are the whole indent's; only for `neo_hookean` and `j2` under "
                  "`rounded_cone`, `sphere`, `cone`, `flat_punch` or `profile_table`"),
          D::at<&C::specimen, &S::f_bar>("specimen.f_bar")
              .default_is("true for j2 and crystal, and for neo_hookean with poisson_ratio > 0.45; "
                          "false for other neo_hookean cases")
              .comment("F-bar element")
              .describe("the F-bar element (isochoric plastic flow, and a nearly incompressible "
                        "elastic material, lock plain hexahedra)"),
          D::at<&C::specimen, &S::elements_per_side>("specimen.elements_per_side")
              .range(between(1, true, max_elements_per_side, true),
                     "the tensile cube has n x n x n elements of 1 um; n must satisfy 1 <= n <= " +
                         format_number(max_elements_per_side))
              .comment("tensile: cube of n^3 elements of 1 um")
              .describe("tensile: a cube of n³ elements of 1 µm"),
          D::at<&C::specimen, &S::grains>("specimen.grains")
              .expect("a grain layout")
              .comment("single | per_element (tensile)")
              .describe("`single`: every element has `material.orientation`; `per_element`: a "
                        "uniformly random orientation per element (tensile only)"),
          D::at<&C::specimen, &S::seed>("specimen.seed")
              .comment("random orientations (per_element)")
              .describe("seed of the random orientations (`per_element`)"),
      };
    }

    std::vector<Key> loading_keys()
    {
      using D = Declare;
      return {
          D::at<&C::loading, &L::control>("loading.control")
              .expect("a loading control")
              .comment("depth | force")
              .describe("`force`: the indenter depth becomes an unknown (indentation only)"),
          D::at<&C::loading, &L::max_depth>("loading.max_depth")
              .unit("um")
              .expect("a depth in um")
              .range(above(0), "must be > 0 um")
              .allowed_is("> 0, < `refined_region[2]`")
              .comment("[um] (force control: the largest admissible depth)")
              .describe("depth control: the maximum depth; force control: the largest admissible "
                        "depth (the run stops with an error beyond it)"),
          D::at<&C::loading, &L::max_force>("loading.max_force")
              .unit("mN")
              .expect("a force in mN")
              .allowed_is("force control: > 0; depth control: 0")
              .comment("[mN] (force control)")
              .describe("force control: the maximum indenter force (whole indent); must stay 0 "
                        "under depth control"),
          D::at<&C::loading, &L::steps>("loading.steps")
              .range(between(1, true, max_steps, true),
                     "must satisfy 1 <= steps <= " + std::to_string(int(max_steps)))
              .comment("increments to the maximum (tensile: max_strain)")
              .describe("increments to the maximum (tensile: equal increments of log strain to "
                        "`max_strain`)"),
          D::at<&C::loading, &L::spacing>("loading.spacing")
              .expect("an increment spacing")
              .comment("uniform | geometric: increments equal, or proportional to depth (force)")
              .describe("`uniform`: `steps` equal increments to the maximum; `geometric`: the "
                        "first increment goes to `first_fraction` of the maximum, each further "
                        "one is a constant ratio larger, `steps` in all (depth or force "
                        "increments proportional to the value reached: the same relative step at "
                        "every depth, where a self-similar tip's step-size error is the same)"),
          D::at<&C::loading, &L::first_fraction>("loading.first_fraction")
              .expect("a fraction of the maximum")
              .range(between(0, false, 0.5, true), "must satisfy 0 < first_fraction <= 0.5")
              .written_if(&geometric_spacing)
              .comment("geometric: first target / maximum [-]")
              .describe("`geometric` spacing: the first target as a fraction of the maximum "
                        "depth (force)"),
          D::at<&C::loading, &L::partial_unloads, &PU::every>("loading.partial_unloads.every")
              .unit("um")
              .expect("a depth in um")
              .range(finite_at_least(0), "must be a finite depth >= 0 um (0: no partial unloads)")
              .allowed_is("0, or > 0 and < `max_depth` (depth control)")
              .written_if(&partial_unloads_given)
              .default_is("0 (none)")
              .comment("[um] a partial unload at every multiple of this depth")
              .describe("partial unloads on the way down (depth control, first cycle): at every "
                        "multiple of this depth below `max_depth` the force is lowered by "
                        "`fraction` of its value, the indenter returns to the depth and loading "
                        "goes on; each is analysed by Oliver–Pharr into `hardness_depth.csv` "
                        "(see the user guide); 0: none"),
          D::at<&C::loading, &L::partial_unloads, &PU::fraction>("loading.partial_unloads.fraction")
              .expect("a fraction of the force")
              .range(between(0, false, 0.5, true), "must satisfy 0 < fraction <= 0.5")
              .written_if(&partial_unloads_given)
              .comment("of the force at each partial unload [-]")
              .describe("how far each partial unload lowers the force, as a fraction of the "
                        "force where it starts"),
          D::at<&C::loading, &L::partial_unloads, &PU::points>("loading.partial_unloads.points")
              .range(between(3, true, 100, true), "must satisfy 3 <= points <= 100")
              .written_if(&partial_unloads_given)
              .comment("force-paced steps of each partial unload")
              .describe("unloading steps of each partial unload (equal force drops after a "
                        "short first probe); with the starting point they are the points of its "
                        "Oliver–Pharr fit"),
          D::at<&C::loading, &L::unload>("loading.unload")
              .comment("then back until the force vanishes (force control: to 1 % of max_force)")
              .describe("then back until the force vanishes (force control: to 1 % of "
                        "`max_force`)"),
          D::at<&C::loading, &L::unload_steps>("loading.unload_steps")
              .range(at_most(max_steps),
                     "must satisfy 0 <= unload_steps <= " + std::to_string(int(max_steps)) +
                         " (0: the increment of loading)")
              .comment("0: same increment size as loading")
              .describe("unloading increments; 0: same increment as loading"),
          D::at<&C::loading, &L::unload_points>("loading.unload_points")
              .range(at_most(10000),
                     "must satisfy 0 <= unload_points <= 10000 (0: uniform depth steps)")
              .comment("depth control: force drop per unloading step <= max force / unload_points; "
                       "0: off")
              .describe(
                  "depth control: each unloading step lowers the force by about (maximum "
                  "force)/`unload_points` (the depth increment comes from the last step's "
                  "secant unloading stiffness; the first takes a quarter of the nominal "
                  "increment), so the elastic recovery, a small part of the depth, is "
                  "resolved for the Oliver–Pharr fit; still at most the nominal increment; 0: "
                  "uniform depth steps only"),
          D::at<&C::loading, &L::hold_steps>("loading.hold_steps")
              .range(at_most(max_steps),
                     "must satisfy 0 <= hold_steps <= " + std::to_string(int(max_steps)))
              .comment("increments holding the maximum")
              .describe("increments holding the maximum depth or force (recorded as `hold`; the "
                        "rate-independent models do not creep)"),
          D::at<&C::loading, &L::cycles>("loading.cycles")
              .range(between(1, true, 1000, true), "must satisfy 1 <= cycles <= 1000")
              .comment("load-hold-unload cycles")
              .describe("load–hold–unload cycles to the same maximum (> 1 needs `unload: true`)"),
          D::at<&C::loading, &L::max_cutbacks>("loading.max_cutbacks")
              .range(at_most(max_cutbacks),
                     "must satisfy 0 <= max_cutbacks <= " + format_number(max_cutbacks))
              .comment("successive halvings of an increment")
              .describe("successive halvings of a failing increment"),
          D::at<&C::loading, &L::max_strain>("loading.max_strain")
              .expect("a logarithmic strain")
              .range(
                  between(0, false, 1, true),
                  "the final logarithmic strain of the tensile test must satisfy 0 < strain <= 1")
              .comment("tensile: final logarithmic strain along z [-]")
              .describe("tensile: final logarithmic strain along z"),
      };
    }

    std::vector<Key> contact_keys()
    {
      using D = Declare;
      return {
          // Measured indenter-metal coefficients lie below 0.5; 2 leaves room for studies without
          // admitting a typo (e.g. 10 for 0.10).
          D::at<&C::contact, &CP::friction_coefficient>("contact.friction_coefficient")
              .expect("the Coulomb coefficient mu")
              .range(between(0, true, 2, true),
                     "the Coulomb coefficient mu must satisfy 0 <= mu <= 2 (0: frictionless)")
              .comment("Coulomb mu [-], 0: frictionless")
              .describe("Coulomb μ (0: frictionless)"),
          D::at<&C::contact, &CP::penalty>("contact.penalty")
              .unit("GPa/um")
              .expect("a penalty in GPa/um")
              .range(at_least(0), "must be >= 0 GPa/um (0: chosen automatically)")
              .default_is("0 (= 30 μ/h, μ shear modulus, h contact-element size)")
              .comment("[GPa/um], 0: automatic")
              .describe("augmentation parameter; 0: chosen automatically"),
          D::at<&C::contact, &CP::penetration_tolerance>("contact.penetration_tolerance")
              .unit("um")
              .expect("a length in um")
              .range(above(0), "must be > 0 um")
              .comment("[um]")
              .describe("largest admissible penetration at convergence"),
          D::at<&C::contact, &CP::max_augmentations>("contact.max_augmentations")
              .range(between(1, true, max_iterations, true),
                     "must satisfy 1 <= max_augmentations <= " +
                         std::to_string(int(max_iterations)))
              .describe("augmentation passes of an increment"),
      };
    }

    std::vector<Key> solver_keys()
    {
      using D = Declare;
      return {
          D::at<&C::solver, &SP::residual_tolerance>("solver.residual_tolerance")
              .expect("a relative tolerance")
              .range(between(0, false, 1, false),
                     "must satisfy 0 < tolerance < 1 (relative to a force of the run)")
              .comment("relative to the run's largest indenter force")
              .describe(
                  "indentation: relative to the largest indenter force of the run's converged "
                  "steps and the bottom face's reaction at the increment's iterates after a "
                  "Newton update (the model's forces, a quarter of the indent's with symmetry: "
                  "quarter), so "
                  "that the curve's force error is about this fraction of the largest force "
                  "whatever the contact penalty; tensile: relative to the first residual of "
                  "the increment. The default keeps "
                  "the Newton error below the contact tolerance's: against a reference run "
                  "with 1e-10 and a contact tolerance of 1e-9 µm, `j2_24` deviates by 8.7e-7 "
                  "of the largest force at 1e-8 and 1e-7 and 8.6e-7 at 1e-6 "
                  "(`crystal_24`: 2.54e-6 at both 1e-8 and 1e-7). For curves that agree "
                  "across rank counts to 1e-8, set it to 1e-8 together with "
                  "`contact.penetration_tolerance` 1e-8"),
          D::at<&C::solver, &SP::absolute_tolerance>("solver.absolute_tolerance")
              .unit("mN")
              .expect("a force in mN")
              .range(above(0), "must be > 0 mN")
              .comment("[mN]")
              .describe("absolute residual tolerance; indentation raises it to the residual's "
                        "round-off level, 1e-13 μ A (μ the shear modulus, A the model's bottom "
                        "face), where that is larger"),
          D::at<&C::solver, &SP::max_newton_iterations>("solver.max_newton_iterations")
              .range(between(1, true, max_iterations, true),
                     "must satisfy 1 <= max_newton_iterations <= " +
                         std::to_string(int(max_iterations)))
              .describe("Newton iterations of an increment before it is cut back"),
          D::at<&C::solver, &SP::linear_solver>("solver.linear_solver")
              .expect("a linear solver")
              .comment("auto | direct (MUMPS) | iterative (AMG-preconditioned CG/GMRES)")
              .describe("`auto`: the kind of lower predicted cost (3D: iterative from about "
                        "300 DOFs; 2D: direct), see docs/performance.md; `direct`: MUMPS LU; "
                        "`iterative`: AMG-preconditioned CG for symmetric tangents, GMRES "
                        "otherwise"),
          D::at<&C::solver, &SP::threads>("solver.threads")
              .range(at_most(1024), "must be between 0 (automatic) and 1024")
              .not_a_result()
              .comment("assembly threads per MPI rank, 0: cores / ranks")
              .describe("threads of the cell loop per MPI rank; 0: the node's cores divided among "
                        "its ranks"),
      };
    }

    std::vector<Key> output_keys()
    {
      using D = Declare;
      return {
          D::at<&C::output, &OU::directory>("output.directory")
              .unit("path")
              .expect("a directory path")
              .non_empty("must be a non-empty directory path")
              .not_a_result()
              .comment("relative paths: relative to the working directory")
              .describe("where the results go; relative to the working directory"),
          D::at<&C::output, &OU::vtu_every>("output.vtu_every")
              .range(at_most(max_steps),
                     "must satisfy 0 <= vtu_every <= " + std::to_string(int(max_steps)) +
                         " (0: at the start, the maximum and the end)")
              .unit("steps")
              .comment("VTU every k-th step (0: at max depth and end)")
              .describe("0: VTU only at the start, at max depth and at the end"),
          D::at<&C::output, &OU::experimental_curve>("output.experimental_curve")
              .unit("path")
              .expect("the path of a CSV with depth and force columns")
              .relative_to_case_file()
              .default_is("\"\" (none)")
              .comment("measured curve (CSV) to overlay and compare; \"\": none")
              .describe(
                  "`test: indentation`: a measured load–penetration curve (CSV with a header, "
                  "the depth and force columns found and their units read from the names as "
                  "for `indentsim analyze`, e.g. `depth_nm,load_uN`), relative to the case "
                  "file's directory; read and checked before the computation; overlaid on "
                  "`load_penetration.png` and compared (`comparison_with_experiment.json`)"),
          D::at<&C::output, &OU::checkpoint_interval_s>("output.checkpoint_interval_s")
              .unit("s")
              .expect("a wall time in s")
              .range(finite_at_least(0),
                     "must be a wall time >= 0 s (0: checkpoint only when stopped)")
              .not_a_result()
              .comment("[s] wall time between checkpoints (0: only when stopped)")
              .describe("indentation: wall time between checkpoints for `--resume` (0: only when "
                        "stopped by Ctrl-C/SIGTERM)"),
          D::at<&C::output, &OU::plots>("output.plots")
              .not_a_result()
              .comment("draw the PNG plots (Python); false: CSV, JSON and VTU only")
              .describe("whether the run draws its PNG plots with Python (about a second each); "
                        "`false` leaves the CSV, JSON and VTU files only, as a calibration's "
                        "forward runs do"),
      };
    }

    std::vector<Key> declare_keys()
    {
      std::vector<Key> keys;
      for (auto &&section : {top_level_keys(), material_keys(), indenter_keys(), specimen_keys(),
                             loading_keys(), contact_keys(), solver_keys(), output_keys()})
        keys.insert(keys.end(), section.begin(), section.end());
      return keys;
    }

    std::vector<Group> declare_groups()
    {
      return {
          {"material.elastic", "elastic constants, lattice frame (crystal)",
           "Elastic constants in the lattice frame (crystal): cubic C11, C12, C44 for fcc and bcc; "
           "hexagonal C11, C12, C13, C33, C44 for hcp (c along z, a1 along x)."},
          {"material.hardening", "extended Voce law (crystal)",
           "The hardening law: for `j2` the law σy(εp) (`law` and its keys; without `law`, "
           "linear with `hardening_modulus`), for `crystal` the extended Voce law (`tau0` to "
           "`q`)."},
          {"material.latent_hardening", "latent hardening (crystal)",
           "Latent hardening between slip systems (crystal): the ratio `q`, or a matrix between "
           "the slip families."},
          {"material.damage_profile", "depth-graded by a damage profile [um, dpa, GPa]",
           "A damage profile (indentation; not with `layers`): the damage d in dpa against the "
           "depth below the undeformed surface and the law that turns it into strength; below "
           "the profile's last depth the material block holds (the substrate)."},
          {"material.damage_profile.law", "dose-to-strength law",
           "The dose-to-strength law of a damage profile: `form` and its keys."},
          {"material.orientation", "Bunge, passive: v_crystal = g v_sample (crystal)",
           "Crystal orientation: `euler_bunge_deg`, or `surface_normal` with "
           "`reference_direction`."},
      };
    }
  } // namespace

  bool Range::contains(const double value) const
  {
    const bool above_lower = lower_included ? value >= lower : value > lower;
    const bool below_upper = upper_included ? value <= upper : value < upper;
    const bool multiple =
        multiple_of == 0 || std::fmod(value, static_cast<double>(multiple_of)) == 0.;
    return above_lower && below_upper && multiple;
  }

  std::string Range::text() const
  {
    // Whole bounds in full ("100000", not "1e+05").
    const auto format_number = [](const double value) {
      return value == std::floor(value) && std::abs(value) < 1e15
                 ? std::to_string(static_cast<long long>(value))
                 : io::format_number(value);
    };
    const bool        has_lower = lower > -infinity;
    const bool        has_upper = upper < infinity;
    const std::string lower_sign = lower_included ? " ≤ " : " < ";
    const std::string upper_sign = upper_included ? " ≤ " : " < ";
    std::string       text;
    if (has_lower && has_upper)
      text = format_number(lower) + lower_sign + "x" + upper_sign + format_number(upper);
    else if (has_lower)
      text = (lower_included ? "≥ " : "> ") + format_number(lower);
    else if (has_upper)
      text = (upper_included ? "≤ " : "< ") + format_number(upper);
    if (!upper_included && upper == infinity)
      text += text.empty() ? "finite" : ", finite";
    if (multiple_of > 0)
      text = "multiple of " + std::to_string(multiple_of) + (text.empty() ? "" : ", " + text);
    return text;
  }

  std::string Key::name() const
  {
    const std::size_t dot = path.rfind('.');
    return dot == std::string::npos ? path : path.substr(dot + 1);
  }

  std::string Key::parent() const
  {
    const std::size_t dot = path.rfind('.');
    return dot == std::string::npos ? std::string() : path.substr(0, dot);
  }

  std::string Key::value_text(const Case &c) const
  {
    Case &readable = const_cast<Case &>(c); // the accessors only read here
    switch (type)
      {
      case ValueType::number:
        return format_number(number(readable));
      case ValueType::whole_number:
        if (zero_word != nullptr && whole_number(readable) == 0)
          return zero_word;
        return std::to_string(whole_number(readable));
      case ValueType::boolean:
        return format_bool(boolean(readable));
      case ValueType::choice:
        return choice.word(c);
      case ValueType::text:
        return text(readable);
      case ValueType::triple:
        return format_triple(triple(readable));
      case ValueType::list:
        return format_list(list(readable));
      case ValueType::words:
        return format_words(words(readable));
      case ValueType::matrix:
        return format_matrix(matrix(readable));
      case ValueType::family_blocks:
        return format_family_blocks(family_blocks(readable));
      case ValueType::layers:
        return format_layers(layers(readable));
      }
    return {};
  }

  const std::vector<Key> &case_keys()
  {
    static const std::vector<Key> keys = declare_keys();
    return keys;
  }

  const std::vector<Group> &case_groups()
  {
    static const std::vector<Group> groups = declare_groups();
    return groups;
  }

  const Key &find_key(const std::string &path)
  {
    for (const auto &key : case_keys())
      if (key.path == path)
        return key;
    throw std::out_of_range("no case-file key '" + path + "'");
  }

  namespace
  {
    // Every map's allowed names, the top level ("") included, from the key paths.
    std::map<std::string, std::vector<std::string>> collect_names()
    {
      std::map<std::string, std::vector<std::string>> names;
      const auto add = [&names](const std::string &map, const std::string &name) {
        auto &list = names[map];
        if (std::find(list.begin(), list.end(), name) == list.end())
          list.push_back(name);
      };
      for (const auto &key : case_keys())
        {
          std::size_t dot = std::string::npos;
          std::string map;
          std::size_t start = 0;
          while ((dot = key.path.find('.', start)) != std::string::npos)
            {
              add(map, key.path.substr(start, dot - start));
              map = key.path.substr(0, dot);
              start = dot + 1;
            }
          add(map, key.path.substr(start));
        }
      return names;
    }
  } // namespace

  const std::vector<std::string> &allowed_names(const std::string &path)
  {
    static const std::map<std::string, std::vector<std::string>> names = collect_names();
    return names.at(path);
  }

  const std::map<std::string, std::vector<std::string>> &maps_with_names()
  {
    static const std::map<std::string, std::vector<std::string>> maps = [] {
      auto names = collect_names();
      names.erase("");
      return names;
    }();
    return maps;
  }

  std::string format_number(const double value)
  {
    std::array<char, 64> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return std::string(buffer.data(), result.ptr);
  }

  std::string format_triple(const std::array<double, 3> &values)
  {
    return "[" + format_number(values[0]) + ", " + format_number(values[1]) + ", " +
           format_number(values[2]) + "]";
  }

  std::string format_list(const std::vector<double> &values)
  {
    std::string text = "[";
    for (std::size_t i = 0; i < values.size(); ++i)
      text += (i == 0 ? "" : ", ") + format_number(values[i]);
    return text + "]";
  }

  std::string format_words(const std::vector<std::string> &values)
  {
    std::string text = "[";
    for (std::size_t i = 0; i < values.size(); ++i)
      text += (i == 0 ? "\"" : ", \"") + values[i] + "\"";
    return text + "]";
  }

  std::string format_matrix(const std::vector<std::vector<double>> &rows)
  {
    std::string text = "[";
    for (std::size_t i = 0; i < rows.size(); ++i)
      text += (i == 0 ? "" : ", ") + format_list(rows[i]);
    return text + "]";
  }

  std::string format_family_block(const FamilyHardening &block)
  {
    std::string text =
        "{tau0: " + format_number(block.tau0) + ", tau1: " + format_number(block.tau1) +
        ", theta0: " + format_number(block.theta0) + ", theta1: " + format_number(block.theta1);
    // The irradiation keys only where the family has irradiation defects.
    if (block.tau_irr > 0 || block.barrier_strength > 0)
      text += ", tau_irr: " + format_number(block.tau_irr) +
              ", softening_slip: " + format_number(block.softening_slip) +
              ", barrier_strength: " + format_number(block.barrier_strength);
    return text + "}";
  }

  std::string format_family_blocks(const std::vector<FamilyHardening> &blocks)
  {
    std::string text = "{";
    for (std::size_t i = 0; i < blocks.size(); ++i)
      text += (i == 0 ? "\"" : ", \"") + blocks[i].family + "\": " + format_family_block(blocks[i]);
    return text + "}";
  }

  std::string format_layers(const std::vector<MaterialLayer> &layers)
  {
    std::string text = "[";
    for (std::size_t i = 0; i < layers.size(); ++i)
      {
        const std::string &overrides = layers[i].overrides; // "{...}" or "{}"
        const std::string  inner = overrides.substr(1, overrides.size() - 2);
        text += (i == 0 ? "{thickness: " : ", {thickness: ") + format_number(layers[i].thickness) +
                (inner.empty() ? "" : ", " + inner) + "}";
      }
    return text + "]";
  }

  std::string format_bool(const bool value)
  {
    return value ? "true" : "false";
  }
} // namespace indentsim::io

// The value checks of a case: first, section by section, the single-key checks declared in
// the schema (ranges, words), then the section's checks that involve several keys, written by
// hand below. Every message names the key path, the value and what is allowed, and, for a
// case read from a file, the file and the line.
#include "case/CaseReading.h"
#include "case/DamageProfile.h"
#include "case/MaterialLayers.h"
#include "case/Schema.h"
#include "indenter/IndenterFactory.h"
#include "indenter/ProfileTable.h"
#include "io/LoadCurveCsv.h"
#include "materials/MaterialFactory.h"
#include "materials/crystal/LatticeElasticity.h"
#include "materials/crystal/Orientation.h"
#include "materials/crystal/SlipSystems.h"
#include "mesh/MeshAdequacy.h"
#include "mesh/MeshDesign.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <stdexcept>

namespace indentsim::io
{
  namespace
  {
    // Why tau1 > 0 when theta0 > 0 (a crystal's common and per-family Voce parameters).
    const std::string voce_needs_tau1 =
        "the Voce law tau_c = tau0 + (tau1 + theta1 Gamma)(1 - exp(-theta0 Gamma / tau1)) divides "
        "by tau1 (theta0 = 0 means no hardening at all: tau_c = tau0)";

    const std::array<const char *, 3> axis_names = {{"x", "y", "z"}};

    // The most sampling slabs of a damage profile (case/DamageProfile.h): far above the 600 of
    // a 3 um profile at the default resolution, low enough that a typo cannot exhaust memory.
    constexpr std::size_t max_damage_slabs = 100000;

    class CaseValidator
    {
    public:
      // `checked_case` receives the automatic mesh's design (specimen.contact_elements: auto).
      CaseValidator(Case &checked_case, const OriginMap *origins, const bool for_run)
        : checked(checked_case)
        , designed(checked_case)
        , value_origins(origins)
        , for_run(for_run)
      {
      }

      // Returns the indenter, built as the run will use it.
      std::unique_ptr<indenter::IndenterSurface> validate() const
      {
        check_section("");
        check_top_level();
        check_section("material");
        check_hardening_law();
        check_crystal_parameters();
        check_layers();
        check_damage_profile();
        check_section("indenter");
        std::unique_ptr<indenter::IndenterSurface> surface = check_indenter();
        check_section("specimen");
        const unsigned int surface_refinement = checked.specimen.surface_refinement;
        if (!tensile() && checked.specimen.automatic_mesh())
          {
            if (surface_refinement != 0 && (surface_refinement & (surface_refinement - 1)) != 0)
              reject("specimen.surface_refinement", std::to_string(surface_refinement),
                     "allowed: auto, 1, 2, 4 or 8 (a power of two: the octree halves cells)");
            design_automatic_mesh(*surface);
          }
        else
          {
            const auto refuse = [&](const char *key, const unsigned int value) {
              reject(key, std::to_string(value),
                     "it sets the automatic mesh: give specimen.contact_elements: auto with it, "
                     "or remove it to mesh the refined region with contact_elements");
            };
            if (checked.specimen.elements_per_radius != 0)
              refuse("specimen.elements_per_radius", checked.specimen.elements_per_radius);
            if (surface_refinement != 0)
              refuse("specimen.surface_refinement", surface_refinement);
          }
        if (!checked.specimen.automatic_mesh() && value_origins != nullptr &&
            value_origins->count("specimen.elements_across_layers") != 0)
          reject("specimen.elements_across_layers",
                 std::to_string(checked.specimen.elements_across_layers),
                 "it sets the automatic mesh's refinement across layers: give "
                 "specimen.contact_elements: auto with it, or remove it (an explicit mesh does "
                 "not refine across layers)");
        check_specimen(*surface);
        check_section("loading");
        check_loading();
        if (!tensile())
          check_contact_fits(*surface);
        check_section("contact");
        check_section("solver");
        check_section("output");
        check_output();
        return surface;
      }

    private:
      const Case      &checked;
      Case            &designed; // the same case, for the design of the automatic mesh
      const OriginMap *value_origins;
      const bool       for_run; // the checks of what the solver cannot compute

      // specimen.contact_elements: auto designs refined_region (and size, unless the case file
      // gives it); the checks below then apply to the designed values. Without origins (a case
      // assembled in code) `size` counts as given.
      void design_automatic_mesh(const indenter::IndenterSurface &surface) const
      {
        const bool given = value_origins == nullptr;
        if (!given && value_origins->count("specimen.refined_region") != 0)
          reject("specimen.refined_region", format_triple(checked.specimen.refined_region),
                 "specimen.contact_elements: auto designs the refined region (it lists the "
                 "design in resolved_case.yaml); remove refined_region, or give "
                 "contact_elements a number to mesh this region");
        mesh::design_mesh(designed, surface, given || value_origins->count("specimen.size") != 0);
      }

      bool tensile() const { return checked.test == TestKind::tensile; }

      // material.layers: for the indentation test, thicknesses finite and >= 0, and each
      // layer's material admissible (read and checked as a material block, MaterialLayers.h).
      void check_layers() const
      {
        const std::vector<MaterialLayer> &layers = checked.material.layers;
        if (layers.empty())
          return;
        const std::string path = "material.layers";
        if (tensile())
          reject(path, format_layers(layers),
                 "layers lie below an indented surface (test: indentation); the tensile test "
                 "models a homogeneous polycrystal");
        for (std::size_t i = 0; i < layers.size(); ++i)
          if (!(layers[i].thickness >= 0) || !std::isfinite(layers[i].thickness))
            reject(path, format_layers(layers),
                   "the thickness of layer " + std::to_string(i) + " (" +
                       format_number(layers[i].thickness) + ") must be a finite number >= 0 um");
        std::string source = checked.source_file.empty() ? "case file" : checked.source_file;
        if (value_origins != nullptr)
          if (const auto origin = value_origins->find(path); origin != value_origins->end())
            source += ":" + std::to_string(origin->second.line + 1);
        layer_materials(checked.material, source);
      }

      // material.damage_profile: for the indentation test and not with layers; the profile
      // from >= 0 and strictly increasing with some damage; the law's form for the model
      // (saturation or table for j2, dispersed_barrier for crystal) with its table in order, or
      // a slip family that the defects harden.
      void check_damage_profile() const
      {
        const MaterialParameters      &m = checked.material;
        const DamageProfileParameters &p = m.damage_profile;
        if (!p.given())
          return;
        const std::string where =
            p.file.empty() ? "material.damage_profile.depth" : "material.damage_profile.file";
        const std::string shown = p.file.empty() ? format_list(p.depth) : "\"" + p.file + "\"";
        if (tensile())
          reject(where, shown,
                 "a damage profile lies below an indented surface (test: indentation); the "
                 "tensile test models a homogeneous polycrystal");
        if (!m.layers.empty())
          reject(where, shown,
                 "give layers or a damage profile, not both (material.layers is given)");
        if (p.depth.size() != p.dpa.size())
          reject("material.damage_profile.dpa", format_list(p.dpa),
                 "one dose per depth (" + std::to_string(p.depth.size()) + " depths, " +
                     std::to_string(p.dpa.size()) + " doses)");
        if (p.depth.size() < 2)
          reject(where, shown, "a profile needs at least 2 points");
        for (std::size_t i = 0; i < p.depth.size(); ++i)
          {
            const std::string row = p.file.empty()
                                        ? "point " + std::to_string(i + 1)
                                        : "row " + std::to_string(i + 1) + " of the data";
            if (!(p.depth[i] >= 0) || !std::isfinite(p.depth[i]) ||
                (i > 0 && !(p.depth[i] > p.depth[i - 1])))
              reject(where, shown,
                     row + ": the depth " + format_number(p.depth[i]) +
                         " um; the depths must be finite, >= 0 and strictly increasing");
            if (!(p.dpa[i] >= 0) || !std::isfinite(p.dpa[i]))
              reject(where, shown,
                     row + ": the dose " + format_number(p.dpa[i]) +
                         " dpa; the doses must be finite and >= 0");
          }
        if (!(peak_dose(p) > 0))
          reject(where, shown, "every dose is 0: the profile would change nothing");
        if (p.depth.back() / p.resolution > max_damage_slabs)
          reject("material.damage_profile.resolution", format_number(p.resolution),
                 "the profile's " + format_number(p.depth.back()) + " um would take more than " +
                     std::to_string(max_damage_slabs) + " slabs; give at least " +
                     format_number(p.depth.back() / max_damage_slabs) + " um");
        if (!p.law.known())
          return;
        const bool crystal = m.model == ModelKind::crystal;
        const bool barrier = p.law == DamageLaw::dispersed_barrier;
        if (m.model == ModelKind::neo_hookean || crystal != barrier)
          reject("material.damage_profile.law.form", p.law.word(),
                 "model: " + m.model.word() + " takes " +
                     (crystal                    ? std::string("form: dispersed_barrier")
                      : m.model == ModelKind::j2 ? std::string("form: saturation or table")
                                                 : std::string("no damage profile (it has no "
                                                               "yield stress)")));
        if (p.law == DamageLaw::table)
          check_damage_table(p);
        if (barrier)
          {
            bool hardened =
                m.family_hardening.size() < families_of(m).size() && m.barrier_strength > 0;
            for (const FamilyHardening &block : m.family_hardening)
              hardened = hardened || block.barrier_strength > 0;
            if (!hardened)
              reject("material.hardening.barrier_strength", format_number(m.barrier_strength),
                     "form: dispersed_barrier needs a barrier strength alpha > 0 for some slip "
                     "family (typically 0.1 to 0.5); with 0 the defects harden nothing");
          }
      }

      // form: table: the doses from 0 and strictly increasing, one increment per dose, >= 0,
      // the first 0 (no damage, no hardening).
      void check_damage_table(const DamageProfileParameters &p) const
      {
        const std::string doses = "material.damage_profile.law.dpa";
        const std::string increments = "material.damage_profile.law.delta_yield_stress";
        if (p.table_dpa.size() < 2 || p.table_dpa.front() != 0)
          reject(doses, format_list(p.table_dpa), "at least 2 doses, the first 0");
        for (std::size_t i = 1; i < p.table_dpa.size(); ++i)
          if (!(p.table_dpa[i] > p.table_dpa[i - 1]))
            reject(doses, format_list(p.table_dpa), "the doses must increase strictly");
        if (p.table_delta_yield_stress.size() != p.table_dpa.size())
          reject(increments, format_list(p.table_delta_yield_stress),
                 "one increment per dose (" + std::to_string(p.table_dpa.size()) + " doses)");
        if (p.table_delta_yield_stress.front() != 0)
          reject(increments, format_list(p.table_delta_yield_stress),
                 "the first increment (at 0 dpa) must be 0");
      }

      // The slip families of a crystal's lattice ({} for a lattice the reader did not know).
      std::vector<std::string> families_of(const MaterialParameters &m) const
      {
        if (!m.lattice.known())
          return {};
        return materials::slip_systems(m.lattice.word(), designed.material.slip_families,
                                       m.lattice == Lattice::hcp ? m.c_over_a : 0.0)
            .families;
      }

      // The single-key checks of the schema for every key of one top-level section.
      void check_section(const std::string &section) const
      {
        for (const auto &key : case_keys())
          {
            const std::string first = key.path.substr(0, key.path.find('.'));
            if ((section.empty() && key.parent().empty()) ||
                (!section.empty() && !key.parent().empty() && first == section))
              check_key(key);
          }
      }

      // The key that gave a number: `key`, or another key with the same storage that the case
      // file gave (material.hardening.modulus for material.hardening_modulus).
      std::string given_path(const Key &key) const
      {
        if (value_origins != nullptr && value_origins->count(key.path) == 0)
          for (const auto &other : case_keys())
            if (other.number != nullptr && other.number == key.number &&
                value_origins->count(other.path) > 0)
              return other.path;
        return key.path;
      }

      void check_key(const Key &key) const
      {
        Case &c = const_cast<Case &>(checked); // the accessors only read here
        switch (key.type)
          {
          case ValueType::number:
            if (key.has_range && !key.range.contains(key.number(c)))
              reject(given_path(key), format_number(key.number(c)), key.range_message);
            break;
          case ValueType::whole_number:
            if (key.zero_word != nullptr && key.whole_number(c) == 0)
              break;
            if (key.has_range && !key.range.contains(key.whole_number(c)))
              reject(key.path, std::to_string(key.whole_number(c)), key.range_message);
            break;
          case ValueType::triple:
            for (unsigned int d = 0; d < 3; ++d)
              if (key.has_range && !key.range.contains(key.triple(c)[d]))
                reject(key.path, format_triple(key.triple(c)),
                       key.range_message + "; the " + axis_names[d] + " entry is not");
            break;
          case ValueType::words: // the allowed words depend on other keys: checked by hand
          case ValueType::matrix:
          case ValueType::family_blocks:
          case ValueType::layers: // check_layers
            break;
          case ValueType::list:
            for (std::size_t i = 0; i < key.list(c).size(); ++i)
              if (key.has_range && !key.range.contains(key.list(c)[i]))
                reject(key.path, format_list(key.list(c)),
                       key.range_message + "; entry " + std::to_string(i) + " (" +
                           format_number(key.list(c)[i]) + ") is not");
            break;
          case ValueType::choice:
            if (!key.choice.known(c))
              reject_unknown_word(key.path, key.choice.word(c), key.choice.words(true));
            if (!key.choice.implemented(c))
              reject(key.path, "'" + key.choice.word(c) + "'", key.not_implemented_message);
            break;
          case ValueType::text:
            if (key.non_empty && key.text(c).empty())
              reject(key.path, "\"\"", key.range_message);
            break;
          case ValueType::boolean:
            break;
          }
      }

      void check_top_level() const
      {
        if (checked.compare_j2 && !tensile())
          reject("compare_j2", format_bool(checked.compare_j2),
                 "only the tensile test can repeat the run with J2 (test: tensile); the "
                 "indentation test compares models through separate case files");
      }

      // The J2 hardening law (the keys each law takes were checked by the reader): only J2 has
      // one (and the J2 comparison of the tensile test); the law is built as the run builds
      // it, and a table's first stress must be the initial yield stress.
      void check_hardening_law() const
      {
        const auto       &m = checked.material;
        const std::string law_path = "material.hardening.law";
        const bool        j2 = m.model == ModelKind::j2 || (tensile() && checked.compare_j2);
        if (!j2 && m.hardening_law != HardeningLaw::linear)
          reject(law_path, m.hardening_law.word(),
                 "a J2 hardening law belongs to model: j2 (or to the J2 comparison of the "
                 "tensile test, compare_j2: true), not to model: " +
                     to_string(m.model) +
                     (m.model == ModelKind::crystal
                          ? " (its hardening is the extended Voce law: material.hardening.tau0, "
                            "tau1, theta0, theta1, q)"
                          : " (no plasticity)"));
        const bool from_file = !m.hardening_file.empty();
        try
          {
            materials::create_hardening_law(m);
          }
        catch (const materials::InvalidHardeningParameter &error)
          {
            reject_hardening_parameter(error.parameter, error.detail);
          }
        if (m.hardening_law == HardeningLaw::table &&
            std::abs(m.hardening_stress.front() - m.yield_stress) > 1e-9 * m.yield_stress)
          {
            const std::string first =
                "the table's first stress (" +
                (from_file ? "the first row of material.hardening.file \"" + m.hardening_file + "\""
                           : std::string("material.hardening.stress[0]")) +
                " = " + format_number(m.hardening_stress.front()) + " GPa)";
            const std::string path =
                given_or_first({"material.yield_stress", from_file ? "material.hardening.file"
                                                                   : "material.hardening.stress"});
            const std::string rule =
                "is the initial yield stress and must equal material.yield_stress (to 1e-9 "
                "relative); give yield_stress: " +
                format_number(m.hardening_stress.front()) + " or correct the table";
            if (path == "material.yield_stress")
              reject(path, format_number(m.yield_stress), first + " " + rule);
            reject(path,
                   from_file ? "\"" + m.hardening_file + "\"" : format_list(m.hardening_stress),
                   first + " differs from yield_stress = " + format_number(m.yield_stress) +
                       " GPa; it " + rule);
          }
      }

      // An invalid parameter of the hardening law, named by its key.
      [[noreturn]] void reject_hardening_parameter(const std::string &parameter,
                                                   const std::string &detail) const
      {
        const auto &m = checked.material;
        if (parameter == "plastic_strain" || parameter == "stress")
          {
            if (!m.hardening_file.empty())
              reject("material.hardening.file", "\"" + m.hardening_file + "\"",
                     "the table's " + detail + " (entries counted from 0 in file order)");
            const std::string path = "material.hardening." + parameter;
            reject(path,
                   format_list(parameter == "stress" ? m.hardening_stress
                                                     : m.hardening_plastic_strain),
                   detail);
          }
        if (parameter == "hardening_modulus")
          {
            const std::string path =
                given_or_first({"material.hardening.modulus", "material.hardening_modulus"});
            reject(path, format_number(m.hardening_modulus), detail);
          }
        const std::string path = parameter == "yield_stress"    ? "material.yield_stress"
                                 : parameter == "young_modulus" ? "material.young_modulus"
                                                                : "material.hardening." + parameter;
        reject(path, find_key(path).value_text(checked), detail);
      }

      // Keys of the crystal model. They are checked for every model (the resolved case always
      // holds them), but only model: crystal uses them.
      void check_crystal_parameters() const
      {
        const auto &m = checked.material;

        check_lattice();
        check_family_hardening();
        // Cubic stiffness positive definite: eigenvalues C11 + 2 C12 (dilatation), C11 - C12
        // (tetragonal shear) and C44 (shear). The hexagonal one: check_lattice.
        const std::string constants = "(C11 = " + format_number(m.C11) +
                                      ", C12 = " + format_number(m.C12) +
                                      ", C44 = " + format_number(m.C44) + " GPa)";
        const bool cubic = m.lattice != Lattice::hcp;
        if (cubic && !(m.C44 > 0.))
          reject("material.elastic.C44", format_number(m.C44),
                 "the cubic stiffness must be positive definite: C44 > 0 GPa " + constants);
        if (cubic && !(m.C11 - m.C12 > 0.))
          {
            const std::string path =
                given_or_first({"material.elastic.C12", "material.elastic.C11"});
            reject(path, format_number(path == "material.elastic.C11" ? m.C11 : m.C12),
                   "the cubic stiffness must be positive definite: C11 - C12 > 0 " + constants);
          }
        if (cubic && !(m.C11 + 2. * m.C12 > 0.))
          {
            const std::string path =
                given_or_first({"material.elastic.C12", "material.elastic.C11"});
            reject(path, format_number(path == "material.elastic.C11" ? m.C11 : m.C12),
                   "the cubic stiffness must be positive definite: C11 + 2 C12 > 0 (a positive "
                   "bulk modulus) " +
                       constants);
          }
        if (m.theta0 > 0. && !(m.tau1 > 0.))
          {
            // The message names the key given (or the first) with its value, and the other
            // key's value in the rule (never the key twice).
            const std::string path =
                given_or_first({"material.hardening.tau1", "material.hardening.theta0"});
            const bool tau1 = path == "material.hardening.tau1";
            reject(path, format_number(tau1 ? m.tau1 : m.theta0),
                   "tau1 must be > 0 when theta0 > 0 (here " +
                       (tau1 ? "theta0 = " + format_number(m.theta0)
                             : "tau1 = " + format_number(m.tau1)) +
                       " GPa): " + voce_needs_tau1);
          }

        const auto &o = m.orientation;
        if (!o.kind.known())
          reject_unknown_word("material.orientation.kind", o.kind.word(),
                              choice_words<OrientationKind>(true));
        try
          {
            materials::create_orientation(m);
          }
        catch (const std::invalid_argument &error)
          {
            const std::string what = error.what();
            if (o.kind == OrientationKind::euler_bunge_deg)
              reject("material.orientation.euler_bunge_deg", format_triple(o.euler_bunge_deg),
                     what);
            else if (what.rfind("reference_direction", 0) == 0)
              reject("material.orientation.reference_direction", format_list(o.reference_direction),
                     what);
            else
              reject("material.orientation.surface_normal", format_list(o.surface_normal), what);
          }
      }

      // Every indenter key is checked for every shape (the resolved case always holds them) but
      // used only by its shapes; the profile table file is read only for shape: profile_table.
      // Returns the indenter, built as the run will build it.
      std::unique_ptr<indenter::IndenterSurface> check_indenter() const
      {
        const auto &ind = checked.indenter;
        if (!(ind.edge_radius >= 0. && ind.edge_radius <= ind.radius))
          {
            const std::string path = given_or_first({"indenter.edge_radius", "indenter.radius"});
            const bool        edge = path == "indenter.edge_radius";
            reject(path, format_number(edge ? ind.edge_radius : ind.radius),
                   "the rim rounding of the flat punch must satisfy 0 <= edge_radius <= radius "
                   "(um; 0: a sharp rim; here " +
                       (edge ? "radius = " + format_number(ind.radius)
                             : "edge_radius = " + format_number(ind.edge_radius)) +
                       " um)");
          }
        // A sharp pyramid's contact normal jumps from face to face across an edge: Newton's
        // method stalls on the nodes along the edges, or with a rounding of a few nm a node
        // slides off the edge onto one face (the mirror-symmetry guard of the run reports it).
        if (for_run &&
            (ind.shape == IndenterShape::vickers || ind.shape == IndenterShape::berkovich) &&
            !(ind.tip_radius > 0))
          reject("indenter.tip_radius", format_number(ind.tip_radius),
                 "a vickers or berkovich pyramid needs a rounded tip, tip_radius > 0 um (real "
                 "tips: 0.02-0.2 um): across a sharp edge the contact normal jumps from face to "
                 "face, and Newton's method stalls on the nodes along the edges; 0.01 um or more "
                 "keeps those nodes on the edge (docs/user-guide.md, \"Indenters\")");
        if (ind.shape == IndenterShape::profile_table && ind.file.empty())
          reject("indenter.file", "\"\"",
                 "shape: profile_table needs the table: file: a CSV path (relative to the case "
                 "file's directory) with the header r_um,z_um (profile) or depth_um,area_um2 "
                 "(area function)");
        try
          {
            return indenter::create_indenter(ind);
          }
        catch (const indenter::ProfileTableError &error)
          {
            reject("indenter.file", "\"" + ind.file + "\"", error.what());
          }
        catch (const std::invalid_argument &error)
          {
            reject("indenter.shape", to_string(ind.shape), error.what());
          }
      }

      void check_specimen(const indenter::IndenterSurface &surface) const
      {
        const auto &s = checked.specimen;
        for (unsigned int d = 0; d < 3; ++d)
          if (s.refined_region[d] > s.size[d])
            reject("specimen.refined_region", format_triple(s.refined_region),
                   std::string("the refined region must fit inside the specimen: its ") +
                       axis_names[d] + " extent " + format_number(s.refined_region[d]) +
                       " um exceeds specimen.size = " + format_triple(s.size));
        const bool quarter = s.symmetry == Symmetry::quarter;
        if (!tensile() && quarter && !surface.mirror_symmetric_about_xz_and_yz())
          reject_quarter_symmetry_of_the_indenter();
        if (checked.material.model == ModelKind::crystal && !tensile() && quarter)
          check_quarter_symmetry_of_the_lattice();
        if (s.symmetry == Symmetry::axisymmetric)
          check_axisymmetric_model();
        if (s.grains == Grains::per_element && !tensile())
          reject("specimen.grains", to_string(s.grains),
                 "a random orientation per element is only implemented for test: tensile; the "
                 "indentation test models a single crystal (use grains: single)");
      }

      void check_loading() const
      {
        const auto &l = checked.loading;
        const auto &s = checked.specimen;
        if (!(l.max_depth < s.refined_region[2]))
          reject("loading.max_depth", format_number(l.max_depth),
                 "must be smaller than the depth of the refined region, specimen.refined_region"
                 "[2] = " +
                     format_number(s.refined_region[2]) + " um");
        if (l.control == Control::force)
          {
            if (tensile())
              reject("loading.control", to_string(l.control),
                     "force control is implemented for the indentation test only");
            if (!(l.max_force > 0.))
              reject("loading.max_force", format_number(l.max_force),
                     "force control needs the maximum indenter force, > 0 mN");
          }
        else if (l.max_force != 0.)
          reject("loading.max_force", format_number(l.max_force),
                 "is the target of force control; with loading.control: depth the maximum is "
                 "loading.max_depth (remove max_force or set control: force)");
        if (l.spacing == Spacing::geometric && tensile())
          reject("loading.spacing", to_string(l.spacing),
                 "geometric increments are for the indentation test; the tensile test takes "
                 "`steps` equal increments of strain");
        if (l.spacing != Spacing::geometric &&
            l.first_fraction != LoadingParameters{}.first_fraction)
          reject("loading.first_fraction", format_number(l.first_fraction),
                 "sets the first increment of geometric spacing; with loading.spacing: uniform "
                 "every increment is max_depth (max_force) / steps (remove first_fraction or set "
                 "spacing: geometric)");
        if (l.spacing == Spacing::geometric && l.steps < 2)
          reject("loading.steps", std::to_string(l.steps),
                 "geometric spacing needs at least 2 steps (the first to first_fraction of the "
                 "maximum, then the geometric ones)");
        if (l.cycles > 1 && !l.unload)
          reject("loading.cycles", std::to_string(l.cycles),
                 "several load-unload cycles need loading.unload: true");
        if (l.partial_unloads.enabled())
          check_partial_unloads();
      }

      // Partial unloads are placed by depth: they need depth control and the indentation
      // test, and at least one lies above the maximum depth.
      void check_partial_unloads() const
      {
        const auto       &l = checked.loading;
        const std::string key = "loading.partial_unloads.every";
        const std::string every = format_number(l.partial_unloads.every);
        if (tensile())
          reject(key, every, "partial unloads are for the indentation test");
        if (l.control == Control::force)
          reject(key, every, "partial unloads are placed by depth and need loading.control: depth");
        if (l.cycles > 1)
          reject(key, every,
                 "partial unloads are made in a single loading (loading.cycles: 1); the "
                 "cycles repeat the whole load-unload programme");
        if (!(l.partial_unloads.every < l.max_depth))
          reject(key, every,
                 "must be smaller than loading.max_depth = " + format_number(l.max_depth) +
                     " um (a partial unload lies at every multiple of it below the maximum)");
        if (l.max_depth / l.partial_unloads.every > 1000)
          reject(key, every,
                 "gives more than 1000 partial unloads to loading.max_depth = " +
                     format_number(l.max_depth) + " um");
      }

      // The refined region must hold the contact predicted at the maximum of the loading
      // (mesh/MeshAdequacy.h: the indenter's cross-section with the pile-up allowance, within
      // the margin of the refined half-widths); the run stops if the contact goes beyond it.
      void check_contact_fits(const indenter::IndenterSurface &surface) const
      {
        const auto prediction = mesh::predict_contact(checked, surface);
        if (!prediction)
          return;
        const auto  &s = checked.specimen;
        const double fraction = mesh::refined_fraction(prediction->extent, s);
        if (fraction <= mesh::guard::refined_region_margin)
          return;
        using mesh::short_number;
        const bool along_x = prediction->extent.x / s.refined_region[0] >=
                             prediction->extent.y / s.refined_region[1];
        const double reach = along_x ? prediction->extent.x : prediction->extent.y;
        const double half = (along_x ? s.refined_region[0] : s.refined_region[1]) / 2;
        const bool   force = checked.loading.control == Control::force;
        std::string  alternative =
            force ? "a smaller loading.max_force"
                   : "loading.max_depth <= " +
                        short_number(mesh::largest_depth_held(checked, surface)) + " um";
        reject("specimen.refined_region", format_triple(s.refined_region),
               "the refined region cannot hold the contact at the maximum " +
                   std::string(force ? "force" : "depth") + ": the contact is predicted to reach " +
                   short_number(reach) + " um from the axis along " + (along_x ? "x" : "y") +
                   " (from " + prediction->basis + "), beyond " +
                   short_number(100 * mesh::guard::refined_region_margin) +
                   " % of the refined half-width " + short_number(half) +
                   " um; contact nodes exist only on the refined region, so the force would "
                   "mean nothing beyond it. Use " +
                   mesh::enlargement_advice(s, prediction->extent) + ", or " + alternative);
      }

      void check_output() const
      {
        const auto &o = checked.output;
        if (o.experimental_curve.empty())
          return;
        if (checked.test != TestKind::indentation)
          reject("output.experimental_curve", "\"" + o.experimental_curve + "\"",
                 "a measured load-penetration curve belongs to test: indentation");
        try
          {
            const LoadCurve curve = read_load_curve_csv(o.experimental_curve);
            if (curve.depth.size() < 2)
              throw std::invalid_argument("it has fewer than 2 data rows");
          }
        catch (const std::invalid_argument &error)
          {
            reject("output.experimental_curve", "\"" + o.experimental_curve + "\"",
                   std::string(error.what()) +
                       " (a CSV with a header; depth and force columns with their units in "
                       "the names, e.g. depth_nm,load_uN)");
          }
      }

      // The first of `paths` that the case file gave explicitly, else the first: a check on a
      // pair of values then points at the line the user wrote.
      // material.lattice with its own keys: hcp needs c_over_a, C13 and C33 (which no cubic
      // lattice takes) and a positive-definite hexagonal stiffness; slip_families are the
      // lattice's, each once (none given: the lattice's default ones, written in the resolved
      // case).
      void check_lattice() const
      {
        const auto &m = checked.material;
        if (!m.lattice.known())
          return; // named by the single-key check, with the allowed words
        const std::string                                 lattice = m.lattice.word();
        const bool                                        hcp = m.lattice == Lattice::hcp;
        const std::vector<std::pair<std::string, double>> hcp_keys = {
            {"material.c_over_a", m.c_over_a},
            {"material.elastic.C13", m.C13},
            {"material.elastic.C33", m.C33}};
        for (const auto &[path, value] : hcp_keys)
          {
            const bool given = value_origins != nullptr && value_origins->count(path) > 0;
            if (!hcp && given)
              reject(path, format_number(value),
                     "only the hexagonal lattice takes it (material.lattice = " + lattice + ")");
            if (hcp && !(value > 0.))
              reject(path, format_number(value),
                     "material.lattice = hcp needs c/a, C13 and C33 (> 0), e.g. zirconium: "
                     "c_over_a: 1.593, elastic: {C11: 143.5, C12: 72.5, C13: 65.4, C33: 164.9, "
                     "C44: 32.1}");
          }
        if (hcp)
          if (const char *error =
                  materials::LatticeElasticity::hexagonal(m.C11, m.C12, m.C13, m.C33, m.C44)
                      .parameter_error())
            reject(given_or_first({"material.elastic.C13", "material.elastic.C11"}),
                   "C11 = " + format_number(m.C11) + ", C12 = " + format_number(m.C12) +
                       ", C13 = " + format_number(m.C13) + ", C33 = " + format_number(m.C33) +
                       ", C44 = " + format_number(m.C44),
                   error);
        // The resolved case names the families a bcc or hcp run uses.
        if (m.slip_families.empty() && m.lattice != Lattice::fcc)
          designed.material.slip_families = materials::default_slip_families(lattice);
        // The library names an unknown or repeated family and the allowed ones.
        try
          {
            materials::slip_systems(lattice, m.slip_families, hcp ? m.c_over_a : 0.0);
          }
        catch (const std::invalid_argument &error)
          {
            const std::string what = error.what(), prefix = "material.slip_families: ";
            reject("material.slip_families", format_words(m.slip_families),
                   what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
          }
      }

      // The per-family Voce blocks and the latent matrix: for the crystal model only, each
      // block a family of the case, the matrix one row and column per family.
      void check_family_hardening() const
      {
        const auto &m = checked.material;
        if (m.family_hardening.empty() && m.latent_matrix.empty())
          return;
        const bool crystal = m.model == ModelKind::crystal;
        for (const FamilyHardening &block : m.family_hardening)
          {
            const std::string path = "material.hardening." + block.family;
            if (!crystal)
              reject(path, format_family_block(block),
                     "a slip family's hardening is for model: crystal (here model: " +
                         m.model.word() + ")");
          }
        if (!crystal && !m.latent_matrix.empty())
          reject("material.latent_hardening.matrix", format_matrix(m.latent_matrix),
                 "latent hardening is for model: crystal (here model: " + m.model.word() + ")");
        if (!m.lattice.known())
          return;
        const std::vector<std::string> families =
            materials::slip_systems(m.lattice.word(), designed.material.slip_families,
                                    m.lattice == Lattice::hcp ? m.c_over_a : 0.0)
                .families;
        const std::string listed = "material.slip_families = " + format_words(families);
        for (const FamilyHardening &block : m.family_hardening)
          {
            const std::string path = "material.hardening." + block.family;
            if (std::find(families.begin(), families.end(), block.family) == families.end())
              reject(path, format_family_block(block),
                     "not a slip family of this crystal (" + listed +
                         "); name one of them, quoted, e.g. \"" + families.front() +
                         "\": {tau0: " + format_number(m.tau0) + "}");
            // The common keys' ranges (the schema's) apply to each block's values.
            for (const auto &[name, value] : {std::pair{"tau0", block.tau0},
                                              {"tau1", block.tau1},
                                              {"theta0", block.theta0},
                                              {"theta1", block.theta1},
                                              {"tau_irr", block.tau_irr},
                                              {"softening_slip", block.softening_slip},
                                              {"barrier_strength", block.barrier_strength}})
              if (const Key &key = find_key(std::string("material.hardening.") + name);
                  !key.range.contains(value))
                reject(path + "." + name, format_number(value), key.range_message);
            if (block.theta0 > 0. && !(block.tau1 > 0.))
              reject(path + ".tau1", format_number(block.tau1),
                     "tau1 must be > 0 when theta0 > 0 (here theta0 = " +
                         format_number(block.theta0) + " GPa): " + voce_needs_tau1);
          }
        if (m.latent_matrix.empty())
          return;
        const std::size_t n = families.size();
        const std::string matrix_path = "material.latent_hardening.matrix";
        bool              square = m.latent_matrix.size() == n;
        for (const auto &row : m.latent_matrix)
          square = square && row.size() == n;
        if (!square)
          reject(matrix_path, format_matrix(m.latent_matrix),
                 "needs " + std::to_string(n) + " rows of " + std::to_string(n) +
                     " ratios, one per slip family in the order of " + listed);
        for (std::size_t f = 0; f < n; ++f)
          for (std::size_t g = 0; g < n; ++g)
            if (!(m.latent_matrix[f][g] >= 0.) || !std::isfinite(m.latent_matrix[f][g]))
              reject(matrix_path, format_matrix(m.latent_matrix),
                     "the latent ratios must be >= 0 and finite; row " + std::to_string(f) +
                         ", column " + std::to_string(g) + " (" +
                         format_number(m.latent_matrix[f][g]) + ") is not");
      }

      std::string given_or_first(std::initializer_list<std::string> paths) const
      {
        if (value_origins != nullptr)
          for (const auto &path : paths)
            if (value_origins->count(path) > 0)
              return path;
        return *paths.begin();
      }

      // The axisymmetric model is exact only for an isotropic material under an axisymmetric
      // indenter; the tensile test is a 3D polycrystal.
      void check_axisymmetric_model() const
      {
        const std::string why = "specimen.symmetry: axisymmetric models the (r, z) section of a "
                                "cylinder and is exact only for ";
        if (tensile())
          reject("specimen.symmetry", "axisymmetric",
                 "the tensile test models a 3D polycrystal cube; use symmetry: full");
        if (checked.material.model == ModelKind::crystal)
          reject("specimen.symmetry", "axisymmetric",
                 why + "isotropic materials (neo_hookean, j2), not material.model: crystal (a "
                       "crystal's slip systems break the axial symmetry); use symmetry: full, or "
                       "quarter where the lattice allows it");
        const auto &shape = checked.indenter.shape;
        if (shape == IndenterShape::vickers || shape == IndenterShape::berkovich)
          reject("specimen.symmetry", "axisymmetric",
                 why +
                     "axisymmetric indenters (rounded_cone, sphere, cone, flat_punch, "
                     "profile_table), not indenter.shape: " +
                     to_string(shape) +
                     "; use symmetry: full, or the cone of the same area function (half-angle "
                     "70.3 deg) in axisymmetric mode");
      }

      // The quarter model imposes u_x = 0 on x = 0 and u_y = 0 on y = 0, exact only if both are
      // mirror planes of the indenter (IndenterSurface::mirror_symmetric_about_xz_and_yz).
      [[noreturn]] void reject_quarter_symmetry_of_the_indenter() const
      {
        const auto &ind = checked.indenter;
        std::string shape = "indenter.shape = " + to_string(ind.shape);
        std::string advice = "use symmetry: full";
        if (ind.shape == IndenterShape::vickers)
          {
            shape += " with rotation_deg = " + format_number(ind.rotation_deg);
            advice = "a Vickers pyramid has them when rotation_deg is a multiple of 45; use "
                     "rotation_deg: 0 (faces towards +-x, +-y) or 45 (edges along x and y), or "
                     "symmetry: full";
          }
        else if (ind.shape == IndenterShape::berkovich)
          advice = "a three-sided pyramid never has two perpendicular mirror planes; use "
                   "symmetry: full";
        reject("specimen.symmetry", to_string(checked.specimen.symmetry),
               "the quarter model (u_x = 0 on x = 0, u_y = 0 on y = 0) needs the planes x = 0 "
               "and y = 0 to be mirror planes of the indenter, and " +
                   shape + " is not mirror-symmetric about both; " + advice);
      }

      // The quarter model imposes u_x = 0 on x = 0 and u_y = 0 on y = 0; for a crystal that is
      // exact only if both planes are mirror planes of the lattice (its point group).
      void check_quarter_symmetry_of_the_lattice() const
      {
        const auto                &o = checked.material.orientation;
        const dealii::Tensor<2, 3> g = materials::create_orientation(checked.material);
        const dealii::Tensor<1, 3> e_x({1., 0., 0.}), e_y({0., 1., 0.});
        const std::string          lattice = checked.material.lattice.word();
        const bool                 x_mirror = materials::is_mirror_plane(lattice, g, e_x);
        const bool                 y_mirror = materials::is_mirror_plane(lattice, g, e_y);
        if (x_mirror && y_mirror)
          return;
        const std::string orientation =
            o.kind == OrientationKind::surface_normal
                ? "material.orientation: surface_normal " + format_list(o.surface_normal) +
                      ", reference_direction " + format_list(o.reference_direction)
                : "material.orientation: euler_bunge_deg " + format_triple(o.euler_bunge_deg);
        reject("specimen.symmetry", to_string(checked.specimen.symmetry),
               "the quarter model needs the sample planes x = 0 and y = 0 to be mirror planes "
               "of the " +
                   lattice + " lattice, but for " + orientation + " the plane " +
                   (x_mirror ? "y = 0" : (y_mirror ? "x = 0" : "x = 0 (and y = 0)")) +
                   " is not one (e.g. a (111) surface has no two perpendicular mirror planes); "
                   "use symmetry: full");
      }

      [[noreturn]] void reject(const std::string &path, const std::string &value,
                               const std::string &what) const
      {
        int         line = -1;
        std::string shown = value;
        if (value_origins != nullptr)
          {
            if (const auto origin = value_origins->find(path); origin != value_origins->end())
              line = origin->second.line;
            else
              shown += " (default)";
          }
        fail(checked.source_file, line, path + " = " + shown + ": " + what);
      }

      [[noreturn]] void reject_unknown_word(const std::string &path, const std::string &word,
                                            const std::vector<std::string> &allowed) const
      {
        std::string message = "unknown value; allowed: " + join(allowed, " | ");
        if (const std::string guess = closest_name(word, allowed); !guess.empty())
          message += " (did you mean '" + guess + "'?)";
        reject(path, "'" + word + "'", message);
      }
    };
  } // namespace

  std::unique_ptr<indenter::IndenterSurface>
  validate_values(Case &checked, const OriginMap *origins, const bool for_run)
  {
    return CaseValidator(checked, origins, for_run).validate();
  }
} // namespace indentsim::io

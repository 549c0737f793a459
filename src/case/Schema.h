// The case-file schema: every key of a case file declared once, with its type, unit, default
// (the value in a default-constructed Case), admissible range or words, the comment of the
// resolved case, the description of the reference (docs/case-file-reference.md) and where it
// is stored in Case. The reader, the single-key checks of the validator, the resolved-case
// writer, the fingerprint and the reference all iterate over this table; checks that involve
// several keys are written by hand in CaseValidator.cc. Units: um, mN, GPa.
#pragma once

#include "case/Case.h"

#include <array>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace indentsim::io
{
  // The largest specimen.contact_elements (the schema's bound; guards name it in advice).
  inline constexpr unsigned int max_contact_elements = 512;

  enum class ValueType
  {
    number,       // double
    whole_number, // unsigned int
    boolean,
    choice,        // Choice<E>: a word of its table
    text,          // a string the user chooses freely (a path)
    triple,        // three numbers
    list,          // one or more numbers (std::vector<double>)
    words,         // one or more words (std::vector<std::string>)
    matrix,        // a square list of lists of numbers (std::vector<std::vector<double>>)
    family_blocks, // maps named by slip families, under the key's parent map
                   // (std::vector<FamilyHardening>; the key's name is a placeholder)
    layers         // a list of maps, each a thickness and material keys
                   // (std::vector<MaterialLayer>)
  };

  // Admissible values: an interval, open or closed at each end (infinite ends exclude infinity),
  // and for whole numbers optionally a multiple of `multiple_of`.
  struct Range
  {
    double       lower = -std::numeric_limits<double>::infinity();
    bool         lower_included = false;
    double       upper = std::numeric_limits<double>::infinity();
    bool         upper_included = false;
    unsigned int multiple_of = 0;

    bool contains(double value) const;
    // For the reference: "> 0", "0 ≤ x ≤ 2", "multiple of 4, ≥ 4", "finite".
    std::string text() const;
  };

  // Access to a Choice<E> member without knowing E.
  struct ChoiceAccess
  {
    std::string (*word)(const Case &) = nullptr;
    void (*assign)(Case &, const std::string &) = nullptr;
    bool (*known)(const Case &) = nullptr;
    bool (*implemented)(const Case &) = nullptr;
    std::vector<std::string> (*words)(bool implemented_only) = nullptr;
  };

  struct Key
  {
    std::string path; // "material.elastic.C11"
    ValueType   type = ValueType::number;
    std::string unit;         // "GPa", "um", ... ; "" for dimensionless values and words
    std::string expected;     // the reader's "expected ..." (e.g. "E in GPa"); triples: the list
    std::string entry_unit;   // triples: what each entry is ("um", "degrees")
    std::string comment;      // the comment of the line in resolved_case.yaml
    std::string description;  // the reference's description
    std::string default_text; // the reference's default, where not the Case{} value
    std::string allowed_text; // the reference's "allowed", where checked by hand
    bool        has_range = false;
    Range       range;
    std::string range_message; // the validator's "what is allowed" for a value out of range
    std::string not_implemented_message; // choices: a word recognised but not implemented
    bool        required = false;        // no default: the case file must give it
    bool        non_empty = false;       // text: "" is not admissible (range_message says why)
    bool        relative_to_case_file = false; // text: a path relative to the case file's directory
    bool        determines_results = true;     // false: left out of the fingerprint (Fingerprint.h)
    const char *zero_word = nullptr; // whole numbers: the word stored as 0 ("auto"), or none
    bool (*written)(const Case &) =
        nullptr; // resolved case: written only if true (nullptr: always)
    // The fingerprint: included only if true (nullptr: when written). A table read from a file
    // is fingerprinted by its content, which the resolved case leaves to the file.
    bool (*fingerprinted)(const Case &) = nullptr;

    // Where the value is stored: the one accessor that matches `type`.
    double &(*number)(Case &) = nullptr;
    unsigned int &(*whole_number)(Case &) = nullptr;
    bool &(*boolean)(Case &) = nullptr;
    std::string &(*text)(Case &) = nullptr;
    std::array<double, 3> &(*triple)(Case &) = nullptr;
    std::vector<double> &(*list)(Case &) = nullptr;
    std::vector<std::string> &(*words)(Case &) = nullptr;
    std::vector<std::vector<double>> &(*matrix)(Case &) = nullptr;
    std::vector<FamilyHardening> &(*family_blocks)(Case &) = nullptr;
    std::vector<MaterialLayer> &(*layers)(Case &) = nullptr;
    ChoiceAccess choice;

    // "C11" for "material.elastic.C11"; the map holding it: "material.elastic" ("" on top).
    std::string name() const;
    std::string parent() const;
    // The value as the resolved case writes it, strings unquoted.
    std::string value_text(const Case &c) const;
  };

  // A map nested in a section (material.elastic, material.hardening, material.orientation).
  struct Group
  {
    std::string path;
    std::string comment;     // the resolved case's comment of the "  elastic:" line
    std::string description; // the reference's text above the section's table
  };

  // Every key, in the order of the case file, the reader and the resolved case.
  const std::vector<Key> &case_keys();
  // The nested maps.
  const std::vector<Group> &case_groups();
  // The key at `path`; throws std::out_of_range for an unknown path.
  const Key &find_key(const std::string &path);
  // The names allowed in the map at `path` ("" the top level, "material", "material.elastic"),
  // in file order.
  const std::vector<std::string> &allowed_names(const std::string &path);
  // Every map except the top level with its allowed names, ordered by path.
  const std::map<std::string, std::vector<std::string>> &maps_with_names();

  // Shortest text that reads back to the identical double, independent of the locale.
  std::string format_number(double value);
  std::string format_triple(const std::array<double, 3> &values);
  std::string format_list(const std::vector<double> &values);
  std::string format_words(const std::vector<std::string> &values);        // ["a", "b"], quoted
  std::string format_matrix(const std::vector<std::vector<double>> &rows); // [[1, 2], [3, 4]]
  // {tau0: 0.4, tau1: 0.1, theta0: 1, theta1: 0.01}
  std::string format_family_block(const FamilyHardening &block);
  // {"{110}<111>": {tau0: ...}, "{112}<111>": {...}}
  std::string format_family_blocks(const std::vector<FamilyHardening> &blocks);
  std::string format_bool(bool value);
  // [{thickness: 1.5, yield_stress: 0.6}, ...]
  std::string format_layers(const std::vector<MaterialLayer> &layers);
} // namespace indentsim::io

// Internal to Schema.cc: the steps in which an entry of the schema table is declared,
//   Declare::at<&Case::material, &MaterialParameters::C11>("material.elastic.C11")
//     .unit("GPa").expect("C11 in GPa").comment("[GPa]").describe("...")
// and the ranges of admissible values.
#pragma once

#include "case/Schema.h"

#include <limits>
#include <string>
#include <type_traits>

namespace indentsim::io::schema_builder
{
  inline constexpr double infinity = std::numeric_limits<double>::infinity();

  // Bounded below only (infinity admitted, as `!(x > lower)` checks).
  inline Range above(const double lower)
  {
    return {lower, false, infinity, true, 0};
  }
  inline Range at_least(const double lower)
  {
    return {lower, true, infinity, true, 0};
  }
  // Bounded below and finite.
  inline Range finite_above(const double lower)
  {
    return {lower, false, infinity, false, 0};
  }
  inline Range finite_at_least(const double lower)
  {
    return {lower, true, infinity, false, 0};
  }
  inline Range at_most(const double upper)
  {
    return {-infinity, true, upper, true, 0};
  }
  inline Range between(const double lower, const bool lower_included, const double upper,
                       const bool upper_included)
  {
    return {lower, lower_included, upper, upper_included, 0};
  }
  inline Range finite()
  {
    return {};
  }

  // The member of a Case reached through `Members` (e.g. &Case::material,
  // &MaterialParameters::C11).
  template <auto... Members>
  decltype(auto) stored(Case &c)
  {
    return (c.*....*Members);
  }

  template <typename T>
  struct ChoiceEnum;
  template <typename Enum>
  struct ChoiceEnum<Choice<Enum>>
  {
    using type = Enum;
  };

  // One entry of the table, built in steps: Declare::at<members...>("path").unit("GPa")...
  class Declare
  {
  public:
    template <auto... Members>
    static Declare at(const char *path)
    {
      Declare d;
      Key    &k = d.key;
      k.path = path;
      using T = std::remove_cvref_t<decltype(stored<Members...>(std::declval<Case &>()))>;
      if constexpr (std::is_same_v<T, double>)
        {
          k.type = ValueType::number;
          k.number = &stored<Members...>;
        }
      else if constexpr (std::is_same_v<T, unsigned int>)
        {
          k.type = ValueType::whole_number;
          k.whole_number = &stored<Members...>;
        }
      else if constexpr (std::is_same_v<T, bool>)
        {
          k.type = ValueType::boolean;
          k.boolean = &stored<Members...>;
        }
      else if constexpr (std::is_same_v<T, std::string>)
        {
          k.type = ValueType::text;
          k.text = &stored<Members...>;
        }
      else if constexpr (std::is_same_v<T, std::array<double, 3>>)
        {
          k.type = ValueType::triple;
          k.triple = &stored<Members...>;
          k.expected = "[x, y, z] in um";
          k.entry_unit = "um";
        }
      else if constexpr (std::is_same_v<T, std::vector<double>>)
        {
          k.type = ValueType::list;
          k.list = &stored<Members...>;
        }
      else if constexpr (std::is_same_v<T, std::vector<std::string>>)
        {
          k.type = ValueType::words;
          k.words = &stored<Members...>;
        }
      else if constexpr (std::is_same_v<T, std::vector<std::vector<double>>>)
        {
          k.type = ValueType::matrix;
          k.matrix = &stored<Members...>;
        }
      else if constexpr (std::is_same_v<T, std::vector<FamilyHardening>>)
        {
          k.type = ValueType::family_blocks;
          k.family_blocks = &stored<Members...>;
        }
      else if constexpr (std::is_same_v<T, std::vector<MaterialLayer>>)
        {
          k.type = ValueType::layers;
          k.layers = &stored<Members...>;
        }
      else
        {
          using Enum = typename ChoiceEnum<T>::type;
          // The const accessors only read through the const_cast.
          k.type = ValueType::choice;
          k.choice.word = [](const Case &c) {
            return stored<Members...>(const_cast<Case &>(c)).word();
          };
          k.choice.assign = [](Case &c, const std::string &word) {
            stored<Members...>(c) = Choice<Enum>(word);
          };
          k.choice.known = [](const Case &c) {
            return stored<Members...>(const_cast<Case &>(c)).known();
          };
          k.choice.implemented = [](const Case &c) {
            return stored<Members...>(const_cast<Case &>(c)).implemented();
          };
          k.choice.words = &choice_words<Enum>;
        }
      return d;
    }

    Declare &unit(const char *text) { return key.unit = text, *this; }
    Declare &expect(const char *text) { return key.expected = text, *this; }
    Declare &entries(const char *list, const char *entry)
    {
      key.expected = list;
      key.entry_unit = entry;
      return *this;
    }
    Declare &comment(const char *text) { return key.comment = text, *this; }
    Declare &describe(const char *text) { return key.description = text, *this; }
    Declare &default_is(const char *text) { return key.default_text = text, *this; }
    Declare &allowed_is(const char *text) { return key.allowed_text = text, *this; }
    Declare &range(const Range &range, const std::string &message)
    {
      key.has_range = true;
      key.range = range;
      key.range_message = message;
      return *this;
    }
    Declare &not_implemented(const char *message)
    {
      return key.not_implemented_message = message, *this;
    }
    Declare &required() { return key.required = true, *this; }
    Declare &non_empty(const char *message)
    {
      key.non_empty = true;
      key.range_message = message;
      return *this;
    }
    // A whole number that may be the word `word` instead, stored as 0.
    Declare &or_word(const char *word) { return key.zero_word = word, *this; }
    Declare &relative_to_case_file() { return key.relative_to_case_file = true, *this; }
    Declare &not_a_result() { return key.determines_results = false, *this; }
    Declare &written_if(bool (*condition)(const Case &)) { return key.written = condition, *this; }
    Declare &fingerprinted_if(bool (*condition)(const Case &))
    {
      return key.fingerprinted = condition, *this;
    }

    operator Key() const { return key; }

  private:
    Key key;
  };

} // namespace indentsim::io::schema_builder

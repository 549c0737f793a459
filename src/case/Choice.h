// A case-file choice (material.model, indenter.shape, ...): an enum class with one table of
// its words, shared by the reader, the validator, the resolved-case writer and the generated
// reference.
//
// Choice<E> holds an E, or, when a word that names no E was given (a typo in a case file, or a
// case assembled in code), that word: the validator then rejects it with the list of allowed
// words and a "did you mean", exactly like every other bad value, in its place among the
// other checks. Consumers compare with enumerators (`loading.control == LoadingControl::force`).
#pragma once

#include <algorithm>
#include <array>
#include <ostream>
#include <string>
#include <vector>

namespace indentsim::io
{
  // One word of a choice. `implemented` is false for a word that is recognised (and explained
  // in the message) but not yet supported, such as the bcc lattice.
  template <typename Enum>
  struct ChoiceWord
  {
    Enum        value;
    const char *word;
    bool        implemented = true;
  };

  // Specialised next to each enum: `static constexpr std::array<ChoiceWord<E>, N> words`.
  template <typename Enum>
  struct ChoiceWords;

  template <typename Enum>
  class Choice
  {
  public:
    Choice(const Enum value)
      : value_(value)
    {
    }

    // The enumerator named `word`, or an unknown choice that keeps the word.
    Choice(const std::string &word)
    {
      for (const auto &entry : ChoiceWords<Enum>::words)
        if (word == entry.word)
          {
            value_ = entry.value;
            return;
          }
      known_ = false;
      unknown_word_ = word;
    }

    Choice(const char *word)
      : Choice(std::string(word))
    {
    }

    // Whether the word names an enumerator (implemented or not).
    bool known() const { return known_; }

    // The enumerator; meaningful only if known().
    Enum value() const { return value_; }

    std::string word() const
    {
      if (!known_)
        return unknown_word_;
      for (const auto &entry : ChoiceWords<Enum>::words)
        if (entry.value == value_)
          return entry.word;
      return {};
    }

    bool implemented() const
    {
      if (!known_)
        return false;
      for (const auto &entry : ChoiceWords<Enum>::words)
        if (entry.value == value_)
          return entry.implemented;
      return false;
    }

    bool operator==(const Choice &) const = default;
    bool operator==(const Enum value) const { return known_ && value_ == value; }
    // By word: for tests and messages that speak of the word as written.
    bool operator==(const char *word) const { return this->word() == word; }
    bool operator==(const std::string &word) const { return this->word() == word; }

  private:
    Enum        value_ = ChoiceWords<Enum>::words[0].value;
    bool        known_ = true;
    std::string unknown_word_;
  };

  template <typename Enum>
  std::string to_string(const Choice<Enum> &choice)
  {
    return choice.word();
  }

  template <typename Enum>
  std::ostream &operator<<(std::ostream &out, const Choice<Enum> &choice)
  {
    return out << choice.word();
  }

  // The words of a choice, all of them or only the implemented ones, in table order.
  template <typename Enum>
  std::vector<std::string> choice_words(const bool implemented_only)
  {
    std::vector<std::string> words;
    for (const auto &entry : ChoiceWords<Enum>::words)
      if (entry.implemented || !implemented_only)
        words.emplace_back(entry.word);
    return words;
  }
} // namespace indentsim::io

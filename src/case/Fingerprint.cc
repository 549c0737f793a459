// The fingerprint of a case (see Fingerprint.h).
#include "case/Fingerprint.h"
#include "case/CaseFile.h"
#include "case/Schema.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace indentsim::io
{
  std::string canonical_case_text(const Case &resolved_case)
  {
    std::vector<std::string> lines;
    for (const auto &key : case_keys())
      if (key.determines_results &&
          (key.fingerprinted != nullptr ? key.fingerprinted(resolved_case)
                                        : key.written == nullptr || key.written(resolved_case)))
        lines.push_back(key.path + ": " + key.value_text(resolved_case));
    std::sort(lines.begin(), lines.end());
    return join(lines, "\n") + "\n";
  }

  std::uint64_t fnv1a_64(const std::string &text)
  {
    std::uint64_t hash = 14695981039346656037ull; // FNV offset basis
    for (const unsigned char byte : text)
      {
        hash ^= byte;
        hash *= 1099511628211ull; // FNV prime
      }
    return hash;
  }

  std::uint64_t case_fingerprint(const Case &resolved_case)
  {
    return fnv1a_64(canonical_case_text(resolved_case));
  }

  std::vector<KeyDifference> case_differences(const Case &old_case, const Case &new_case)
  {
    const auto value = [](const Key &key, const Case &c) {
      const bool set = key.fingerprinted != nullptr ? key.fingerprinted(c)
                                                    : key.written == nullptr || key.written(c);
      return set ? key.value_text(c) : "(not set)";
    };
    std::vector<KeyDifference> differences;
    for (const auto &key : case_keys())
      if (key.determines_results)
        if (std::string old_value = value(key, old_case), new_value = value(key, new_case);
            old_value != new_value)
          differences.push_back({key.path, std::move(old_value), std::move(new_value)});
    return differences;
  }
} // namespace indentsim::io

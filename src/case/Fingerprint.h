// The fingerprint of a case: a hash of every key that determines the results, shared by the
// checkpoint (a checkpoint resumes only the case that wrote it) and the study (a finished case
// is not run again; its folder name carries the key).
//
// Keys that do not determine results are left out (Key::determines_results in Schema.cc):
//   output.directory             where the results go, not what they are (a study sets it);
//   output.checkpoint_interval_s when checkpoints are written; a resumed run gives the same
//                                results whatever the interval;
//   solver.threads               how the cell loop is shared among threads; the assembly is
//                                bitwise independent of it (CellWorkspace.h).
// Every other key, the output keys vtu_every and experimental_curve included (they change the
// files a run leaves), is part of the fingerprint, and so is the form of the crystal
// orientation that was given (Euler angles, or surface normal and reference direction).
// The source file's name is not a key and never part of it.
#pragma once

#include "case/Case.h"

#include <cstdint>
#include <string>
#include <vector>

namespace indentsim::io
{
  // "path: value" lines (values as in the resolved case, strings unquoted) of the keys that
  // determine the results, sorted, each ended by a newline.
  std::string canonical_case_text(const Case &resolved_case);

  // FNV-1a 64-bit hash of `text`.
  std::uint64_t fnv1a_64(const std::string &text);

  // fnv1a_64(canonical_case_text(resolved_case)).
  std::uint64_t case_fingerprint(const Case &resolved_case);

  // A key of the fingerprint whose value differs between two cases (values as in the resolved
  // case; "(not set)" for a key written in only one of them).
  struct KeyDifference
  {
    std::string path, old_value, new_value;
  };
  // The keys of the fingerprint (those of canonical_case_text) that differ between `old_case`
  // and `new_case`, in the order of the schema: empty exactly when the fingerprints agree
  // (barring a hash collision).
  std::vector<KeyDifference> case_differences(const Case &old_case, const Case &new_case);
} // namespace indentsim::io

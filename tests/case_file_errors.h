// The case-file tests' view of an error: a YAML text parsed as the file "bad.yaml" and the message
// it is rejected with. Shared by tests/unit/test_case_file.cc, test_case_hardening.cc,
// test_mesh_design.cc, test_material_layers.cc and test_damage_profile.cc.
#pragma once

#include "case/CaseFile.h"

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

namespace indentsim::test_case_files
{
  // The start of a J2 indentation case with the paper's material (Table 1), for tests that add
  // the blocks under test (layers, damage profiles).
  inline const std::string j2_material = "test: indentation\n"
                                         "material:\n"
                                         "  model: j2\n"
                                         "  young_modulus: 69.0\n"
                                         "  poisson_ratio: 0.26\n"
                                         "  yield_stress: 0.305\n"
                                         "  hardening_modulus: 0.5\n";

  // Parses `yaml` (as file "bad.yaml") and returns the error message, or "" if none was thrown.
  inline std::string error_of(const std::string &yaml)
  {
    try
      {
        io::parse_case_yaml(yaml, "bad.yaml");
      }
    catch (const io::CaseFileError &error)
      {
        return error.what();
      }
    return "";
  }

  // Asserts that `yaml` is rejected with a message naming the file and containing every part.
  inline void expect_rejected(const std::string &yaml, std::initializer_list<std::string> parts)
  {
    const std::string message = error_of(yaml);
    SCOPED_TRACE("case file:\n" + yaml + "\nmessage: " + message);
    ASSERT_FALSE(message.empty()) << "no CaseFileError thrown";
    EXPECT_EQ(message.rfind("bad.yaml", 0), 0u) << "message does not start with the file name";
    for (const auto &part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "'";
  }
} // namespace indentsim::test_case_files

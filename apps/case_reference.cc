// Writes the case-file reference (docs/case-file-reference.md) generated from the case schema
// to standard output. A separate small program rather than a subcommand of indentsim: it is a
// maintainer's tool (the documentation is written from it, a unit test compares), and the
// user's command line stays as it is.
#include "case/CaseReference.h"

#include <iostream>

int main()
{
  std::cout << indentsim::io::case_file_reference_markdown();
  return 0;
}

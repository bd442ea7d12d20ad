// SPDX-License-Identifier: BSD-3-Clause
// The stiff and extreme cases of SplatStabilityCases.h (issue 16) on one mapper and backend:
//   TestSplatStability -mapper surface|volume -backend cpu|opengl [-group NAME]
// Every case of the group must render without a NaN or Inf value in the mapper's float image,
// count what it skipped (with a warning), refuse bad input with an error where the case says so,
// and draw something where the scene is visible. Prints one line per case.
#include "SplatStabilityRun.h"

#include <cstdio>
#include <cstring>

int main(int argc, char* argv[])
{
  const std::string mapper = splattest::Argument(argc, argv, "-mapper");
  const std::string backendName = splattest::Argument(argc, argv, "-backend");
  const std::string group = splattest::Argument(argc, argv, "-group");
  const int kind = mapper == "volume" ? splatstability::Volume : splatstability::Surface;
  const int backend = backendName == "opengl" ? vtkSplatBackend::OPENGL : vtkSplatBackend::CPU;
  int failures = 0, ran = 0;
  for (const splatstability::Case& c : splatstability::Cases())
  {
    if (c.Kind != kind || (!group.empty() && c.Group != group))
    {
      continue;
    }
    ++ran;
    const splatstability::Result r = splatstability::Run(c, backend);
    const std::vector<std::string> problems = splatstability::Check(c, r);
    std::printf("%-10s %-32s %s: nan/inf %lld, covered %lld, skipped %lld (%s)%s%s\n",
      c.Group.c_str(), c.Name.c_str(), r.Backend == vtkSplatBackend::OPENGL ? "OpenGL" : "CPU",
      static_cast<long long>(r.NonFinite), static_cast<long long>(r.Covered),
      static_cast<long long>(r.Skipped), r.Why.c_str(), r.Error ? ", error: " : "",
      r.Error ? r.Message.c_str() : "");
    // Inputs refused or empty draw nothing and leave the backend unset (AUTO).
    if (r.Backend != backend && r.Backend != vtkSplatBackend::AUTO)
    {
      std::printf("  FAILED: drawn by backend %d, not %d\n", r.Backend, backend);
      ++failures;
    }
    for (const std::string& problem : problems)
    {
      std::printf("  FAILED: %s\n", problem.c_str());
      ++failures;
    }
    std::fflush(stdout);
  }
  if (ran == 0)
  {
    std::printf("no case in group '%s' for the %s mapper\n", group.c_str(), mapper.c_str());
    return EXIT_FAILURE;
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}

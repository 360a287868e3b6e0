// bleedsim info: what this binary is and where it can run.
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "core/runtime/build_info.h"

namespace bleedsim::cli {

int info_command() {
  std::printf("bleedsim %s (git %s)\n", version(), git_sha());
  std::printf("build      %s\n", build_flags());
  std::printf("cpu        %s\n", make_cpu_backend(0)->device_name().c_str());
  std::string why_not;
  if (cuda_device_available(&why_not))
    std::printf("cuda       %s\n", make_cuda_backend()->device_name().c_str());
  else
    std::printf("cuda       unavailable: %s\n", why_not.c_str());
  return 0;
}

}  // namespace bleedsim::cli

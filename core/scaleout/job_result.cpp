#include "core/scaleout/job_result.h"

namespace bleedsim {

void write_origin(ByteWriter& out, const JobOrigin& origin) {
  out.i32(origin.rank);
  out.text(origin.host);
  out.i32(origin.cuda_device);
  out.f64(origin.seconds);
}

JobOrigin read_origin(ByteReader& in, const std::string& what) {
  JobOrigin origin;
  origin.rank = in.i32(what + "'s rank");
  origin.host = in.text(what + "'s host");
  origin.cuda_device = in.i32(what + "'s CUDA device");
  origin.seconds = in.f64(what + "'s seconds");
  return origin;
}

}  // namespace bleedsim

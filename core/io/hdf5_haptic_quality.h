#pragma once
// The force's quality, contact by contact (core/haptics/contact_quality.h), as the group
// /haptics/quality of a run's HDF5 file (docs/output-format.md, "The force's quality").
#include <string>

#include "core/haptics/contact_quality.h"

namespace bleedsim {

// Adds /haptics/quality to the finished, closed HDF5 file at `path`, which has /haptics. The meter
// has been fed every tick of the file's channel and finished.
void write_haptic_quality(const std::string& path, const ContactQualityMeter& meter);

}  // namespace bleedsim

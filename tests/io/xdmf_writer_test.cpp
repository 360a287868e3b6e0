// The XDMF description's ring runs and its refusals; what ParaView's reader makes of a run's
// description is tests/python/test_paraview.py's.
#include "core/io/xdmf_writer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/physics/particles.h"

namespace bleedsim {
namespace {

constexpr std::uint32_t kLifetime = 100;

TEST(XdmfRingRun, IsTheSlotsWhoseAgeIsBelowTheLifetimeEndingAtTheNewest) {
  // 8 slots, 11 emitted: ids 3..10, the newest in slot 2; ids 3 and 4 (slots 3, 4) have expired.
  const std::vector<std::uint32_t> ages = {2, 1, 0, kLifetime, kLifetime, 5, 4, 3};
  const RingRun run = ring_run(11, ages.data(), 8, kLifetime);
  EXPECT_EQ(run.first, 5u);
  EXPECT_EQ(run.count, 6u);
}

TEST(XdmfRingRun, HoldsTheAspiratedInItsRangeAndNoSlotNeverUsed) {
  // 3 emitted into 8 slots; the suction took id 1, which still ages in its slot.
  const std::vector<std::uint32_t> ages = {7, kAspirated | 6, 5, kNeverUsed, kNeverUsed, kNeverUsed, kNeverUsed,
                                           kNeverUsed};
  const RingRun run = ring_run(3, ages.data(), 8, kLifetime);
  EXPECT_EQ(run.first, 0u);
  EXPECT_EQ(run.count, 3u);
  // Once its lifetime has run out, an aspirated particle's id has left the range too.
  const std::vector<std::uint32_t> later = {kLifetime, kAspirated | kLifetime, 98, 0, kNeverUsed, kNeverUsed,
                                            kNeverUsed, kNeverUsed};
  EXPECT_EQ(ring_run(4, later.data(), 8, kLifetime).first, 2u);
  EXPECT_EQ(ring_run(4, later.data(), 8, kLifetime).count, 2u);
}

TEST(XdmfRingRun, AFullRingStartsAfterTheNewest) {
  const std::vector<std::uint32_t> ages = {1, 0, 3, 2};
  const RingRun run = ring_run(10, ages.data(), 4, kLifetime);
  EXPECT_EQ(run.first, 2u);
  EXPECT_EQ(run.count, 4u);
}

std::vector<FieldLayout> panel_fields() {
  return {{"frame", ElementType::u8, 4, 4, 3, "1", "RGBA"}, {"spread/stain", ElementType::f32, 1, 4, 3, "1", "stain"}};
}

TEST(XdmfWriter, AFrameWithoutEveryFieldIsRefused) {
  XdmfWriter writer("frames.h5", panel_fields(), PixelGrid{4, 3, 0.5f, 0.5f}, 0);
  const std::vector<std::uint8_t> frame(48);
  EXPECT_THROW(writer.add_frame(0.1, {frame.data()}), std::invalid_argument);
}

TEST(XdmfWriter, WithoutParticleArraysDescribesThePanelAlone) {
  XdmfWriter writer("frames.h5", panel_fields(), PixelGrid{4, 3, 0.5f, 0.5f}, kLifetime);
  const std::vector<std::uint8_t> frame(48);
  const std::vector<float> stain(12);
  writer.add_frame(0.1, {frame.data(), stain.data()});
  const std::string text = writer.text();
  EXPECT_NE(text.find(R"(<Grid Name="panel" GridType="Collection" CollectionType="Temporal">)"), std::string::npos);
  EXPECT_EQ(text.find("particles"), std::string::npos) << text;
  EXPECT_NE(text.find(R"(Dimensions="1 3 4" NumberType="Float" Precision="4" Format="HDF">frames.h5:/spread/stain<)"),
            std::string::npos)
      << text;
}

}  // namespace
}  // namespace bleedsim

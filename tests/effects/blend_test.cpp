// Compositing the blood over the tissue in linear light (core/physics/blend.h, core/physics/optics.h):
// the sRGB round trip, Beer–Lambert through every absorber as one film, the headlight's falloff
// against its closed form, and the highlight: none from a flat film, and on a spherical cap of
// blood where the mirror geometry puts it. The colours against haemoglobin's sourced coefficients,
// computed independently in NumPy, are tests/effects/optics_colours.py's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/effects/blend/blend_stage.h"
#include "core/effects/blend/optics_params.h"
#include "core/physics/optics_tables.h"
#include "core/runtime/image.h"

namespace bleedsim {
namespace {

TEST(ByteConversion, EveryByteSurvivesTheRoundTrip) {
  for (int v = 0; v < 256; ++v)
    EXPECT_EQ(byte_from_unit(unit_from_byte(std::uint8_t(v))), v) << "byte " << v;
}

TEST(ByteConversion, ClampsOutOfRangeAndNotANumber) {
  EXPECT_EQ(byte_from_unit(-0.3f), 0);
  EXPECT_EQ(byte_from_unit(1.7f), 255);
  EXPECT_EQ(byte_from_unit(NAN), 0);
  EXPECT_EQ(byte_from_unit(0.5f), 128);  // 127.5 rounds half up
}

// The blend's tables in host memory, and its work over host arrays (blend_work: what the stage runs).
struct Compositor {
  std::vector<float> tables = optics_tables();
  SrgbTables srgb = srgb_tables(tables.data());
  const float* boundaries = tables.data() + kSrgbBytes;

  BlendPixel pixel(const std::uint8_t* tissue, const float* stain, const float* film, const float* residue,
                   const OpticsParams& optics, bool lit, const Domain& domain, std::uint8_t* frame,
                   const float* fixed_light = nullptr) const {
    // Unlit, a scene draws its blood with the defaults' absorption: the tests that pass lit = false
    // pass those.
    Scene scene;
    scene.domain = domain;
    if (lit) scene.effects.set(optics);
    return blend_work(scene, tables.data(), tissue, stain, film, residue, frame, fixed_light);
  }
};

TEST(Srgb, EveryByteSurvivesDecodingAndEncoding) {
  const Compositor c;
  for (int b = 0; b < 256; ++b) EXPECT_EQ(srgb_from_linear(c.srgb, linear_from_srgb(c.srgb, std::uint8_t(b))), b) << b;
  // IEC 61966-2-1's breakpoints, and the ends.
  EXPECT_FLOAT_EQ(linear_from_srgb(c.srgb, 10), float(10 / 255.0 / 12.92));
  EXPECT_FLOAT_EQ(linear_from_srgb(c.srgb, 128), float(std::pow((128 / 255.0 + 0.055) / 1.055, 2.4)));
  EXPECT_EQ(srgb_from_linear(c.srgb, -1.0f), 0);
  EXPECT_EQ(srgb_from_linear(c.srgb, 2.0f), 255);
}

// Rounding to the nearest byte: a linear value just below a boundary stays, at it goes up.
TEST(Srgb, EncodesToTheNearestByte) {
  // No step of the bucket table holds more than one boundary, so the walk is short; and the count
  // is right at the buckets' own starts.
  const Compositor c;
  for (int k = 0; k < kSrgbBuckets; ++k) {
    const float start = float(k) / float(kSrgbBuckets);
    int count = 0;
    while (count < 255 && c.boundaries[count] <= start) ++count;
    EXPECT_EQ(c.srgb.bucket_start[k], float(count)) << k;
    EXPECT_EQ(srgb_from_linear(c.srgb, start), count) << k;
    if (k > 0) {
      EXPECT_LE(c.srgb.bucket_start[k] - c.srgb.bucket_start[k - 1], 1.0f) << k;
    }
  }
  // And the last step, up to 1: at most one boundary above its start.
  EXPECT_LE(255.0f - c.srgb.bucket_start[kSrgbBuckets - 1], 1.0f);
}

// The byte of v is the number of boundaries ≤ v, for every v: a dense sweep of [0, 1) (2²² values,
// each bucket's start and its neighbours among them) against a binary search of the boundaries.
TEST(Srgb, EncodesEveryValueAsTheBoundariesItReaches) {
  const Compositor c;
  const int steps = 1 << 22;
  for (int k = 0; k < steps; ++k) {
    for (const float v : {float(k) / float(steps), std::nextafter(float(k) / float(steps), 0.0f)}) {
      const int expected = int(std::upper_bound(c.boundaries, c.boundaries + 255, v) - c.boundaries);
      ASSERT_EQ(srgb_from_linear(c.srgb, v), expected) << v;
    }
  }
}

TEST(Srgb, EncodesBoundariesToTheByteAbove) {
  const Compositor c;
  for (int k = 0; k < 255; ++k) {
    const float boundary = c.boundaries[k];
    EXPECT_EQ(srgb_from_linear(c.srgb, boundary), k + 1) << k;
    EXPECT_EQ(srgb_from_linear(c.srgb, std::nextafter(boundary, 0.0f)), k) << k;
  }
}

TEST(BeerLambert, TheTableFollowsTheExponential) {
  const std::vector<float> t = optics_tables();
  const float* table = t.data() + 2 * kSrgbBytes - 1;
  EXPECT_EQ(transmitted(table, 0.0f), 1.0f);
  for (double x = 0.0; x < 40.0; x += 0.0137) {
    const double exact = x < 32.0 ? std::exp(-x) : std::exp(-32.0);
    // Linear interpolation at steps of 1/64 errs by at most (1/64)²/8 of the value.
    EXPECT_NEAR(transmitted(table, float(x)), exact, 3.1e-5 * exact + 1e-7) << x;
  }
}

TEST(Blend, WithNothingOverItTheTissueKeepsItsBytes) {
  const Compositor c;
  const Domain domain{1, 1, 1.0, 1.0};
  for (int v = 0; v < 256; v += 5) {
    const std::uint8_t tissue[4] = {std::uint8_t(v), std::uint8_t(255 - v), std::uint8_t(v / 2), 200};
    std::uint8_t frame[4];
    c.pixel(tissue, nullptr, nullptr, nullptr, OpticsParams{}, false, domain, frame)(0, 0);
    EXPECT_EQ(std::vector<int>(frame, frame + 4), std::vector<int>(tissue, tissue + 4)) << v;
  }
}

// Light goes down through the blood and back up: exp(−2·μ_c·h) per channel, in linear light; the
// stain and the residue are the same absorber as the film, so stain s, residue r and film h give
// what one film of h + s·stain_depth + r gives.
TEST(Blend, BeerLambertTwiceThroughEveryAbsorberAsOneFilm) {
  const Compositor c;
  const Domain domain{1, 1, 1.0, 1.0};
  const OpticsParams optics;
  const BloodOptics blood = blood_optics(optics);
  const std::uint8_t tissue[4] = {202, 113, 113, 255};
  for (const float h : {0.01f, 0.05f, 0.1f, 0.5f, 1.0f}) {
    std::uint8_t frame[4];
    c.pixel(tissue, nullptr, &h, nullptr, optics, false, domain, frame)(0, 0);
    for (int ch = 0; ch < 3; ++ch) {
      const double light = linear_from_srgb(c.srgb, tissue[ch]) * std::exp(-2.0 * blood.absorption_per_mm[ch] * h);
      // The table's interpolation errs by at most (1/64)²/8 of the value: within the byte's rounding,
      // or on the other side of one boundary.
      EXPECT_NEAR(frame[ch], srgb_from_linear(c.srgb, float(light)), 1) << "h " << h << " channel " << ch;
    }
    const float stain = h / blood.stain_depth_mm, half = h / 2;
    std::uint8_t as_stain[4], as_parts[4];
    c.pixel(tissue, &stain, nullptr, nullptr, optics, false, domain, as_stain)(0, 0);
    c.pixel(tissue, nullptr, &half, &half, optics, false, domain, as_parts)(0, 0);
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(as_stain[ch], frame[ch], 1) << "h " << h;  // s·depth rounds h by an ulp
      EXPECT_EQ(as_parts[ch], frame[ch]) << "h " << h;        // h/2 + h/2 = h exactly
    }
  }
}

// A panel of width × height pixels of `pitch` mm, every pixel the same tissue, the film given.
struct Panel {
  Domain domain;
  std::vector<std::uint8_t> tissue, frame;
  std::vector<float> film;
  Panel(int width, int height, double pitch, std::uint8_t grey)
      : domain{width, height, width * pitch, height * pitch},
        tissue(std::size_t(width) * height * 4, grey),
        frame(tissue.size()),
        film(std::size_t(width) * height, 0.0f) {}
  void draw(const Compositor& c, const OpticsParams& optics, const float* fixed_light = nullptr) {
    const BlendPixel blend =
        c.pixel(tissue.data(), nullptr, film.data(), nullptr, optics, true, domain, frame.data(), fixed_light);
    for (int j = 0; j < domain.height_px; ++j)
      for (int i = 0; i < domain.width_px; ++i) blend(i, j);
  }
  int at(int i, int j, int channel = 0) const { return frame[(std::size_t(j) * domain.width_px + i) * 4 + channel]; }
};

// The headlight at height h over the panel's centre lights a point ρ from below it by
// (h² / (h² + ρ²))^(3/2) of what it gives below it: inverse square times the cosine of incidence.
TEST(Headlight, FallsOffAsAPointSource) {
  const Compositor c;
  OpticsParams optics;
  optics.specular = optics.sheen = 0.0;
  optics.camera_height_mm = 10.0;
  Panel panel(201, 1, 0.1, 200);
  panel.draw(c, optics);
  for (int i = 0; i < 201; i += 10) {
    const double rho = (i + 0.5) * 0.1 - 10.05, h2 = 100.0;
    const double expected = linear_from_srgb(c.srgb, 200) * std::pow(h2 / (h2 + rho * rho), 1.5);
    EXPECT_NEAR(panel.at(i, 0), srgb_from_linear(c.srgb, float(expected)), 1) << "ρ " << rho;
  }
}

// A flat film adds no highlight of its own (the wet tissue plane's reflection is the sheen's), so
// the frame with the blood's highlight on equals the frame with it off.
TEST(Highlight, AFlatFilmShowsNone) {
  const Compositor c;
  OpticsParams on, off;
  on.sheen = off.sheen = 0.0;
  off.specular = 0.0;
  Panel with(64, 48, 0.1, 90), without(64, 48, 0.1, 90);
  std::fill(with.film.begin(), with.film.end(), 0.2f);
  std::fill(without.film.begin(), without.film.end(), 0.2f);
  with.draw(c, on);
  without.draw(c, off);
  EXPECT_EQ(with.frame, without.frame);
}

// A spherical cap of blood (radius R, height H, centred at (x0, y0) off the point under the lens)
// mirrors the headlight where its normal points at the lens: on the line from the sphere's centre
// O = (x0, y0, H − R) to the lens C, at S = O + R·(C − O)/|C − O|. On black tissue, without falloff,
// the frame is the highlight alone; its brightest pixels lie within a pixel of S's.
TEST(Highlight, ASphericalCapShowsOneAtItsMirrorPoint) {
  const Compositor c;
  OpticsParams optics;
  optics.falloff = false;
  optics.sheen = 0.0;
  optics.specular = 0.8;  // below white, so the peak is not clipped flat
  optics.shininess = 1024;
  optics.camera_height_mm = 20.0;
  const double pitch = 0.02, x0 = 6.0, y0 = 5.5, a = 1.0, H = 0.25, R = (a * a + H * H) / (2 * H);
  Panel panel(400, 400, pitch, 0);  // 8 × 8 mm; the lens over (4, 4)
  for (int j = 0; j < 400; ++j)
    for (int i = 0; i < 400; ++i) {
      const double rho2 = std::pow((i + 0.5) * pitch - x0, 2) + std::pow((j + 0.5) * pitch - y0, 2);
      if (rho2 < a * a) panel.film[std::size_t(j) * 400 + i] = float(std::sqrt(R * R - rho2) + H - R);
    }
  panel.draw(c, optics);
  const double cx = 4.0, cy = 4.0, cz = 20.0, oz = H - R;
  const double dx = cx - x0, dy = cy - y0, dz = cz - oz, d = std::sqrt(dx * dx + dy * dy + dz * dz);
  const double sx = x0 + R * dx / d, sy = y0 + R * dy / d;
  int brightest = 0;
  for (int j = 0; j < 400; ++j)
    for (int i = 0; i < 400; ++i) brightest = std::max(brightest, panel.at(i, j));
  ASSERT_GT(brightest, 200) << "no highlight on the cap";
  double mx = 0, my = 0;
  int count = 0;
  for (int j = 0; j < 400; ++j)
    for (int i = 0; i < 400; ++i)
      if (panel.at(i, j) == brightest) mx += (i + 0.5) * pitch, my += (j + 0.5) * pitch, ++count;
  mx /= count, my /= count;
  std::cout << "mirror point (" << sx << ", " << sy << ") mm; brightest " << brightest << " over " << count
            << " pixels centred at (" << mx << ", " << my << ") mm" << std::endl;
  EXPECT_LE(std::hypot(mx - sx, my - sy), pitch);
  // And nothing off the cap: the tissue around stays black.
  EXPECT_EQ(panel.at(10, 10), 0);
}

// The fixed light the stage makes once (FixedLightPixel) stands in for the falloff everywhere and
// for the whole lobe where nothing stands on the tissue: the frame must be the same bytes as the
// one computed pixel by pixel. The panel has all three kinds of pixel: bare tissue, a flat film
// (level, but raised), and the slopes of a cap; the light has every term on.
TEST(FixedLight, ChangesNoByteOfTheFrame) {
  const Compositor c;
  OpticsParams optics;
  optics.falloff = true;
  optics.sheen = 0.05;
  optics.specular = 0.6;
  optics.camera_x_mm = 0.7;
  optics.camera_height_mm = 15.0;
  Panel computed(160, 120, 0.05, 170), fixed(160, 120, 0.05, 170);
  int bare = 0;
  for (Panel* p : {&computed, &fixed})
    for (int j = 0; j < 120; ++j)
      for (int i = 0; i < 160; ++i) {
        const double x = (i + 0.5) * 0.05, y = (j + 0.5) * 0.05, rho2 = (x - 5.5) * (x - 5.5) + (y - 3.0) * (y - 3.0);
        float& h = p->film[std::size_t(j) * 160 + i];
        if (x < 2.0) h = 0.1f;                                            // a flat film
        else if (rho2 < 1.0) h = float(0.3 * (1.0 - rho2));               // a cap
        else bare += p == &computed;                                      // bare tissue
      }
  ASSERT_GT(bare, 1000);
  Scene scene;
  scene.domain = fixed.domain;
  scene.effects.set(optics);
  std::vector<float> light(std::size_t(160) * 120 * kFixedLightChannels);
  const FixedLightPixel make{headlight(optics, scene.domain), scene.domain.grid(), light.data()};
  for (int j = 0; j < 120; ++j)
    for (int i = 0; i < 160; ++i) make(i, j);
  computed.draw(c, optics);
  fixed.draw(c, optics, light.data());
  EXPECT_EQ(fixed.frame, computed.frame);
  // Not trivially: the frame shows the falloff and a highlight on the cap.
  EXPECT_NE(computed.at(10, 60), computed.at(80, 60));
  EXPECT_GT(*std::max_element(computed.frame.begin(), computed.frame.end()), computed.at(159, 119));
}

}  // namespace
}  // namespace bleedsim
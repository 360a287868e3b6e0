// The tissue under the blood (core/runtime/tissue.h): the procedural mucosa is deterministic and looks like
// mucosa, and PNG textures load exactly or resample by the documented bilinear rule.
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/runtime/hash.h"
#include "core/runtime/input_error.h"
#include "core/io/tissue_png.h"
#include "core/runtime/tissue.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;

// Channel c of pixel (x, y).
int channel(const Image& image, int x, int y, int c) {
  return image.rgba.at((std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 4 + std::size_t(c));
}

double mean_of_channel(const Image& image, int c) {
  double sum = 0.0;
  for (std::size_t i = std::size_t(c); i < image.rgba.size(); i += 4) sum += image.rgba[i];
  return sum / double(image.rgba.size() / 4);
}

double variance_of_channel(const Image& image, int c) {
  const double mean = mean_of_channel(image, c);
  double sum = 0.0;
  for (std::size_t i = std::size_t(c); i < image.rgba.size(); i += 4) sum += (image.rgba[i] - mean) * (image.rgba[i] - mean);
  return sum / double(image.rgba.size() / 4);
}

// ---- Procedural mucosa ------------------------------------------------------------------------

TEST(ProceduralTissue, HasTheRequestedSize) {
  const Image image = procedural_tissue(37, 11, 5);
  EXPECT_EQ(image.width, 37);
  EXPECT_EQ(image.height, 11);
  EXPECT_EQ(image.rgba.size(), std::size_t{37} * 11 * 4);
}

TEST(ProceduralTissue, GivesTheSameBytesForTheSameArguments) {
  EXPECT_EQ(procedural_tissue(96, 64, 9).rgba, procedural_tissue(96, 64, 9).rgba);
}

TEST(ProceduralTissue, GivesDifferentBytesForADifferentSeed) {
  EXPECT_NE(procedural_tissue(96, 64, 9).rgba, procedural_tissue(96, 64, 10).rgba);
}

TEST(ProceduralTissue, IsOpaqueEverywhere) {
  const Image image = procedural_tissue(96, 64, 1);
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) ASSERT_EQ(image.rgba[i], 255) << "byte " << i;
}

TEST(ProceduralTissue, IsRedderThanItIsGreenOrBlue) {
  // Pink mucosa: the blend takes the stain out of green and blue, so red must dominate.
  const Image image = procedural_tissue(128, 96, 2);
  const double red = mean_of_channel(image, 0);
  EXPECT_GT(red, mean_of_channel(image, 1));
  EXPECT_GT(red, mean_of_channel(image, 2));
}

TEST(ProceduralTissue, IsNotUniform) {
  // Mottling and vessels vary the colour; a flat fill would show no stain edge against texture.
  const Image image = procedural_tissue(128, 96, 2);
  EXPECT_GT(variance_of_channel(image, 1), 4.0);  // a standard deviation above 2 levels
}

TEST(ProceduralTissue, MatchesItsPinnedHash) {
  // Pinned from the code as it is. A change here means every golden frame drawn over procedural
  // tissue changes too: regenerate them with scripts/update-goldens, in a commit of its own.
  const Image image = procedural_tissue(64, 48, 3);
  EXPECT_EQ(hex64(fnv1a64(image.rgba.data(), image.rgba.size())), "06932717799dbcb9");
}

TEST(ProceduralTissue, RefusesSizesThatAreNotPositive) {
  EXPECT_THROW(procedural_tissue(0, 10, 1), std::invalid_argument);
  EXPECT_THROW(procedural_tissue(10, 0, 1), std::invalid_argument);
  EXPECT_THROW(procedural_tissue(-4, 10, 1), std::invalid_argument);
}

// ---- PNG textures -----------------------------------------------------------------------------

// A folder of its own for each test (tests may run in parallel), removed afterwards.
class LoadTissuePng : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("bleedsim-LoadTissuePng." + std::string(test->name()) + "-" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  std::string write_png(const std::string& name, int width, int height, int channels,
                        const std::vector<std::uint8_t>& pixels) {
    const std::string path = (dir_ / name).string();
    EXPECT_NE(stbi_write_png(path.c_str(), width, height, channels, pixels.data(), width * channels), 0) << path;
    return path;
  }

  // The file as a scenario's tissue.texture names it.
  InputFile texture(const std::string& path) const { return {path, "texture", key_, where_}; }

  const SourcePlace where_{"scenarios/x.toml", 12, 11};
  const std::string key_ = "tissue.texture";
  fs::path dir_;
};

// Four pixels whose channels differ, so a mix-up of pixels or channels shows.
//   (0,0) (1,0)
//   (0,1) (1,1)
const std::vector<std::uint8_t> k2x2 = {
    10,  200, 0,   255,  // (0,0)
    20,  100, 60,  128,  // (1,0)
    30,  0,   120, 0,    // (0,1)
    40,  50,  255, 64,   // (1,1)
};

TEST_F(LoadTissuePng, LoadsAPngOfThePanelsSizeExactly) {
  const Image image = load_tissue_png(texture(write_png("pattern.png", 2, 2, 4, k2x2)), 2, 2);
  EXPECT_EQ(image.width, 2);
  EXPECT_EQ(image.height, 2);
  EXPECT_EQ(image.rgba, k2x2);
}

TEST_F(LoadTissuePng, ResamplesBilinearlyByTheDocumentedRule) {
  const Image image = load_tissue_png(texture(write_png("pattern.png", 2, 2, 4, k2x2)), 4, 4);
  ASSERT_EQ(image.width, 4);
  ASSERT_EQ(image.height, 4);
  // Destination pixel i samples source coordinate (i + ½)·2/4 − ½: −0.25, 0.25, 0.75, 1.25.
  //
  // Corner (0, 0): (−0.25, −0.25) clamps to source pixel (0, 0), which it copies.
  for (int c = 0; c < 4; ++c) EXPECT_EQ(channel(image, 0, 0, c), k2x2[std::size_t(c)]) << "channel " << c;
  // Corner (3, 3): (1.25, 1.25) clamps to source pixel (1, 1).
  for (int c = 0; c < 4; ++c) EXPECT_EQ(channel(image, 3, 3, c), k2x2[std::size_t(12 + c)]) << "channel " << c;

  // Inner (1, 1): (0.25, 0.25), so weights ¾·¾ = 9/16 on (0,0), ¾·¼ = 3/16 on (1,0) and on (0,1),
  // ¼·¼ = 1/16 on (1,1); round half up.
  //   red   (9·10  + 3·20  + 3·30  + 1·40) / 16 = 280/16  = 17.5   → 18
  //   green (9·200 + 3·100 + 3·0   + 1·50) / 16 = 2150/16 = 134.375 → 134
  //   blue  (9·0   + 3·60  + 3·120 + 1·255)/ 16 = 795/16  = 49.6875 → 50
  //   alpha (9·255 + 3·128 + 3·0   + 1·64) / 16 = 2743/16 = 171.4375 → 171
  EXPECT_EQ(channel(image, 1, 1, 0), 18);
  EXPECT_EQ(channel(image, 1, 1, 1), 134);
  EXPECT_EQ(channel(image, 1, 1, 2), 50);
  EXPECT_EQ(channel(image, 1, 1, 3), 171);

  // Inner (2, 1): (0.75, 0.25): ¼·¾ = 3/16 on (0,0), ¾·¾ = 9/16 on (1,0), ¼·¼ = 1/16 on (0,1),
  // ¾·¼ = 3/16 on (1,1).
  //   red   (3·10 + 9·20 + 1·30 + 3·40) / 16 = 360/16 = 22.5 → 23
  EXPECT_EQ(channel(image, 2, 1, 0), 23);

  // Edge (1, 0): (0.25, −0.25), the row clamped to 0: ¾ of (0,0) and ¼ of (1,0).
  //   red   (3·10 + 1·20) / 4 = 12.5 → 13
  //   green (3·200 + 1·100) / 4 = 175
  EXPECT_EQ(channel(image, 1, 0, 0), 13);
  EXPECT_EQ(channel(image, 1, 0, 1), 175);
}

TEST_F(LoadTissuePng, RefusesAFolderSayingSo) {
  try {
    load_tissue_png(texture(dir_.string()), 2, 2);
    FAIL() << "a folder was accepted as a texture";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tissue.texture: cannot read texture '" + dir_.string() +
                                         "': it is a directory, not a regular file"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(LoadTissuePng, LoadsGrayscaleAsEqualRgbAndOpaqueAlpha) {
  const std::vector<std::uint8_t> gray = {0, 77, 200, 255, 13, 128};
  const Image image = load_tissue_png(texture(write_png("gray.png", 3, 2, 1, gray)), 3, 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) {
      const int expected = gray[std::size_t(y * 3 + x)];
      EXPECT_EQ(channel(image, x, y, 0), expected) << x << ", " << y;
      EXPECT_EQ(channel(image, x, y, 1), expected) << x << ", " << y;
      EXPECT_EQ(channel(image, x, y, 2), expected) << x << ", " << y;
      EXPECT_EQ(channel(image, x, y, 3), 255) << x << ", " << y;
    }
  }
}

TEST_F(LoadTissuePng, RefusesAMissingFileNamingTheKeyAndPath) {
  const std::string path = (dir_ / "nowhere.png").string();
  try {
    load_tissue_png(texture(path), 4, 4);
    FAIL() << "loaded a file that does not exist";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "scenarios/x.toml:12:11: tissue.texture: cannot read texture '" + path +
                                         "': " + std::strerror(ENOENT));
    EXPECT_EQ(e.key(), key_);
    EXPECT_EQ(e.where().line, 12);
  }
}

TEST_F(LoadTissuePng, RefusesAFileThatIsNotAPng) {
  const std::string path = (dir_ / "junk.png").string();
  std::ofstream(path, std::ios::binary) << "GIF89a, or anything else that is not a PNG";
  try {
    load_tissue_png(texture(path), 4, 4);
    FAIL() << "decoded junk";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("scenarios/x.toml:12:11: tissue.texture: cannot decode texture '" + path + "' as a PNG", 0),
              0u)
        << what;
  }
}

TEST_F(LoadTissuePng, RefusesSizesThatAreNotPositive) {
  const std::string path = write_png("pattern.png", 2, 2, 4, k2x2);
  EXPECT_THROW(load_tissue_png(texture(path), 0, 4), std::invalid_argument);
  EXPECT_THROW(load_tissue_png(texture(path), 4, -1), std::invalid_argument);
}


// ---- Limits (issue 13, item 5): a texture's size is known from its header, before decoding ------

// A PNG signature and an IHDR chunk stating width x height (8-bit RGBA), and nothing after: enough
// for the header, not for stb to decode.
std::string png_header(std::uint32_t width, std::uint32_t height) {
  std::string bytes = std::string("\x89PNG\r\n\x1a\n", 8) + std::string("\0\0\0\x0dIHDR", 8);
  for (const std::uint32_t v : {width, height})
    for (int shift = 24; shift >= 0; shift -= 8) bytes += char((v >> shift) & 0xff);
  return bytes + std::string("\x08\x06\0\0\0", 5);
}

TEST_F(LoadTissuePng, RefusesATexturePastTheCapFromItsHeaderAlone) {
  const std::string path = (dir_ / "huge.png").string();
  std::ofstream(path, std::ios::binary) << png_header(20000, 300);
  try {
    load_tissue_png(texture(path), 64, 48);
    FAIL() << "a 20000 px wide texture was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "scenarios/x.toml:12:11: tissue.texture: texture '" + path +
                                         "' is 20000 x 300 px; a texture may be at most 16384 px on a side (it is "
                                         "resampled to the panel anyway)");
  }
  EXPECT_THROW(read_tissue_png_header(texture(path)), InputError) << "bleedsim validate reads only the header";
}

TEST_F(LoadTissuePng, ReadsTheHeaderAloneAndCountsWhatDecodingTakes) {
  const std::string path = (dir_ / "header-only.png").string();
  std::ofstream(path, std::ios::binary) << png_header(1000, 500);
  const TextureHeader header = read_tissue_png_header(texture(path));
  EXPECT_EQ(header.width, 1000);
  EXPECT_EQ(header.height, 500);
  EXPECT_EQ(header.file_bytes, 29u);
  EXPECT_EQ(header.bit_depth, 8);
  EXPECT_EQ(header.colour_type, 6);
  EXPECT_FALSE(header.interlaced);
  // The file, beside the inflated rows (500 · (1 + 4 · 1000)) and the unfiltered RGBA (4 bytes a
  // pixel): stb's most, more than the RGBA beside the 64 x 48 panel resampled from it.
  const MemoryPart part = texture_memory(header, texture(path), 64, 48);
  EXPECT_EQ(part.bytes, Count(29 + 500 * 4001 + 4 * 1000 * 500));
  EXPECT_EQ(part.key, key_);
  EXPECT_NE(part.what.find("1000 x 500 px texture '" + path + "'"), std::string::npos) << part.what;
}

// A PNG chunk: its length, type, data and CRC (stb does not check the CRC; zlib's is correct here).
std::string chunk(const std::string& type, const std::string& data) {
  std::string out;
  const auto word = [&out](std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out += char((v >> shift) & 0xff);
  };
  word(std::uint32_t(data.size()));
  out += type + data;
  word(std::uint32_t(crc32(crc32(0, reinterpret_cast<const Bytef*>(type.data()), 4),
                           reinterpret_cast<const Bytef*>(data.data()), uInt(data.size()))));
  return out;
}

// stb trusted a PNG past its header: it allocated an IDAT chunk's stated length before reading it (a
// 426-byte file made it ask for 2 GiB, a 43-byte file cut inside a chunk's header 1 GiB;
// fuzz/tissue_png_fuzzer), and inflates image data for as
// long as the stream goes on. Both are refused before stb sees the file.
TEST_F(LoadTissuePng, RefusesChunksAndImageDataPastWhatTheHeaderStates) {
  const std::string ihdr = png_header(1, 1).substr(8, 21);  // length, type and data of a 1 x 1 RGBA IHDR
  const std::string start = std::string("\x89PNG\r\n\x1a\n", 8) + ihdr + std::string(4, '\0');
  std::string claims = start + std::string("\x7f\xff\xff\xffIDAT", 8) + "short";
  try {
    decode_tissue_png(claims, texture("claims.png"), 2, 2);
    FAIL() << "a 2 GiB chunk in a small file was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a chunk claims 2147483647 bytes, more than the file holds"),
              std::string::npos) << e.what();
  }
  // A chunk's header that the file cuts short, its length claiming 1 GiB.
  const std::string cut = start + std::string("\x40\x00\x00\x1aIDATxN", 10);
  try {
    decode_tissue_png(cut, texture("cut.png"), 2, 2);
    FAIL() << "a file ending inside a chunk's header was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("it ends inside a chunk: 10 bytes are left"), std::string::npos) << e.what();
  }
  // 10 MB of zeros compress to ~10 KB; a 1 x 1 image holds 5 bytes of rows.
  const std::string zeros(10 << 20, '\0');
  std::string packed(compressBound(uLong(zeros.size())), '\0');
  uLongf packed_size = uLongf(packed.size());
  ASSERT_EQ(compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size,
                      reinterpret_cast<const Bytef*>(zeros.data()), uLong(zeros.size()), 9), Z_OK);
  packed.resize(packed_size);
  const std::string bomb = start + chunk("IDAT", packed) + chunk("IEND", "");
  try {
    decode_tissue_png(bomb, texture("bomb.png"), 2, 2);
    FAIL() << "a deflate bomb was inflated";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("its image data inflates to more than the 1 x 1 px its header states"),
              std::string::npos) << e.what();
  }
}

TEST_F(LoadTissuePng, RefusesToDecodeWhatDoesNotFitTheRoom) {
  const std::string path = write_png("pattern.png", 2, 2, 4, k2x2);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes(std::istreambuf_iterator<char>(in), {});
  EXPECT_EQ(decode_tissue_png(bytes, texture(path), 2, 2).rgba, k2x2);
  try {
    decode_tissue_png(bytes, texture(path), 2, 2, 100);
    FAIL() << "decoded in 100 bytes";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), key_);
    EXPECT_NE(std::string(e.what()).find("needs"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("but only 100 B is available"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bleedsim

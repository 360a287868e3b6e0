#include "fuzz/obj_mutator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string_view>
#include <utility>
#include <vector>

namespace bleedsim::fuzz {
namespace {

using Rng = std::minstd_rand;
using Lines = std::vector<std::string>;

std::size_t below(Rng& rng, std::size_t n) { return n == 0 ? 0 : rng() % n; }

template <std::size_t N>
std::string pick(Rng& rng, const char* const (&options)[N]) {
  return options[below(rng, N)];
}

Lines lines_of(const std::string& text) {
  Lines lines;
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    lines.push_back(text.substr(start, end - start));
  if (start < text.size()) lines.push_back(text.substr(start));
  return lines;
}

std::string text_of(const Lines& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + '\n';
  return text;
}

// A statement's keyword and fields, split at blanks, and back.
Lines fields_of(const std::string& line) {
  Lines fields;
  for (std::size_t at = 0; at < line.size();) {
    const std::size_t end = std::min(line.find_first_of(" \t", at), line.size());
    if (end > at) fields.push_back(line.substr(at, end - at));
    at = end + 1;
  }
  return fields;
}

std::string line_of(const Lines& fields) {
  std::string line;
  for (const std::string& field : fields) line += (line.empty() ? "" : " ") + field;
  return line;
}

bool is(const std::string& line, std::string_view keyword) {
  return line.compare(0, keyword.size(), keyword) == 0 &&
         (line.size() == keyword.size() || line[keyword.size()] == ' ' || line[keyword.size()] == '\t');
}

std::size_t count(const Lines& lines, const char* keyword) {
  return std::size_t(std::count_if(lines.begin(), lines.end(), [&](const std::string& l) { return is(l, keyword); }));
}

// A line that `keep` takes, chosen at random; lines.size() where there is none.
template <class Keep>
std::size_t some_line(Rng& rng, const Lines& lines, Keep keep) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (keep(lines[i])) kept.push_back(i);
  return kept.empty() ? lines.size() : kept[below(rng, kept.size())];
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

std::string corner(std::size_t v, std::size_t vt) { return std::to_string(v) + "/" + std::to_string(vt); }

// Numbers at the edges of what the reader takes (core/io/mesh_obj.cpp: number_problem,
// index_problem): about ±1e6 and a double's range, past the smallest double, signed zero, NaN and
// infinities as text, what strtod or atoi take and from_chars does not (hex, a leading plus or dot,
// a trailing letter), indices past 32 and 64 bits, and numbers of hundreds of digits.
std::string edge_number(Rng& rng) {
  static const char* const kEdges[] = {
      "1e6",  "1000000.0000001", "-1e6", "1e308", "1e309", "-1e308", "4.9e-324", "1e-400", "-0", "0", "nan",
      "-nan", "inf", "-inf", "infinity", "0x10", "+1", ".5", "5.", "1e", "1.5e3x", "1,5", "-", "4294967299",
      "2147483648", "18446744073709551617", "-4294967297", "-1", "1", "2", "3"};
  switch (below(rng, 4)) {
    case 0: return std::string(1 + below(rng, 400), '9');
    case 1: return "0." + std::string(below(rng, 400), '0') + "1";
    default: return pick(rng, kEdges);
  }
}

// A face's corner at the edge of what the reader takes: indices just past the file's (`vertices`
// of them) either way, 0, and forms that are not v, v/vt, v//vn or v/vt/vn.
std::string edge_corner(Rng& rng, std::size_t vertices) {
  static const char* const kForms[] = {"0", "-1", "1//1", "1/", "/1", "1//", "//1", "1/1/1/1", "1/0", "0/1", "/"};
  const std::string n = std::to_string(vertices), past = std::to_string(vertices + 1);
  switch (below(rng, 4)) {
    case 0: return pick(rng, kForms);
    case 1: return past + "/1";
    case 2: return "-" + (below(rng, 2) ? n : past) + "/-1";
    default: return edge_number(rng) + "/1";
  }
}

// A statement as a mesh file may hold it: geometry mostly, now and then one the reader ignores.
std::string statement(Rng& rng, const Lines& lines) {
  static const char* const kOthers[] = {"", "# a comment", "g part", "o object", "s 1", "usemtl red", "mtllib m.mtl",
                                        "l 1 2", "p 1", "vw 1 1 2147483648", "vp 0.5 0.5", "\r"};
  const auto coordinate = [&] { return number((double(below(rng, 2001)) - 1000.0) / 64.0); };
  switch (below(rng, 5)) {
    case 0: return "v " + coordinate() + " " + coordinate() + " " + coordinate();
    case 1: return "vt " + number(double(below(rng, 65)) / 64.0) + " " + number(double(below(rng, 65)) / 64.0);
    case 2: {
      const std::size_t v = std::max<std::size_t>(count(lines, "v"), 1);
      const std::size_t vt = std::max<std::size_t>(count(lines, "vt"), 1);
      std::string face = "f";
      for (std::size_t k = 0, corners = 3 + below(rng, 3); k < corners; ++k)
        face += " " + corner(1 + below(rng, v), 1 + below(rng, vt));
      return face;
    }
    case 3: return "vn 0 0 1";
    default: return pick(rng, kOthers);
  }
}

// A polygon of its own vertices and uvs, and its face: convex, a star (non-convex), its corners out
// of order (crossing itself), on a line or with a corner twice (no area); flat, tilted or not plane.
// Its face names them back from its line (-1 the last) or from the file's start.
void add_polygon(Rng& rng, Lines& lines) {
  const std::size_t n = 3 + below(rng, 10), shape = below(rng, 5), lift = below(rng, 3);
  std::vector<std::pair<double, double>> points;
  for (std::size_t k = 0; k < n; ++k) {
    const double angle = 6.283185307179586 * double(k) / double(n), r = shape == 1 && k % 2 ? 0.4 : 1.0;
    points.emplace_back(shape == 3 ? double(k) : r * std::cos(angle), shape == 3 ? 0.0 : r * std::sin(angle));
  }
  if (shape == 4) points[1 + below(rng, n - 1)] = points[0];
  std::vector<std::size_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = k;
  if (shape == 2) std::shuffle(order.begin(), order.end(), rng);

  const bool relative = below(rng, 2);
  const std::size_t v0 = count(lines, "v"), vt0 = count(lines, "vt");
  Lines block;
  for (const auto& [x, y] : points) {
    const double z = lift == 0 ? 0.0 : lift == 1 ? 0.5 * x : double(below(rng, 9)) / 8.0;
    block.push_back("v " + number(x) + " " + number(y) + " " + number(z));
  }
  double extent = 1;  // the uvs are the points, scaled into the texture
  for (const auto& [x, y] : points) extent = std::max({extent, std::fabs(x), std::fabs(y)});
  for (const auto& [x, y] : points)
    block.push_back("vt " + number(0.5 + 0.5 * x / extent) + " " + number(0.5 + 0.5 * y / extent));
  std::string face = "f";
  for (const std::size_t k : order) {
    const std::string back = std::to_string(n - k);
    face += " " + (relative ? "-" + back + "/-" + back : corner(v0 + k + 1, vt0 + k + 1));
  }
  block.push_back(face);
  // Named from the start, the block must come after every other vertex; named back, anywhere.
  const std::size_t at = relative ? below(rng, lines.size() + 1) : lines.size();
  lines.insert(lines.begin() + std::ptrdiff_t(at), block.begin(), block.end());
}

// A face's corners: one more (one of its own again, or another), one fewer, reordered, or about
// the most a face may have (255: tinyobjloader counts them in a byte).
bool change_corners(Rng& rng, Lines& lines) {
  const std::size_t f = some_line(rng, lines, [](const std::string& l) { return is(l, "f"); });
  if (f == lines.size()) return false;
  Lines fields = fields_of(lines[f]);
  const std::size_t corners = fields.size() - 1;
  switch (below(rng, 5)) {
    case 0: {
      std::string added = corner(1 + below(rng, count(lines, "v") + 1), 1 + below(rng, count(lines, "vt") + 1));
      if (corners && below(rng, 2)) added = fields[1 + below(rng, corners)];
      fields.insert(fields.begin() + std::ptrdiff_t(1 + below(rng, corners + 1)), added);
      break;
    }
    case 1:
      if (corners) fields.erase(fields.begin() + std::ptrdiff_t(1 + below(rng, corners)));
      break;
    case 2: std::reverse(fields.begin() + 1, fields.end()); break;
    case 3: std::shuffle(fields.begin() + 1, fields.end(), rng); break;
    default:
      if (corners) fields.resize(254 + below(rng, 4), fields[1]);
  }
  lines[f] = line_of(fields);
  return true;
}

// One of a statement's numbers, or a face's corners, at an edge.
bool replace_with_edge(Rng& rng, Lines& lines) {
  const std::size_t l = some_line(rng, lines, [](const std::string& line) { return fields_of(line).size() > 1; });
  if (l == lines.size()) return false;
  Lines fields = fields_of(lines[l]);
  std::string& field = fields[1 + below(rng, fields.size() - 1)];
  field = fields[0] == "f" && below(rng, 2) ? edge_corner(rng, count(lines, "v")) : edge_number(rng);
  lines[l] = line_of(fields);
  return true;
}

}  // namespace

std::string mutate_obj(const std::string& text, Rng& rng) {
  Lines lines = lines_of(text);
  const std::size_t some = below(rng, lines.size()), other = below(rng, lines.size());
  // Lines go about as often as they come, so that inputs do not only grow.
  switch (lines.empty() ? 7 : below(rng, 9)) {
    case 0:
    case 1: lines.erase(lines.begin() + std::ptrdiff_t(some)); break;
    case 2: {
      const std::string copy = lines[some];
      lines.insert(lines.begin() + std::ptrdiff_t(other), copy);
      break;
    }
    case 3: std::swap(lines[some], lines[other]); break;
    case 4:
    case 5:
      if (!replace_with_edge(rng, lines)) add_polygon(rng, lines);
      break;
    case 6:
      if (!change_corners(rng, lines)) add_polygon(rng, lines);
      break;
    case 7: add_polygon(rng, lines); break;
    default: lines.insert(lines.begin() + std::ptrdiff_t(below(rng, lines.size() + 1)), statement(rng, lines));
  }
  return text_of(lines);
}

}  // namespace bleedsim::fuzz

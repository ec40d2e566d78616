#include "io/complex.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/detail/text_lines.hpp"

namespace delcert::io {

using detail::Line;
using detail::parse_count;

namespace {

std::vector<int> parse_simplex(const std::vector<std::string_view>& tokens, std::size_t first, std::size_t num_vertices,
                               const std::string& file, long line) {
  std::vector<int> s;
  if (tokens.size() > first + kMaxSimplexVertices)
    throw InputError(file, line,
                     "a simplex with " + std::to_string(tokens.size() - first) + " vertices; at most " +
                         std::to_string(kMaxSimplexVertices) +
                         " are allowed (ambient dimension <= " + std::to_string(kMaxAmbientDimension) + "), and a simplex of an m-manifold has m + 1");
  for (std::size_t k = first; k < tokens.size(); ++k) {
    long v = parse_count(tokens[k], file, line, "a vertex index");
    if (static_cast<std::size_t>(v) >= num_vertices)
      throw InputError(file, line,
                       "vertex index " + std::to_string(v) + " out of range: there are " +
                           std::to_string(num_vertices) + " vertices (indices are 0-based)");
    s.push_back(static_cast<int>(v));
  }
  auto sorted = s;
  std::sort(sorted.begin(), sorted.end());
  if (auto it = std::adjacent_find(sorted.begin(), sorted.end()); it != sorted.end())
    throw InputError(file, line, "vertex " + std::to_string(*it) + " repeated in a simplex; a simplex has distinct vertices");
  return s;
}

void check_unique(const std::vector<std::vector<int>>& simplices, const std::vector<long>& line_of, const std::string& file) {
  std::map<std::vector<int>, long> seen;
  for (std::size_t i = 0; i < simplices.size(); ++i) {
    auto key = simplices[i];
    std::sort(key.begin(), key.end());
    auto [it, inserted] = seen.emplace(key, line_of[i]);
    if (!inserted)
      throw InputError(file, line_of[i], "simplex listed twice (first on line " + std::to_string(it->second) + ")");
  }
}

}  // namespace

ComplexFile parse_complex(const std::string& text, const std::string& file) {
  auto lines = detail::split_lines(text);
  if (lines.empty()) throw InputError(file, 0, "empty file; expected a 'delcert-complex v1' or 'OFF' header");
  const Line& head = lines[0];
  std::string tag(head.tokens[0]);
  ComplexFile out;
  std::vector<long> line_of;
  if (tag == "delcert-complex") {
    if (head.tokens.size() != 2 || head.tokens[1] != "v1")
      throw InputError(file, head.number, "unsupported complex format version; this reader knows 'delcert-complex v1'");
    if (lines.size() < 2 || lines[1].tokens.size() != 2)
      throw InputError(file, lines.size() < 2 ? head.number : lines[1].number,
                       "expected a line 'NUM_VERTICES NUM_SIMPLICES'");
    out.counts_line = lines[1].number;
    long nv = parse_count(lines[1].tokens[0], file, lines[1].number, "the vertex count");
    long ns = parse_count(lines[1].tokens[1], file, lines[1].number, "the simplex count");
    // Vertex indices are ints everywhere downstream: a larger count would let an index wrap.
    if (nv > std::numeric_limits<int>::max())
      throw InputError(file, lines[1].number,
                       "the vertex count " + std::to_string(nv) + " exceeds " +
                           std::to_string(std::numeric_limits<int>::max()) + ", the largest supported");
    out.complex.num_vertices = static_cast<std::size_t>(nv);
    if (static_cast<long>(lines.size()) - 2 != ns)
      throw InputError(file, lines.back().number,
                       "the header announces " + std::to_string(ns) + " simplices but the file has " +
                           std::to_string(lines.size() - 2));
    for (std::size_t i = 2; i < lines.size(); ++i) {
      out.complex.simplices.push_back(parse_simplex(lines[i].tokens, 0, out.complex.num_vertices, file, lines[i].number));
      line_of.push_back(lines[i].number);
    }
  } else if (tag == "OFF") {
    PointsFile pf = parse_points_file(text, file, PointReadOptions{3, true});
    std::size_t nv = pf.points.size();
    // The counts line is the first line after "OFF" (or on the same line).
    std::size_t counts_idx = head.tokens.size() > 1 ? 0 : 1;
    const auto& ct = lines[counts_idx].tokens;
    std::size_t off = counts_idx == 0 ? 1 : 0;
    out.counts_line = lines[counts_idx].number;
    long nf = parse_count(ct[off + 1], file, lines[counts_idx].number, "the face count");
    std::size_t first_face = counts_idx + 1 + nv;
    if (static_cast<long>(lines.size() - first_face) != nf)
      throw InputError(file, lines.back().number,
                       "the header announces " + std::to_string(nf) + " faces but the file has " +
                           std::to_string(lines.size() - first_face));
    out.complex.num_vertices = nv;
    for (std::size_t i = first_face; i < lines.size(); ++i) {
      const auto& t = lines[i].tokens;
      long k = parse_count(t[0], file, lines[i].number, "the face size");
      if (k != 3) throw InputError(file, lines[i].number, "face has " + std::to_string(k) + " vertices; only triangles are simplicial");
      if (t.size() < 4) throw InputError(file, lines[i].number, "triangle lists fewer than 3 vertices");
      // OFF allows colour values after the indices; ignore them.
      std::vector<std::string_view> idx(t.begin() + 1, t.begin() + 4);
      out.complex.simplices.push_back(parse_simplex(idx, 0, nv, file, lines[i].number));
      line_of.push_back(lines[i].number);
    }
    out.embedded_points = std::move(pf.points);
    out.embedded_point_lines = std::move(pf.lines);
  } else {
    throw InputError(file, head.number, "unknown complex format '" + tag + "'; expected 'delcert-complex v1' or 'OFF'");
  }
  check_unique(out.complex.simplices, line_of, file);
  return out;
}

ComplexFile read_complex(const std::string& path) { return parse_complex(read_file(path), path); }

std::string format_complex(const Complex& c) {
  std::string out = "delcert-complex v1\n" + std::to_string(c.num_vertices) + " " + std::to_string(c.simplices.size()) + "\n";
  for (const auto& s : c.simplices) {
    for (std::size_t k = 0; k < s.size(); ++k) {
      if (k) out += ' ';
      out += std::to_string(s[k]);
    }
    out += '\n';
  }
  return out;
}

void write_complex(const std::string& path, const Complex& c) { write_file_atomically(path, format_complex(c)); }

std::string format_off(const PointSet& points, const Complex& c) {
  if (points.dimension != 3 || c.num_vertices != points.size())
    throw std::invalid_argument("OFF needs points in R^3 and a complex on exactly those vertices");
  std::string out = "OFF\n" + std::to_string(points.size()) + " " + std::to_string(c.simplices.size()) + " 0\n" +
                    format_coordinate_lines(points);
  for (const auto& s : c.simplices) {
    if (s.size() != 3) throw std::invalid_argument("OFF faces must be triangles");
    out += "3 " + std::to_string(s[0]) + " " + std::to_string(s[1]) + " " + std::to_string(s[2]) + "\n";
  }
  return out;
}

void write_off(const std::string& path, const PointSet& points, const Complex& c) {
  write_file_atomically(path, format_off(points, c));
}

}  // namespace delcert::io

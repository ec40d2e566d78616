#include "io/complex.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <set>
#include <span>
#include <string>
#include <limits>
#include <map>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/detail/text_lines.hpp"
#include "io/mesh.hpp"

namespace delcert::io {

using detail::Line;
using detail::parse_count;

namespace {

std::vector<int> parse_simplex(std::span<const std::string_view> tokens, std::size_t first, std::size_t num_vertices,
                               const std::string& file, long line) {
  std::vector<int> s;
  if (tokens.size() > first + kMaxSimplexVertices)
    throw InputError(file, line,
                     "a simplex with " + std::to_string(tokens.size() - first) + " vertices; at most " +
                         std::to_string(kMaxSimplexVertices) +
                         " are allowed (ambient dimension <= " + std::to_string(kMaxAmbientDimension) + "), and a simplex of an m-manifold has m + 1");
  s.reserve(tokens.size() - first);
  for (std::size_t k = first; k < tokens.size(); ++k) {
    long v = parse_count(tokens[k], file, line, "a vertex index");
    if (static_cast<std::size_t>(v) >= num_vertices)
      throw InputError(file, line,
                       "vertex index " + std::to_string(v) + " out of range: there are " +
                           std::to_string(num_vertices) + " vertices (indices are 0-based)");
    s.push_back(static_cast<int>(v));
  }
  std::array<int, kMaxSimplexVertices> sorted{};  // no allocation per simplex
  std::copy(s.begin(), s.end(), sorted.begin());
  std::sort(sorted.begin(), sorted.begin() + s.size());
  if (auto it = std::adjacent_find(sorted.begin(), sorted.begin() + s.size()); it != sorted.begin() + s.size())
    throw InputError(file, line, "vertex " + std::to_string(*it) + " repeated in a simplex; a simplex has distinct vertices");
  return s;
}

void check_unique(const std::vector<std::vector<int>>& simplices, const std::vector<long>& line_of, const std::string& file) {
  // Sorted vertex lists ordered by (vertices, position): a repeat follows its first occurrence.
  // The one reported is the earliest simplex in the file that repeats an earlier one.
  std::vector<std::vector<int>> keys(simplices);
  for (auto& k : keys) std::sort(k.begin(), k.end());
  std::vector<std::size_t> order(keys.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] != keys[b] ? keys[a] < keys[b] : a < b; });
  std::size_t repeat = keys.size(), first = 0;
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (keys[order[k]] != keys[order[k - 1]] || (k >= 2 && keys[order[k - 2]] == keys[order[k]])) continue;
    if (order[k] < repeat) repeat = order[k], first = order[k - 1];  // the second occurrence of its group
  }
  if (repeat == keys.size()) return;
  throw InputError(file, line_of[repeat],
                   line_of[repeat] > 0 ? "simplex listed twice (first on line " + std::to_string(line_of[first]) + ")"
                                       : "simplex " + std::to_string(repeat) + " listed twice (the same vertices as an earlier one)");
}

bool all_digits(std::string_view t) {
  return !t.empty() && std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// face[i]: simplices[i] (sorted) is a proper face of another listed simplex.
std::vector<bool> faces_of_others(const std::vector<std::vector<int>>& sorted) {
  std::map<int, std::vector<std::size_t>> containing;
  for (std::size_t i = 0; i < sorted.size(); ++i)
    for (int v : sorted[i]) containing[v].push_back(i);
  std::vector<bool> face(sorted.size(), false);
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    if (sorted[i].empty()) continue;
    int rarest = sorted[i][0];
    for (int v : sorted[i])
      if (containing[v].size() < containing[rarest].size()) rarest = v;
    for (std::size_t j : containing[rarest])
      if (sorted[j].size() > sorted[i].size() &&
          std::includes(sorted[j].begin(), sorted[j].end(), sorted[i].begin(), sorted[i].end())) {
        face[i] = true;
        break;
      }
  }
  return face;
}

// A filtration value as GUDHI writes one: a finite decimal or "inf" (infinite filtration).
bool is_filtration_value(std::string_view t) {
  if (t == "inf" || t == "+inf") return true;
  double x = 0;
  const char* end = t.data() + t.size();
  auto [ptr, ec] = std::from_chars(t.data() + (!t.empty() && t[0] == '+' ? 1 : 0), end, x);
  return ec == std::errc() && ptr == end && std::isfinite(x);
}

// A Python float's spelling (print(*simplex, filtration)): a number that is not an integer's digits.
bool is_decimal_filtration_value(std::string_view t) { return is_filtration_value(t) && !all_digits(t); }

// The three layouts of a GUDHI simplex list, one simplex per line (docs/formats.md):
//   plain        "0 1 2"            vertex indices only
//   filtered     "0 1 2 0.35"       vertex indices, then the filtration value (Python:
//                                   for s, f in st.get_filtration(): print(*s, f))
//   simplex_tree "2 2 1 0 0.35"     the dimension k, the k + 1 vertices in decreasing order, the
//                                   filtration value (C++: std::cout << simplex_tree, GUDHI's operator<<)
enum class GudhiLayout { plain, filtered, simplex_tree };

// The vertex tokens of a line in a layout.
std::span<const std::string_view> vertex_tokens(const Line& l, GudhiLayout layout) {
  std::span<const std::string_view> t = l.tokens;
  switch (layout) {
    case GudhiLayout::plain: return t;
    case GudhiLayout::filtered: return t.first(t.size() - 1);
    case GudhiLayout::simplex_tree: return t.subspan(1, t.size() - 2);
  }
  return t;
}

// Every line "k v_k ... v_0 f" with k + 1 distinct vertices in decreasing order, at least one of
// dimension >= 1, and every facet of a listed simplex listed (a simplex tree holds all faces).
bool reads_as_simplex_tree(const detail::Lines& lines) {
  std::set<std::vector<long>> listed;
  std::vector<std::vector<long>> simplices;
  bool above_vertices = false;
  for (const Line& l : lines) {
    const auto& t = l.tokens;
    if (t.size() < 3 || t.size() > kMaxSimplexVertices + 2 || !all_digits(t[0]) || !is_filtration_value(t[t.size() - 1]))
      return false;
    if (t[0].size() > 2 || std::stol(std::string(t[0])) + 3 != static_cast<long>(t.size())) return false;
    std::vector<long> s;
    for (std::size_t k = 1; k + 1 < t.size(); ++k) {
      if (!all_digits(t[k]) || t[k].size() > 9) return false;
      s.push_back(std::stol(std::string(t[k])));
      if (s.size() > 1 && s[s.size() - 2] <= s.back()) return false;
    }
    above_vertices = above_vertices || s.size() > 1;
    std::reverse(s.begin(), s.end());
    if (!listed.insert(s).second) return false;
    simplices.push_back(std::move(s));
  }
  if (!above_vertices) return false;
  for (const auto& s : simplices) {
    if (s.size() < 2) continue;
    for (std::size_t drop = 0; drop < s.size(); ++drop) {
      std::vector<long> facet;
      for (std::size_t k = 0; k < s.size(); ++k)
        if (k != drop) facet.push_back(s[k]);
      if (!listed.count(facet)) return false;
    }
  }
  return true;
}

// Which layout a headerless list of lines has; throws (with the line) when it is none of them.
GudhiLayout gudhi_layout(const detail::Lines& lines, const std::string& file) {
  if (reads_as_simplex_tree(lines)) return GudhiLayout::simplex_tree;
  // The first line that ends in a decimal filtration value, if any: then every line must.
  long filtered_line = 0;
  std::string filtered_value;
  for (const Line& l : lines)
    if (is_decimal_filtration_value(l.tokens[l.tokens.size() - 1])) {
      filtered_line = l.number;
      filtered_value = l.tokens[l.tokens.size() - 1];
      break;
    }
  const bool filtered = filtered_line > 0;
  const GudhiLayout layout = filtered ? GudhiLayout::filtered : GudhiLayout::plain;
  for (const Line& l : lines) {
    const auto& t = l.tokens;
    if (filtered && !is_decimal_filtration_value(t[t.size() - 1]))
      throw InputError(file, l.number,
                       "this line does not end in a filtration value, but line " + std::to_string(filtered_line) +
                           " does ('" + filtered_value +
                           "'): a GUDHI simplex list gives a filtration value on every line (a decimal, e.g. 0.0) or on none");
    if (filtered && t.size() < 2)
      throw InputError(file, l.number, "a filtration value without a simplex; expected vertex indices, then the value");
    for (auto v : vertex_tokens(l, layout))
      if (!all_digits(v))
        throw InputError(file, l.number,
                         "expected a vertex index (a non-negative integer), found '" + std::string(v) +
                             "'; a GUDHI simplex list has vertex indices, then " +
                             (filtered ? "the filtration value" : "optionally a filtration value (a decimal, on every line)"));
  }
  return layout;
}

// Which format, when none was given: a tag on the first line, then the mesh formats (first line
// "ply", first word "solid", extension .obj/.ply/.stl), then headerless lines of integers (gudhi
// when every line has the same length or every shorter line is a face of a longer one).
ComplexFormat detect_format(const std::string& text, const std::string& file, const detail::Lines& lines) {
  if (!lines.empty()) {
    const std::string_view tag = lines[0].tokens[0];
    if (tag == "delcert-complex") return ComplexFormat::delcert;
    if (tag == "OFF") return ComplexFormat::off;
  }
  if (auto mf = detect_mesh_format(text, file))
    return *mf == MeshFormat::obj ? ComplexFormat::obj : *mf == MeshFormat::ply ? ComplexFormat::ply : ComplexFormat::stl;
  if (lines.empty())
    throw InputError(file, 0, "empty file; expected a 'delcert-complex v1' or 'OFF' header, an OBJ/PLY/STL mesh or a "
                              "GUDHI simplex list");
  // Lines of integers, each maybe followed by a filtration value: a GUDHI simplex list.
  bool numbers = true;
  for (const Line& l : lines)
    for (std::size_t k = 0; k < l.tokens.size(); ++k)
      numbers = numbers && (all_digits(l.tokens[k]) || (k + 1 == l.tokens.size() && is_filtration_value(l.tokens[k])));
  // A first line that starts with a vertex index: a GUDHI simplex list with a bad line, named here.
  if (!numbers && all_digits(lines[0].tokens[0])) gudhi_layout(lines, file);
  if (!numbers)
    throw InputError(file, lines[0].number,
                     "unknown complex format '" + std::string(lines[0].tokens[0]) +
                         "'; expected 'delcert-complex v1' or 'OFF' on the first line, an OBJ, PLY or STL mesh (by "
                         "content or extension), or a GUDHI simplex list (lines of vertex indices); name the format "
                         "with --complex-format (" + kComplexFormatNames + ")");
  // Lines of different lengths: a simplex-tree export lists every face of its simplices, so every
  // shorter line is a face of a longer one. A line that is not (such as a count line "6 8" before
  // triangles on vertices 0..5) makes the file ambiguous.
  const GudhiLayout layout = gudhi_layout(lines, file);
  if (layout == GudhiLayout::simplex_tree) return ComplexFormat::gudhi;  // closed under faces: checked
  std::vector<std::vector<int>> simplices;
  for (const Line& l : lines) {
    std::vector<int> s;
    for (auto t : vertex_tokens(l, layout))
      s.push_back(static_cast<int>(
          std::min<long>(parse_count(t, file, l.number, "a vertex index"), std::numeric_limits<int>::max() - 1)));
    std::sort(s.begin(), s.end());
    simplices.push_back(std::move(s));
  }
  const std::vector<bool> face = faces_of_others(simplices);
  std::size_t longest = 0;
  for (const auto& s : simplices) longest = std::max(longest, s.size());
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (simplices[i].size() < longest && !face[i])
      throw InputError(file, lines[i].number,
                       "cannot tell the complex format: headerless lines of integers of different lengths, and this "
                       "line (" + std::to_string(simplices[i].size()) + " numbers) is not a face of a longer line as "
                       "in a GUDHI simplex list with faces. If the file lists simplices, pass --complex-format gudhi "
                       "(faces are dropped, maximal simplices kept); if its first line is a count header, it is another "
                       "format: add its tag ('delcert-complex v1' or 'OFF') or pass --complex-format (" +
                           kComplexFormatNames + ")");
  return ComplexFormat::gudhi;
}

// GUDHI simplex lists: every line a simplex; the maximal simplices are kept.
void parse_gudhi(const detail::Lines& lines, const std::string& file, std::size_t num_vertices, ComplexFile& out,
                 std::vector<long>& line_of) {
  if (lines.empty()) throw InputError(file, 0, "empty GUDHI simplex list; expected one simplex per line");
  const GudhiLayout layout = gudhi_layout(lines, file);  // (vertex tokens are digits from here on)
  std::size_t nv = num_vertices;
  if (nv == 0) {
    long largest = -1;
    for (const Line& l : lines)
      for (auto t : vertex_tokens(l, layout)) largest = std::max(largest, parse_count(t, file, l.number, "a vertex index"));
    if (largest >= std::numeric_limits<int>::max())
      throw InputError(file, 0, "vertex index " + std::to_string(largest) + " is too large");
    nv = static_cast<std::size_t>(largest + 1);
  }
  std::vector<std::vector<int>> all;
  std::vector<long> all_lines;
  for (const Line& l : lines) {
    all.push_back(parse_simplex(vertex_tokens(l, layout), 0, nv, file, l.number));
    if (layout == GudhiLayout::simplex_tree) std::reverse(all.back().begin(), all.back().end());  // increasing, as listed by Python
    all_lines.push_back(l.number);
  }
  check_unique(all, all_lines, file);
  // A simplex is dropped when another listed simplex contains it.
  std::vector<std::vector<int>> sorted = all;
  for (auto& s : sorted) std::sort(s.begin(), s.end());
  const std::vector<bool> face = faces_of_others(sorted);
  std::size_t dropped = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (face[i]) {
      ++dropped;
      continue;
    }
    out.complex.simplices.push_back(all[i]);
    line_of.push_back(all_lines[i]);
  }
  out.complex.num_vertices = nv;
  const char* what = layout == GudhiLayout::simplex_tree ? "GUDHI simplex tree (dimension, vertices, filtration value per line)"
                     : layout == GudhiLayout::filtered   ? "GUDHI simplex list with filtration values"
                                                         : "GUDHI simplex list";
  const std::string values = layout == GudhiLayout::plain ? "" : ", filtration values ignored";
  if (dropped)
    out.note = std::string(what) + ": " + std::to_string(all.size()) + " simplices read" + values + ", " +
               std::to_string(dropped) + " faces of other listed simplices dropped, " +
               std::to_string(out.complex.simplices.size()) + " maximal simplices kept";
  else if (layout != GudhiLayout::plain)
    out.note = std::string(what) + ": " + std::to_string(all.size()) + " simplices read" + values;
}

}  // namespace

std::optional<ComplexFormat> complex_format_from_name(const std::string& name) {
  for (ComplexFormat f : {ComplexFormat::automatic, ComplexFormat::delcert, ComplexFormat::off, ComplexFormat::obj,
                          ComplexFormat::ply, ComplexFormat::stl, ComplexFormat::gudhi})
    if (name == to_string(f)) return f;
  return std::nullopt;
}

const char* to_string(ComplexFormat f) {
  switch (f) {
    case ComplexFormat::automatic: return "auto";
    case ComplexFormat::delcert: return "delcert";
    case ComplexFormat::off: return "off";
    case ComplexFormat::obj: return "obj";
    case ComplexFormat::ply: return "ply";
    case ComplexFormat::stl: return "stl";
    case ComplexFormat::gudhi: return "gudhi";
  }
  return "?";
}

ComplexFile parse_complex(const std::string& text, const std::string& file, const ComplexReadOptions& options) {
  ComplexFile out;
  std::vector<long> line_of;
  const bool binary_mesh = options.format == ComplexFormat::ply || options.format == ComplexFormat::stl;
  // A binary mesh is not split into lines (its bytes are not text).
  const detail::Lines lines = binary_mesh ? detail::Lines{} : detail::split_lines(text), none;  // (a line is tokenised when read)
  ComplexFormat format = options.format;
  if (format == ComplexFormat::automatic)
    format = detect_format(text, file, detect_mesh_format(text, file) ? none : lines);
  out.format = format;
  if (format == ComplexFormat::obj || format == ComplexFormat::ply || format == ComplexFormat::stl) {
    Mesh mesh = parse_mesh(text, file,
                           format == ComplexFormat::obj   ? MeshFormat::obj
                           : format == ComplexFormat::ply ? MeshFormat::ply
                                                          : MeshFormat::stl);
    out.complex = std::move(mesh.triangles);
    out.embedded_point_lines.assign(mesh.points.size(), 0);
    out.embedded_points = std::move(mesh.points);
    line_of.assign(out.complex.simplices.size(), 0);
    if (mesh.merged_vertices)
      out.note = std::to_string(mesh.merged_vertices) + " vertex copies with identical coordinates merged (" +
                 std::to_string(out.embedded_points->size()) + " distinct vertices)";
    check_unique(out.complex.simplices, line_of, file);
    return out;
  }
  if (format == ComplexFormat::gudhi) {
    parse_gudhi(lines, file, options.num_vertices, out, line_of);
    check_unique(out.complex.simplices, line_of, file);
    return out;
  }
  if (lines.empty()) throw InputError(file, 0, "empty file; expected a 'delcert-complex v1' or 'OFF' header");
  const Line head = lines[0];
  std::string tag(head.tokens[0]);
  if (format == ComplexFormat::delcert && tag != "delcert-complex")
    throw InputError(file, head.number, "--complex-format delcert: expected the first line 'delcert-complex v1', found '" + tag + "'");
  if (format == ComplexFormat::off && tag != "OFF")
    throw InputError(file, head.number, "--complex-format off: expected the first line 'OFF', found '" + tag + "'");
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
    const auto ct = lines[counts_idx].tokens;
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
      const auto t = lines[i].tokens;
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

ComplexFile read_complex(const std::string& path, const ComplexReadOptions& options) {
  return parse_complex(read_file(path), path, options);
}

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

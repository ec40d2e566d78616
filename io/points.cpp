#include "io/points.hpp"

#include <algorithm>
#include <charconv>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/detail/text_lines.hpp"
#include "io/mesh.hpp"

namespace delcert::io {

using detail::Line;
using detail::parse_count;
using detail::parse_finite_double;

namespace {

// Reads `count` coordinate lines of `dim` numbers starting at lines[first]; records line numbers.
void read_coordinate_lines(const detail::Lines& lines, std::size_t first, long count, int dim,
                           const std::string& file, PointSet& out, std::vector<long>& line_of_point) {
  if (static_cast<long>(lines.size() - first) < count) {
    long last = lines.empty() ? 0 : lines.back().number;
    throw InputError(file, last,
                     "file ends after " + std::to_string(lines.size() - first) + " points but the header announces " +
                         std::to_string(count));
  }
  out.coordinates.reserve(static_cast<std::size_t>(count) * dim);
  for (long i = 0; i < count; ++i) {
    const Line l = lines[first + i];
    if (static_cast<int>(l.tokens.size()) != dim)
      throw InputError(file, l.number,
                       "point has " + std::to_string(l.tokens.size()) + " coordinates, expected " + std::to_string(dim));
    for (auto t : l.tokens) out.coordinates.push_back(parse_finite_double(t, file, l.number));
    line_of_point.push_back(l.number);
  }
}

void check_duplicates(const PointSet& ps, const std::vector<long>& line_of_point, const std::string& file) {
  std::vector<std::size_t> order(ps.size());
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](std::size_t i) { return ps.point(i); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    auto pa = key(a), pb = key(b);
    if (std::lexicographical_compare(pa.begin(), pa.end(), pb.begin(), pb.end())) return true;
    if (std::lexicographical_compare(pb.begin(), pb.end(), pa.begin(), pa.end())) return false;
    return a < b;
  });
  for (std::size_t k = 1; k < order.size(); ++k) {
    auto pa = key(order[k - 1]), pb = key(order[k]);
    if (std::equal(pa.begin(), pa.end(), pb.begin()))
      throw InputError(file, line_of_point[order[k]],
                       "duplicate point: identical to point " + std::to_string(order[k - 1]) + " on line " +
                           std::to_string(line_of_point[order[k - 1]]) + "; remove one of them");
  }
}

}  // namespace

PointsFile parse_points_file(const std::string& text, const std::string& file, const PointReadOptions& options) {
  if (auto mesh_format = detect_mesh_format(text, file)) {
    // The vertices of an OBJ, PLY or STL mesh (identical coordinates merged), as the complex reader reads them.
    PointsFile out;
    out.points = parse_mesh(text, file, *mesh_format).points;
    out.lines.assign(out.points.size(), 0);
    if (options.expected_dimension && options.expected_dimension != 3)
      throw InputError(file, 0, std::string("a ") + to_string(*mesh_format) + " mesh has points in R^3 but the manifold lives in R^" +
                                    std::to_string(options.expected_dimension));
    return out;
  }
  auto lines = detail::split_lines(text);
  if (lines.empty()) throw InputError(file, 0, "empty file; expected a 'delcert-points v1', 'OFF' or 'nOFF' header");
  const Line head = lines[0];
  PointsFile out;
  PointSet& ps = out.points;
  std::vector<long>& line_of_point = out.lines;
  std::string tag(head.tokens[0]);
  if (tag == "delcert-points") {
    if (head.tokens.size() != 2 || head.tokens[1] != "v1")
      throw InputError(file, head.number, "unsupported points format version '" +
                                              (head.tokens.size() > 1 ? std::string(head.tokens[1]) : "") +
                                              "'; this reader knows 'delcert-points v1'");
    if (lines.size() < 2 || lines[1].tokens.size() != 2)
      throw InputError(file, lines.size() < 2 ? head.number : lines[1].number, "expected a line 'DIMENSION COUNT'");
    long dim = parse_count(lines[1].tokens[0], file, lines[1].number, "the dimension");
    long count = parse_count(lines[1].tokens[1], file, lines[1].number, "the point count");
    if (dim < 1 || dim > 1000) throw InputError(file, lines[1].number, "dimension must be between 1 and 1000");
    ps.dimension = static_cast<int>(dim);
    read_coordinate_lines(lines, 2, count, ps.dimension, file, ps, line_of_point);
    if (lines.size() > static_cast<std::size_t>(2 + count))
      throw InputError(file, lines[2 + count].number,
                       "extra data after the " + std::to_string(count) + " announced points");
  } else if (tag == "OFF" || tag == "nOFF") {
    std::size_t next = 1;
    long dim = 3;
    std::vector<std::string_view> rest(head.tokens.begin() + 1, head.tokens.end());
    auto take_line = [&]() -> std::vector<std::string_view> {
      if (!rest.empty()) return std::exchange(rest, {});
      if (next >= lines.size()) throw InputError(file, lines.back().number, "unexpected end of " + tag + " header");
      const auto t = lines[next++].tokens;
      return {t.begin(), t.end()};
    };
    long header_line = head.number;
    if (tag == "nOFF") {
      auto t = take_line();
      header_line = lines[next - 1].number;
      dim = parse_count(t[0], file, header_line, "the dimension");
      if (dim < 1 || dim > 1000) throw InputError(file, header_line, "dimension must be between 1 and 1000");
      if (t.size() > 1) rest.assign(t.begin() + 1, t.end());
    }
    auto counts = take_line();
    header_line = next > 0 ? lines[next - 1].number : head.number;
    if (counts.size() < 2)
      throw InputError(file, header_line, "expected 'NUM_VERTICES NUM_FACES [NUM_EDGES]' in the " + tag + " header");
    long nv = parse_count(counts[0], file, header_line, "the vertex count");
    parse_count(counts[1], file, header_line, "the face count");
    ps.dimension = static_cast<int>(dim);
    read_coordinate_lines(lines, next, nv, ps.dimension, file, ps, line_of_point);
  } else {
    throw InputError(file, head.number, "unknown points format '" + tag +
                                            "'; expected a first line 'delcert-points v1', 'OFF' or 'nOFF', or an OBJ, PLY or STL mesh");
  }
  if (options.expected_dimension && ps.dimension != options.expected_dimension)
    throw InputError(file, head.number,
                     "points are in dimension " + std::to_string(ps.dimension) + " but the manifold lives in R^" +
                         std::to_string(options.expected_dimension));
  if (options.reject_duplicates) check_duplicates(ps, line_of_point, file);
  return out;
}

PointSet parse_points(const std::string& text, const std::string& file, const PointReadOptions& options) {
  return parse_points_file(text, file, options).points;
}

PointSet read_points(const std::string& path, const PointReadOptions& options) {
  return parse_points(read_file(path), path, options);
}

std::string format_double(double x) {
  char buf[64];
  auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, ptr);
}

std::string format_points(const PointSet& points, PointFormat format) {
  std::string out;
  switch (format) {
    case PointFormat::delcert:
      out = "delcert-points v1\n" + std::to_string(points.dimension) + " " + std::to_string(points.size()) + "\n";
      break;
    case PointFormat::off:
      if (points.dimension != 3) throw std::invalid_argument("OFF holds points in R^3 only; use nOFF");
      out = "OFF\n" + std::to_string(points.size()) + " 0 0\n";
      break;
    case PointFormat::noff:
      out = "nOFF\n" + std::to_string(points.dimension) + "\n" + std::to_string(points.size()) + " 0 0\n";
      break;
  }
  return out + format_coordinate_lines(points);
}

std::string format_coordinate_lines(const PointSet& points) {
  std::string out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    auto p = points.point(i);
    for (int k = 0; k < points.dimension; ++k) {
      if (k) out += ' ';
      out += format_double(p[k]);
    }
    out += '\n';
  }
  return out;
}

void write_points(const std::string& path, const PointSet& points, PointFormat format) {
  write_file_atomically(path, format_points(points, format));
}

}  // namespace delcert::io

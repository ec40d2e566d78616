#include "io/mesh.hpp"

// The readers behind CGAL::IO::read_polygon_soup, in their stream forms (the file-name forms would
// read the file a second time). The only CGAL include of io/.
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"

namespace delcert::io {

namespace {

std::string lower_extension(const std::string& name) {
  auto dot = name.find_last_of('.');
  auto slash = name.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = name.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// The first whitespace-delimited word of the text.
std::string_view first_word(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  std::size_t s = i;
  while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  return text.substr(s, i - s);
}

// 1-based line numbers of the lines whose first word is `word`, in order (ASCII formats only).
std::vector<long> lines_starting_with(std::string_view text, std::string_view word) {
  std::vector<long> out;
  long number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    ++number;
    if (first_word(text.substr(pos, end - pos)) == word) out.push_back(number);
    pos = end + 1;
  }
  return out;
}

struct PlyHeader {
  bool ascii = false;
  long end_header_line = 0;
  std::vector<std::pair<std::string, unsigned long long>> elements;  // in file order
  std::vector<std::pair<std::string, std::string>> vertex_properties;  // (name, type) of the vertex element
};

bool is_ply_scalar(const std::string& t) {
  for (const char* k : {"char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8", "int16",
                        "uint16", "int32", "uint32", "float32", "float64"})
    if (t == k) return true;
  return false;
}

// Reads and checks the PLY header before CGAL does. CGAL's reader trusts the header: a property
// before any element is undefined behaviour in it (found by fuzzing), a list length of 32 bits
// lets a file ask for gigabytes, and announced counts are not compared with the file's size. So
// the header must be well formed here (keywords, types, a property after its element, each
// element once), list
// lengths are 8 or 16 bits unsigned (uchar, uint8, ushort, uint16: what exporters write), vertex
// coordinates x, y, z float or double, and no element count may exceed the file's size in bytes. Also gives the lines of an ASCII file's faces.
PlyHeader scan_ply_header(std::string_view text, const std::string& file) {
  PlyHeader h;
  long number = 0;
  std::size_t pos = 0;
  auto bad = [&](const std::string& what) {
    throw InputError(file, number, "malformed PLY header: " + what);
  };
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    ++number;
    std::istringstream line(std::string(text.substr(pos, end - pos)));
    pos = end + 1;
    std::string key;
    line >> key;
    if (number == 1) {
      if (key != "ply") bad("the first line must be 'ply'");
      continue;
    }
    if (number == 2) {
      std::string f, version;
      if (key != "format" || !(line >> f >> version) ||
          (f != "ascii" && f != "binary_little_endian" && f != "binary_big_endian"))
        bad("the second line must be 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      h.ascii = f == "ascii";
      continue;
    }
    if (key == "comment" || key == "obj_info") continue;
    if (key == "element") {
      std::string what;
      unsigned long long count = 0;
      if (!(line >> what >> count)) bad("expected 'element NAME COUNT'");
      if (count > text.size())
        throw InputError(file, number,
                         "the PLY header announces " + std::to_string(count) + " " + what + " elements but the file has only " +
                             std::to_string(text.size()) + " bytes");
      for (const auto& e : h.elements)
        if (e.first == what) bad("a second element '" + what + "'");
      h.elements.emplace_back(what, count);
    } else if (key == "property") {
      if (h.elements.empty()) bad("a property before any element");
      std::string type, name;
      if (!(line >> type)) bad("expected 'property TYPE NAME' or 'property list SIZE_TYPE INDEX_TYPE NAME'");
      if (type == "list") {
        std::string size_type, index_type;
        if (!(line >> size_type >> index_type >> name)) bad("expected 'property list SIZE_TYPE INDEX_TYPE NAME'");
        if (size_type != "uchar" && size_type != "uint8" && size_type != "ushort" && size_type != "uint16")
          bad("list length type '" + size_type +
              "': delcert reads lists whose lengths are uchar, uint8, ushort or uint16 (as exporters write them)");
        if (!is_ply_scalar(index_type)) bad("unknown list index type '" + index_type + "'");
      } else {
        if (!is_ply_scalar(type)) bad("unknown property type '" + type + "'");
        if (!(line >> name)) bad("expected 'property TYPE NAME'");
      }
      if (h.elements.back().first == "vertex") h.vertex_properties.emplace_back(name, type);
    } else if (key == "end_header") {
      h.end_header_line = number;
      // CGAL reads x, y, z as float or double whatever they are declared (undefined behaviour
      // for any other type, found by fuzzing).
      for (const char* c : {"x", "y", "z"}) {
        auto it = std::find_if(h.vertex_properties.begin(), h.vertex_properties.end(),
                               [&](const auto& p) { return p.first == c; });
        if (it == h.vertex_properties.end()) bad(std::string("the vertex element has no property ") + c);
        if (it->second != "float" && it->second != "double" && it->second != "float32" && it->second != "float64")
          bad(std::string("vertex coordinate ") + c + " is of type '" + it->second +
              "'; delcert reads coordinates of type float or double");
      }
      return h;
    } else {
      bad("unknown keyword '" + key + "'");
    }
  }
  throw InputError(file, 0, "PLY header without 'end_header'");
}

}  // namespace

const char* to_string(MeshFormat f) {
  switch (f) {
    case MeshFormat::obj: return "OBJ";
    case MeshFormat::ply: return "PLY";
    case MeshFormat::stl: return "STL";
  }
  return "?";
}

std::optional<MeshFormat> detect_mesh_format(std::string_view text, const std::string& name) {
  const std::string_view w = first_word(text);
  if (w == "OFF" || w == "nOFF" || w.rfind("delcert-", 0) == 0) return std::nullopt;
  if (w == "ply") return MeshFormat::ply;
  if (w == "solid") return MeshFormat::stl;
  const std::string ext = lower_extension(name);
  if (ext == "obj") return MeshFormat::obj;
  if (ext == "ply") return MeshFormat::ply;
  if (ext == "stl") return MeshFormat::stl;
  return std::nullopt;
}

Mesh parse_mesh(const std::string& text, const std::string& file, MeshFormat format) {
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  std::vector<long> face_lines;  // the line of each face, where known (ASCII); else empty
  std::vector<long> vertex_lines;  // the line of each vertex of the file (STL: each corner), where known
  std::size_t stl_copies = 0;    // vertex copies CGAL's STL reader merged
  bool ok = false;
  std::istringstream in(text, std::ios::in | std::ios::binary);
  const auto quiet = CGAL::parameters::verbose(false);
  try {
    switch (format) {
      case MeshFormat::obj:
        ok = CGAL::IO::read_OBJ(in, points, faces, quiet);
        face_lines = lines_starting_with(text, "f");
        vertex_lines = lines_starting_with(text, "v");
        break;
      case MeshFormat::ply: {
        const PlyHeader h = scan_ply_header(text, file);
        ok = CGAL::IO::read_PLY(in, points, faces, quiet);
        if (h.ascii && h.elements.size() >= 2 && h.elements[0].first == "vertex" && h.elements[1].first == "face")
          for (std::size_t k = 0; k < h.elements[1].second; ++k)
            face_lines.push_back(h.end_header_line + static_cast<long>(h.elements[0].second + k) + 1);
        if (h.ascii && !h.elements.empty() && h.elements[0].first == "vertex")
          for (std::size_t k = 0; k < h.elements[0].second; ++k) vertex_lines.push_back(h.end_header_line + static_cast<long>(k) + 1);
        break;
      }
      case MeshFormat::stl: {
        std::vector<std::array<std::size_t, 3>> triangles;
        ok = CGAL::IO::read_STL(in, points, triangles, quiet);
        for (const auto& t : triangles) faces.push_back({t[0], t[1], t[2]});
        // CGAL's STL reader has already merged the 3 corners stored per facet into shared vertices.
        if (3 * faces.size() > points.size()) stl_copies = 3 * faces.size() - points.size();
        if (first_word(text) == "solid") face_lines = lines_starting_with(text, "facet"), vertex_lines = lines_starting_with(text, "vertex");
        break;
      }
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(file, 0, std::string("CGAL's ") + to_string(format) + " reader failed: " + e.what());
  }
  if (face_lines.size() != faces.size()) face_lines.assign(faces.size(), 0);
  if (!ok)
    throw InputError(file, 0,
                     std::string("not a readable ") + to_string(format) +
                         " file (CGAL's polygon-soup reader refused it); check the file, or pass --complex-format if it is "
                         "another format");
  if (faces.empty())
    throw InputError(file, 0, std::string("the ") + to_string(format) + " file has no faces; a surface mesh of triangles is expected");
  Mesh mesh;
  mesh.points.dimension = 3;
  mesh.merged_vertices = stl_copies;
  // Merge vertices with identical coordinates, in order of first appearance. Identical as numbers
  // (0 and -0 are one vertex, as for the points reader's duplicate test and CGAL's STL reader):
  // the certifier reads every double as the rational it represents.
  std::map<std::array<double, 3>, int> index_of;
  std::vector<int> new_index(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::array<double, 3> c{points[i].x(), points[i].y(), points[i].z()};
    for (double x : c)
      if (!std::isfinite(x))
        throw InputError(file, 0, "vertex " + std::to_string(i) + " has a coordinate that is not a finite number");
    const std::array<double, 3>& key = c;
    auto [it, inserted] = index_of.emplace(key, static_cast<int>(mesh.points.size()));
    if (inserted) mesh.points.push_back(c);
    else ++mesh.merged_vertices;
    new_index[i] = it->second;
  }
  mesh.triangles.num_vertices = mesh.points.size();
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& face = faces[f];
    if (face.size() != 3)
      throw InputError(file, face_lines[f],
                       "face " + std::to_string(f) + " has " + std::to_string(face.size()) +
                           " vertices; only triangles are simplices (triangulate the mesh first, e.g. with CGAL's "
                           "triangulate_faces or your mesher's triangulation option)");
    std::vector<int> t;
    for (std::size_t v : face) {
      if (v >= points.size())
        throw InputError(file, face_lines[f],
                         "face " + std::to_string(f) + ": vertex index " + std::to_string(v) + " out of range (" +
                             std::to_string(points.size()) + " vertices)");
      t.push_back(new_index[v]);
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      throw InputError(file, face_lines[f],
                       "face " + std::to_string(f) + " is degenerate: two of its corners are the same vertex" +
                           (mesh.merged_vertices ? " (after merging identical coordinates)" : std::string()));
    mesh.triangles.simplices.push_back(std::move(t));
  }
  // The file's own vertices. STL has none: CGAL's reader gave each facet's corners as indices into the points it
  // merged, so corner k of facet f is file vertex 3f + k.
  if (format == MeshFormat::stl) {
    for (const auto& face : faces)
      for (std::size_t v : face) {
        mesh.file_vertices.push_back({points[v].x(), points[v].y(), points[v].z()});
        mesh.file_to_vertex.push_back(new_index[v]);
      }
    for (std::size_t f = 0; f < faces.size(); ++f) mesh.file_faces.push_back({3 * f, 3 * f + 1, 3 * f + 2});
  } else {
    for (const auto& p : points) mesh.file_vertices.push_back({p.x(), p.y(), p.z()});
    mesh.file_to_vertex = new_index;
    for (const auto& face : faces) mesh.file_faces.push_back({face[0], face[1], face[2]});
  }
  if (vertex_lines.size() != mesh.file_vertices.size()) vertex_lines.assign(mesh.file_vertices.size(), 0);
  mesh.file_vertex_lines = std::move(vertex_lines);
  return mesh;
}

std::string format_ply(const PointSet& points, const Complex& c) {
  if (points.dimension != 3 || c.num_vertices != points.size())
    throw std::invalid_argument("PLY needs points in R^3 and a complex on exactly those vertices");
  std::string out = "ply\nformat ascii 1.0\ncomment written by delcert\nelement vertex " + std::to_string(points.size()) +
                    "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                    std::to_string(c.simplices.size()) + "\nproperty list uchar int vertex_indices\nend_header\n" +
                    format_coordinate_lines(points);
  for (const auto& s : c.simplices) {
    if (s.size() != 3) throw std::invalid_argument("PLY faces must be triangles");
    out += "3 " + std::to_string(s[0]) + " " + std::to_string(s[1]) + " " + std::to_string(s[2]) + "\n";
  }
  return out;
}

MeshOutputFormat mesh_output_format(const std::string& path, const std::string& option) {
  const std::string ext = lower_extension(path);
  if (ext == "off") return MeshOutputFormat::off;
  if (ext == "ply") return MeshOutputFormat::ply;
  throw InputError(path, 0, option + ": the file name must end in .off or .ply (the format written)");
}

std::string format_mesh(const PointSet& points, const Complex& triangles, MeshOutputFormat format) {
  return format == MeshOutputFormat::off ? format_off(points, triangles) : format_ply(points, triangles);
}

}  // namespace delcert::io

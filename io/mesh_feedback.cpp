#include "io/mesh_feedback.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <deque>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/mesh.hpp"
#include "io/points.hpp"
#include "io/spec.hpp"

namespace delcert::io {

namespace {

using Edge = std::pair<int, int>;        // certified vertices, first < second
using Tri = std::array<int, 3>;          // certified vertices, sorted
constexpr std::size_t kJsonCap = 1000;   // entries of each list in the certificate

Edge edge(int a, int b) { return a < b ? Edge{a, b} : Edge{b, a}; }
Tri sorted(Tri t) { return std::sort(t.begin(), t.end()), t; }

// "OFF", "OBJ", "PLY", "STL": as users write the formats' names.
std::string format_name(ComplexFormat f) {
  std::string s = to_string(f);
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string first_word(const std::string& text) {
  std::size_t i = 0;
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  std::size_t s = i;
  while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  return text.substr(s, i - s);
}

// The number the file gives a vertex: OBJ counts from 1 (its f lines do), the others from 0.
std::size_t file_number(const MeshSource& src, std::size_t v) { return src.format == ComplexFormat::obj ? v + 1 : v; }

std::string coordinates_text(const std::array<double, 3>& p) {
  return "(" + format_double(p[0]) + ", " + format_double(p[1]) + ", " + format_double(p[2]) + ")";
}

nlohmann::json vertex_json(const MeshSource& src, std::size_t v) {
  nlohmann::json j;
  if (src.format == ComplexFormat::stl) j["facet"] = v / 3, j["corner"] = v % 3;
  else j["file_index"] = file_number(src, v);
  j["line"] = src.vertex_lines[v] ? nlohmann::json(src.vertex_lines[v]) : nlohmann::json(nullptr);
  j["coordinates"] = {format_double(src.vertices[v][0]), format_double(src.vertices[v][1]), format_double(src.vertices[v][2])};
  j["vertex"] = src.to_vertex[v];
  return j;
}

// A triangle in the file's terms: its file vertices' numbers (STL: "facet f").
std::string triangle_text(const MeshSource& src, const std::array<std::size_t, 3>& t) {
  if (src.format == ComplexFormat::stl) return "facet " + std::to_string(t[0] / 3);
  return std::to_string(file_number(src, t[0])) + "-" + std::to_string(file_number(src, t[1])) + "-" +
         std::to_string(file_number(src, t[2]));
}

// The triangles of the output, on certified vertices, oriented: the source's faces that are in Del_RM first (file
// order, as written), then the others, each turned against a written neighbour across a shared edge (breadth first,
// a component without one from its smallest triangle in increasing order). kept[i] >= 0: the source face it is.
struct Oriented {
  std::vector<Tri> triangles;
  std::vector<long> kept;
};

Oriented orient(const MeshSource& src, const std::vector<std::vector<int>>& del_rm) {
  std::set<Tri> wanted;
  for (const auto& s : del_rm) {
    if (s.size() != 3) throw std::invalid_argument("Del_RM(P) of a surface has triangles only");
    wanted.insert(sorted({s[0], s[1], s[2]}));
  }
  Oriented out;
  std::set<Tri> placed;
  std::set<Edge> directed;  // (u, v): some written triangle runs u -> v
  auto place = [&](const Tri& t, long kept) {
    out.triangles.push_back(t), out.kept.push_back(kept), placed.insert(sorted(t));
    for (int k = 0; k < 3; ++k) directed.insert({t[k], t[(k + 1) % 3]});
  };
  for (std::size_t f = 0; f < src.faces.size(); ++f) {
    const Tri t{src.to_vertex[src.faces[f][0]], src.to_vertex[src.faces[f][1]], src.to_vertex[src.faces[f][2]]};
    if (wanted.count(sorted(t)) && !placed.count(sorted(t))) place(t, static_cast<long>(f));
  }
  std::map<Edge, std::vector<Tri>> pending;  // by undirected edge
  std::size_t left = 0;
  for (const Tri& t : wanted)
    if (!placed.count(t)) {
      ++left;
      for (int k = 0; k < 3; ++k) pending[edge(t[k], t[(k + 1) % 3])].push_back(t);
    }
  std::deque<std::size_t> queue;
  for (std::size_t i = 0; i < out.triangles.size(); ++i) queue.push_back(i);
  auto it = wanted.begin();
  while (left) {
    if (queue.empty()) {  // a component with no written triangle: its smallest, as it is
      while (placed.count(*it)) ++it;
      place(*it, -1), --left, queue.push_back(out.triangles.size() - 1);
    }
    const Tri t = out.triangles[queue.front()];
    queue.pop_front();
    for (int k = 0; k < 3; ++k) {
      const int u = t[k], v = t[(k + 1) % 3];
      auto p = pending.find(edge(u, v));
      if (p == pending.end()) continue;
      for (const Tri& n : p->second) {
        if (placed.count(n)) continue;
        const int w = n[0] != u && n[0] != v ? n[0] : n[1] != u && n[1] != v ? n[1] : n[2];
        // Across u -> v the neighbour runs v -> u: (v, u, w), unless that direction is taken already.
        const Tri o = directed.count({v, u}) ? Tri{u, v, w} : Tri{v, u, w};
        place(o, -1), --left, queue.push_back(out.triangles.size() - 1);
      }
    }
  }
  return out;
}

std::string stl_facet(const std::array<std::array<double, 3>, 3>& c) {
  // The normal is for viewers (readers recompute it; CGAL's ignores it): floating point, certifies nothing.
  const double ux = c[1][0] - c[0][0], uy = c[1][1] - c[0][1], uz = c[1][2] - c[0][2];
  const double vx = c[2][0] - c[0][0], vy = c[2][1] - c[0][1], vz = c[2][2] - c[0][2];
  double n[3] = {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& x : n) x = len > 0 && std::isfinite(len) ? x / len : 0.0;
  std::string s = "  facet normal " + format_double(n[0]) + " " + format_double(n[1]) + " " + format_double(n[2]) +
                  "\n    outer loop\n";
  for (const auto& p : c)
    s += "      vertex " + format_double(p[0]) + " " + format_double(p[1]) + " " + format_double(p[2]) + "\n";
  return s + "    endloop\n  endfacet\n";
}

}  // namespace

const char* mesh_extension(ComplexFormat f) {
  switch (f) {
    case ComplexFormat::off: return "off";
    case ComplexFormat::obj: return "obj";
    case ComplexFormat::ply: return "ply";
    case ComplexFormat::stl: return "stl";
    default: return "";
  }
}

std::optional<ComplexFormat> mesh_format_of(const std::string& text, const std::string& path, ComplexFormat given) {
  if (given != ComplexFormat::automatic) {
    if (given == ComplexFormat::off || given == ComplexFormat::obj || given == ComplexFormat::ply ||
        given == ComplexFormat::stl)
      return given;
    return std::nullopt;
  }
  if (first_word(text) == "OFF") return ComplexFormat::off;
  if (const auto mf = detect_mesh_format(text, path))
    return *mf == MeshFormat::obj ? ComplexFormat::obj : *mf == MeshFormat::ply ? ComplexFormat::ply : ComplexFormat::stl;
  return std::nullopt;
}

MeshSource parse_mesh_source(const std::string& text, const std::string& path, ComplexFormat format) {
  MeshSource src;
  src.format = format, src.path = path;
  if (format == ComplexFormat::off) {  // OFF: no merging (the points reader refuses duplicates)
    ComplexFile cf = parse_complex(text, path, {ComplexFormat::off, 0});
    for (std::size_t i = 0; i < cf.embedded_points->size(); ++i) {
      const auto p = cf.embedded_points->point(i);
      src.vertices.push_back({p[0], p[1], p[2]});
      src.to_vertex.push_back(static_cast<int>(i)), src.first_copy.push_back(i);
    }
    src.vertex_lines = cf.embedded_point_lines;
    src.vertex_lines.resize(src.vertices.size(), 0);
    for (const auto& s : cf.complex.simplices)
      src.faces.push_back({static_cast<std::size_t>(s[0]), static_cast<std::size_t>(s[1]), static_cast<std::size_t>(s[2])});
    return src;
  }
  if (format != ComplexFormat::obj && format != ComplexFormat::ply && format != ComplexFormat::stl)
    throw InputError(path, 0, "not a surface mesh (" + format_name(format) + "): OFF, OBJ, PLY or STL expected");
  Mesh mesh = parse_mesh(text, path,
                         format == ComplexFormat::obj ? MeshFormat::obj : format == ComplexFormat::ply ? MeshFormat::ply : MeshFormat::stl);
  src.vertices = std::move(mesh.file_vertices), src.vertex_lines = std::move(mesh.file_vertex_lines);
  src.faces = std::move(mesh.file_faces), src.to_vertex = std::move(mesh.file_to_vertex);
  src.first_copy.assign(mesh.points.size(), 0);
  std::vector<char> seen(mesh.points.size(), 0);
  for (std::size_t v = 0; v < src.to_vertex.size(); ++v)
    if (!seen[src.to_vertex[v]]) seen[src.to_vertex[v]] = 1, src.first_copy[src.to_vertex[v]] = v;
  return src;
}

std::string merge_note(const MeshSource& src) {
  const std::size_t n = src.first_copy.size(), entries = src.vertices.size();
  if (src.format == ComplexFormat::stl)
    return "STL: " + std::to_string(entries) + " corner entries (3 per facet) merged into " + std::to_string(n) +
           " vertices by exact coordinates";
  if (entries == n) return "";
  return format_name(src.format) + ": " + std::to_string(entries) + " vertices merged into " +
         std::to_string(n) + " by exact coordinates; a merged vertex is named by its first copy in the file";
}

std::string numbering_note(const MeshSource& src) {
  switch (src.format) {
    case ComplexFormat::obj: return "vertices numbered from 1, as OBJ's f lines number them";
    case ComplexFormat::stl: return "STL has no vertex numbers: a vertex is named by its first facet corner, facets and corners numbered from 0";
    default: return "vertices numbered from 0, as " + format_name(src.format) + " faces number them";
  }
}

std::string vertex_name(const MeshSource& src, std::size_t v) {
  std::string s = src.format == ComplexFormat::stl ? "facet " + std::to_string(v / 3) + " corner " + std::to_string(v % 3)
                                                   : "vertex " + std::to_string(file_number(src, v));
  if (src.vertex_lines[v]) s += " (line " + std::to_string(src.vertex_lines[v]) + ")";
  return s;
}

MeshFeedback non_delaunay_edges(const MeshSource& src, const std::vector<std::vector<int>>& del_rm, std::size_t shown) {
  std::set<Tri> rm;
  std::set<Edge> rm_edges;
  for (const auto& s : del_rm) {
    if (s.size() != 3) throw std::invalid_argument("Del_RM(P) of a surface has triangles only");
    const Tri t = sorted({s[0], s[1], s[2]});
    rm.insert(t);
    rm_edges.insert({t[0], t[1]}), rm_edges.insert({t[0], t[2]}), rm_edges.insert({t[1], t[2]});
  }
  // The mesh on certified vertices: each edge with the opposite vertex of every triangle holding it.
  std::map<Edge, std::vector<int>> opposite;
  std::set<Tri> given;
  std::vector<std::size_t> not_in_rm;  // faces of the file
  for (std::size_t f = 0; f < src.faces.size(); ++f) {
    Tri t{src.to_vertex[src.faces[f][0]], src.to_vertex[src.faces[f][1]], src.to_vertex[src.faces[f][2]]};
    for (int k = 0; k < 3; ++k) opposite[edge(t[k], t[(k + 1) % 3])].push_back(t[(k + 2) % 3]);
    given.insert(sorted(t));
    if (!rm.count(sorted(t))) not_in_rm.push_back(f);
  }
  std::vector<Tri> missing;
  for (const Tri& t : rm)
    if (!given.count(t)) missing.push_back(t);

  MeshFeedback fb;
  auto name = [&](int v) { return src.first_copy[v]; };
  const std::string fmt = format_name(src.format);
  nlohmann::json edges = nlohmann::json::array();
  std::vector<std::string> edge_lines;
  long total = 0;
  // In the order of the file's numbers (the first copies'), then the certified indices.
  std::vector<Edge> bad;
  for (const auto& [e, opp] : opposite)
    if (!rm_edges.count(e)) bad.push_back(e);
  auto key = [&](const Edge& e) {
    const std::size_t a = name(e.first), b = name(e.second);
    return std::make_pair(std::min(a, b), std::max(a, b));
  };
  std::sort(bad.begin(), bad.end(), [&](const Edge& x, const Edge& y) { return key(x) < key(y); });
  for (const Edge& e : bad) {
    ++total;
    const auto [fa, fb_] = key(e);
    const int a = src.to_vertex[fa], b = src.to_vertex[fb_];
    const std::vector<int>& opp = opposite.at(e);
    nlohmann::json flip = nullptr;
    std::string advice;
    if (opp.size() != 2) {
      advice = "no flip: the edge is in " + std::to_string(opp.size()) + " triangle(s) of the mesh, not 2";
    } else {
      const int c = opp[0], d = opp[1];
      const bool in_rm = c != d && rm_edges.count(edge(c, d)) > 0, in_mesh = c != d && opposite.count(edge(c, d)) > 0;
      const bool both = rm.count(sorted({a, c, d})) && rm.count(sorted({b, c, d}));
      const std::size_t fc = std::min(name(c), name(d)), fd = std::max(name(c), name(d));
      if (in_rm && !in_mesh) {
        flip = {{"to", {vertex_json(src, fc), vertex_json(src, fd)}}, {"new_triangles_in_Del_RM", both}};
        advice = "flip it to " +
                 (src.format == ComplexFormat::stl ? vertex_name(src, fc) + " - " + vertex_name(src, fd)
                                                   : std::to_string(file_number(src, fc)) + "-" + std::to_string(file_number(src, fd))) +
                 (both ? ": both new triangles are in Del_RM(P)" : ": an edge of Del_RM(P), but not both new triangles are");
      } else {
        advice = in_mesh ? "no flip: the other diagonal is already an edge of the mesh"
                         : "no flip: the other diagonal of its two triangles is not in Del_RM(P) either";
      }
    }
    if (edges.size() < kJsonCap)
      edges.push_back({{"edge", {vertex_json(src, fa), vertex_json(src, fb_)}}, {"in_triangles", opp.size()},
                       {"flip", flip}, {"advice", advice}});
    if (edge_lines.size() < shown)
      edge_lines.push_back("  edge " + (src.format == ComplexFormat::stl ? vertex_name(src, fa) + " - " + vertex_name(src, fb_)
                                                                         : std::to_string(file_number(src, fa)) + "-" +
                                                                               std::to_string(file_number(src, fb_))) +
                           "  " + coordinates_text(src.vertices[fa]) + " - " + coordinates_text(src.vertices[fb_]) +
                           "; " + advice);
  }
  nlohmann::json extra = nlohmann::json::array(), absent = nlohmann::json::array();
  for (std::size_t f : not_in_rm)
    if (extra.size() < kJsonCap)
      extra.push_back({{"face", f}, {"vertices", {vertex_json(src, src.faces[f][0]), vertex_json(src, src.faces[f][1]),
                                                  vertex_json(src, src.faces[f][2])}}});
  for (const Tri& t : missing)
    if (absent.size() < kJsonCap)
      absent.push_back({{"vertices", {vertex_json(src, name(t[0])), vertex_json(src, name(t[1])), vertex_json(src, name(t[2]))}}});
  const std::string note = merge_note(src);
  fb.json = {{"about", "presentation (io/mesh_feedback.cpp), derived from check 12's Del_RM(P) (certified complete and "
                       "pure) and the mesh file's bytes, in the file's own numbering; no verdict rests on it"},
             {"file", src.path},
             {"format", fmt},
             {"numbering", numbering_note(src)},
             {"merged", note.empty() ? nlohmann::json(nullptr) : nlohmann::json(note)},
             {"non_delaunay_edges", edges},
             {"non_delaunay_edges_total", total},
             {"triangles_not_in_Del_RM", extra},
             {"triangles_not_in_Del_RM_total", not_in_rm.size()},
             {"Del_RM_triangles_missing", absent},
             {"Del_RM_triangles_missing_total", missing.size()}};
  auto& L = fb.lines;
  L.push_back("mesh " + src.path + " (" + fmt + "; " + numbering_note(src) + ")");
  if (!note.empty()) L.push_back("mesh " + note);
  if (total == 0 && not_in_rm.empty() && missing.empty()) {
    L.push_back("mesh every triangle of the mesh is in Del_RM(P), and every triangle of Del_RM(P) in the mesh");
    return fb;
  }
  L.push_back("mesh " + std::to_string(total) + " edge(s) of the mesh not in Del_RM(P) (not Delaunay)" +
              (total > static_cast<long>(shown) ? ", the first " + std::to_string(shown) + ":" : total ? ":" : ""));
  for (auto& l : edge_lines) L.push_back(std::move(l));
  auto list = [&](const std::string& what, std::size_t n, const std::vector<std::string>& items) {
    if (!n) return;
    std::string s = "mesh " + std::to_string(n) + " " + what + ":";
    for (std::size_t i = 0; i < items.size(); ++i) s += (i ? ", " : " ") + items[i];
    if (n > items.size()) s += ", ...";
    L.push_back(s);
  };
  std::vector<std::string> ex, ab;
  for (std::size_t i = 0; i < not_in_rm.size() && i < shown; ++i) ex.push_back(triangle_text(src, src.faces[not_in_rm[i]]));
  for (std::size_t i = 0; i < missing.size() && i < shown; ++i) {
    const Tri& t = missing[i];
    if (src.format == ComplexFormat::stl)
      ab.push_back("(" + vertex_name(src, name(t[0])) + ", " + vertex_name(src, name(t[1])) + ", " + vertex_name(src, name(t[2])) + ")");
    else
      ab.push_back(triangle_text(src, {name(t[0]), name(t[1]), name(t[2])}));
  }
  list("triangle(s) of the mesh not in Del_RM(P)", not_in_rm.size(), ex);
  list("triangle(s) of Del_RM(P) missing from the mesh", missing.size(), ab);
  return fb;
}

std::string format_fixed_mesh(const MeshSource& src, const std::vector<std::vector<int>>& del_rm) {
  const Oriented o = orient(src, del_rm);
  if (src.format == ComplexFormat::stl) {
    std::string out = "solid delcert_fixed\n";
    for (std::size_t i = 0; i < o.triangles.size(); ++i) {
      std::array<std::array<double, 3>, 3> c;
      for (int k = 0; k < 3; ++k)
        c[k] = o.kept[i] >= 0 ? src.vertices[src.faces[o.kept[i]][k]] : src.vertices[src.first_copy[o.triangles[i][k]]];
      out += stl_facet(c);
    }
    return out + "endsolid delcert_fixed\n";
  }
  PointSet points;
  points.dimension = 3;
  for (const auto& p : src.vertices) points.push_back(p);
  Complex c;
  c.num_vertices = src.vertices.size();
  for (std::size_t i = 0; i < o.triangles.size(); ++i) {
    std::vector<int> t(3);
    for (int k = 0; k < 3; ++k)
      t[k] = static_cast<int>(o.kept[i] >= 0 ? src.faces[o.kept[i]][k] : src.first_copy[o.triangles[i][k]]);
    c.simplices.push_back(std::move(t));
  }
  if (src.format == ComplexFormat::off) return format_off(points, c);
  if (src.format == ComplexFormat::ply) return format_ply(points, c);
  std::string out = "# Del_RM(P) of " + src.path + ", written by delcert-certify --fix-out\n";
  for (const auto& p : src.vertices)
    out += "v " + format_double(p[0]) + " " + format_double(p[1]) + " " + format_double(p[2]) + "\n";
  for (const auto& t : c.simplices)
    out += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  return out;
}

void check_fix_out(const std::string& fix_out, const std::string& manifold, const std::string& complex,
                   const std::string& complex_format, const std::vector<std::string>& inputs,
                   const std::vector<std::string>& other_outputs) {
  const std::string what = "--fix-out writes Del_RM(P) as a surface mesh in the format of --complex";
  if (complex.empty()) throw InputError(fix_out, 0, what + ", and no --complex was given");
  const ManifoldSpec spec = parse_spec(read_spec_text(manifold), manifold);
  if (spec.intrinsic_dimension != 2 || spec.ambient_dimension != 3)
    throw InputError(fix_out, 0, what + ": a surface in R^3, and " + manifold + " is a " +
                                     std::to_string(spec.intrinsic_dimension) + "-manifold in R^" +
                                     std::to_string(spec.ambient_dimension));
  if (!std::filesystem::is_regular_file(complex))  // (a FIFO read here would be empty for the certifier)
    throw InputError(fix_out, 0, what + ", which is read again for it: " + complex + " must be a regular file");
  const auto given = complex_format_from_name(complex_format).value_or(ComplexFormat::automatic);
  const auto format = mesh_format_of(read_file(complex), complex, given);
  if (!format)
    throw InputError(fix_out, 0, what + ", and " + complex + " is not a mesh (OFF, OBJ, PLY or STL); drop --fix-out");
  const std::string ext = mesh_extension(*format);
  std::string name = fix_out.substr(fix_out.find_last_of('/') == std::string::npos ? 0 : fix_out.find_last_of('/') + 1);
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (name.size() <= ext.size() + 1 || name.compare(name.size() - ext.size() - 1, ext.size() + 1, "." + ext) != 0)
    throw InputError(fix_out, 0, what + " (" + format_name(*format) + " here): name the file ." + ext);
  check_output_path(fix_out, "--fix-out", inputs, other_outputs);
}

MeshReport report_mesh(const nlohmann::json& inputs, bool restricted, const std::vector<std::vector<int>>& del_rm,
                       const std::string& why_not, const std::string& fix_out,
                       const std::function<std::string(std::string_view)>& sha256) {
  MeshReport r;
  const nlohmann::json& complex = inputs["complex"];
  if (!complex.is_object() || inputs["manifold"]["intrinsic_dimension"] != 2) return r;
  const auto format = complex_format_from_name(complex["read"]["format"].get<std::string>());
  if (!format || !mesh_format_of("", "", *format)) return r;
  const std::string path = complex["path"];
  if (!std::filesystem::is_regular_file(path)) return r;  // (read once only: a FIFO, a device)
  const std::string text = read_file(path);
  if (sha256(text) != complex["sha256"].get<std::string>())
    throw InputError(path, 0, "the file changed while it was certified (its SHA-256 is not the certificate's); nothing written");
  const MeshSource src = parse_mesh_source(text, path, *format);
  if (restricted && !del_rm.empty()) {
    MeshFeedback fb = non_delaunay_edges(src, del_rm);
    const bool same = fb.json["non_delaunay_edges_total"] == 0 && fb.json["triangles_not_in_Del_RM_total"] == 0 &&
                      fb.json["Del_RM_triangles_missing_total"] == 0;
    if (!same) r.json = std::move(fb.json), r.lines = std::move(fb.lines);
  } else if (restricted) {
    const std::string note = merge_note(src);
    r.json = {{"about", "presentation (io/mesh_feedback.cpp); no verdict rests on it"}, {"file", path},
              {"format", format_name(*format)}, {"numbering", numbering_note(src)},
              {"merged", note.empty() ? nlohmann::json(nullptr) : nlohmann::json(note)},
              {"non_delaunay_edges", nullptr},
              {"why_not", "Del_RM(P) is not certified complete and pure (check 12), so no edge is known not to be in it"}};
    if (!note.empty()) r.lines.push_back("mesh " + note);
    r.lines.push_back("mesh no edge list: Del_RM(P) is not certified complete and pure (check 12: " + why_not + ")");
  }
  if (fix_out.empty()) return r;
  if (del_rm.empty()) {
    r.lines.push_back("fix-out            not written: Del_RM(P) is not certified complete and pure (check 12: " + why_not + ")");
    return r;
  }
  r.fixed_mesh = format_fixed_mesh(src, del_rm);
  r.lines.push_back("fix-out            " + fix_out + ": Del_RM(P), " + std::to_string(del_rm.size()) + " triangles, as " +
                    format_name(*format) + (*format == ComplexFormat::stl ? "" : " with every vertex of " + path + " at its index") +
                    "; certify it with --points and --complex that file");
  return r;
}

}  // namespace delcert::io

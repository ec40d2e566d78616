// The Python module `delcert` (pybind11): the four commands on numpy arrays.
//
//   delcert.sample(manifold, eps, seed=1)                          -> float64 array (n, N)
//   delcert.tangential(manifold, points, threads=0)                -> int64 array (k, m+1)
//   delcert.refine(manifold, points=None, eps=None, ...)           -> dict: points, complex, claims, report, converged
//                                                                     (+ eps_per_point with sizing='curvature')
//   delcert.certify(manifold, points, complex=None, kind=None, claims=None, ...,
//                   complex_format='auto', residual_tolerance=None, out=None, report=None, fix_out=None)
//                                                                  -> the certificate as a dict
//
// Each function makes the library calls its command makes (core/app/*_command.cpp,
// certify/main.cpp), on the same readers: a points array is turned into the delcert-points text
// (shortest round-trip decimals, so bit for bit the same doubles) and read by io::parse_points
// under the name "points", so it gets every check a points file gets. certify() writes its array
// inputs to a private temporary folder and calls certify::run_certify on the files, exactly as
// delcert-certify does. A file path (str or os.PathLike) is accepted wherever the command line
// takes a file, and is then read by the same reader as there, with the same messages.
//
// Bad input raises delcert.InputError (a ValueError) with the message the command prints after
// "delcert: " / "delcert-certify: ". For an array, "points:LINE:" becomes "points row R:" (R
// 0-based), and likewise for "complex". A bug raises RuntimeError ("internal error: ...").
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <stdlib.h>  // mkdtemp

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "certify/certify.hpp"
#include "certify/detail/sha256.hpp"
#include "core/manifold/manifold.hpp"
#include "core/manifold/on_manifold.hpp"
#include "core/refine/refine_output.hpp"
#include "core/refine/refiner.hpp"
#include "core/sampling/sampling.hpp"
#include "core/support/parallel.hpp"
#include "core/tangential/tangent_planes.hpp"
#include "core/tangential/tangential_complex.hpp"
#include "exact/interval.hpp"
#include "io/atomic_file.hpp"
#include "io/complex.hpp"
#include "io/input_error.hpp"
#include "io/mesh_feedback.hpp"  // certify(fix_out=...): a mesh's edges in its file's numbering, as delcert-certify
#include "io/points.hpp"
#include "io/spec.hpp"
#include "report/html_report.hpp"  // certify(report=...): presentation only, as in delcert-certify

namespace py = pybind11;
using namespace delcert;

namespace {

// Raised in Python as delcert.InputError (a subclass of ValueError).
class BindingInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

constexpr int kMaxThreads = 256;  // as every command's --threads

// An argument that is a file path: str or os.PathLike (not bytes, not an array).
bool is_path(const py::handle& obj) {
  if (py::isinstance<py::str>(obj)) return true;
  return py::isinstance(obj, py::module_::import("os").attr("PathLike"));
}

std::string path_text(const py::handle& obj) {
  return py::str(py::module_::import("os").attr("fspath")(obj)).cast<std::string>();
}

// A text the readers got from an array: the line numbers in their messages are lines of that
// text, `header_lines` before row 0. "NAME:LINE: ..." becomes "NAME row ROW: ...".
struct ArrayName {
  std::string name;
  long header_lines = 2;
};

std::string rewrite_message(std::string message, const std::string& temp_prefix, const std::vector<ArrayName>& arrays) {
  if (!temp_prefix.empty())
    for (std::size_t at; (at = message.find(temp_prefix)) != std::string::npos;) message.erase(at, temp_prefix.size());
  for (const auto& a : arrays) {
    const std::string head = a.name + ":";
    if (message.compare(0, head.size(), head) != 0) continue;
    std::size_t end = head.size();
    while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end]))) ++end;
    if (end == head.size() || end >= message.size() || message[end] != ':') continue;
    const long line = std::stol(message.substr(head.size(), end - head.size()));
    if (line <= a.header_lines) continue;
    message = a.name + " row " + std::to_string(line - a.header_lines - 1) + message.substr(end);
    // Other lines the message names ("identical to point 3 on line 6", "first on line 9") are rows too.
    const std::string on_line = "on line ";
    for (std::size_t at = 0; (at = message.find(on_line, at)) != std::string::npos;) {
      std::size_t e = at + on_line.size();
      while (e < message.size() && std::isdigit(static_cast<unsigned char>(message[e]))) ++e;
      const long other = e > at + on_line.size() ? std::stol(message.substr(at + on_line.size(), e - at - on_line.size())) : 0;
      if (other <= a.header_lines) {
        at = e;
        continue;
      }
      const std::string row = "in row " + std::to_string(other - a.header_lines - 1);
      message.replace(at, e - at, row);
      at += row.size();
    }
  }
  return message;
}

// Runs `body`, turning io::InputError into delcert.InputError with the rewritten message.
template <class F>
auto translating(const std::string& temp_prefix, const std::vector<ArrayName>& arrays, F&& body) {
  try {
    return body();
  } catch (const io::InputError& e) {
    throw BindingInputError(rewrite_message(e.what(), temp_prefix, arrays));
  }
}

void check_threads(int threads) {
  if (threads < 0 || threads > kMaxThreads)
    throw BindingInputError("threads: " + std::to_string(threads) +
                            " is out of range; give 0 (one thread per hardware thread) or a thread count from 1 to " +
                            std::to_string(kMaxThreads));
}

std::string describe_shape(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// The points argument as the delcert-points text and the name the reader reports it under.
struct PointsArgument {
  std::string name;       // the path, or "points"
  bool from_array = false;
  std::string array_text;  // for an array: its delcert-points v1 text
  std::size_t rows = 0;    // for an array: its number of rows
};

PointsArgument points_argument(const py::handle& obj, int N) {
  PointsArgument out;
  if (is_path(obj)) {
    out.name = path_text(obj);
    return out;
  }
  out.name = "points";
  out.from_array = true;
  py::array a = py::module_::import("numpy").attr("asarray")(obj);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw BindingInputError("points: expected a float64 array of shape (n, " + std::to_string(N) +
                            ") or a file path, got an array of dtype " + py::str(a.dtype()).cast<std::string>());
  if (a.ndim() != 2 || a.shape(1) != N)
    throw BindingInputError("points: expected an array of shape (n, " + std::to_string(N) + ") (the manifold lives in R^" +
                            std::to_string(N) + "), got shape " + describe_shape(a));
  auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!d) throw BindingInputError("points: cannot be converted to float64");
  io::PointSet ps;
  ps.dimension = N;
  ps.coordinates.assign(d.data(), d.data() + d.size());
  for (std::size_t k = 0; k < ps.coordinates.size(); ++k)
    if (!std::isfinite(ps.coordinates[k]))
      throw BindingInputError("points row " + std::to_string(k / N) + ": coordinate " + std::to_string(k % N) + " is " +
                              (std::isnan(ps.coordinates[k]) ? "NaN" : "infinite") + "; every coordinate must be finite");
  out.array_text = io::format_points(ps);
  out.rows = ps.size();
  return out;
}

// Reads the points as the command does (io::read_points with the manifold's dimension; duplicates
// refused), then checks them on M (manifold::check_on_manifold).
io::PointSet read_points_argument(const PointsArgument& p, const manifold::Manifold& manifold) {
  io::PointReadOptions options;
  options.expected_dimension = manifold.ambient_dimension();
  io::PointSet points =
      p.from_array ? io::parse_points(p.array_text, p.name, options) : io::read_points(p.name, options);
  manifold::check_on_manifold(manifold, points, p.name);
  return points;
}

py::array_t<double> to_array(const io::PointSet& points) {
  const auto n = static_cast<py::ssize_t>(points.size()), N = static_cast<py::ssize_t>(points.dimension);
  py::array_t<double> a({n, N});
  std::copy(points.coordinates.begin(), points.coordinates.end(), a.mutable_data());
  return a;
}

// The maximal simplices: an int64 array (k, d) when they all have d vertices (a pure complex,
// the usual case), else a list of int64 arrays.
py::object to_array(const io::Complex& complex, int m) {
  std::size_t d = complex.simplices.empty() ? static_cast<std::size_t>(m + 1) : complex.simplices.front().size();
  const bool uniform = std::all_of(complex.simplices.begin(), complex.simplices.end(),
                                   [d](const std::vector<int>& s) { return s.size() == d; });
  if (!uniform) {
    py::list out;
    for (const auto& s : complex.simplices) out.append(py::array_t<std::int64_t>(s.size(), std::vector<std::int64_t>(s.begin(), s.end()).data()));
    return out;
  }
  py::array_t<std::int64_t> a({static_cast<py::ssize_t>(complex.simplices.size()), static_cast<py::ssize_t>(d)});
  std::int64_t* out = a.mutable_data();
  for (const auto& s : complex.simplices) out = std::copy(s.begin(), s.end(), out);
  return a;
}

py::object json_to_python(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

manifold::Manifold read_manifold(const std::string& source) { return manifold::Manifold(io::read_spec(source)); }

// ------------------------------------------------------------------------------------------ sample

// As `delcert sample`'s --eps validator: a finite normal double > 0.
void check_eps(double eps) {
  const std::string give = "; give a number > 0, e.g. 0.25";
  const std::string shown = py::str(py::float_(eps)).cast<std::string>();
  if (std::isnan(eps)) throw BindingInputError("eps: " + shown + " is not a number" + give);
  if (std::isinf(eps)) throw BindingInputError("eps: " + shown + " is too large" + give);
  if (eps <= 0) throw BindingInputError("eps: " + shown + " is not positive" + give);
  if (eps < std::numeric_limits<double>::min()) throw BindingInputError("eps: " + shown + " is too small" + give);
}

py::array_t<double> py_sample(const py::object& manifold_arg, double eps, std::uint64_t seed) {
  const std::string source = path_text(manifold_arg);
  check_eps(eps);
  io::PointSet points = translating("", {}, [&] {
    py::gil_scoped_release release;
    manifold::Manifold manifold = read_manifold(source);
    sampling::EpsNetOptions options;
    options.eps = eps;
    options.seed = seed;
    sampling::check_eps_net_size(manifold, options);  // as `delcert sample`: refuse a run that cannot end
    auto net = sampling::eps_net(manifold, options);
    manifold::check_sample_on_manifold(manifold, net.points, source);
    return std::move(net.points);
  });
  return to_array(points);
}

// -------------------------------------------------------------------------------------- tangential

py::object py_tangential(const py::object& manifold_arg, const py::object& points_arg, int threads) {
  const std::string source = path_text(manifold_arg);
  check_threads(threads);
  manifold::Manifold manifold = translating("", {}, [&] { return read_manifold(source); });
  const int m = manifold.intrinsic_dimension();
  if (m < 2 || m > 4)
    throw BindingInputError(io::InputError(manifold.spec().source, 0,
                                           "intrinsic dimension " + std::to_string(m) +
                                               ": the tangential complex is implemented for m = 2, 3 and 4")
                                .what());
  const PointsArgument p = points_argument(points_arg, manifold.ambient_dimension());
  const std::vector<ArrayName> arrays{{"points"}};
  io::Complex complex = translating("", p.from_array ? arrays : std::vector<ArrayName>{}, [&] {
    py::gil_scoped_release release;
    io::PointSet points = read_points_argument(p, manifold);
    const int resolved = support::resolve_threads(threads);
    tangential::TangentPlanes planes;
    try {
      planes = tangential::compute_tangent_planes(manifold, points, resolved);
    } catch (const std::domain_error& e) {
      throw io::InputError(p.name, 0, e.what());
    }
    tangential::StarOptions options;
    options.threads = resolved;
    tangential::TangentialComplex tc;
    try {
      tc = tangential::TangentialComplex(points, planes, options);
    } catch (const std::invalid_argument& e) {
      throw io::InputError(p.name, 0, e.what());
    }
    tangential::Assembly assembly = tc.assemble(resolved);
    return std::move(assembly.complex);
  });
  return to_array(complex, m);
}

// ------------------------------------------------------------------------------------------ refine

// An exact constant as `delcert refine` takes it: a str ("0.1", "1/10", "1e-1"), an int, or a
// float (written as Python's repr, the shortest text that reads back to it).
std::string rational_text(const py::handle& obj, const std::string& option) {
  if (py::isinstance<py::bool_>(obj))
    throw BindingInputError(option + ": expected a number (str, int or float), got a bool");
  if (py::isinstance<py::str>(obj)) return obj.cast<std::string>();
  if (py::isinstance<py::int_>(obj)) return py::str(obj).cast<std::string>();
  if (py::isinstance<py::float_>(obj)) return py::repr(obj).cast<std::string>();
  throw BindingInputError(option + ": expected a number (str, int or float), got " +
                          py::str(py::type::of(obj).attr("__name__")).cast<std::string>());
}

py::dict py_refine(const py::object& manifold_arg, const py::object& points_arg, const py::object& eps_arg,
                       const std::string& mode, const py::object& gamma0, const py::object& alpha, const py::object& beta,
                       const py::object& delta0, std::uint64_t seed, int threads, std::size_t max_inserted,
                       std::size_t max_rounds, const py::object& out_arg, std::size_t max_points,
                       const std::string& sizing, const py::object& sizing_c_arg, const py::object& eps_floor_arg,
                       bool restricted_check, bool look_ahead) {
  const std::string source = path_text(manifold_arg);
  check_threads(threads);
  if (mode != "practical" && mode != "paper")
    throw BindingInputError("mode: '" + mode + "' is not one of practical, paper");
  if (sizing != "uniform" && sizing != "curvature")
    throw BindingInputError("sizing: '" + sizing + "' is not one of uniform, curvature");
  const bool curvature = sizing == "curvature";
  // As `delcert refine --sizing-c C --eps-floor F`: exact rationals, read by parse_rational_option
  // (None: not given; the command's default c = 1/2 and floor = eps/10).
  std::optional<std::string> sizing_c, eps_floor;
  if (!sizing_c_arg.is_none()) sizing_c = rational_text(sizing_c_arg, "--sizing-c");
  if (!eps_floor_arg.is_none()) eps_floor = rational_text(eps_floor_arg, "--eps-floor");
  refine::ConstantTexts texts;
  if (!eps_arg.is_none()) texts.eps = rational_text(eps_arg, "--eps");
  if (!delta0.is_none()) texts.delta0 = rational_text(delta0, "--delta0");
  texts.gamma0 = rational_text(gamma0, "--gamma0");
  texts.alpha = rational_text(alpha, "--alpha");
  texts.beta = rational_text(beta, "--beta");
  const std::string out = out_arg.is_none() ? std::string() : path_text(out_arg);
  const bool given_points = !points_arg.is_none();
  const std::string points_path = given_points && is_path(points_arg) ? path_text(points_arg) : std::string();

  // Every output is checked before any work, as the command does.
  translating("", {}, [&] {
    if (out.empty()) return 0;
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(out, ec) && !fs::is_directory(out, ec))
      throw io::InputError(out, 0, "--out: exists and is not a directory; refine writes a directory of four files");
    std::vector<std::string> outs;
    for (const char* f : {"points.txt", "complex.txt", "claims.json", "report.json"}) outs.push_back((fs::path(out) / f).string());
    if (curvature) outs.push_back((fs::path(out) / "eps.txt").string());
    for (const auto& o : outs) io::check_output_path(o, "--out", {source, points_path}, {}, true);
    return 0;
  });
  manifold::Manifold manifold = translating("", {}, [&] { return read_manifold(source); });
  const int m = manifold.intrinsic_dimension();
  auto input_error = [](const io::InputError& e) { return BindingInputError(e.what()); };
  if (m < 2 || m > 4)
    throw input_error(io::InputError(manifold.spec().source, 0,
                                     "intrinsic dimension " + std::to_string(m) + ": refinement is implemented for m = 2, 3 and 4"));
  if (!given_points && !texts.eps)
    throw input_error(io::InputError("delcert.refine", 0, "give points, or eps to start from an eps-net of M"));

  std::optional<PointsArgument> p;
  if (given_points) p = points_argument(points_arg, manifold.ambient_dimension());
  const std::vector<ArrayName> arrays = p && p->from_array ? std::vector<ArrayName>{{"points"}} : std::vector<ArrayName>{};

  refine::RefineResult result;
  std::string claims_json, report_json;
  translating("", arrays, [&] {
    refine::RefineParameters params;
    params.mode = mode == "paper" ? refine::RefineMode::paper : refine::RefineMode::practical;
    params.constants = refine::parse_constants(texts, m);
    // The sizing field, as `delcert refine` fills it (core/app/refine_command.cpp), same checks in
    // the same order.
    if (curvature) {
      if (params.mode == refine::RefineMode::paper)
        throw io::InputError("delcert.refine", 0,
                             "sizing='curvature' needs mode='practical' (the paper's Algorithm 1 uses one eps)");
      params.sizing.kind = refine::SizingKind::curvature;
      params.sizing.c = refine::parse_rational_option("--sizing-c", sizing_c ? *sizing_c : std::string("0.5"));
      if (eps_floor) params.sizing.floor = refine::parse_rational_option("--eps-floor", *eps_floor);
      if (!params.constants.eps)
        throw io::InputError("delcert.refine", 0, "sizing='curvature' needs eps (the field's cap)");
      try {
        refine::SizingField check = params.sizing;
        refine::resolve_sizing(check, *params.constants.eps);
      } catch (const refine::ParameterError& e) {
        throw io::InputError("delcert.refine", 0, e.what());
      }
    } else if (sizing_c || eps_floor) {
      throw io::InputError("delcert.refine", 0, "sizing_c and eps_floor need sizing='curvature'");
    }
    params.seed = seed;
    params.threads = threads;
    params.max_inserted = max_inserted;
    params.max_rounds = max_rounds;
    params.max_points = max_points;
    params.restricted_check = restricted_check;
    params.look_ahead = look_ahead;
    py::gil_scoped_release release;
    io::PointSet input;
    std::string input_text;
    if (p) {
      input = read_points_argument(*p, manifold);
      input_text = p->from_array ? "a numpy array (delcert.refine)" : p->name;
    } else {
      sampling::EpsNetOptions eo;
      eo.eps = refine::as_doubles(params.constants).eps;
      eo.seed = seed;
      sampling::check_eps_net_size(manifold, eo);  // as `delcert refine --eps`: refuse a run that cannot end
      int halvings = 0;  // as `delcert refine --eps`: a net of at least m + 2 points
      auto net = sampling::eps_net_with_at_least(manifold, eo, static_cast<std::size_t>(m + 2), &halvings);
      manifold::check_sample_on_manifold(manifold, net.points, source);
      input = std::move(net.points);
      std::string net_eps = params.constants.eps.value().text;
      if (halvings > 0) net_eps = "(" + net_eps + ")/" + std::to_string(1L << halvings);
      input_text = "eps-net of " + manifold.spec().name + " (delcert sample --eps " + net_eps + " --seed " +
                   std::to_string(seed) + ")";
    }
    const std::string where = p ? p->name : std::string("delcert.refine");
    try {
      result = refine::refine(manifold, input, params);
    } catch (const std::invalid_argument& e) {
      throw io::InputError(where, 0, e.what());
    } catch (const std::domain_error& e) {
      throw io::InputError(where, 0, e.what());
    }
    refine::OutputContext ctx;
    ctx.manifold = manifold.spec().name;
    ctx.manifold_source = manifold.spec().source;
    ctx.input = input_text;
    const refine::ClaimsOutcome claims = refine::make_claims(result);
    claims_json = claims.json;
    report_json = refine::make_report(result, ctx, claims);
    if (!out.empty()) refine::write_refine_output(out, result, ctx);
    return 0;
  });
  py::dict d;
  d["points"] = to_array(result.points);
  d["complex"] = to_array(result.complex, m);
  d["claims"] = json_to_python(claims_json);
  d["report"] = json_to_python(report_json);
  d["converged"] = result.converged;
  d["input_size"] = result.input_size;
  if (curvature) {
    // ε(p) per point, the doubles the refiner used (eps.txt holds each as the 6-digit decimal at
    // or above it, at most eps).
    py::array_t<double> e(static_cast<py::ssize_t>(result.local_eps.size()));
    std::copy(result.local_eps.begin(), result.local_eps.end(), e.mutable_data());
    d["eps_per_point"] = e;
  }
  return d;
}

// ----------------------------------------------------------------------------------------- certify

// A private temporary folder, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    path_ = (std::filesystem::temp_directory_path() / "delcert-python-XXXXXX").string();
    if (mkdtemp(path_.data()) == nullptr) throw std::runtime_error("cannot create a temporary directory");
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// The complex argument as delcert-complex text: an int array (k, d) or a sequence of sequences of ints.
std::string complex_text(const py::handle& obj, std::size_t num_vertices) {
  io::Complex c;
  c.num_vertices = num_vertices;
  auto add_row = [&](const py::array& row, std::size_t r) {
    const char kind = row.dtype().kind();
    if (kind != 'i' && kind != 'u' && !(kind == 'f' && row.size() == 0))
      throw BindingInputError("complex row " + std::to_string(r) + ": expected integer vertex indices, got dtype " +
                              py::str(row.dtype()).cast<std::string>());
    auto ints = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(row);
    std::vector<int> s;
    for (py::ssize_t k = 0; k < ints.size(); ++k) {
      const std::int64_t v = ints.data()[k];
      if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
        throw BindingInputError("complex row " + std::to_string(r) + ": vertex index " + std::to_string(v) +
                                " is out of range");
      s.push_back(static_cast<int>(v));
    }
    c.simplices.push_back(std::move(s));
  };
  py::object np = py::module_::import("numpy");
  if (py::isinstance<py::array>(obj)) {
    py::array a = py::reinterpret_borrow<py::array>(obj);
    const char kind = a.dtype().kind();
    if (kind != 'i' && kind != 'u')
      throw BindingInputError("complex: expected an integer array of shape (k, m+1) or a file path, got dtype " +
                              py::str(a.dtype()).cast<std::string>());
    if (a.ndim() != 2) throw BindingInputError("complex: expected an array of shape (k, m+1), got shape " + describe_shape(a));
    for (py::ssize_t r = 0; r < a.shape(0); ++r)
      add_row(np.attr("asarray")(a.attr("__getitem__")(py::int_(r))), static_cast<std::size_t>(r));
  } else {
    if (!py::isinstance<py::sequence>(obj))
      throw BindingInputError("complex: expected an integer array of shape (k, m+1), a list of simplices or a file path");
    std::size_t r = 0;
    for (const auto& row : obj) add_row(np.attr("asarray")(row), r++);
  }
  return io::format_complex(c);
}

// The values of delcert-certify --complex-format.
constexpr const char* kComplexFormats[] = {"auto", "delcert", "off", "obj", "ply", "stl", "gudhi"};

py::object py_certify(const py::object& manifold_arg, const py::object& points_arg, const py::object& complex_arg,
                           const py::object& kind_arg, const py::object& claims_arg, int threads, bool skip_restricted,
                           bool times, const std::string& complex_format, const py::object& residual_tolerance_arg,
                           const py::object& out_arg, const py::object& report_arg, const py::object& fix_out_arg) {
  check_threads(threads);
  certify::CertifyOptions o;
  o.manifold = path_text(manifold_arg);
  // --complex-format: one of the command's values (run_certify itself would read an unknown name as auto).
  if (std::find_if(std::begin(kComplexFormats), std::end(kComplexFormats),
                   [&](const char* f) { return complex_format == f; }) == std::end(kComplexFormats))
    throw BindingInputError("complex_format: '" + complex_format +
                            "' is not one of auto, delcert, off, obj, ply, stl, gudhi");
  if (complex_format != "auto" && complex_arg.is_none())
    throw BindingInputError("complex_format needs complex (it says how to read the given complex file)");
  if (complex_format != "auto" && complex_format != "delcert" && !complex_arg.is_none() && !is_path(complex_arg))
    throw BindingInputError("complex_format: '" + complex_format +
                            "' names the format of a complex file; an array or list of simplices is given as it is "
                            "(leave complex_format out, or give 'delcert')");
  o.complex_format = complex_format;
  // --residual-tolerance: exact, as on the command line (a float is written as its repr); it is
  // read, and refused with the command's message, by run_certify.
  if (!residual_tolerance_arg.is_none()) o.residual_tolerance = rational_text(residual_tolerance_arg, "--residual-tolerance");
  const std::string out = out_arg.is_none() ? std::string() : path_text(out_arg);
  const std::string report_path = report_arg.is_none() ? std::string() : path_text(report_arg);
  const std::string fix_out = fix_out_arg.is_none() ? std::string() : path_text(fix_out_arg);
  if (!fix_out.empty() && !is_path(complex_arg))
    throw BindingInputError("fix_out needs complex given as a surface mesh file (OFF, OBJ, PLY or STL): the fixed "
                            "mesh is written in that file's format and vertex numbering");
  o.threads = threads == 0 ? static_cast<int>(std::max(1u, std::thread::hardware_concurrency())) : threads;
  o.skip_restricted = skip_restricted;
  if (!kind_arg.is_none()) {
    const std::string kind = kind_arg.cast<std::string>();
    if (kind != "tangential" && kind != "restricted" && kind != "intrinsic")
      throw BindingInputError("kind: '" + kind + "' is not one of tangential, restricted, intrinsic");
    if (complex_arg.is_none())
      throw BindingInputError("kind needs complex (it says what the given complex is claimed to be)");
    o.kind = kind == "restricted"  ? certify::ComplexKind::restricted
             : kind == "intrinsic" ? certify::ComplexKind::intrinsic
                                   : certify::ComplexKind::tangential;
  }
  if (const std::string why = exact::directed_rounding_failure(); !why.empty())
    throw std::runtime_error("internal error: directed rounding does not work on this machine or build (" + why +
                             "); no enclosure could be trusted");

  TempDir temp;
  const std::string prefix = temp.path() + "/";
  std::vector<ArrayName> arrays;
  std::size_t num_points = 0;
  bool num_points_known = false;
  if (is_path(points_arg)) {
    o.points = path_text(points_arg);
  } else {
    // The dimension is the manifold's (the reader checks it again); its errors are reported by run_certify.
    const int N = translating("", {}, [&] { return io::read_spec(o.manifold).ambient_dimension; });
    const PointsArgument p = points_argument(points_arg, N);
    o.points = prefix + "points";
    io::write_file_atomically(o.points, p.array_text);
    arrays.push_back({"points"});
    num_points = p.rows;
    num_points_known = true;
  }
  if (!complex_arg.is_none()) {
    if (is_path(complex_arg)) {
      o.complex = path_text(complex_arg);
    } else {
      if (!num_points_known) {
        // The vertex count of the text is the number of points; a points file that cannot be
        // read is reported by run_certify below (the count then only needs to be some number).
        try {
          num_points = io::read_points(o.points, {0, false}).size();
        } catch (const io::InputError&) {
        }
      }
      o.complex = prefix + "complex";
      io::write_file_atomically(o.complex, complex_text(complex_arg, num_points));
      arrays.push_back({"complex"});
    }
  }
  if (!claims_arg.is_none()) {
    if (is_path(claims_arg)) {
      o.claims = path_text(claims_arg);
    } else {
      if (!py::isinstance<py::dict>(claims_arg))
        throw BindingInputError("claims: expected a dict (the claims.json object) or a file path");
      o.claims = prefix + "claims";
      io::write_file_atomically(o.claims,
                                py::module_::import("json").attr("dumps")(claims_arg, py::arg("indent") = 2).cast<std::string>() + "\n");
    }
  }
  // The outputs, as delcert-certify --out and --report: checked before any work (not an input, a
  // writable folder, not each other), then written together or not at all, after the certificate.
  translating(prefix, arrays, [&] {
    const std::vector<std::string> inputs{o.manifold, o.points, o.complex, o.claims};
    if (!out.empty()) io::check_output_path(out, "--out", inputs);
    if (!report_path.empty() && !report::viewer_available())
      throw BindingInputError(report::viewer_missing_message());  // as delcert-certify --report
    if (!report_path.empty()) io::check_output_path(report_path, "--report", inputs, {out});
    if (!fix_out.empty()) io::check_fix_out(fix_out, o.manifold, o.complex, o.complex_format, inputs, {out, report_path});
    return 0;
  });
  std::string text = translating(prefix, arrays, [&] {
    py::gil_scoped_release release;
    certify::Certificate cert = certify::run_certify(o);
    // A surface mesh: its non-Delaunay edges in its file's numbering and fix_out's mesh, as delcert-certify adds them.
    const io::MeshReport mesh = io::report_mesh(cert.inputs, cert.parameters["kind"] == "restricted", cert.restricted_complex,
                                                cert.checks[11].details.value("reason", cert.checks[11].summary), fix_out,
                                                certify::detail::Sha256::hex);
    if (!mesh.json.is_null()) cert.inputs["complex"]["mesh_feedback"] = mesh.json;
    std::string t = cert.to_text(times);
    // The certificate names its inputs: a temporary file is named as its argument ("points", ...).
    for (std::size_t at; (at = t.find(prefix)) != std::string::npos;) t.erase(at, prefix.size());
    std::vector<std::pair<std::string, std::string>> files;
    if (mesh.fixed_mesh) files.emplace_back(fix_out, *mesh.fixed_mesh);
    if (!out.empty()) files.emplace_back(out, t);  // the bytes of the returned certificate
    // The page reads the points and the complex from the files run_certify read (the temporary
    // copies of arrays are still there).
    if (!report_path.empty())
      files.emplace_back(report_path, report::format_html_report(nlohmann::json::parse(t), o.points, o.complex));
    io::write_files_atomically(files);
    return t;
  });
  return json_to_python(text);
}

}  // namespace

PYBIND11_MODULE(delcert, m) {
  m.doc() =
      "delcert: certified Delaunay triangulations of manifolds.\n\n"
      "sample, tangential, refine and certify do what the commands `delcert sample`, `delcert tangential`,\n"
      "`delcert refine` and `delcert-certify` do, on numpy arrays: points are float64 arrays (n, N),\n"
      "simplices int64 arrays (k, m+1) of 0-based point indices. A manifold is 'builtin:NAME' or a spec\n"
      "file path. Bad input raises delcert.InputError (a ValueError) with the command's message.";
  m.attr("__version__") = DELCERT_VERSION;
  static py::exception<BindingInputError>& input_error =
      py::register_exception<BindingInputError>(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const io::InputError& e) {  // not caught by `translating`: no array names to rewrite
      PyErr_SetString(input_error.ptr(), e.what());
    }
  });

  m.def("builtin_manifolds", &io::builtin_spec_names, "Names of the built-in manifolds (use as 'builtin:NAME').");

  m.def("sample", &py_sample, py::arg("manifold"), py::arg("eps"), py::arg("seed") = 1,
        "An eps-net of M by farthest-point selection from a dense sample (`delcert sample`):\n"
        "a float64 array (n, N), the same for the same manifold, eps and seed.");

  m.def("tangential", &py_tangential, py::arg("manifold"), py::arg("points"), py::arg("threads") = 0,
        "The tangential Delaunay complex Del_TM(P) of points on M (`delcert tangential`): its maximal\n"
        "simplices, sorted, as an int64 array (k, m+1) (a list of arrays if they differ in size).\n"
        "points: a float64 array (n, N) or a points file path.");

  m.def("refine", &py_refine, py::arg("manifold"), py::arg("points") = py::none(), py::arg("eps") = py::none(),
        py::arg("mode") = "practical", py::arg("gamma0") = "0.15", py::arg("alpha") = "0.3", py::arg("beta") = "1.1",
        py::arg("delta0") = py::none(), py::arg("seed") = 1, py::arg("threads") = 0, py::arg("max_inserted") = 0,
        py::arg("max_rounds") = 0, py::arg("out") = py::none(), py::arg("max_points") = 0,
        py::arg("sizing") = "uniform", py::arg("sizing_c") = py::none(), py::arg("eps_floor") = py::none(),
        py::arg("restricted_check") = true, py::arg("look_ahead") = false,
        "Refines a sample of M until its tangential complex is thick, protected and consistent\n"
        "(`delcert refine`). Start from points (an array or a file path) or, without them, from an\n"
        "eps-net. The constants are exact: give them as str ('0.25', '1/4'), int or float. Returns a\n"
        "dict: points, complex, claims (claims.json as a dict), report (report.json as a dict),\n"
        "converged, input_size. out=DIR also writes the four files, as `delcert refine --out DIR`.\n"
        "sizing='uniform' (one eps, the default) or 'curvature' (`--sizing curvature`, practical mode,\n"
        "needs eps): eps(x) = min(eps, max(eps_floor, sizing_c / kappa_max(x))), sizing_c exact\n"
        "(default 1/2), eps_floor exact (default eps/10); sizing_c and eps_floor only with 'curvature'.\n"
        "With 'curvature' claims is version 3, the dict also has eps_per_point (float64 array (n,),\n"
        "eps(p) per point as the refiner used it, each <= eps), and out=DIR also writes eps.txt.\n"
        "restricted_check=False is `--no-restricted-check` (no not_restricted rule); look_ahead=True is\n"
        "`--look-ahead`.");

  m.def("certify", &py_certify, py::arg("manifold"), py::arg("points"), py::arg("complex") = py::none(),
        py::arg("kind") = py::none(), py::arg("claims") = py::none(), py::arg("threads") = 0,
        py::arg("skip_restricted") = false, py::arg("times") = true, py::arg("complex_format") = "auto",
        py::arg("residual_tolerance") = py::none(), py::arg("out") = py::none(), py::arg("report") = py::none(),
        py::arg("fix_out") = py::none(),
        "The independent certificate (`delcert-certify`), as a dict: certificate['verdict'] is\n"
        "'CERTIFIED', 'REFUTED' or 'UNDECIDED'. Each option is the command's flag of the same name:\n"
        "  points              array (n, N) or file path (--points)\n"
        "  complex             int array (k, m+1), list of simplices or file path (--complex; None: audit\n"
        "                      the points' own Del_TM)\n"
        "  kind                'tangential', 'restricted' or 'intrinsic' (--kind; needs complex)\n"
        "  complex_format      how to read a complex file: 'auto' (detected, the default), 'delcert', 'off',\n"
        "                      'obj', 'ply', 'stl' or 'gudhi' (--complex-format; needs complex; an array or\n"
        "                      list is given as it is: 'auto' or 'delcert' only)\n"
        "  residual_tolerance  largest |F_i(p)| accepted for an input point, replacing the spec's\n"
        "                      (--residual-tolerance): a str read exactly ('1e-6', '1/1000000'), an int, or a\n"
        "                      float (its repr); recorded in the certificate's inputs.residual_tolerance\n"
        "  claims              dict or claims.json path (--claims)\n"
        "  threads             0 (one per hardware thread) or 1 to 256 (--threads)\n"
        "  skip_restricted     True: no checks 11-15 (--skip-restricted)\n"
        "  times               False leaves the wall-clock times out (--no-times)\n"
        "  out                 also write the certificate JSON to this path, the bytes of the returned\n"
        "                      dict (--out)\n"
        "  report              also write the certificate as a self-contained HTML page (--report)\n"
        "  fix_out             a surface mesh file given as complex: when check 12 proves Del_RM(P) complete\n"
        "                      and pure, write its triangles to this path in the mesh's format and vertex\n"
        "                      numbering (--fix-out); certificate['inputs']['complex']['mesh_feedback'] lists\n"
        "                      the mesh's non-Delaunay edges in the file's numbering\n"
        "out, report and fix_out are checked before any work (not an input, in an existing folder, not each\n"
        "other) and written together, atomically, or not at all: bad input raises InputError and\n"
        "writes nothing. Whatever the verdict, the certificate is returned (and written).");
}

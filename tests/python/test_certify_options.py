"""delcert.certify()'s options that are delcert-certify's flags of the same name (issue 41):
complex_format (--complex-format), residual_tolerance (--residual-tolerance), out (--out) and
report (--report) and fix_out (--fix-out). Each is checked against the command on the same files, and bad values are
refused with InputError (a ValueError) and no file written. Run by ctest (label "python") with
PYTHONPATH, DELCERT_BINARY_DIR and DELCERT_FIXTURES_DIR set (tests/CMakeLists.txt).
"""
import json
import os
import pathlib
import re
import shutil
import subprocess

import numpy as np
import pytest

import delcert

BINARY_DIR = pathlib.Path(os.environ.get("DELCERT_BINARY_DIR", "build"))
FIXTURES = pathlib.Path(os.environ.get("DELCERT_FIXTURES_DIR", "fixtures"))
THREADS = 2
OCTAHEDRON = FIXTURES / "points" / "octahedron.off"
MISSING = FIXTURES / "certify" / "octahedron-missing.complex"  # one triangle of the octahedron left out
# The octahedron scaled by 1 + 1e-7: |F(p)| = 2.0000001e-7 at every vertex, above sphere-2's 1e-9.
OFF_SPHERE = FIXTURES / "meshes" / "octahedron-off-sphere.obj"


def rows(path, header_lines, dtype):
    """The rows of a delcert or OFF file: its lines after `header_lines` lines that are not comments."""
    lines = [line for line in pathlib.Path(path).read_text().splitlines() if line.strip() and not line.startswith("#")]
    return np.array([[dtype(x) for x in line.split()] for line in lines[header_lines:]])


def run_certify_cli(*args):
    result = subprocess.run([str(BINARY_DIR / "delcert-certify"), *map(str, args)], capture_output=True, text=True)
    return result.returncode, result.stdout, result.stderr


def test_the_options_are_the_commands_flags():
    # Every option of delcert-certify's --help but --halo (MPI ranks only) and --no-times (times=False,
    # as refine's restricted_check=False is --no-restricted-check) is a keyword of certify().
    _, help_text, _ = run_certify_cli("--help")
    flags = set(re.findall(r"(?<![\w-])--[a-z][a-z-]*[a-z]", help_text))
    flags -= {"--help", "--version", "--halo", "--no-times"}
    assert {"--manifold", "--points", "--complex", "--complex-format", "--residual-tolerance", "--out",
            "--report"} <= flags, flags
    doc = delcert.certify.__doc__
    signature = doc.splitlines()[0]
    keywords = set(re.findall(r"(\w+): ", signature))
    for flag in sorted(flags):
        assert flag[2:].replace("-", "_") in keywords, (flag, signature)
        if flag != "--manifold":
            assert f"({flag}" in doc, (flag, "not named in the docstring")
    assert "times: bool = True" in signature


# ------------------------------------------------------------------------------------------- out

def test_out_holds_the_returned_certificate_byte_for_byte_as_the_command(tmp_path):
    out = tmp_path / "py.json"
    cert = delcert.certify("builtin:sphere-2", OCTAHEDRON, MISSING, threads=THREADS, times=False, out=out)
    assert cert["verdict"] == "REFUTED"  # written whatever the verdict, as --out
    assert json.loads(out.read_text()) == cert
    code, _, err = run_certify_cli("--manifold", "builtin:sphere-2", "--points", OCTAHEDRON, "--complex", MISSING,
                                   "--threads", THREADS, "--no-times", "--out", tmp_path / "cli.json")
    assert code == 1, err
    assert out.read_bytes() == (tmp_path / "cli.json").read_bytes()
    # From arrays: the file names the inputs as the dict does ("points", "complex").
    points = rows(OCTAHEDRON, 2, float)
    triangles = rows(MISSING, 2, int)
    again = delcert.certify("builtin:sphere-2", points, triangles, threads=THREADS, times=False, out=out)
    assert json.loads(out.read_text()) == again
    assert again["inputs"]["points"]["path"] == "points" and again["verdict"] == "REFUTED"


def test_out_is_checked_before_any_work_and_not_written_on_bad_input(tmp_path):
    out = tmp_path / "cert.json"
    # An output that is an input is refused, as by the command, and the input is untouched.
    copy = tmp_path / "points.off"
    shutil.copy(OCTAHEDRON, copy)
    with pytest.raises(delcert.InputError, match="--out"):
        delcert.certify("builtin:sphere-2", copy, MISSING, out=copy)
    assert copy.read_bytes() == OCTAHEDRON.read_bytes()
    with pytest.raises(delcert.InputError, match="--out"):
        delcert.certify("builtin:sphere-2", OCTAHEDRON, MISSING, out=tmp_path / "no-such-folder" / "c.json")
    # Bad input: no certificate.
    with pytest.raises(delcert.InputError, match="wrong-count"):
        delcert.certify("builtin:sphere-2", OCTAHEDRON, FIXTURES / "certify" / "octahedron-wrong-count.complex",
                        out=out)
    assert not out.exists()


# ---------------------------------------------------------------------------------------- report

def test_report_is_the_commands_page_and_shows_the_verdict(tmp_path):
    out, page = tmp_path / "py.json", tmp_path / "py.html"
    cert = delcert.certify("builtin:sphere-2", OCTAHEDRON, MISSING, threads=THREADS, times=False, out=out,
                           report=page)
    html = page.read_text()
    assert html.startswith("<!DOCTYPE html>") or html.lstrip().lower().startswith("<!doctype html")
    assert f'<p id="overall" class="verdict-{cert["verdict"]}">verdict: <span class="verdict">REFUTED</span></p>' in html
    code, _, err = run_certify_cli("--manifold", "builtin:sphere-2", "--points", OCTAHEDRON, "--complex", MISSING,
                                   "--threads", THREADS, "--no-times", "--out", tmp_path / "cli.json",
                                   "--report", tmp_path / "cli.html")
    assert code == 1, err
    assert page.read_bytes() == (tmp_path / "cli.html").read_bytes()
    # Audit mode (no complex) and arrays: a page too, with its verdict.
    net = delcert.sample("builtin:sphere-2", eps=0.5, seed=1)
    audit = delcert.certify("builtin:sphere-2", net, threads=THREADS, skip_restricted=True, report=page)
    assert f'class="verdict-{audit["verdict"]}">verdict: <span class="verdict">{audit["verdict"]}</span>' in page.read_text()


def test_report_and_out_are_written_together_or_not_at_all(tmp_path):
    out, page = tmp_path / "c.json", tmp_path / "r.html"
    with pytest.raises(delcert.InputError, match="--report"):
        delcert.certify("builtin:sphere-2", OCTAHEDRON, MISSING, out=out, report=out)
    with pytest.raises(delcert.InputError, match="--report"):
        delcert.certify("builtin:sphere-2", OCTAHEDRON, MISSING, report=MISSING)
    with pytest.raises(delcert.InputError):
        delcert.certify("builtin:sphere-2", OCTAHEDRON, FIXTURES / "certify" / "octahedron-wrong-count.complex",
                        out=out, report=page)
    assert not out.exists() and not page.exists()
    assert list(tmp_path.iterdir()) == []  # no temporary left beside them either


# -------------------------------------------------------------------------------- complex_format

def test_complex_format_reads_a_file_detection_cannot(tmp_path):
    # An OBJ mesh under a name without its extension: detection refuses it, complex_format='obj'
    # reads it, and the certificate is the command's with --complex-format obj.
    mesh = tmp_path / "octahedron-mesh.txt"
    shutil.copy(FIXTURES / "meshes" / "octahedron.obj", mesh)
    with pytest.raises(delcert.InputError, match="octahedron-mesh.txt"):
        delcert.certify("builtin:sphere-2", OCTAHEDRON, mesh, threads=THREADS)
    cert = delcert.certify("builtin:sphere-2", OCTAHEDRON, mesh, complex_format="obj", kind="tangential",
                           threads=THREADS, times=False)
    assert cert["verdict"] == "CERTIFIED"
    assert cert["inputs"]["complex"]["read"]["format"] == "obj"
    assert cert["inputs"]["complex"]["simplices"] == 8
    code, stdout, err = run_certify_cli("--manifold", "builtin:sphere-2", "--points", OCTAHEDRON, "--complex", mesh,
                                        "--complex-format", "obj", "--kind", "tangential", "--threads", THREADS,
                                        "--no-times", "--out", tmp_path / "cli.json")
    assert code == 0, err
    assert json.loads((tmp_path / "cli.json").read_text()) == cert
    # The ambiguous fixture: refused with the message naming --complex-format, as by the command.
    ambiguous = FIXTURES / "meshes" / "ambiguous.txt"
    with pytest.raises(delcert.InputError) as e:
        delcert.certify("builtin:sphere-2", OCTAHEDRON, ambiguous)
    code, _, err = run_certify_cli("--manifold", "builtin:sphere-2", "--points", OCTAHEDRON, "--complex", ambiguous)
    assert code == 2 and err.strip() == "delcert-certify: " + str(e.value)
    assert "--complex-format gudhi" in str(e.value)
    # A named format is used whatever the content: a GUDHI list read as OFF is refused.
    with pytest.raises(delcert.InputError):
        delcert.certify("builtin:sphere-2", OCTAHEDRON, FIXTURES / "meshes" / "octahedron.gudhi", complex_format="off")
    assert delcert.certify("builtin:sphere-2", OCTAHEDRON, FIXTURES / "meshes" / "octahedron.gudhi",
                           complex_format="gudhi", threads=THREADS)["inputs"]["complex"]["read"]["format"] == "gudhi"


def test_bad_complex_format_is_refused():
    triangles = rows(FIXTURES / "certify" / "octahedron.complex", 2, int)
    with pytest.raises(delcert.InputError, match="complex_format: 'xyz' is not one of auto, delcert, off"):
        delcert.certify("builtin:sphere-2", OCTAHEDRON, MISSING, complex_format="xyz")
    with pytest.raises(delcert.InputError, match="complex_format needs complex"):
        delcert.certify("builtin:sphere-2", OCTAHEDRON, complex_format="gudhi")
    with pytest.raises(delcert.InputError, match="complex_format: 'obj' names the format of a complex file"):
        delcert.certify("builtin:sphere-2", OCTAHEDRON, triangles, complex_format="obj")
    # 'delcert' is what an array is written as: accepted.
    assert delcert.certify("builtin:sphere-2", OCTAHEDRON, triangles, complex_format="delcert",
                           threads=THREADS)["verdict"] == "CERTIFIED"


# ---------------------------------------------------------------------------- residual_tolerance

def test_residual_tolerance_admits_points_the_spec_refuses_and_is_recorded(tmp_path):
    # Claimed tangential, the points must be on M within the tolerance: refused with the spec's 1e-9...
    with pytest.raises(delcert.InputError, match="not on M.*--residual-tolerance"):
        delcert.certify("builtin:sphere-2", OFF_SPHERE, OFF_SPHERE, kind="tangential", threads=THREADS)
    # ... certified with 1e-6, given as text, fraction or float, each read exactly.
    for tolerance in ("1e-6", "1/1000000", 1e-6):
        cert = delcert.certify("builtin:sphere-2", OFF_SPHERE, OFF_SPHERE, kind="tangential", threads=THREADS,
                               residual_tolerance=tolerance, times=False)
        assert cert["verdict"] == "CERTIFIED", tolerance
        assert cert["inputs"]["residual_tolerance"] == {"source": "--residual-tolerance", "value": "0.000001"}
        assert cert["checks"][0]["details"]["off_manifold_points"] == 0
    # The same certificate as the command's with the flag.
    code, _, err = run_certify_cli("--manifold", "builtin:sphere-2", "--points", OFF_SPHERE, "--complex", OFF_SPHERE,
                                   "--kind", "tangential", "--threads", THREADS, "--residual-tolerance", "1e-6",
                                   "--no-times", "--out", tmp_path / "cli.json")
    assert code == 0, err
    assert json.loads((tmp_path / "cli.json").read_text()) == cert
    # A mesher's output (restricted, the default for meshes) is read either way; the tolerance
    # decides which points the certificate counts as off M.
    spec = delcert.certify("builtin:sphere-2", OFF_SPHERE, OFF_SPHERE, threads=THREADS, skip_restricted=False)
    assert spec["inputs"]["residual_tolerance"]["source"] == "the manifold spec"
    assert spec["checks"][0]["details"]["off_manifold_points"] == 6
    # From an array too (the module writes it to a file run_certify reads, as a points file).
    points = OFF_SPHERE.read_text().splitlines()
    coords = np.array([[float(x) for x in line.split()[1:]] for line in points if line.startswith("v ")])
    faces = np.array([[int(x) - 1 for x in line.split()[1:]] for line in points if line.startswith("f ")])
    with pytest.raises(delcert.InputError, match="not on M"):
        delcert.certify("builtin:sphere-2", coords, faces, kind="tangential", threads=THREADS)
    assert delcert.certify("builtin:sphere-2", coords, faces, kind="tangential", threads=THREADS,
                           residual_tolerance="1e-6")["verdict"] == "CERTIFIED"


def test_bad_residual_tolerance_is_refused_with_the_commands_message(tmp_path):
    out = tmp_path / "c.json"
    for bad in ("0", "-1e-6", "abc", "inf", "nan"):
        with pytest.raises(delcert.InputError) as e:
            delcert.certify("builtin:sphere-2", OFF_SPHERE, OFF_SPHERE, residual_tolerance=bad, out=out)
        code, _, err = run_certify_cli("--manifold", "builtin:sphere-2", "--points", OFF_SPHERE, "--complex",
                                       OFF_SPHERE, f"--residual-tolerance={bad}")
        assert code == 2 and err.strip() == "delcert-certify: " + str(e.value), bad
        assert not out.exists()
    with pytest.raises(delcert.InputError, match="--residual-tolerance: expected a number"):
        delcert.certify("builtin:sphere-2", OFF_SPHERE, OFF_SPHERE, residual_tolerance=[1e-6])


# ------------------------------------------------------------------------------------------ fix_out

# CGAL's sphere mesh with the edge 0-12 (0-based) of its face 0 flipped to 58-196, written by
# fixtures/meshes/make_meshes.py (the same fixture as docs/tutorial.md).
FLIPPED = FIXTURES / "meshes" / "sphere-one-flip.obj"
FLIPPED_EDGE, ITS_FLIP = (58, 196), (0, 12)


def test_fix_out_writes_the_commands_fixed_mesh_and_the_edges_are_in_the_certificate(tmp_path):
    mesh, fixed, cli_fixed = FLIPPED, tmp_path / "fixed.obj", tmp_path / "cli-fixed.obj"
    (c, d), (a, b) = FLIPPED_EDGE, ITS_FLIP
    cert = delcert.certify("builtin:sphere-2", mesh, mesh, threads=THREADS, times=False, fix_out=fixed,
                           out=tmp_path / "py.json")
    assert cert["verdict"] == "REFUTED"
    feedback = cert["inputs"]["complex"]["mesh_feedback"]
    assert feedback["non_delaunay_edges_total"] == 1
    edge = feedback["non_delaunay_edges"][0]
    assert [v["file_index"] for v in edge["edge"]] == [min(c, d) + 1, max(c, d) + 1]  # OBJ numbering, from 1
    assert [v["file_index"] for v in edge["flip"]["to"]] == [min(a, b) + 1, max(a, b) + 1]
    # The command's fixed mesh and certificate, byte for byte.
    code, _, err = run_certify_cli("--manifold", "builtin:sphere-2", "--points", mesh, "--complex", mesh,
                                   "--threads", THREADS, "--no-times", "--fix-out", cli_fixed,
                                   "--out", tmp_path / "cli.json")
    assert code == 1, err
    assert fixed.read_bytes() == cli_fixed.read_bytes()
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "cli.json").read_bytes()
    # The fixed mesh certifies, and has nothing to say about its edges.
    again = delcert.certify("builtin:sphere-2", fixed, fixed, threads=THREADS)
    assert again["verdict"] == "CERTIFIED"
    assert "mesh_feedback" not in again["inputs"]["complex"]


def test_fix_out_is_refused_before_any_work_where_it_cannot_be_written(tmp_path):
    mesh = FLIPPED
    with pytest.raises(delcert.InputError, match="fix_out needs complex given as a surface mesh file"):
        delcert.certify("builtin:sphere-2", OCTAHEDRON, [[0, 1, 2]], fix_out=tmp_path / "x.obj")
    with pytest.raises(delcert.InputError, match="--fix-out"):  # not the mesh's format
        delcert.certify("builtin:sphere-2", mesh, mesh, fix_out=tmp_path / "x.stl", out=tmp_path / "c.json")
    with pytest.raises(delcert.InputError, match="--fix-out"):  # the input itself
        delcert.certify("builtin:sphere-2", mesh, mesh, fix_out=mesh)
    assert list(tmp_path.iterdir()) == []

"""The Python module `delcert` (python/delcert_module.cpp), run by ctest (label "python").

ctest sets PYTHONPATH to the built module's folder and DELCERT_BINARY_DIR / DELCERT_FIXTURES_DIR
(the programs, to compare the module's certificates with delcert-certify's on the same files).
"""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import delcert

BINARY_DIR = pathlib.Path(os.environ.get("DELCERT_BINARY_DIR", "build"))
FIXTURES = pathlib.Path(os.environ.get("DELCERT_FIXTURES_DIR", "fixtures"))
THREADS = 2


@pytest.fixture(scope="module")
def sphere_net():
    return delcert.sample("builtin:sphere-2", eps=0.4, seed=3)


@pytest.fixture(scope="module")
def torus_refined():
    return delcert.refine("builtin:clifford-torus-2", eps="0.25", seed=1, threads=THREADS)


def write_points(path, points):
    lines = ["delcert-points v1", f"{points.shape[1]} {points.shape[0]}"]
    lines += [" ".join(repr(float(x)) for x in row) for row in points]
    path.write_text("\n".join(lines) + "\n")


def write_complex(path, num_vertices, simplices):
    lines = ["delcert-complex v1", f"{num_vertices} {len(simplices)}"]
    lines += [" ".join(str(int(v)) for v in s) for s in simplices]
    path.write_text("\n".join(lines) + "\n")


def run_certify_cli(*args):
    result = subprocess.run([str(BINARY_DIR / "delcert-certify"), *map(str, args)], capture_output=True, text=True)
    return result.returncode, result.stdout, result.stderr


# ------------------------------------------------------------------------------------------ sample

def test_sample_is_on_the_sphere_and_seeded(sphere_net):
    assert sphere_net.dtype == np.float64
    assert sphere_net.ndim == 2 and sphere_net.shape[1] == 3
    assert sphere_net.shape[0] > 20
    # On S^2 up to the spec's residual tolerance (1e-9 on |x|^2 - 1).
    assert np.all(np.abs(np.sum(sphere_net**2, axis=1) - 1) <= 1e-9)
    # eps-sparse: every two points at least eps apart.
    d = np.linalg.norm(sphere_net[:, None, :] - sphere_net[None, :, :], axis=2)
    assert d[np.triu_indices(len(sphere_net), 1)].min() >= 0.4
    again = delcert.sample("builtin:sphere-2", eps=0.4, seed=3)
    assert np.array_equal(again, sphere_net)
    other = delcert.sample("builtin:sphere-2", eps=0.4, seed=4)
    assert not np.array_equal(other, sphere_net)


def test_sample_matches_the_command(tmp_path):
    out = tmp_path / "net.txt"
    subprocess.run([str(BINARY_DIR / "delcert"), "sample", "--manifold", "builtin:sphere-2", "--eps", "0.4",
                    "--seed", "3", "--out", str(out)], check=True, capture_output=True)
    rows = [line.split() for line in out.read_text().splitlines()[2:]]
    from_file = np.array([[float(x) for x in row] for row in rows])
    assert np.array_equal(from_file, delcert.sample("builtin:sphere-2", eps=0.4, seed=3))


# -------------------------------------------------------------------------------------- tangential

def test_tangential_complex_of_a_sample_certifies_or_is_refuted_as_by_the_command(sphere_net, tmp_path):
    simplices = delcert.tangential("builtin:sphere-2", sphere_net, threads=THREADS)
    assert simplices.dtype == np.int64 and simplices.shape[1] == 3
    assert simplices.min() >= 0 and simplices.max() == len(sphere_net) - 1
    cert = delcert.certify("builtin:sphere-2", sphere_net, simplices, threads=THREADS)
    # The complex is the points' own Del_TM: check 3 (stars) must certify it exactly.
    stars = next(c for c in cert["checks"] if c["name"] == "stars")
    assert stars["verdict"] == "CERTIFIED"
    # The same verdict as delcert-certify on the same points and complex, written as files.
    write_points(tmp_path / "p.txt", sphere_net)
    write_complex(tmp_path / "c.txt", len(sphere_net), simplices)
    code, out, err = run_certify_cli("--manifold", "builtin:sphere-2", "--points", tmp_path / "p.txt",
                                     "--complex", tmp_path / "c.txt", "--threads", THREADS)
    assert out.splitlines()[-1] == "verdict: " + cert["verdict"], err
    # ... and the same simplices as delcert tangential on that file.
    subprocess.run([str(BINARY_DIR / "delcert"), "tangential", "--manifold", "builtin:sphere-2", "--points",
                    str(tmp_path / "p.txt"), "--out", str(tmp_path / "t.txt")], check=True, capture_output=True)
    from_cli = [list(map(int, line.split())) for line in (tmp_path / "t.txt").read_text().splitlines()[2:]]
    assert simplices.tolist() == from_cli


def test_tangential_accepts_a_points_file():
    # The octahedron: each vertex's star is its four triangles; eight triangles in all.
    simplices = delcert.tangential("builtin:sphere-2", str(FIXTURES / "points" / "octahedron.off"))
    assert simplices.shape == (8, 3)
    assert np.bincount(simplices.ravel()).tolist() == [4] * 6


# ------------------------------------------------------------------------------- refine and certify

def test_refined_torus_certifies(torus_refined, tmp_path):
    r = torus_refined
    assert r["converged"] is True
    assert r["points"].shape[1] == 4 and r["points"].shape[0] >= r["input_size"]
    assert r["complex"].shape[1] == 3
    assert r["claims"]["format"] == "delcert-claims v2"
    cert = delcert.certify("builtin:clifford-torus-2", r["points"], r["complex"], claims=r["claims"],
                           threads=THREADS, times=False)
    assert cert["verdict"] == "CERTIFIED"
    assert cert["inputs"]["points"]["path"] == "points"
    # The command on the same data, written by refine(out=...), gives the same verdict and the same certificate.
    out = tmp_path / "refined"
    again = delcert.refine("builtin:clifford-torus-2", eps="0.25", seed=1, threads=THREADS, out=out)
    assert np.array_equal(again["points"], r["points"]) and np.array_equal(again["complex"], r["complex"])
    code, stdout, err = run_certify_cli("--manifold", "builtin:clifford-torus-2", "--points", out / "points.txt",
                                        "--complex", out / "complex.txt", "--claims", out / "claims.json",
                                        "--threads", THREADS, "--no-times", "--out", tmp_path / "cert.json")
    assert code == 0 and stdout.splitlines()[-1] == "verdict: CERTIFIED", err
    from_cli = json.loads((tmp_path / "cert.json").read_text())
    by_files = delcert.certify("builtin:clifford-torus-2", out / "points.txt", out / "complex.txt",
                               claims=out / "claims.json", threads=THREADS, times=False)
    assert by_files == from_cli
    # Apart from the input names, the certificate of the arrays is the command's.
    del from_cli["inputs"], cert["inputs"]
    assert cert == from_cli


def test_broken_complex_is_not_certified(torus_refined):
    r = torus_refined
    broken = r["complex"][1:]  # one triangle dropped
    cert = delcert.certify("builtin:clifford-torus-2", r["points"], broken, claims=r["claims"], threads=THREADS,
                           skip_restricted=True)
    assert cert["verdict"] == "REFUTED"
    stars = next(c for c in cert["checks"] if c["name"] == "stars")
    assert stars["verdict"] == "REFUTED"


def test_refine_from_points_keeps_them_first(sphere_net):
    r = delcert.refine("builtin:sphere-2", sphere_net, threads=THREADS)
    assert np.array_equal(r["points"][: len(sphere_net)], sphere_net)
    assert r["input_size"] == len(sphere_net)


def test_refine_curvature_sizing_matches_the_command(tmp_path):
    # As tests/core/refine/refine_sizing_test.cpp: the 4-2-1 ellipsoid, eps 0.5 (the field's cap),
    # --sizing curvature with the default c = 1/2 and floor eps/10. The same files, byte for byte,
    # as `delcert refine` with the same arguments, eps.txt included, and eps(p) per point returned.
    spec = str(FIXTURES / "specs" / "uneven" / "ellipsoid-4-2-1.json")
    out = tmp_path / "py"
    r = delcert.refine(spec, eps="0.5", sizing="curvature", seed=1, threads=THREADS, out=out)
    subprocess.run([str(BINARY_DIR / "delcert"), "refine", "--manifold", spec, "--eps", "0.5", "--sizing", "curvature",
                    "--seed", "1", "--threads", str(THREADS), "--out", str(tmp_path / "cli")],
                   check=True, capture_output=True)
    for name in ("points.txt", "complex.txt", "claims.json", "eps.txt"):
        assert (out / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert r["converged"]
    assert r["claims"]["format"] == "delcert-claims v3"
    assert r["claims"]["star_radius_per_point"] == "eps.txt" and "star_radius" not in r["claims"]
    assert r["claims"] == json.loads((tmp_path / "cli" / "claims.json").read_text())
    assert r["report"]["sizing"]["kind"] == "curvature"
    cli_points = np.loadtxt(tmp_path / "cli" / "points.txt", skiprows=2, ndmin=2)
    assert np.array_equal(r["points"], cli_points)
    cli_complex = np.loadtxt(tmp_path / "cli" / "complex.txt", skiprows=2, dtype=np.int64, ndmin=2)
    assert np.array_equal(r["complex"], cli_complex)
    # eps(p): one per point, at most the cap, at least the floor eps/10, and at most eps.txt's
    # decimal for the same point (written at or above the refiner's double).
    e = r["eps_per_point"]
    assert isinstance(e, np.ndarray) and e.dtype == np.float64 and e.shape == (len(r["points"]),)
    assert np.all(e <= 0.5) and np.all(e >= 0.05)
    assert e.min() < 0.13 and e.max() == 0.5  # the sharp ends (c / kappa_max = 1/8) and the flat parts
    written = np.loadtxt(tmp_path / "cli" / "eps.txt", comments="#")
    assert written.shape == e.shape and np.all(e <= written)
    # Uniform sizing (the default) returns no eps_per_point and writes no eps.txt.
    uniform = delcert.refine(spec, eps="0.5", seed=1, threads=THREADS, out=tmp_path / "uniform")
    assert "eps_per_point" not in uniform and uniform["claims"]["format"] == "delcert-claims v2"
    assert not (tmp_path / "uniform" / "eps.txt").exists()


# -------------------------------------------------------------------------------------- bad inputs

def test_unknown_manifold_has_the_command_message(tmp_path):
    with pytest.raises(delcert.InputError) as e:
        delcert.sample("builtin:no-such-manifold", eps=0.3)
    code, _, err = run_certify_cli("--manifold", "builtin:no-such-manifold", "--points",
                                   FIXTURES / "points" / "octahedron.off")
    assert code == 2
    assert err.strip() == "delcert-certify: " + str(e.value)
    assert isinstance(e.value, ValueError)


def test_bad_arrays_are_refused(sphere_net):
    with pytest.raises(ValueError, match=r"shape \(n, 3\).*got shape \(10, 4\)"):
        delcert.tangential("builtin:sphere-2", np.zeros((10, 4)))
    with pytest.raises(ValueError, match=r"got shape \(30,\)"):
        delcert.tangential("builtin:sphere-2", np.zeros(30))
    with pytest.raises(ValueError, match="dtype"):
        delcert.tangential("builtin:sphere-2", np.array([["a", "b", "c"]]))
    nan = sphere_net.copy()
    nan[5, 1] = np.nan
    with pytest.raises(delcert.InputError, match="points row 5: coordinate 1 is NaN"):
        delcert.tangential("builtin:sphere-2", nan)
    dup = np.vstack([sphere_net, sphere_net[:1]])
    with pytest.raises(delcert.InputError,
                       match=rf"^points row {len(sphere_net)}: duplicate point: identical to point 0 in row 0; remove one"):
        delcert.certify("builtin:sphere-2", dup)
    off = sphere_net * 1.01
    with pytest.raises(delcert.InputError, match=r"points: point 0 \(0-based\) is not on sphere-2"):
        delcert.tangential("builtin:sphere-2", off)
    with pytest.raises(delcert.InputError, match="eps: 0.0 is not positive"):
        delcert.sample("builtin:sphere-2", eps=0.0)
    # An eps whose eps-net could not end is refused before any sampling, as on the command line.
    with pytest.raises(delcert.InputError, match="too small for this command.*give eps >="):
        delcert.sample("builtin:sphere-2", eps=1e-5)
    with pytest.raises(delcert.InputError, match="too small for this command.*give eps >="):
        delcert.refine("builtin:sphere-2", eps=1e-5)
    with pytest.raises(delcert.InputError, match="threads"):
        delcert.certify("builtin:sphere-2", sphere_net, threads=1000)
    with pytest.raises(delcert.InputError, match="kind needs complex"):
        delcert.certify("builtin:sphere-2", sphere_net, kind="restricted")


def test_bad_complex_and_claims_have_the_command_messages(torus_refined, tmp_path):
    r = torus_refined
    bad = r["complex"].copy()
    bad[3, 0] = len(r["points"])  # index out of range
    with pytest.raises(delcert.InputError, match=r"^complex row 3: .*indices are 0-based"):
        delcert.certify("builtin:clifford-torus-2", r["points"], bad, threads=THREADS)
    twice = np.vstack([r["complex"], r["complex"][2:3]])
    with pytest.raises(delcert.InputError, match=rf"^complex row {len(twice) - 1}: simplex listed twice \(first in row 2\)"):
        delcert.certify("builtin:clifford-torus-2", r["points"], twice, threads=THREADS)
    with pytest.raises(delcert.InputError, match="claims"):
        delcert.certify("builtin:clifford-torus-2", r["points"], r["complex"], claims={"format": "delcert-claims v2",
                                                                                       "covering": 0.5})
    # The same reader as the command: the same message for the same file.
    with pytest.raises(delcert.InputError) as e:
        delcert.certify("builtin:sphere-2", FIXTURES / "points" / "octahedron.off",
                        FIXTURES / "certify" / "octahedron-wrong-count.complex")
    code, _, err = run_certify_cli("--manifold", "builtin:sphere-2", "--points", FIXTURES / "points" / "octahedron.off",
                                   "--complex", FIXTURES / "certify" / "octahedron-wrong-count.complex")
    assert code == 2 and err.strip() == "delcert-certify: " + str(e.value)
    with pytest.raises(delcert.InputError, match="--gamma0: 'x' is not a number"):
        delcert.refine("builtin:sphere-2", eps="0.5", gamma0="x")


# ---------------------------------------------------------------------------- GUDHI's tangential complex

def test_gudhi_tangential_complex_in_five_lines():
    """The README's example: GUDHI's tangential complex of an eps-net of S^2, certified."""
    gudhi = pytest.importorskip("gudhi")
    points = delcert.sample("builtin:sphere-2", eps=0.3, seed=1)
    tc = gudhi.TangentialComplex(intrisic_dim=2, points=points); tc.compute_tangential_complex()
    triangles = [s for s, _ in tc.create_simplex_tree().get_skeleton(2) if len(s) == 3]
    certificate = delcert.certify("builtin:sphere-2", points, triangles, threads=THREADS)
    # GUDHI estimates T_p by local PCA, delcert-certify recomputes Del_TM(P) with the exact T_p: on
    # this net (80 points, seed 1) the two agree and every check passes.
    assert certificate["verdict"] == "CERTIFIED"
    assert certificate["inputs"]["complex"]["simplices"] == len(triangles) == 156
    # One triangle fewer is refuted: the certificate is about GUDHI's complex, not recomputed instead of it.
    assert delcert.certify("builtin:sphere-2", points, triangles[1:], threads=THREADS,
                           skip_restricted=True)["verdict"] == "REFUTED"


def test_refine_shrinks_eps_locally_from_a_coarse_eps():
    # Issue 15 item 1: the 8-1-1 ellipsoid from eps = bounding-box diameter / 4 (its eps-net has
    # 3 points; the net is taken at eps/2) converges, with eps shrunk locally, and the points cap
    # stops a run with the partial output.
    spec = str(FIXTURES / "specs" / "uneven" / "ellipsoid-8-1-1.json")
    r = delcert.refine(spec, eps="4.22", seed=1, threads=THREADS)
    assert r["converged"]
    assert r["report"]["local_eps"]["max_level"] > 0
    assert "(4.22)/2" in r["report"]["input"]["source"]
    assert r["claims"]["star_radius"] == "4.22"
    capped = delcert.refine(spec, eps="4.22", seed=1, threads=THREADS, max_points=40)
    assert not capped["converged"]
    assert capped["report"]["stop_reason"] == "max_points"
    assert len(capped["points"]) == 40
    # restricted_check=False is --no-restricted-check: the not_restricted rule (3 points here at
    # seed 1) is off, and the report says so.
    assert r["report"]["parameters"]["restricted_check"] is True
    assert r["report"]["rules"]["not_restricted"]["inserted"] > 0
    off = delcert.refine(spec, eps="4.22", seed=1, threads=THREADS, restricted_check=False)
    assert off["report"]["parameters"]["restricted_check"] is False
    assert off["report"]["rules"]["not_restricted"]["inserted"] == 0
    # The not_intrinsic rule (the certifier's own engines, issue 40) then repairs the same flips.
    assert r["report"]["rules"]["not_intrinsic"]["inserted"] == 0
    assert off["report"]["rules"]["not_intrinsic"]["inserted"] == r["report"]["rules"]["not_restricted"]["inserted"]
    assert len(off["points"]) == len(r["points"])
    ahead = delcert.refine(spec, eps="4.22", seed=1, threads=THREADS, look_ahead=True)
    assert ahead["report"]["parameters"]["look_ahead"] is True
    assert ahead["converged"]


def test_bad_sizing_options_are_refused_as_by_the_command(tmp_path):
    # The cases tests/core/refine/refine_sizing_test.cpp refuses, and an unknown field; nothing is written.
    spec = str(FIXTURES / "specs" / "uneven" / "ellipsoid-4-2-1.json")
    out = tmp_path / "o"
    cases = [
        (dict(sizing="curvy"), "sizing: 'curvy' is not one of uniform, curvature"),
        (dict(sizing="curvature", eps_floor="0.6"), "--eps-floor: must not exceed --eps = 0.5"),
        (dict(sizing="curvature", sizing_c=0), "--sizing-c: must be a positive number (got 0)"),
        (dict(sizing="curvature", sizing_c="abc"), "--sizing-c: 'abc' is not a number"),
        (dict(eps_floor="0.1"), "sizing_c and eps_floor need sizing='curvature'"),
        (dict(sizing_c="0.5"), "sizing_c and eps_floor need sizing='curvature'"),  # even the default value
        (dict(sizing="curvature", mode="paper"), "sizing='curvature' needs mode='practical'"),
    ]
    for kwargs, message in cases:
        with pytest.raises(delcert.InputError) as e:
            delcert.refine(spec, eps="0.5", out=out, **kwargs)
        assert message in str(e.value), kwargs
    with pytest.raises(delcert.InputError) as e:
        delcert.refine(spec, FIXTURES / "points" / "octahedron.off", sizing="curvature", out=out)
    assert "sizing='curvature' needs eps (the field's cap)" in str(e.value)
    assert not out.exists()

# README.md's Python example: GUDHI's tangential complex of an eps-net of S^2, certified by delcert.
# After `bash scripts/demo.sh` (which builds the module into build/python/), from the repository root:
#
#   PYTHONPATH=build/python /usr/bin/python3 examples/python/certify_gudhi.py      # prints CERTIFIED
#
# Debian's /usr/bin/python3 has numpy and GUDHI (python3-numpy, python3-gudhi; scripts/setup.sh
# installs them); a python3 found first on PATH (pyenv, a venv) may not. tests/python/test_examples.py runs it.
import delcert, gudhi                     # PYTHONPATH=build/python
points = delcert.sample("builtin:sphere-2", eps=0.3, seed=1)
tc = gudhi.TangentialComplex(intrisic_dim=2, points=points); tc.compute_tangential_complex()
triangles = [s for s, _ in tc.create_simplex_tree().get_skeleton(2) if len(s) == 3]
print(delcert.certify("builtin:sphere-2", points, triangles)["verdict"])       # CERTIFIED

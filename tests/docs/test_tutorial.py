"""docs/tutorial.md and README.md run as written (issue 41). Every ```sh block is run with bash (-e, -o pipefail), in
order, in one fresh folder that holds `build` (this build) and `fixtures` (the repository's) as symbolic
links, as the page says; its exit status must be the block's `exit=N` (0 when not given), and every
non-empty line of the ```text block that follows it (before the next ```sh) must appear in its output
(stdout and stderr) as a whole line, modulo trailing spaces and ctest's run times. README.md's blocks
are run the same way where they say `exit=N` (its setup commands are not run here: CI runs them), and its
CMake snippet must be tests/install/readme/CMakeLists.txt, which ctest -L install runs. Run by ctest (label
"docs") with DELCERT_BINARY_DIR and DELCERT_SOURCE_DIR set (tests/CMakeLists.txt).
"""
import os
import pathlib
import re
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("DELCERT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY_DIR = pathlib.Path(os.environ.get("DELCERT_BINARY_DIR", SOURCE_DIR / "build"))
TUTORIAL = SOURCE_DIR / "docs" / "tutorial.md"
README = SOURCE_DIR / "README.md"


def blocks(page=TUTORIAL, only_marked=False):
    """[(command, exit status, [expected lines])] in the page's order (only_marked: the sh blocks with exit=N)."""
    text = page.read_text()
    fences = list(re.finditer(r"^```(\w*)([^\n]*)\n(.*?)^```\s*$", text, re.S | re.M))
    out = []
    for f in fences:
        language, info, body = f.group(1), f.group(2), f.group(3)
        if language == "sh":
            status = re.search(r"exit=(\d+)", info)
            out.append([body, int(status.group(1)) if status else 0, [], bool(status)])
        elif language == "text":
            assert out and not out[-1][2], "a text block must follow a sh block, one each"
            out[-1][2] = [line.rstrip() for line in body.splitlines() if line.strip()]
    return [b[:3] for b in out if b[3] or not only_marked]


def normalise(line):
    # ctest prints each test's time ("Passed    0.14 sec", "Total Test time (real) =   0.17 sec").
    return re.sub(r"\s+[0-9.]+ sec$", "", line.rstrip())


def test_the_page_has_the_three_walks():
    commands = "\n".join(b[0] for b in blocks())
    assert "--fix-out" in commands and "/usr/bin/python3" in commands and "delcert_add_certificate_test" in commands
    assert all(expected for _, _, expected in blocks()), "every command shows what it prints"


def run_as_written(page, tmp_path, only_marked=False):
    for link, target in (("build", BINARY_DIR), ("fixtures", SOURCE_DIR / "fixtures")):
        (tmp_path / link).symlink_to(target, target_is_directory=True)
    for command, status, expected in blocks(page, only_marked):
        run = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", command], cwd=tmp_path, capture_output=True,
                             text=True, timeout=600)
        output = {normalise(line) for line in (run.stdout + "\n" + run.stderr).splitlines()}
        assert run.returncode == status, (command, run.returncode, run.stdout[-3000:], run.stderr[-3000:])
        for line in expected:
            assert normalise(line) in output, (command, line, run.stdout[-5000:])


def test_every_command_runs_as_written(tmp_path):
    run_as_written(TUTORIAL, tmp_path)


def test_the_readmes_first_certificate_prints_what_it_shows(tmp_path):
    assert len(blocks(README, only_marked=True)) == 1
    run_as_written(README, tmp_path, only_marked=True)


def test_the_readmes_cmake_snippet_is_the_one_the_install_tests_run():
    snippets = re.findall(r"^```cmake\n(.*?)^```", README.read_text(), re.S | re.M)
    assert snippets == [(SOURCE_DIR / "tests" / "install" / "readme" / "CMakeLists.txt").read_text()]
    usage = re.findall(r"^```cmake\n(.*?)^```", (SOURCE_DIR / "docs" / "usage.md").read_text(), re.S | re.M)
    assert usage == snippets


def test_the_readme_stays_short():
    assert len(README.read_text().splitlines()) < 200  # the rest is in docs/ (issue 41)

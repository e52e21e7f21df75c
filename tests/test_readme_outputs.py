"""The command output that README.md and docs/*.md show is what the commands print.

Every fenced block right after a ``<!-- checked-output -->`` line is a session: lines starting
with ``$ `` are commands, the lines after each one are its expected output. The blocks run in
order in one temporary folder into which ``anvilwave examples ex`` has copied the shipped
examples (a docs page's ``anvilwave/examples/`` paths are read as ``ex/``). Run-dependent parts
are masked on both sides: wall times (``10.3 s``), real-time ratios (``(5x real time)``) and the
one-off kernel compilation notice. Only cheap commands are marked (version, examples, the modes
of a small anvil, the Case method on the shipped record, one Table 1 blow, the XL installation).

The commands run as a newcomer's do: a modal-data cache of their own, empty at the start and
filled by these commands alone, with the library's default BLAS threads. Not the test session's
shared cache: the test workers fill that with one BLAS thread each (tests/conftest.py), and a
mode set solved with other BLAS thread counts differs in its last bits, which the XL
installation's 1605 blows carry to its last one (1606 blows, 40.01 m).
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
MARK = "<!-- checked-output -->"
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def sessions(path: Path) -> list[tuple[int, str, list[str]]]:
    """(line, command, expected output lines) of every checked block of a page, in order."""
    lines = path.read_text(encoding="utf-8").splitlines()
    out = []
    for i, line in enumerate(lines):
        if line.strip() != MARK:
            continue
        assert lines[i + 1].startswith("```"), f"{path.name}:{i + 1}: {MARK} not before a block"
        j = i + 2
        while not lines[j].startswith("```"):
            if lines[j].startswith("$ "):
                out.append((j + 1, lines[j][2:], []))
            else:
                assert out and out[-1][0] > i, f"{path.name}:{j + 1}: output before a command"
                out[-1][2].append(lines[j])
            j += 1
    return out


def mask(text: str) -> list[str]:
    text = re.sub(r"\b\d+(\.\d+)? s\b", "<time> s", text)
    # a wall-time column, right-aligned: its width changes with the time, so the blanks
    # before it are taken as one
    text = re.sub(r" *\b\d+\.\d+s\b", " <time>s", text)
    text = re.sub(r"\(\d+(\.\d+)? ms per blow\)", "(<time> ms per blow)", text)
    text = re.sub(r"\([\d.]+x real time\)", "(<ratio>x real time)", text)
    return [line.rstrip() for line in text.splitlines()
            if line.strip() and "compiling kernels" not in line]


CASES = [(page, *s) for page in PAGES for s in sessions(page)]


def test_the_readme_has_checked_blocks():
    assert sum(1 for c in CASES if c[0].name == "README.md") >= 4


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    return tmp_path_factory.mktemp("readme")


@pytest.fixture(scope="module")
def newcomer_env(workdir):
    """The environment of the shown commands: the session's, with a cache of their own."""
    return {**os.environ, "ANVILWAVE_CACHE_DIR": str(workdir / "cache")}


@pytest.mark.slow
@pytest.mark.parametrize(("page", "line", "command", "expected"), CASES,
                         ids=[f"{c[0].name}:{c[1]}" for c in CASES])
def test_shown_output_is_what_the_command_prints(workdir, newcomer_env, page, line, command,
                                                 expected):
    argv = shlex.split(command.replace("anvilwave/examples/", "ex/"))
    assert argv[0] == "anvilwave", f"{page.name}:{line}: only anvilwave commands are checked"
    cwd = workdir
    if argv[1:2] == ["examples"]:  # into a fresh folder: the copy never overwrites
        cwd = workdir / f"copy{line}"
        cwd.mkdir()
    elif not (workdir / "ex").exists():
        subprocess.run([sys.executable, "-m", "anvilwave", "examples", "ex"], cwd=workdir,
                       check=True, capture_output=True, env=newcomer_env)
    done = subprocess.run([sys.executable, "-m", "anvilwave", *argv[1:]], cwd=cwd,
                          capture_output=True, text=True, timeout=600, env=newcomer_env)
    assert done.returncode == 0, done.stderr
    assert mask(done.stdout) == mask("\n".join(expected)), f"{page.name}:{line}: {command}"

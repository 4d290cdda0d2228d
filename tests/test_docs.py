"""The documentation site and the code in it.

- ``test_site_builds_strict``: ``mkdocs build --strict`` (broken links, pages missing from
  the navigation, docstrings the API reference cannot parse all fail it).
- ``test_page_code_runs``: every ``python`` code block of the getting-started page, the
  tutorials and the how-to guides runs, top to bottom, one namespace per page, in a scratch
  directory, so the documented code cannot rot. A block that must not run in the suite (a
  long run) is preceded by the line ``<!-- docs-test: skip (REASON) -->``; the reason is
  required and such blocks are kept rare.
"""

from __future__ import annotations

import importlib.util
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
EXECUTED = ["getting-started.md", "tutorials/*.md", "how-to/*.md"]
SKIP = re.compile(r"<!--\s*docs-test:\s*skip\s*\((?P<reason>[^)]+)\)\s*-->")
FENCE = re.compile(r"^```python[^\n]*\n(?P<code>.*?)^```\s*$", re.S | re.M)


def executed_pages() -> list[Path]:
    pages: list[Path] = []
    for pattern in EXECUTED:
        pages += sorted(DOCS.glob(pattern))
    return pages


def code_blocks(text: str) -> list[tuple[int, str, str | None]]:
    """(line, code, skip reason or None) of each ```python block."""
    blocks = []
    for m in FENCE.finditer(text):
        before = text[: m.start()].rstrip("\n").rsplit("\n", 1)[-1]
        skip = SKIP.fullmatch(before.strip())
        blocks.append((text.count("\n", 0, m.start()) + 1, m.group("code"), skip["reason"] if skip else None))
    return blocks


def test_code_block_parser():
    text = "x\n```python\na = 1\n```\n<!-- docs-test: skip (takes an hour) -->\n```python\nb = 2\n```\n"
    assert code_blocks(text) == [(2, "a = 1\n", None), (6, "b = 2\n", "takes an hour")]


def test_tutorials_exist_and_run_code():
    names = {p.relative_to(DOCS).as_posix() for p in executed_pages()}
    for page in ["tutorials/conveyor.md", "tutorials/belt-drive.md", "tutorials/startup-study.md",
                 "tutorials/read-results.md", "getting-started.md"]:
        assert page in names
        blocks = code_blocks((DOCS / page).read_text(encoding="utf-8"))
        assert any(reason is None for _, _, reason in blocks), f"{page} has no executed code"


@pytest.mark.parametrize("page", executed_pages(), ids=lambda p: p.relative_to(DOCS).as_posix())
def test_page_code_runs(page: Path, tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    monkeypatch.chdir(tmp_path)
    # Pages refer to the repository's example files by their path from the repository root.
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    namespace: dict = {"__name__": "__docs__"}
    for line, code, reason in code_blocks(page.read_text(encoding="utf-8")):
        if reason is not None:
            compile(code, f"{page.name}:{line}", "exec")  # skipped blocks must still parse
            continue
        try:
            exec(compile(code, f"{page.relative_to(DOCS)}:{line}", "exec"), namespace)
        except Exception as err:
            raise AssertionError(f"{page.relative_to(DOCS)}, code block at line {line} failed: {err!r}") from err
    import matplotlib.pyplot as plt

    plt.close("all")


@pytest.mark.skipif(importlib.util.find_spec("mkdocs") is None or importlib.util.find_spec("mkdocstrings") is None,
                    reason='the docs tools are not installed: pip install ".[docs]" (CI installs them)')
def test_site_builds_strict(tmp_path):
    out = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")],
        cwd=ROOT, capture_output=True, text=True, timeout=300,
    )
    assert out.returncode == 0, f"mkdocs build --strict failed:\n{out.stdout}\n{out.stderr}"
    assert (tmp_path / "site" / "reference" / "api" / "index.html").is_file()


def test_runtime_page_names_the_checkpoint_format_version():
    """docs/runtime.md describes the checkpoint format the engine writes."""
    found = [m for f in sorted((ROOT / "rust" / "src").rglob("*.rs"))
             for m in re.findall(r"pub const FORMAT_VERSION: u32 = (\d+);", f.read_text(encoding="utf-8"))]
    assert len(found) == 1, found
    page = (DOCS / "runtime.md").read_text(encoding="utf-8")
    assert f"**Format (version {found[0]}" in page
    assert f"format version, u32 = {found[0]}" in page


def test_docs_cite_only_files_in_the_repository():
    """The docs carry the facts they rely on: no pointers to the project's shared folder or seed papers."""
    for page in DOCS.rglob("*.md"):
        text = page.read_text(encoding="utf-8")
        for outside in ("shared/seeds", "../shared", "seeds/", "seed 00"):
            assert outside not in text, f"{page.relative_to(ROOT)} cites {outside!r}, which is not in the repository"


def test_pages_added_elsewhere_reach_the_navigation(tmp_path):
    """mkdocs_hooks.place_unlisted: a page missing from mkdocs.yml's nav is placed in its section."""
    spec = importlib.util.spec_from_file_location("mkdocs_hooks", ROOT / "mkdocs_hooks.py")
    hooks = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(hooks)
    for rel, text in {"index.md": "# Home\n", "cli.md": "# Command line\n", "tutorials/new.md": "# A new tutorial\n",
                      "odd.md": "no heading\n", "tutorials/listed.md": "# Listed\n"}.items():
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text(text, encoding="utf-8")
    nav = [{"Home": "index.md"}, {"Tutorials": [{"Listed": "tutorials/listed.md"}]}, {"Reference": []}]
    added = hooks.place_unlisted(nav, tmp_path)
    assert sorted(added) == ["cli.md", "odd.md", "tutorials/new.md"]
    assert nav == [
        {"Home": "index.md"},
        {"Tutorials": [{"Listed": "tutorials/listed.md"}, {"A new tutorial": "tutorials/new.md"}]},
        {"Reference": [{"Command line": "cli.md"}]},
        {"More": [{"Odd": "odd.md"}]},
    ]


def test_install_pages_name_the_declared_rust_version():
    """README and getting started state the Rust version that Cargo.toml declares."""
    version = re.search(r'^rust-version = "([^"]+)"', (ROOT / "Cargo.toml").read_text(encoding="utf-8"), re.M)[1]
    for page in (ROOT / "README.md", DOCS / "getting-started.md"):
        text = page.read_text(encoding="utf-8")
        assert "`rust-version`" in text and f"({version})" in text, f"{page.name} does not name rust-version {version}"

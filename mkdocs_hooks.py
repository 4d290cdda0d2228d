"""MkDocs hook: every page in docs/ reaches the navigation.

mkdocs.yml lists the pages by task. A page that another branch adds without touching that
list is placed by PLACEMENT (its path relative to docs/) or by its folder; anything else goes
under "More". So the site never hides a page, and a strict build never fails only because a
page was added.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

# Pages expected from other work, by section (the section titles of mkdocs.yml).
PLACEMENT = {
    "results.md": "Reference",
    "cli.md": "Reference",
    "warnings.md": "How-to guides",
    "sweeps.md": "How-to guides",
    "belt-drives.md": "Explanation",
    "architecture.md": "Developer",
}
FOLDERS = {
    "tutorials": "Tutorials",
    "how-to": "How-to guides",
    "reference": "Reference",
    "explanation": "Explanation",
    "developer": "Developer",
}


def _listed(nav: Any) -> set[str]:
    """Every page path in a nav tree."""
    found: set[str] = set()
    if isinstance(nav, str):
        found.add(nav)
    elif isinstance(nav, dict):
        for value in nav.values():
            found |= _listed(value)
    elif isinstance(nav, list):
        for item in nav:
            found |= _listed(item)
    return found


def _title(path: Path) -> str:
    """The page's first level-1 heading, else its file name."""
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("# "):
            return line[2:].strip()
    return path.stem.replace("-", " ").capitalize()


def _section(nav: list, title: str) -> list:
    for item in nav:
        if isinstance(item, dict) and title in item and isinstance(item[title], list):
            return item[title]
    entries: list = []
    nav.append({title: entries})
    return entries


def place_unlisted(nav: list, docs_dir: Path) -> list[str]:
    """Add the pages of ``docs_dir`` that ``nav`` does not list; return their paths."""
    listed = _listed(nav)
    added = []
    for page in sorted(docs_dir.rglob("*.md")):
        rel = page.relative_to(docs_dir).as_posix()
        if rel in listed or any(part.startswith((".", "_")) for part in page.relative_to(docs_dir).parts):
            continue
        if rel in PLACEMENT:
            section = PLACEMENT[rel]
        else:
            section = FOLDERS.get(rel.split("/")[0], "More") if "/" in rel else "More"
        _section(nav, section).append({_title(page): rel})
        added.append(rel)
    return added


def on_config(config: Any, **kwargs: Any) -> Any:
    if config.nav:
        place_unlisted(config.nav, Path(config.docs_dir))
    return config

"""The front page and the docs: every relative link and anchor in README.md and docs/ resolves and
stays inside the repository, every docs page is in the index, README stays a front page (under 250
lines), and the pages read as reference, not diary: no line names a commit hash, one of our issue
numbers, a "round" of work, "this session" or a "(before ...)" figure (figures carry the date and
machine of their run, nothing else)."""

import re
from pathlib import Path

import pytest

from support import REPO

PAGES = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)|<img[^>]+src=\"([^\"]+)\"")
HASH = re.compile(r"\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}\b")


def slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def anchors(page: Path) -> set:
    text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)  # no headings inside code blocks
    return {slug(m) for m in re.findall(r"^#+\s+(.+)$", text, re.M)}


def links(page: Path) -> list:
    text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)
    return [a or b for a, b in LINK.findall(text)]


def local_links(page: Path) -> list[tuple[str, Path, str]]:
    """(link, the file it names resolved, its anchor) of the page's links into the file system."""
    out = []
    for target in links(page):
        if not re.match(r"[a-z]+://|mailto:", target):
            path, _, anchor = target.partition("#")
            out.append((target, (page.parent / path).resolve() if path else page, anchor))
    return out


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_every_link_and_anchor_resolves(page: Path):
    broken = []
    for target, resolved, anchor in local_links(page):
        if not resolved.exists():
            broken.append(f"{target} (no such file)")
        elif anchor and resolved.suffix == ".md" and anchor not in anchors(resolved):
            broken.append(f"{target} (no heading '{anchor}' in {resolved.name})")
    assert not broken, f"{page.relative_to(REPO)}: " + "; ".join(broken)


DIARY = re.compile(
    r"\bround (one|two|three|four)\b|\b(earlier|later|this|that|next|the) rounds?\b|\brounds? (one|two)\b"
    r"|\bthis session\b|\bsession's\b|(?<!RotorS )(?<!RotorS' )\bissues? \d+|\(issue \d+|\(before[: ]",
    re.I,
)


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_pages_read_as_reference_not_diary(page: Path):
    text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)
    found = [f"{i + 1}: {m.group(0)!r}" for i, line in enumerate(text.splitlines()) for m in DIARY.finditer(line)]
    assert not found, f"{page.relative_to(REPO)}: diary words (rounds, sessions, our issue numbers, before-figures): " + "; ".join(found)


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_no_link_or_path_leaves_the_repository(page: Path):
    outside = [target for target, resolved, _ in local_links(page) if resolved != REPO and REPO not in resolved.parents]
    text = page.read_text()
    outside += re.findall(r"\.\./shared/\S*|/work/\S*", text)
    assert not outside, f"{page.relative_to(REPO)} points outside the repository: {outside}"


def test_every_docs_page_is_in_the_index():
    index = {Path(t.partition("#")[0]).name for t in links(REPO / "docs" / "README.md")}
    missing = [p.name for p in PAGES[1:] if p.name != "README.md" and p.name not in index]
    assert not missing, f"docs/README.md does not list {', '.join(missing)}"


def test_readme_is_a_front_page_and_no_line_names_a_commit():
    lines = (REPO / "README.md").read_text().splitlines()
    assert len(lines) < 250, f"README.md has {len(lines)} lines; move detail to a docs page"
    named = [
        f"{p.relative_to(REPO)}:{i + 1}: {h}"
        for p in PAGES
        for i, line in enumerate(p.read_text().splitlines())
        for h in HASH.findall(line)
    ]
    assert not named, "commit hashes in the docs: " + "; ".join(named)

"""mkdocs hooks: the guide (index.md) and the gallery (gallery.md) are README.md, so the site
never drifts from what GitHub shows. Links into docs/ become site links; links to other files
of the repository (benchmarks/RESULTS.md) become their path as code, as the site has no copy."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
_LINK = re.compile(r"(!?)\[([^\]]*)\]\(([^)\s]+)\)")
_GALLERY = re.compile(r"<!-- gallery:start -->(.*?)<!-- gallery:end -->", re.S)


def _site_links(markdown: str) -> str:
    def fix(match: re.Match) -> str:
        bang, text, target = match.groups()
        if target.startswith(("http://", "https://", "#", "mailto:")):
            return match.group(0)
        if target.startswith("docs/"):
            return f"{bang}[{text}]({target[len('docs/'):]})"
        return f"`{target}`" if text == target else f"{text} (`{target}`)"

    return _LINK.sub(fix, markdown)


def readme() -> str:
    return (ROOT / "README.md").read_text(encoding="utf-8")


def on_page_markdown(markdown: str, page, config, files) -> str:
    name = page.file.src_uri
    if name == "index.md":
        return _site_links(readme())
    if name == "gallery.md":
        found = _GALLERY.search(readme())
        table = found.group(1) if found else ""
        return markdown + "\n" + _site_links(table)
    return markdown

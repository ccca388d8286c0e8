"""Small HTML builders for the validation report: every text is escaped here, once.

Builders return strings of HTML.  Text arguments are plain text and are escaped; arguments
named ``*_html`` (or values wrapped in :class:`Raw`) are HTML already built by these
functions and are inserted as they are.  The page needs no JavaScript and loads nothing:
the CSS is inline and the images are ``data:image/png;base64`` URIs.  A section is a
:class:`Section` (an HTML string that knows its anchor and title), so that the page's table
of contents lists exactly the sections a report holds.
"""

from __future__ import annotations

import base64
import html
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from string import Template

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
MINUS = "\u2212"  # typographic minus: −1.2 reads better than -1.2 in a table


@dataclass(frozen=True)
class Raw:
    """HTML that a builder made; a table cell holding it is not escaped again."""

    html: str


@dataclass(frozen=True)
class Cell:
    """A table cell with a CSS class (e.g. a deviation's colour band)."""

    text: str | Raw
    css_class: str = ""


def esc(text) -> str:
    """``text`` as HTML text, quotes included (safe inside attributes too)."""
    return html.escape(str(text), quote=True)


# --------------------------------------------------------------------------- numbers


def number(value: float | None, decimals: int = 1, *, signed: bool = False, missing: str = "—") -> str:
    """``12.3``, ``+1.2`` / ``−0.4`` with ``signed``; ``missing`` for None or NaN."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return missing
    value = float(value)
    if round(value, decimals) == 0:
        value = 0.0  # no "−0.0"
    text = f"{value:+.{decimals}f}" if signed else f"{value:.{decimals}f}"
    return text.replace("-", MINUS)


# --------------------------------------------------------------------------- blocks


def paragraph(text: str, *, css_class: str = "") -> str:
    return f"<p{_class(css_class)}>{esc(text)}</p>"


def paragraph_html(inner_html: str, *, css_class: str = "") -> str:
    return f"<p{_class(css_class)}>{inner_html}</p>"


def bullets(items: Iterable[str | Raw]) -> str:
    rows = "".join(f"<li>{_content(item)}</li>" for item in items)
    return f"<ul>{rows}</ul>"


def heading(text: str, level: int = 3) -> str:
    return f"<h{level}>{esc(text)}</h{level}>"


class Section(str):
    """A ``<section>``'s HTML that also carries its ``anchor`` and ``title`` (for the contents)."""

    anchor: str
    title: str

    def __new__(cls, anchor: str, title: str, html_text: str) -> "Section":
        made = super().__new__(cls, html_text)
        made.anchor, made.title = anchor, title
        return made


def section(anchor: str, title: str, body_html: str) -> Section:
    """``<section id=anchor>`` with an ``<h2>`` title."""
    return Section(anchor, title, f'<section id="{esc(anchor)}"><h2>{esc(title)}</h2>{body_html}</section>')


def table(headers: Sequence[str | Raw], rows: Iterable[Sequence], *, caption: str = "",
          css_class: str = "data", first_column_header: bool = True, model: str = "") -> str:
    """A table; cells are text, numbers already formatted, :class:`Cell` or :class:`Raw`.

    The first cell of each row is a row header (``<th scope="row">``) unless told otherwise.
    ``model`` names the model whose values the table holds ("uncalibrated model", "calibrated
    model", or both): shown as a tag in the caption and kept in ``data-model``.
    """
    head = "".join(f'<th scope="col">{_content(h)}</th>' for h in headers)
    body = []
    for row in rows:
        cells = []
        for index, cell in enumerate(row):
            tag = "th" if index == 0 and first_column_header else "td"
            scope = ' scope="row"' if tag == "th" else ""
            css = cell.css_class if isinstance(cell, Cell) else ""
            content = cell.text if isinstance(cell, Cell) else cell
            cells.append(f"<{tag}{scope}{_class(css)}>{_content(content)}</{tag}>")
        body.append(f"<tr>{''.join(cells)}</tr>")
    tag = f'<span class="model">{esc(model)}</span>' if model else ""
    cap = f"<caption>{esc(caption)}{' ' if caption and tag else ''}{tag}</caption>" if caption or tag else ""
    data_model = f' data-model="{esc(model)}"' if model else ""
    return (f'<table{_class(css_class)}{data_model}>{cap}<thead><tr>{head}</tr></thead>'
            f'<tbody>{"".join(body)}</tbody></table>')


def png_image(png: bytes, alt: str, *, caption: str = "") -> str:
    """A ``<figure>`` with the PNG embedded as a base64 data URI."""
    if not png.startswith(PNG_MAGIC):
        raise ValueError(f"figure {alt!r}: not PNG data")
    data = base64.b64encode(png).decode("ascii")
    cap = f"<figcaption>{esc(caption)}</figcaption>" if caption else ""
    return f'<figure><img src="data:image/png;base64,{data}" alt="{esc(alt)}">{cap}</figure>'


def grid(blocks_html: Iterable[str]) -> str:
    """Blocks side by side where the page is wide enough, stacked where it is not."""
    return '<div class="grid">' + "".join(f"<div>{b}</div>" for b in blocks_html) + "</div>"


def definition_table(pairs: Iterable[tuple[str, str | Raw]]) -> str:
    """Two columns, name and value, without a header row."""
    rows = "".join(f'<tr><th scope="row">{esc(k)}</th><td>{_content(v)}</td></tr>' for k, v in pairs)
    return f'<table class="pairs"><tbody>{rows}</tbody></table>'


def code(text: str) -> Raw:
    return Raw(f"<code>{esc(text)}</code>")


def page(title: str, body_html: str, contents: Sequence[tuple[str, str]] = ()) -> str:
    """The complete document: doctype, inline CSS, ``body_html`` in a ``<main>``.

    ``contents`` (anchor, title) become a table of contents that stays in view while the page
    scrolls: a sidebar on a wide window, a bar above the page on a narrow one.
    """
    nav = ""
    if contents:
        items = "".join(f'<li><a href="#{esc(anchor)}">{esc(name)}</a></li>' for anchor, name in contents)
        nav = f'<nav class="contents" aria-label="Contents"><strong>Contents</strong><ol>{items}</ol></nav>'
    return _PAGE.substitute(title=esc(title), css=_CSS, body=body_html, nav=nav,
                            layout=' class="with-contents"' if nav else "")


# --------------------------------------------------------------------------- helpers


def _content(value) -> str:
    return value.html if isinstance(value, Raw) else esc(value)


def _class(css_class: str) -> str:
    return f' class="{esc(css_class)}"' if css_class else ""


_PAGE = Template("""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>$title</title>
<style>$css</style>
</head>
<body$layout>
$nav
<main>
$body
</main>
</body>
</html>
""")

_CSS = """
:root { --ink: #1d232b; --muted: #5b6470; --rule: #d5dae0; --band: #f4f6f8; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--ink); background: #fff;
       font: 15px/1.5 "DejaVu Sans", "Segoe UI", Helvetica, Arial, sans-serif; }
main { max-width: 1100px; margin: 0 auto; padding: 24px 28px 60px; }
body.with-contents { display: flex; align-items: flex-start; }
body.with-contents main { flex: 1 1 auto; min-width: 0; margin: 0; }
nav.contents { position: sticky; top: 0; flex: 0 0 230px; height: 100vh; overflow-y: auto;
               padding: 24px 12px 24px 18px; border-right: 1px solid var(--rule); background: var(--band);
               font-size: 13.5px; }
nav.contents ol { margin: 6px 0 0; padding-left: 20px; }
nav.contents li { margin: 3px 0; }
nav.contents a { color: #2a5d8f; text-decoration: none; }
nav.contents a:hover { text-decoration: underline; }
section { scroll-margin-top: 8px; }
@media (max-width: 900px) {
  body.with-contents { display: block; }
  nav.contents { z-index: 1; height: auto; max-height: 40vh; border-right: 0; border-bottom: 1px solid var(--rule);
                 padding: 8px 14px; }
  nav.contents ol { columns: 2; }
}
h1 { font-size: 26px; margin: 0 0 4px; }
h2 { font-size: 20px; margin: 36px 0 10px; padding-top: 10px; border-top: 2px solid var(--rule); }
h3 { font-size: 16px; margin: 18px 0 6px; }
p, ul { max-width: 960px; }
.meta { color: var(--muted); margin: 0 0 12px; }
.summary { background: var(--band); border-left: 4px solid #3b6ea5; padding: 10px 14px; }
.note { color: var(--muted); font-size: 13.5px; }
table { border-collapse: collapse; margin: 6px 0 14px; font-size: 13.5px; }
caption { text-align: left; font-weight: bold; padding: 4px 0; }
caption span.model { font-weight: normal; font-size: 12px; color: #2a5d8f; border: 1px solid #9fb8d3;
                     border-radius: 3px; padding: 0 5px; white-space: nowrap; }
th, td { border: 1px solid var(--rule); padding: 3px 7px; vertical-align: top; }
thead th { background: var(--band); text-align: center; }
table.data td { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
table.data th[scope=row] { text-align: left; font-weight: normal; white-space: nowrap; }
table.text td, table.data td.text { text-align: left; white-space: normal; }
td.small { font-size: 12.5px; color: var(--muted); }
span.muted { font-size: 12.5px; color: var(--muted); }
details { margin: 4px 0 14px; }
summary { cursor: pointer; color: #2a5d8f; }
table.text th[scope=row] { text-align: left; font-weight: normal; }
table.pairs th { text-align: left; font-weight: normal; color: var(--muted); }
table.pairs td { word-break: break-all; }
td.dev-0 { background: #d9f0d3; }
td.dev-1 { background: #fbf3c4; }
td.dev-2 { background: #fbd9b0; }
td.dev-3 { background: #f4b6b0; }
span.dev-0, span.dev-1, span.dev-2, span.dev-3 { padding: 0 6px; border: 1px solid var(--rule); }
span.dev-0 { background: #d9f0d3; } span.dev-1 { background: #fbf3c4; }
span.dev-2 { background: #fbd9b0; } span.dev-3 { background: #f4b6b0; }
.grid { display: flex; flex-wrap: wrap; gap: 0 28px; align-items: flex-start; }
figure { margin: 10px 0 18px; }
figure img { display: block; width: 100%; max-width: 1040px; height: auto; border: 1px solid var(--rule); }
figcaption { color: var(--muted); font-size: 13.5px; margin-top: 4px; max-width: 960px; }
code { font-size: 13px; background: var(--band); padding: 0 3px; }
"""

"""Text written as reStructuredText: plain text that reads the same, literals, headings."""

from __future__ import annotations

import re

# code in plain text: ``x`` or `x`, and command-line options (--model), which typography would
# otherwise turn into dashes
_LITERAL = re.compile(r"``.+?``|`[^`]+`|(?<![\w-])--?[A-Za-z][\w-]*")


def rst_text(text: str) -> str:
    """Plain text (a help string, a source comment) as reStructuredText that reads the same.

    Code between single or double backticks (as the help strings and comments write it) and
    command-line options (``--model``) become literals; the characters that would start markup
    elsewhere (``*``, ``|``, ``_``, ``\\``) are escaped.
    """
    out, end = [], 0
    for match in _LITERAL.finditer(text):
        out.append(escape(text[end:match.start()]))
        out.append(literal(match.group(0).strip("`")))
        end = match.end()
    out.append(escape(text[end:]))
    return "".join(out)


def escape(text: str) -> str:
    """``text`` with the characters that start markup escaped."""
    return re.sub(r"([\\*|_`<>\[\]])", r"\\\1", text)


def literal(text: str) -> str:
    """``text`` as an inline literal wherever it stands: escaped spaces around it let it touch a
    word; text with spaces at its ends (which an inline literal cannot hold) as the role."""
    text = text.replace("`", "'")
    return f"\\ ``{text}``\\ " if text.strip() == text and text else f":literal:`{text}`"


def heading(title: str, level: str) -> list[str]:
    return [title, level * max(len(title), 4), ""]


def indent(text: str, by: str = "   ") -> list[str]:
    return [by + line if line.strip() else "" for line in text.splitlines()]

"""The site's generated reference: the command line from its argparse parser, the description's
keys from its pydantic schema, the public API from ``feedtherm.__all__``.

Each part is enumerated by a plain function that returns data (:func:`cli_commands`,
:func:`description_sections`, :func:`api_entries`) and written as reStructuredText by another
(:func:`cli_rst`, :func:`description_rst`, :func:`api_rst`), so that the tests
(tests/docs/test_docs_reference.py) read what the pages hold without building the site.  The
directives ``feedtherm-cli``, ``feedtherm-description-keys`` and ``feedtherm-api`` put that text
into a page (docs/reference/).
"""

from __future__ import annotations

import inspect
from pathlib import Path

from .api import ApiEntry, api_entries, api_rst
from .cli import Command, Option, cli_commands, cli_rst
from .description import Key, Section, description_rst, description_sections, field_comments
from .rst import rst_text


__all__ = ["ApiEntry", "Command", "Key", "Option", "Section", "api_entries", "api_rst", "cli_commands", "cli_rst",
           "description_rst", "description_sections", "field_comments", "rst_text", "setup"]


def _source_files(*objects) -> set[str]:
    """The files that define ``objects`` (modules, classes) and this extension: a page generated
    from them is read again when one changes (an incremental build would otherwise keep it)."""
    files = {str(path) for path in Path(__file__).parent.glob("*.py")}
    for obj in objects:
        try:
            files.add(inspect.getsourcefile(obj))
        except TypeError:
            continue
    return {f for f in files if f}


def _cli_sources() -> set[str]:
    import feedtherm.cli

    return _source_files(feedtherm.cli)


def _description_sources() -> set[str]:
    from feedtherm.system import quantities

    return _source_files(quantities, *(cls for section in description_sections() for cls in section.model.__mro__
                                       if cls.__module__.startswith("feedtherm.")))


def _api_sources() -> set[str]:
    import feedtherm

    return _source_files(feedtherm)


def setup(app):
    from docutils import nodes
    from docutils.statemachine import StringList
    from sphinx.util.docutils import SphinxDirective
    from sphinx.util.nodes import nested_parse_with_titles

    def directive(make_text, sources):
        class Generated(SphinxDirective):
            has_content = False

            def run(self):
                container = nodes.container()
                text = make_text()
                for path in sorted(sources()):
                    self.env.note_dependency(path)
                nested_parse_with_titles(self.state, StringList(text.splitlines(), source=self.get_source_info()[0]),
                                         container)
                return container.children

        return Generated

    app.add_directive("feedtherm-cli", directive(cli_rst, _cli_sources))
    app.add_directive("feedtherm-description-keys", directive(description_rst, _description_sources))
    app.add_directive("feedtherm-api", directive(api_rst, _api_sources))
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}

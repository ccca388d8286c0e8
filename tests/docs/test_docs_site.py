"""The documentation site, built as ``make docs`` builds it (every warning an error) but without
running the tutorials (``-D plot_gallery=0``: ``make docs`` runs them), from a copy of docs/, so
that the working tree is left as it was; then served over HTTP, as a reader gets it (the search
fetches the pages' text, which a browser refuses from ``file:`` URLs), and opened in headless
Chromium: the front page, a tutorial and a search render with their content.  The reference
pages hold every key of a description, every option of every command and every public name.

Chromium is the Debian package ``chromium`` that ``make test`` installs (target ``setup-test``).
"""

from __future__ import annotations

import ast
import functools
import html
import re
import shutil
import subprocess
import sys
import threading
import time
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path

import pytest
from reference_walk import parser_options, schema_keys

import feedtherm
from feedtherm.system.schema import FeedSystem

DOCS = Path(__file__).resolve().parents[2] / "docs"
CHROMIUM = "/usr/bin/chromium"
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    """The built site's folder (the build's wall time printed: `pytest -s` shows it)."""
    root = tmp_path_factory.mktemp("docs_site")
    source = root / "docs"
    shutil.copytree(DOCS, source, ignore=shutil.ignore_patterns("_build", "auto_tutorials", "__pycache__"))
    started = time.perf_counter()
    build = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html", "-D", "plot_gallery=0",
                            "-d", str(root / "doctrees"), str(source), str(root / "html")],
                           capture_output=True, text=True, timeout=600)
    print(f"\nthe site built in {time.perf_counter() - started:.1f} s (tutorials not run)")
    assert build.returncode == 0, build.stdout[-3000:] + build.stderr[-5000:]
    return root / "html"


class _QuietHandler(SimpleHTTPRequestHandler):
    def log_message(self, format, *args) -> None:  # noqa: A002 - the base class's name
        pass


@pytest.fixture(scope="module")
def served(site) -> str:
    """The site's address on a local HTTP server, for as long as the module's tests run."""
    server = ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(_QuietHandler, directory=str(site)))
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{server.server_address[1]}/"
    server.shutdown()
    server.server_close()
    thread.join()


def chromium(url: str, profile: Path, *extra: str) -> subprocess.CompletedProcess:
    if not Path(CHROMIUM).exists():
        pytest.fail(f"{CHROMIUM} is missing: the site's tests need headless Chromium; `make test` installs it "
                    "(target setup-test: apt-get install chromium)")
    return subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0",
                           *extra, "--dump-dom", url], capture_output=True, text=True, timeout=180)


def script_errors(stderr: str) -> list[str]:
    """Lines in which a page's script threw."""
    return [line for line in stderr.splitlines() if "Uncaught" in line]


def text_of(markup: str) -> str:
    """The text a reader sees: tags dropped, entities resolved, white space collapsed, typographic
    apostrophes and quotes plain."""
    text = html.unescape(re.sub(r"<[^>]+>", " ", markup)).translate(str.maketrans("‘’“”", "''\"\""))
    return " ".join(text.split())


def test_the_front_page_renders(served, tmp_path):
    run = chromium(served, tmp_path / "profile")
    assert run.returncode == 0, run.stderr[-2000:]
    dom = run.stdout
    assert re.search(r"<title>feedtherm\b[^<]*</title>", dom)
    assert "<h1>feedtherm" in dom
    text = text_of(dom)
    assert "Transient temperature field and thermal elongation of machine-tool feed drives" in text
    for section in ("auto_tutorials/index.html", "howto/index.html", "reference/index.html", "explanation/index.html"):
        assert f'href="{section}"' in dom, section
    assert script_errors(run.stderr) == []


def test_a_tutorial_renders(served, tmp_path):
    scripts = sorted((DOCS / "tutorials").glob("plot_*.py"))
    assert scripts, "docs/tutorials holds no plot_*.py tutorial"
    script = scripts[0]
    source = script.read_text(encoding="utf-8")
    module = ast.parse(source)
    title = ast.get_docstring(module).strip().splitlines()[0]
    first_code = ast.get_source_segment(source, module.body[1]).splitlines()[0]  # after the docstring
    run = chromium(f"{served}auto_tutorials/{script.stem}.html", tmp_path / "profile")
    assert run.returncode == 0, run.stderr[-2000:]
    text = text_of(run.stdout)
    assert title in text
    assert "".join(first_code.split()) in "".join(text.split())  # the code, split into highlighted tokens
    assert f"Download Python source code: {script.name}" in text
    assert script_errors(run.stderr) == []


def test_the_search_page_finds_pages(served, tmp_path):
    run = chromium(f"{served}search.html?q=calibration", tmp_path / "profile",
                   "--virtual-time-budget=15000")  # the search index loads and the search runs
    assert run.returncode == 0, run.stderr[-2000:]
    dom = run.stdout
    assert re.search(r"Search finished, found [1-9]\d* pages? matching", text_of(dom)), text_of(dom)[-2000:]
    results = re.findall(r'<li class="kind-[a-z]+"><a href="([^"]+)"', dom)
    assert "calibration.html" in results
    assert script_errors(run.stderr) == []


def test_the_built_reference_lists_every_description_key(site):
    page = (site / "reference" / "description.html").read_text(encoding="utf-8")
    terms = {text_of(term) for term in re.findall(r"<dt>(.*?)</dt>", page, flags=re.S)}
    assert sorted(set(schema_keys(FeedSystem)) - terms) == []


def test_the_built_reference_lists_every_option(site):
    page = (site / "reference" / "cli.html").read_text(encoding="utf-8")
    documented: dict[str, set[str]] = {}
    for section in page.split('<section id="')[1:]:
        anchor = section.split('"', 1)[0]
        if anchor.startswith("feedtherm"):
            program = "feedtherm " + anchor.removeprefix("feedtherm").lstrip("-") if anchor != "feedtherm" else "feedtherm"
            documented[program] = set(re.findall(r'<span class="sig-name descname"><span class="pre">([^<]+)</span>',
                                                 section))
    expected = parser_options()
    assert sorted(documented) == sorted(expected)
    missing = [f"{program} {name}" for program, names in expected.items() for name in names
               if name not in documented[program]]
    assert missing == []


def test_the_built_reference_documents_every_public_name(site):
    page = (site / "reference" / "api.html").read_text(encoding="utf-8")
    anchors = set(re.findall(r'<dt class="sig sig-object py" id="([^"]+)"', page))
    for name in feedtherm.__all__:
        if name != "__version__":
            assert ("feedtherm.simulate.simulate" if name == "simulate" else f"feedtherm.{name}") in anchors, name


def test_a_script_error_is_seen(tmp_path):
    """The pages' check for script errors is not vacuous: a page that throws shows up."""
    page = tmp_path / "broken.html"
    page.write_text("<!DOCTYPE html><p>x</p><script>throw new Error('broken on purpose')</script>", encoding="utf-8")
    run = chromium(page.as_uri(), tmp_path / "profile")
    assert any("broken on purpose" in line for line in script_errors(run.stderr))

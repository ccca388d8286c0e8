"""Sphinx configuration of feedtherm's documentation site (``make docs``).

The pages are Markdown (MyST); the tutorials are sphinx-gallery scripts, executed when the site
builds (``-D plot_gallery=0`` skips that, as the site's tests do); the reference of the command
line and of the description's keys is generated from the code by the local extension
``_ext/feedtherm_reference/``, the Python API by autodoc with numpydoc.
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # the tutorials' figures are drawn without a display

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

import feedtherm  # noqa: E402 (after the extension's path, and the backend, are set)

project = "feedtherm"
author = "the feedtherm authors"
copyright = "the feedtherm authors, MIT licence"
release = feedtherm.__version__
version = release

extensions = [
    "myst_parser",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
    "feedtherm_reference",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
# examples/ are plain scripts the tests run, not pages; tutorial/ is the tutorials' data;
# sphinx-gallery writes the tutorials' pages from tutorials/ into auto_tutorials/.
exclude_patterns = ["_build", "examples", "tutorial", "tutorials"]
templates_path: list[str] = []

# --------------------------------------------------------------------------- Markdown (MyST)

myst_enable_extensions = ["colon_fence", "deflist", "dollarmath"]
# Every heading down to ### gets an anchor, so that pages can link to a section as page.md#anchor.
myst_heading_anchors = 3

# --------------------------------------------------------------------------- the API (autodoc, numpydoc)

autodoc_typehints = "none"  # numpydoc's Parameters sections state the types, with units
autodoc_member_order = "bysource"
numpydoc_show_class_members = False  # the classes' members are documented by autodoc below them
numpydoc_xref_param_type = False
# Warnings (errors under -W) for the public objects' docstrings: each has a summary, documents
# every parameter its signature takes and none it does not, and its sections are numpydoc's.
numpydoc_validation_checks = {"GL06", "GL07", "GL08", "SS01", "PR01", "PR02", "PR10", "RT02"}
# The public types are dataclasses: their fields are documented as Attributes, which numpydoc's
# PR01 (it reads the fields as the constructor's parameters) does not count.
numpydoc_validation_overrides = {"PR01": [r"\n\s*Attributes\n\s*-{10}"]}

# --------------------------------------------------------------------------- the tutorials (sphinx-gallery)

sphinx_gallery_conf = {
    "examples_dirs": ["tutorials"],
    "gallery_dirs": ["auto_tutorials"],
    "filename_pattern": r"/plot_",  # every plot_ script is executed (the default runs them too; stated)
    "ignore_pattern": r"__init__\.py",
    "download_all_examples": False,
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
    "reset_modules": ("matplotlib",),
    "remove_config_comments": True,
    "show_memory": False,
    "write_computation_times": False,  # sg_execution_times.rst would be a page in no toctree
    "abort_on_example_error": True,
}

# --------------------------------------------------------------------------- HTML (PyData theme)

html_theme = "pydata_sphinx_theme"
html_title = f"feedtherm {release}"
html_static_path: list[str] = []
html_show_sourcelink = False
html_theme_options = {
    "navbar_align": "left",
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version", "theme-version"],
}
html_sidebars = {"index": []}

"""The validation report: one self-contained HTML file (``report.html``).

``write_report(validation, path)`` renders a :class:`~feedtherm.analysis.validation_types.Validation`
into one page with its images embedded as base64 PNG and its CSS inline: no external URL,
no JavaScript.  It reads only the Validation, which carries what the report says of the bench
(its operating points, where its sensors are, its report notes).  A section appears only where
the Validation holds its content (a builder returns "" otherwise), and the table of contents,
which stays in view while the page scrolls, lists the sections present.  In order
(docs/report.md):

title and summary · headline: predictive accuracy · deviation tables · the thermal error as a
displacement · sensor curves · measured time series · ISO 230-3 drift tests · screw field ·
equilibrium time · final values against speed and ambient · dual against single drive · heat
budget · inferred heat per source · measurement consistency · sensitivity ranking ·
inconsistencies in the data · calibrated values · assumptions and provenance · thermal-error
compensation (with ``validate --compensation``) · prediction bands and Sobol indices (with
``validate --uncertainty``).

Modules: ``html`` (escaping builders and the page), ``figures`` (the PNGs), ``data`` (shared
numbers), and one module per group of sections (``comparison``, ``fidelity``, ``transients``,
``operating``, ``context``, ``compensation``, ``uncertainty``, ``measured_series``).
"""

from __future__ import annotations

import contextlib
import os
import uuid
from datetime import datetime
from pathlib import Path

from ...analysis.validation_types import Validation
from ...errors import FeedthermError
from .comparison import deviations_section, title_section
from .compensation import compensation_section
from .context import assumptions_section, calibrated_section, inconsistencies_section, sensitivity_section
from .displacement import displacement_section
from .fidelity import consistency_section, headline_section, inferred_heat_section
from .figures import compact_png
from .html import page
from .drift_tests import drift_tests_section
from .measured_series import measured_series_section
from .operating import dual_single_section, heat_budget_section, trends_section
from .transients import equilibrium_section, screw_field_section, sensor_curves_section
from .uncertainty import uncertainty_section

REPORT_HTML = "report.html"

_SECTIONS = (
    headline_section,
    deviations_section,
    displacement_section,
    sensor_curves_section,
    measured_series_section,
    drift_tests_section,
    screw_field_section,
    equilibrium_section,
    trends_section,
    dual_single_section,
    heat_budget_section,
    inferred_heat_section,
    consistency_section,
    sensitivity_section,
    inconsistencies_section,
    calibrated_section,
    assumptions_section,
)


def render_report(validation: Validation, *, generated: datetime | None = None) -> str:
    """The report as one HTML document (a string)."""
    sections = [build(validation) for build in _SECTIONS]
    if validation.compensation is not None:  # a `feedtherm compensate` folder given to `validate --compensation`
        sections.append(compensation_section(validation.compensation["summary"],
                                             _compact(validation.compensation["figures"])))
    if validation.uncertainty is not None:  # a `feedtherm uncertainty` folder given to `validate --uncertainty`
        sections.append(uncertainty_section(validation.uncertainty["summary"],
                                            _compact(validation.uncertainty["figures"])))
    present = [s for s in sections if s]
    contents = [(s.anchor, s.title) for s in present]
    body = title_section(validation, generated) + "".join(present)
    return page(f"feedtherm validation — {validation.system_name}", body, contents)


def _compact(figures: dict[str, bytes]) -> dict[str, bytes]:
    """A study folder's PNGs as the report's own figures are embedded (palette PNG)."""
    return {name: compact_png(png) for name, png in figures.items()}


def write_report(validation: Validation, path: Path) -> Path:
    """Write the report and return its path.

    ``path`` is the file to write when it ends in ``.html``; otherwise it is a directory
    (created if missing) and the file is ``path/report.html``.  The page is rendered in full
    first, then written to a temporary file beside the target and moved over it in one step,
    so a failure never leaves a partial report.
    """
    path = Path(path)
    target = path if path.suffix.lower() in (".html", ".htm") else path / REPORT_HTML
    text = render_report(validation)
    temporary = target.parent / f".{target.name}.partial-{uuid.uuid4().hex[:12]}"
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        temporary.write_text(text, encoding="utf-8")
        os.replace(temporary, target)
    except OSError as exc:
        with contextlib.suppress(OSError):
            temporary.unlink(missing_ok=True)
        raise FeedthermError(f"{target}: cannot write the report ({exc.strerror or exc})") from None
    return target


__all__ = ["REPORT_HTML", "render_report", "write_report"]

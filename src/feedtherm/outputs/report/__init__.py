"""The validation report: one self-contained HTML file (``report.html``).

``write_report(validation, path)`` renders a :class:`~feedtherm.analysis.validation_types.Validation`
into one page with its images embedded as base64 PNG and its CSS inline: no external URL,
no JavaScript.  It reads only the Validation, which carries what the report says of the bench
(its operating points, where its sensors are, its report notes).  Sections, in order (docs/report.md):

1. title and summary · 2. headline: predictive accuracy (physics mode, held out, leave-one-out,
the reference model's in-sample) · 3. deviation tables · 4. the thermal error as a displacement (the
measuring loop, the gain, the error along the stroke) · 5. sensor curves, and measured
time series against the runs where the measurements have them, and the ISO 230-3 drift at
target positions where a test measured them · 6. screw
field · 7. equilibrium time · 8. final values against speed and ambient · 9. dual
against single drive · 10. heat budget · 11. inferred heat per source · 12. measurement
consistency · 13. sensitivity ranking · 14. inconsistencies in the data · 15. calibrated values ·
16. assumptions and provenance · 17. thermal-error compensation (with ``validate --compensation``) ·
18. prediction bands and Sobol indices (with ``validate --uncertainty``).

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
    measured_series_section,  # only with measured time series
    drift_tests_section,  # only with tests measured at targets
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
    body = title_section(validation, generated) + "".join(build(validation) for build in _SECTIONS)
    if validation.compensation is not None:  # a `feedtherm compensate` folder given to `validate --compensation`
        body += compensation_section(validation.compensation["summary"], validation.compensation["figures"])
    if validation.uncertainty is not None:  # a `feedtherm uncertainty` folder given to `validate --uncertainty`
        body += uncertainty_section(validation.uncertainty["summary"], validation.uncertainty["figures"])
    return page(f"feedtherm validation — {validation.system_name}", body)


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

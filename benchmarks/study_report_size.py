"""The validation report's size: `feedtherm validate` as a user runs it, then what report.html holds.

Issue 59 (item 4) bounds the paper bench's report at 1 MB.  The test suite checks the bound on a
report of 30-minute runs (tests/integration/test_report_renders.py); this runs the real command
(3-hour runs on the paper bench, 8-hour runs and the drift tests on ballscrew_example, 2-25 min
on 2 cores) and prints the file's size, its sections, and each embedded figure's bytes.

    .venv/bin/python benchmarks/study_report_size.py [SYSTEM] [--mode physics] [--calibration DIR]
"""

from __future__ import annotations

import argparse
import base64
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

LIMIT_BYTES = 1_000_000


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("system", nargs="?", default="paper")
    parser.add_argument("--mode", default="physics")
    parser.add_argument("--calibration", metavar="DIR")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        command = [sys.executable, "-m", "feedtherm", "validate", args.system, "--mode", args.mode,
                   "--out", str(Path(folder) / "out")]
        if args.calibration:
            command += ["--calibration", args.calibration]
        started = time.perf_counter()
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - started
        report = Path(folder) / "out" / "report.html"
        text = report.read_text(encoding="utf-8")
    size = len(text.encode("utf-8"))
    figures = re.findall(r'<img src="data:image/png;base64,([^"]+)" alt="([^"]*)"', text)
    sections = re.findall(r'<section id="([^"]+)">', text)
    print(f"{' '.join(command[3:])}: {wall:.0f} s")
    print(f"report.html {size:,} bytes ({'under' if size < LIMIT_BYTES else 'OVER'} {LIMIT_BYTES:,}); "
          f"{len(sections)} sections, {len(figures)} figures, {text.count('<table')} tables")
    print("sections:", ", ".join(sections))
    for data, alt in figures:
        print(f"  {len(base64.b64decode(data)):>8,} B  {alt}")
    print(f"  {sum(len(base64.b64decode(d)) for d, _ in figures):>8,} B  figures together (base64: "
          f"{sum(len(d) for d, _ in figures):,} B)")


if __name__ == "__main__":
    main()

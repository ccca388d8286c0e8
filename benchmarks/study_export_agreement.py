"""The exported C against `feedtherm correct`: the largest difference per law kind and log (issue 58).

Run:  .venv/bin/python benchmarks/study_export_agreement.py

Exports each law of tests/law_documents.py with `--to c`, builds it behind tests/controller_harness.py's
driver with the system's cc, and runs ballscrew_example's drift-test log and a 24 h random log
through it and through `correct`; prints the samples, the largest |C - correct| [µm] and whether
the two are equal to the bit.  A few seconds.
"""

import json, sys, tempfile
from pathlib import Path
import numpy as np
ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
from controller_harness import build_driver, run_driver, time_steps, random_day_log
from law_documents import every_document, POSITIONS
from feedtherm.cli import main
from feedtherm.analysis.compensation.apply import correct, read_law
docs = every_document()
tmp = Path(tempfile.mkdtemp())
logs = {"bench": str(ROOT / "src/feedtherm/benches/ballscrew_example/drift_tests.csv"), "day": str(random_day_log(tmp / "day.csv"))}
for kind in ("law", "law_static", "law_adapted", "law_stroke"):
    law_path = tmp / f"{kind}.json"; law_path.write_text(json.dumps(docs[kind]))
    out = tmp / kind
    main(["export", str(law_path), "--to", "c", "--name", "ft_x", "--out", str(out), "--valid-range", "-50 degC,150 degC"])
    exe = build_driver(out, "ft_x")
    law = read_law(law_path)
    for log, path in logs.items():
        worst, n, exact = 0.0, 0, True
        for c in correct(law, path, tuple(POSITIONS) if law.stroke else ()):
            r = np.column_stack([c.readings[k] for k in law.inputs])
            rows = run_driver(exe, time_steps(c.times), r, x=POSITIONS[0], positions=POSITIONS)
            got = rows[:, 5:5 + len(POSITIONS)] if law.stroke else rows[:, :1]
            d = np.abs(got - c.predicted); worst = max(worst, d.max()); n += len(c.times)
            exact &= np.array_equal(got, c.predicted)
        print(kind, log, n, "samples; max |C - correct| =", worst * 1e6, "um; bitwise equal:", exact)

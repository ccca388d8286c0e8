"""Running exported laws as a controller would: the C compiled with the system's cc behind a small
driver, and the LinuxCNC component built with halcompile and fed through its pins in halrun.

The driver reads one sample a line (``dt x T_1 … T_k``, kelvin and seconds; ``nan`` for a failed
sensor) and prints, a line each: the law's value, the guarded output, the standard deviation (an
adapted law), the flags and the bad input; for a stroke law the law's E and the guarded E at
every x of :data:`DRIVER_POSITIONS`-style lists given on the command line.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np

DRIVER = r"""
#include <stdio.h>
#include <stdlib.h>
#include "@H@"
int main(int argc, char **argv)
{
    @P@_state s;
    double dt, x, inputs[@U@_INPUTS], xs[16], e;
    int i, n = argc - 1, code;
    for (i = 0; i < n && i < 16; i++) xs[i] = strtod(argv[i + 1], NULL);
    @P@_init(&s);
    while (scanf("%lf %lf", &dt, &x) == 2) {
        for (i = 0; i < @U@_INPUTS; i++) if (scanf("%lf", &inputs[i]) != 1) return 3;
        @P@_step(&s, dt, inputs);
#if @U@_STROKE
        code = @P@_output_at_m(&s, x, &e);
        printf("%.17g %.17g 0 %d %d", @P@_law_at_m(&s, x), e, @P@_flags(&s) | code, @P@_bad_input(&s));
        for (i = 0; i < n; i++) printf(" %.17g", @P@_law_at_m(&s, xs[i]));
        {
            double offset, slope, bound;
            @P@_offset_slope(&s, &offset, &slope, &bound);
            printf(" %.17g %.17g %.17g", offset, slope, bound);
        }
        printf("\n");
#else
        (void)code; (void)e; (void)x; (void)xs;
        printf("%.17g %.17g %.17g %d %d\n", @P@_law_m(&s), @P@_output_m(&s), @P@_sd_m(&s), @P@_flags(&s),
               @P@_bad_input(&s));
#endif
    }
    return 0;
}
"""


def build_driver(folder: Path, name: str, stem: str | None = None) -> Path:
    """Compile the exported ``<stem>.c`` with a driver in ``folder`` (cc, ISO C99, warnings as errors)."""
    stem = stem or name
    driver = folder / "driver.c"
    driver.write_text(DRIVER.replace("@H@", f"{stem}.h").replace("@P@", name).replace("@U@", name.upper()))
    exe = folder / "driver"
    subprocess.run(["cc", "-std=c99", "-O2", "-Wall", "-Wextra", "-pedantic", "-Werror", "-o", str(exe),
                    str(driver), str(folder / f"{stem}.c"), "-lm"], check=True, capture_output=True, text=True)
    return exe


def run_driver(exe: Path, dts, readings: np.ndarray, x=None, positions=()) -> np.ndarray:
    """The driver's lines as an array: one row per sample (module notes)."""
    x = np.zeros(len(dts)) if x is None else np.broadcast_to(np.asarray(x, float), (len(dts),))
    lines = "\n".join(" ".join(repr(float(v)) for v in (dt, xv, *row)) for dt, xv, row in zip(dts, x, readings))
    done = subprocess.run([str(exe), *(repr(float(p)) for p in positions)], input=lines + "\n", capture_output=True, text=True,
                          check=True)
    return np.array([[float(v) for v in line.split()] for line in done.stdout.splitlines()])


def time_steps(times) -> np.ndarray:
    """dt of every sample [s]: 0 for the first, then the differences, as the evaluator takes them."""
    times = [float(t) for t in times]
    return np.array([0.0] + [b - a for a, b in zip(times, times[1:])])


def random_day_log(path: Path, seed: int = 58) -> Path:
    """24 h of T1-T3 [°C] at irregular intervals (30-90 s), smooth random walks: a measurement file."""
    rng = np.random.default_rng(seed)
    times = np.cumsum(rng.uniform(30.0, 90.0, 1500))
    times = np.concatenate([[0.0], times[times < 86400.0]])
    walk = 20.0 + np.cumsum(rng.normal(0.0, 0.08, (len(times), 3)), axis=0)
    lines = ["condition,time [s],quantity,value,unit"]
    for t, row in zip(times, walk):
        lines += [f"day,{float(t)!r},T{i + 1},{float(v)!r},degC" for i, v in enumerate(row)]
    path.write_text("\n".join(lines) + "\n")
    return path


# --------------------------------------------------------------------------- LinuxCNC

def linuxcnc_available() -> bool:
    """LinuxCNC's tools are here, and its module folder (where halcompile installs) is writable."""
    if not all(shutil.which(tool) for tool in ("halcompile", "halrun", "halstreamer", "halsampler")):
        return False
    done = subprocess.run(["halcompile", "--print-modinc"], capture_output=True, text=True)
    modules = Path("/usr/lib/linuxcnc/modules")
    return done.returncode == 0 and os.access(modules, os.W_OK)


def _hal_environment(tmp: Path) -> dict:
    """halrun's environment: as root, rtapi_app runs as nobody, with its FIFO where nobody may write."""
    env = dict(os.environ)
    if os.geteuid() == 0:
        # pytest's own temporary folders are private to root: the FIFO goes in a folder of /tmp's
        fifo = Path(tempfile.gettempdir()) / f"feedtherm-rtapi-{os.getpid()}"
        fifo.mkdir(exist_ok=True)
        fifo.chmod(0o1777)
        env.update(RTAPI_UID="65534", RTAPI_FIFO_PATH=str(fifo / "fifo"))
    return env


def install_component(folder: Path, name: str) -> Path:
    """``halcompile --install`` the component ``<name>.comp`` of ``folder``; the installed module's path."""
    done = subprocess.run(["halcompile", "--install", f"{name}.comp"], cwd=folder, capture_output=True, text=True)
    if done.returncode:
        raise AssertionError(f"halcompile failed:\n{done.stdout}\n{done.stderr}")
    line = [s for s in done.stdout.splitlines() if s.startswith("cp ")][-1]
    return Path(line.split()[-1]) / f"{name}.so"


def halrun(script: str, tmp: Path, timeout: float = 120.0) -> subprocess.CompletedProcess:
    """Run a HAL script in halrun (a simulated, non-realtime thread), after clearing any HAL left running."""
    env = _hal_environment(tmp)
    subprocess.run(["halrun", "-U"], env=env, capture_output=True)
    path = tmp / "run.hal"
    path.write_text(script)
    try:
        return subprocess.run(["halrun", "-f", str(path)], env=env, capture_output=True, text=True, timeout=timeout)
    finally:
        subprocess.run(["halrun", "-U"], env=env, capture_output=True)


def replay(tmp: Path, name: str, times, readings_degc: np.ndarray, outputs: list[str], position: float | None = None,
           extra: str = "") -> np.ndarray:
    """Feed a logged series through the pins of the component installed from ``tmp/<name>.comp``, one
    sample a thread period, with ``replay`` set:
    streamer → component → sampler.  ``outputs``: the pins recorded, each through a ``scale`` of gain
    1e6 so that halsampler's six decimals keep 1e-12 of the pin's unit.  One row per sample."""
    hal = name.replace("_", "-")
    k = readings_degc.shape[1]
    rows = len(times)
    data = tmp / "series.txt"
    data.write_text("".join(" ".join(repr(float(v)) for v in (t, *row)) + "\n" for t, row in zip(times, readings_degc)))
    lines = [f"loadrt {name}", "loadrt threads name1=t period1=1000000",
             f"loadrt streamer depth={rows + 8} cfg={'f' * (k + 1)}",
             f"loadrt sampler depth={rows + 8} cfg={''.join(_kind(o) for o in outputs)}",
             f"loadrt scale count={len(outputs)}",
             f"setp {hal}.0.replay 1",
             "net time streamer.0.pin.0 => " + f"{hal}.0.sample-time"]
    pins = [f"{hal}.0.temp-{s}" for s in _temperature_pins(tmp, name)]
    for i, pin in enumerate(pins):
        lines.append(f"net in{i} streamer.0.pin.{i + 1} => {pin}")
    for i, pin in enumerate(outputs):
        if _kind(pin) == "f":
            lines += [f"setp scale.{i}.gain 1000000", f"net out{i} {hal}.0.{pin} => scale.{i}.in",
                      f"net scaled{i} scale.{i}.out => sampler.0.pin.{i}"]
        else:
            lines.append(f"net out{i} {hal}.0.{pin.split(':')[0]} => sampler.0.pin.{i}")
    if position is not None:
        lines.append(f"setp {hal}.0.position {position!r}")
    lines += [extra, "addf streamer.0 t", f"addf {hal}.0 t"] + [f"addf scale.{i} t" for i in range(len(outputs))]
    lines += ["addf sampler.0 t", f"loadusr -w halstreamer {data}", "start", f"loadusr -w halsampler -n {rows}"]
    done = halrun("\n".join(lines) + "\n", tmp)
    values = [line.split() for line in done.stdout.splitlines() if line and line[0] in "-0123456789"]
    if len(values) != rows:
        raise AssertionError(f"halrun gave {len(values)} samples, not {rows}:\n{done.stdout[-2000:]}\n{done.stderr[-2000:]}")
    scale = np.array([1e-6 if _kind(o) == "f" else 1.0 for o in outputs])
    return np.array([[float(v) for v in row] for row in values]) * scale


def _kind(output: str) -> str:
    """The sampler's type letter of a recorded pin (module notes of :func:`replay`)."""
    return {"bit": "b", "s32": "s"}.get(output.partition(":")[2], "f")


def _temperature_pins(folder: Path, name: str) -> list[str]:
    """The temperature pins' names, in the law's input order, read from the component's source."""
    comp = (folder / f"{name}.comp").read_text()
    return [line.split()[3][len("temp_"):].replace("_", "-") for line in comp.splitlines()
            if line.startswith("pin in float temp_")]

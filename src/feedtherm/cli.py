"""Command-line interface: one small function per subcommand, calling the public API.

Every input error ends as one line on stderr, exit code 2, no traceback.
"""

from __future__ import annotations

import argparse
import sys

from . import __version__
from .errors import FeedthermError


class _Parser(argparse.ArgumentParser):
    """argparse that reports a usage error as one line (and exit code 2)."""

    def error(self, message: str) -> None:  # noqa: D401 - argparse API
        self.exit(2, f"feedtherm: error: {message} (see feedtherm {self.prog.split()[-1]} --help)\n"
                  if " " in self.prog else f"feedtherm: error: {message} (see feedtherm --help)\n")


def _load(spec: str):
    from .system.load import load_system

    return load_system(spec)


def _condition(loaded, name: str) -> str:
    conditions = loaded.system.conditions
    if name not in conditions:
        raise FeedthermError(f"--condition: no condition {name!r} in {loaded.origin}; conditions: {', '.join(conditions)}")
    return name


def cmd_heat(args: argparse.Namespace) -> int:
    from .boundary import boundary_conditions
    from .outputs.heat_report import heat_json, print_heat

    loaded = _load(args.system)
    condition = _condition(loaded, args.condition)
    if args.mode == "paper" and loaded.system.paper is None:
        raise FeedthermError(f"--mode paper: {loaded.origin} has no [paper] table of printed values")
    bc = boundary_conditions(loaded.system, condition, args.mode)
    if args.json:
        print(heat_json(bc))
    else:
        print_heat(bc, loaded.system.meta.name)
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    from .system.checks import check_system

    loaded = _load(args.system)
    findings = check_system(loaded.system)
    system = loaded.system
    print(f"{loaded.origin}: valid description '{system.meta.name}' — {len(system.parts)} parts, "
          f"{len(system.joints)} joints, {len(system.sources)} heat sources, {len(system.surfaces)} surfaces, "
          f"{len(system.sensors)} sensors, {len(system.conditions)} conditions; sha256 {loaded.sha256[:12]}")
    if not findings:
        print("no inconsistencies found")
    for finding in findings:
        print(f"warning: {finding}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="feedtherm", description="Thermal model of machine-tool feed drives.")
    parser.add_argument("--version", action="version", version=f"feedtherm {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    system_help = "a TOML description or a bundled name (default: paper)"
    heat = sub.add_parser("heat", help="heat per source and CHTC per surface at a condition")
    heat.add_argument("system", nargs="?", default="paper", help=system_help)
    heat.add_argument("--condition", required=True, help="condition name, e.g. I")
    heat.add_argument("--mode", choices=["physics", "paper"], default="physics")
    heat.add_argument("--json", action="store_true", help="print one JSON object")
    heat.set_defaults(func=cmd_heat)

    check = sub.add_parser("check", help="validate a description and list its inconsistencies")
    check.add_argument("system", nargs="?", default="paper", help=system_help)
    check.set_defaults(func=cmd_check)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except FeedthermError as exc:
        print(f"feedtherm: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("feedtherm: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())

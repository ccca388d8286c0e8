"""Reading a law file a user hands over: bounded, parsed strictly, validated, evaluated once.

Every law (``law*.json`` of ``feedtherm compensate``, or one written by hand) goes through
:func:`read_law_document` before anything evaluates it: ``feedtherm correct`` (:func:`.apply.read_law`),
:meth:`.evaluator.CompensationLaw.from_file` and :meth:`.kalman.KalmanLaw.from_file`
(:meth:`~.kalman.KalmanLaw.from_document` checks a document it is given the same way).  In order:

1. the file: a regular file of at most :data:`MAX_LAW_BYTES`, UTF-8 (:mod:`feedtherm.system.files`);
2. its nesting, counted on the text before any parser recurses: at most :data:`MAX_LAW_DEPTH`;
3. JSON, strictly: ``NaN``, ``Infinity``, a number beyond a float's range (``1e400``) and an
   integer of more digits than any law's number are refused, as is a key given twice in one
   object (which value would count is a guess);
4. the schema of its kind (:mod:`.law_schema`, :mod:`.kalman_schema`);
5. the law evaluated once at its reference state (every input and lag at ``reference.temperature_K``,
   else at ISO 1's 20 °C): the result must be finite.  A ``reference.output_m`` that disagrees with
   what the law gives there is possible (a law edited by hand) but suspect: a warning.

Each refusal is one :class:`~feedtherm.errors.FeedthermError` line naming the file, the key path
(``weights_m_per_K[2][0]``) and the reason; the document handed on is the parsed one, untouched,
so a valid law evaluates exactly as before it was checked.
"""

from __future__ import annotations

import difflib
import json
import math
import re
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import BaseModel, ValidationError

from ...errors import FeedthermError
from ...system.files import read_text_file
from .law_schema import FORMAT, ISO_REFERENCE_K, MODELS

#: Largest law file [bytes]: a Kalman estimator of a 31-state model on 22 surfaces is 0.8 MB, a
#: regression law a few kB; 32 MB holds a model of several hundred states and still parses in a moment.
MAX_LAW_BYTES = 32 * 2**20
#: Deepest nesting of objects and lists: a law nests 5 deep at most (the Kalman table's
#: ``table.h_W_per_m2K[i][j][s]``); Python's JSON parser recurses once per level.
MAX_LAW_DEPTH = 16
#: Longest integer literal [digits]: a law's counts are small, its numbers floats.
MAX_INTEGER_DIGITS = 20
#: The kinds a law file may be.
KINDS = (*MODELS, "kalman")
#: A reference output that differs from the law's by more than this [m] (besides rounding) is suspect.
REFERENCE_TOLERANCE_M = 1e-9

_STRING = re.compile(r'"[^"\\]*(?:\\.[^"\\]*)*"', re.S)
_CONTROL = re.compile(r"[\x00-\x1f\x7f-\x9f\u2028\u2029]")


class _Refused:
    """A JSON literal the parser met and a law cannot hold (NaN, 1e400, a 400-digit integer)."""

    def __init__(self, text: str, reason: str):
        self.text, self.reason = text, reason


class _DuplicateKey(Exception):
    pass


def read_law_document(path: str | Path) -> tuple[dict, list[str]]:
    """The parsed document of the law file ``path``, checked (module notes), and its warnings.

    Raises
    ------
    FeedthermError
        One line naming the file, the key path and the reason.
    """
    document = parse_law_file(path)
    return document, check_law(document, str(path))


def parse_law_file(path: str | Path) -> Any:
    """The JSON of ``path`` parsed strictly (module notes, steps 1-3)."""
    path = Path(path)
    origin = one_line(str(path))
    if not path.exists():
        raise FeedthermError(f"{origin}: no such law file (give a law*.json of `feedtherm compensate`)")
    text = read_text_file(path, origin, MAX_LAW_BYTES, "law")
    too_deep = FeedthermError(f"{origin}: objects or lists nest deeper than {MAX_LAW_DEPTH} levels; a law nests 5 "
                              "at most")
    if nesting_depth(text) > MAX_LAW_DEPTH:
        raise too_deep
    refused: list[_Refused] = []

    def constant(text: str):  # NaN, Infinity, -Infinity
        refused.append(_Refused(text, "JSON has no such number"))
        return refused[-1]

    def floating(text: str):
        value = float(text)
        if math.isfinite(value):
            return value
        refused.append(_Refused(text, "beyond the range of a number"))
        return refused[-1]

    def integer(text: str):
        if len(text.lstrip("-")) > MAX_INTEGER_DIGITS:
            refused.append(_Refused(f"{text[:12]}... ({len(text)} digits)", "no law's number has that many digits"))
            return refused[-1]
        return int(text)

    try:
        document = json.loads(text, parse_constant=constant, parse_float=floating, parse_int=integer,
                              object_pairs_hook=_unique_keys)
    except RecursionError:
        raise too_deep from None
    except _DuplicateKey as exc:
        raise FeedthermError(f"{origin}: the key {one_line(repr(exc.args[0]))} appears twice in one object; which "
                             "value counts would be a guess") from None
    except json.JSONDecodeError as exc:
        raise FeedthermError(f"{origin}: not JSON: {exc.msg} at line {exc.lineno}, column {exc.colno}") from None
    except ValueError as exc:  # what the parser's own number conversion refuses
        raise FeedthermError(f"{origin}: not JSON: {one_line(str(exc))}") from None
    if refused:
        where, value = _first_refused(document)
        raise FeedthermError(f"{origin}: {where or 'the document'}: {value.text} is not a finite number "
                             f"({value.reason}); a law's numbers are finite")
    return document


def _unique_keys(pairs: list[tuple[str, Any]]) -> dict:
    document = dict(pairs)
    if len(document) != len(pairs):
        seen = set()
        for key, _ in pairs:
            if key in seen:
                raise _DuplicateKey(key)
            seen.add(key)
    return document


def nesting_depth(text: str) -> int:
    """How deep objects and lists nest in the JSON ``text``, counted without parsing (strings skipped)."""
    skeleton = _STRING.sub('""', text).encode("utf-8", "replace")
    codes = np.frombuffer(skeleton, dtype=np.uint8)
    if not codes.size:
        return 0
    step = np.isin(codes, (ord("["), ord("{"))).astype(np.int64) - np.isin(codes, (ord("]"), ord("}")))
    return int(np.cumsum(step).max())


def _first_refused(document) -> tuple[str, _Refused]:
    """The key path and the literal of the first refused number in ``document`` (document order)."""
    stack: list[tuple[Any, tuple]] = [(document, ())]
    while stack:
        value, loc = stack.pop()
        if isinstance(value, _Refused):
            return key_path(loc), value
        if isinstance(value, dict):
            stack.extend((v, (*loc, k)) for k, v in reversed(list(value.items())))
        elif isinstance(value, list):
            stack.extend((v, (*loc, i)) for i, v in reversed(list(enumerate(value))))
    raise AssertionError("a refused number that is nowhere")  # pragma: no cover


def check_law(document: Any, origin: str) -> list[str]:
    """Steps 4 and 5 of the module notes on an already parsed ``document``; its warnings.

    Raises
    ------
    FeedthermError
        One line naming ``origin``, the key path and the reason.
    """
    origin = one_line(origin)
    if not isinstance(document, dict):
        raise FeedthermError(f"{origin}: a law document is a JSON object ({{\"format\": \"{FORMAT}\", ...}}), "
                             f"not {_kind_of(document)}")
    if document.get("format") != FORMAT:
        raise FeedthermError(f"{origin}: not a law feedtherm can evaluate: not a {FORMAT} document "
                             f"(format: {shown(document.get('format'))})")
    kind = document.get("kind")
    if kind not in KINDS:
        raise FeedthermError(f"{origin}: kind: {shown(kind)} is not allowed; allowed values: "
                             f"{', '.join(map(repr, KINDS))}")
    if kind == "kalman":
        from .kalman_schema import KalmanLawDocument as model
    else:
        model = MODELS[kind]
    try:
        model.model_validate(document)
    except ValidationError as exc:
        raise FeedthermError(f"{origin}: {describe(exc, model)}") from None
    if kind == "kalman":
        _probe_kalman(document, origin)
        return []
    return _probe_regression(document, origin)


def _probe_regression(document: dict, origin: str) -> list[str]:
    """The law at its reference state: finite, and what its ``reference`` block says (a warning if not)."""
    from .evaluator import CompensationLaw

    law = CompensationLaw(document)
    reference = document.get("reference")
    temperature = reference["temperature_K"] if reference else ISO_REFERENCE_K
    readings = {name: temperature for name in law.inputs}
    if law.stroke:
        law.update(0.0, readings, law.x_min)
        values = list(law._coefficients)
    else:
        values = [law.update(0.0, readings)]
        if law.posterior is not None:
            law.reset()
            values.append(law.update_with_sd(0.0, readings)[1])
    if not all(math.isfinite(v) for v in values):
        raise FeedthermError(f"{origin}: the law gives {values[0]:g} m with every input and lag at {temperature:g} K "
                             "(its reference state): not a finite number, not a law")
    if reference is None:
        return []
    stated = reference["output_m"] if isinstance(reference["output_m"], list) else [reference["output_m"]]
    scale = abs(temperature) * sum(abs(w) for w in _numbers(document["weights_m_per_K"]))
    for m, (says, gives) in enumerate(zip(stated, values)):
        if abs(says - gives) > REFERENCE_TOLERANCE_M + 1e-12 * scale:
            where = "reference.output_m" + (f"[{m}]" if isinstance(reference["output_m"], list) else "")
            return [f"{origin}: {where}: the file says {says * 1e6:.6g} µm at {temperature:g} K, but the law gives "
                    f"{gives * 1e6:.6g} µm there; has it been edited by hand?"]
    return []


def _numbers(nested) -> list[float]:
    out, stack = [], [nested]
    while stack:
        value = stack.pop()
        if isinstance(value, list):
            stack.extend(value)
        else:
            out.append(value)
    return out


def _probe_kalman(document: dict, origin: str) -> None:
    """One reading at the table's ambient, at rest, then one a minute later at the table's middle speed:
    the estimate and its standard deviation finite (and E at the stroke's ends, where the law has it)."""
    from .kalman import KalmanLaw

    try:
        law = KalmanLaw.build(document)
        estimator = law.estimator()
        table = document["table"]
        ambient = float(table["ambient_K"])
        readings = {name: ambient for name in (*law.sensors, law.model.ambient)}
        screw = float(np.mean(table["screw_rpm"]))
        with np.errstate(all="ignore"):
            values = [*estimator.update(0.0, readings, 0.0, 0.0), *estimator.update(60.0, readings, screw, screw)]
            if law.model.C_stroke is not None:
                values += [estimator.stroke_error(float(law.model.stroke_x[i])) for i in (0, -1)]
    except (ValueError, ArithmeticError, np.linalg.LinAlgError) as exc:
        raise FeedthermError(f"{origin}: the estimator cannot run at its table's ambient: "
                             f"{one_line(str(exc))}") from None
    if not all(math.isfinite(v) for v in values):
        raise FeedthermError(f"{origin}: the estimator gives a non-finite D at its table's ambient "
                             f"({ambient:g} K): not a law")


# --------------------------------------------------------------------------- one line per violation


def describe(exc: ValidationError, model: type[BaseModel]) -> str:
    """One line for the first error of ``exc``: ``key path: reason`` (a misspelt key before the
    "missing" it causes)."""
    errors = exc.errors(include_url=False)
    error = next((e for e in errors if e["type"] == "extra_forbidden"), errors[0])
    loc, kind, value = tuple(error["loc"]), error["type"], error.get("input")
    path = key_path(loc)
    at = f"{path}: " if path else ""
    if kind == "extra_forbidden":
        parent = key_path(loc[:-1])
        valid = _valid_keys(model, loc[:-1])
        hint = difflib.get_close_matches(str(loc[-1]), valid, n=1, cutoff=0.5)
        suggestion = f"; did you mean {hint[0]!r}?" if hint else (f"; valid keys: {', '.join(valid)}" if valid else "")
        return f"unknown key {shown(loc[-1])}{f' in {parent}' if parent else ''}{suggestion}"
    if kind == "missing":
        return f"{path}: missing (required)"
    if kind in ("float_type", "int_type", "int_from_float", "finite_number"):
        return f"{at}{_not_a_number(value, 'a whole number' if kind.startswith('int') else 'a number')}"
    if kind == "literal_error":
        return f"{at}{shown(value)} is not allowed; allowed values: {error['ctx']['expected']}"
    if kind == "string_type":
        return f"{at}{shown(value)} is not text; write it in quotes"
    if kind == "bool_type":
        return f"{at}{shown(value)} is not true or false"
    if kind in ("list_type", "dict_type", "model_type", "model_attributes_type"):
        wanted = "a list [...]" if kind == "list_type" else "an object {...}"
        return f"{at}must be {wanted}, not {_kind_of(value)}"
    bounds = {"greater_than_equal": ("ge", "must not be below"), "greater_than": ("gt", "must be above"),
              "less_than_equal": ("le", "must not be above"), "less_than": ("lt", "must be below")}
    if kind in bounds:
        key, words = bounds[kind]
        return f"{at}{shown(value)} {words} {error['ctx'][key]}"
    if kind == "too_short":
        return f"{at}must not be empty" if error["ctx"].get("min_length") == 1 else \
            f"{at}{error['ctx']['actual_length']} entries, at least {error['ctx']['min_length']} expected"
    if kind == "too_long":
        return f"{at}more than {error['ctx']['max_length']} entries"
    message = one_line(error["msg"]).removeprefix("Value error, ")
    return f"{at}{message}"


def _not_a_number(value, wanted: str) -> str:
    if isinstance(value, bool):
        return f"{json.dumps(value)} is a boolean, not {wanted}"
    if isinstance(value, str):
        return f"{shown(value)} is text, not {wanted}; write the number without quotes"
    if isinstance(value, float) and value.is_integer() and wanted == "a whole number":
        return f"{value!r} is not a whole number (write it without a decimal point)"
    if isinstance(value, (int, float)):
        return f"{shown(value)} is not {wanted} a law can hold"
    return f"must be {wanted}, not {_kind_of(value)}"


def _kind_of(value) -> str:
    if isinstance(value, bool):
        return f"a boolean ({json.dumps(value)})"
    if value is None:
        return "null"
    if isinstance(value, str):
        return f"text ({shown(value)})"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, dict):
        return "an object"
    return f"a number ({shown(value)})"


def _valid_keys(model: type[BaseModel], loc: tuple) -> list[str]:
    """The keys of the block at ``loc`` (walking the schema from ``model``), for "did you mean"."""
    current: type[BaseModel] | None = model
    for part in loc:
        if current is None:
            return []
        if isinstance(part, int):
            continue
        field = current.model_fields.get(str(part))
        if field is None:  # a dict's key, such as an input's name in envelope.inputs
            continue
        current = _model_in(field.annotation)
    return sorted(current.model_fields) if current is not None else []


def _model_in(annotation) -> type[BaseModel] | None:
    from typing import get_args

    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in get_args(annotation):
        found = _model_in(arg)
        if found is not None:
            return found
    return None


def key_path(loc) -> str:
    """``weights_m_per_K[2][0]``, ``envelope.inputs.<input>``; a key that is no plain name in quotes."""
    text = ""
    for part in loc:
        if isinstance(part, int):
            text += f"[{part}]"
        elif re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", str(part)):
            text += f".{part}" if text else str(part)
        else:
            text += f"[{shown(part)}]"
    return text


def shown(value, width: int = 40) -> str:
    """``value`` as one short line: text quoted with its control characters escaped, numbers as written."""
    text = repr(value) if not isinstance(value, bool) and value is not None else json.dumps(value)
    text = one_line(text)
    return text if len(text) <= width else text[:width - 3] + "..."


def one_line(text: str) -> str:
    """``text`` with every control character (a newline, a carriage return) escaped: one line always."""
    return _CONTROL.sub(lambda m: m.group().encode("unicode_escape").decode("ascii"), text)

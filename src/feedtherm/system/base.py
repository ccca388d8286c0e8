"""The base of every section of a description: unknown keys are errors, values frozen; and the
field types several sections share."""

from __future__ import annotations

from typing import Annotated

from pydantic import AfterValidator, BaseModel, ConfigDict


class Strict(BaseModel):
    """Base of every section: unknown keys are errors, plain numbers finite, values frozen after loading."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


def _at_least_one(paths: list[str]) -> list[str]:
    if not paths:
        raise ValueError("name at least one path")
    return paths


#: The description paths a calibration or uncertainty parameter acts on: one at least.
ParameterPaths = Annotated[list[str], AfterValidator(_at_least_one)]

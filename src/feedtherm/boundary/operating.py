"""The operating point: what the motors and the air are doing at one moment."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..physics.mechanics import speed_table
from ..system.schema import Condition, FeedSystem

_RAD_PER_S_TO_RPM = 60.0 / (2.0 * math.pi)


@dataclass(frozen=True)
class OperatingPoint:
    """Signed motor speeds [rpm], ambient temperature [K] and the screw lead [m].

    ``nut_motor_off``: the dual drive run as a conventional one, its nut held fixed (by the
    motor's holding brake) with no current in the nut motor, whatever torque the thread puts
    on the nut; otherwise a nut at 0 rpm is held by its servo, which carries that torque.
    """

    screw_rpm: float
    nut_rpm: float
    ambient: float
    lead: float
    nut_motor_off: bool = False

    @property
    def relative_rpm(self) -> float:
        """Speed of the screw relative to the nut, [rpm]; drives the screw-nut heat."""
        return self.screw_rpm - self.nut_rpm

    @property
    def table_speed(self) -> float:
        """Signed table speed, [m/s]."""
        return speed_table(self.screw_rpm, self.nut_rpm, self.lead)

    def shaft_rpm(self, shaft: str) -> float:
        """Speed of ``"screw"``, ``"nut"`` or ``"relative"``, [rpm]."""
        return {"screw": self.screw_rpm, "nut": self.nut_rpm, "relative": self.relative_rpm}[shaft]


def operating_point(system: FeedSystem, condition: Condition) -> OperatingPoint:
    """Operating point of a constant condition (the table reverses, magnitudes stay)."""
    return OperatingPoint(
        screw_rpm=condition.screw_speed * _RAD_PER_S_TO_RPM,
        nut_rpm=condition.nut_speed * _RAD_PER_S_TO_RPM,
        ambient=condition.ambient,
        lead=0.0 if system.kinematics is None else system.kinematics.lead,  # no drive: no table motion
    )

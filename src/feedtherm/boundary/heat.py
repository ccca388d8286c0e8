"""Heat of every source at an operating point, from the physics correlations.

Order matters: the guideways' friction force is the screw's axial load, and each motor
delivers the friction torques of everything on its shaft.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from functools import partial

from ..errors import ModelError
from ..physics import (
    ball_screw,
    bearings,
    bearings_skf,
    guideways,
    motors,
    screw_nut,
    screw_nut_rolling,
    servo_motor,
)
from ..physics.mechanics import angular_speed, heat_friction, torque_screw_drive
from ..system.schema import FeedSystem
from ..system.sources import (
    BallScrewSource,
    BearingSource,
    DatasheetMotorLosses,
    FixedSource,
    GuidewaySource,
    MotorSource,
    SlidingScrewSource,
    TorqueSource,
)
from .operating import OperatingPoint
from .physical import check_viscosity, numeric_errors

GRAVITY = 9.80665  # standard gravity, [m/s^2]


@dataclass(frozen=True)
class SourceHeat:
    """Heat of one source [W], where it goes, and the intermediate values that made it."""

    name: str
    power: float
    into: dict[str, float]
    speed_rpm: float
    details: dict[str, float] = field(default_factory=dict)


@contextmanager
def named_failure(path: str):
    """A physics function's refusal (its arguments outside its domain) as one line naming ``path``.

    The correlations check their arguments and raise ``ValueError``; met while evaluating a
    description's source or surface, that is a description the models cannot evaluate at this
    operating point, reported as :class:`~feedtherm.errors.ModelError` with the value's path.
    So is an overflow, a division by zero or an invalid operation inside, where the caller made
    them raise (:func:`~.physical.numeric_errors`, as :func:`source_heats` does): never a
    ``RuntimeWarning``.
    """
    try:
        yield
    except (ValueError, ZeroDivisionError, OverflowError, FloatingPointError, RuntimeWarning) as exc:
        raise ModelError(f"{path}: cannot be evaluated here: {exc}") from None


@dataclass(frozen=True)
class MotorOverload:
    """A motor whose shaft needs more than its rated continuous torque at an operating point."""

    source: str
    torque: float  # [N m], magnitude
    continuous_torque: float  # [N m]

    def describe(self) -> str:
        return (f"sources.{self.source}: the shaft needs {self.torque:.3g} N·m, "
                f"{100.0 * self.torque / self.continuous_torque:.0f} % of its continuous_torque "
                f"{self.continuous_torque:.3g} N·m; the motor cannot run there, so the preloads and frictions "
                "loading that shaft are implausible")


def motor_duties(heats: Mapping[str, SourceHeat]) -> dict[str, float]:
    """Each motor's torque (from the mechanism: the sources on its shaft) over its declared
    ``continuous_torque``; motors that declare none are left out."""
    return {name: heat.details["torque_to_continuous"] for name, heat in heats.items()
            if "torque_to_continuous" in heat.details}


def motor_overloads(heats: Mapping[str, SourceHeat]) -> list[MotorOverload]:
    """The motors whose duty (:func:`motor_duties`) exceeds 1."""
    return [MotorOverload(name, abs(heats[name].details["torque_Nm"]), heats[name].details["continuous_torque_Nm"])
            for name, ratio in motor_duties(heats).items() if ratio > 1.0]


def _sign(x: float) -> float:
    return math.copysign(1.0, x) if x != 0.0 else 0.0


#: A coupled run's sources, each as last evaluated (:func:`source_heats`): by source name, the
#: inputs it was evaluated at, its heat, the torques it put on the motors' shafts and the warnings
#: it raised.
SourceMemo = dict[str, tuple[tuple, SourceHeat, tuple[tuple[str, float], ...], list]]


def source_heats(system: FeedSystem, point: OperatingPoint,
                 temperatures: Mapping[str, float] | None = None, *,
                 memo: SourceMemo | None = None, records: list | None = None) -> dict[str, SourceHeat]:
    """Heat of every declared source at ``point`` (physics mode), keyed by source name.

    ``temperatures`` [K]: each source's own temperature (where its heat enters), at which its
    lubricant's viscosity and its motor winding's resistance are taken; a source left out is
    taken at the frozen temperature of the CHTCs, ambient + ``convection_delta_t``.

    ``memo``, with ``records`` (the list a ``warnings.catch_warnings(record=True)`` around the
    call fills): the sources of the earlier calls for the same ``system``.  A source whose inputs
    are those of its last evaluation (the operating point, its own temperature, a screw's axial
    load, a motor's shaft torque) takes that evaluation's heat, torques and warnings (added to
    ``records``) without recomputing them; the heats are those of an evaluation without it.
    """
    if (memo is None) != (records is None):
        raise TypeError("source_heats: memo and records go together")
    with numeric_errors():  # once: per source, it would cost a quarter of the evaluation
        return _source_heats(system, point, temperatures, memo, records)


def _source_heats(system: FeedSystem, point: OperatingPoint, temperatures: Mapping[str, float] | None,
                  memo: SourceMemo | None = None, records: list | None = None) -> dict[str, SourceHeat]:
    sources = system.sources
    heats: dict[str, SourceHeat] = {}
    # torque each motor must deliver on its shaft, accumulated from the friction elements
    shaft_torque = {"screw": 0.0, "nut": 0.0}
    axial_force = 0.0
    frozen_temperature = point.ambient + system.temperatures.convection_delta_t
    local = dict(temperatures or {})

    def temperature(name: str) -> float:
        return local.get(name, frozen_temperature)

    def why(name: str) -> str:
        """Why source ``name`` is at :func:`temperature` (a viscosity's message says it)."""
        if name in local:
            return "the source's simulated temperature"
        return (f"the ambient {point.ambient - 273.15:.4g} degC plus temperatures.convection_delta_t "
                f"{system.temperatures.convection_delta_t:.4g} K")

    def evaluate(name: str, inputs: tuple, compute) -> SourceHeat:
        """Source ``name``'s heat from ``compute()`` (its heat and its shaft torques), or from the memo
        when ``inputs`` are those of its last evaluation; its torques added to the shafts in order."""
        kept = None if memo is None else memo.get(name)
        if kept is not None and kept[0] == inputs:
            heat, torques = kept[1], kept[2]
            records.extend(kept[3])
        else:
            start = 0 if records is None else len(records)
            with named_failure(f"sources.{name}"):
                heat, torques = compute()
            if memo is not None:
                memo[name] = (inputs, heat, torques, records[start:])
        for shaft, torque in torques:
            shaft_torque[shaft] += torque
        heats[name] = heat
        return heat

    for name, src in sources.items():
        if isinstance(src, GuidewaySource):
            heat = evaluate(name, (point,), partial(_guideway, name, src, point))
            axial_force += heat.details["friction_force_N"]
    for name, src in sources.items():
        T = temperature(name)
        if isinstance(src, SlidingScrewSource):
            evaluate(name, (point, T, axial_force), partial(_sliding_screw, name, src, point, axial_force, T, why))
        elif isinstance(src, BallScrewSource):
            evaluate(name, (point, axial_force), partial(_ball_screw, name, src, point, axial_force))
        elif isinstance(src, BearingSource):
            evaluate(name, (point, T), partial(_bearing, name, src, point, T, why))
        elif isinstance(src, TorqueSource):
            evaluate(name, (point, axial_force), partial(_torque, name, src, point, axial_force))
        elif isinstance(src, FixedSource):
            evaluate(name, (), partial(_fixed, name, src))
    for name, src in sources.items():
        if isinstance(src, MotorSource):
            load = shaft_torque[src.shaft]
            T = temperature(name)
            evaluate(name, (point, T, load), partial(_motor, name, src, point, load, T))
    # a source's heat_factor scales its heat alone: the torques it put on its shaft stay
    return {name: _scaled(heats[name], sources[name].heat_factor) for name in sources}  # declaration order


# Each source's heat, and the torques [N m] it puts on the motors' shafts (:func:`_source_heats`).

def _guideway(name, src: GuidewaySource, point) -> tuple[SourceHeat, tuple]:
    force = guideways.friction_force_guideway(
        src.friction_coefficient, src.moving_mass * GRAVITY + src.external_load,
        src.seal_drag_per_carriage, src.carriages,
    )
    return SourceHeat(name, guideways.heat_guideway(force, point.table_speed), dict(src.into), 0.0,
                      {"friction_force_N": force, "table_speed_m_per_s": point.table_speed}), ()


def _fixed(name, src: FixedSource) -> tuple[SourceHeat, tuple]:
    return SourceHeat(name, src.power, dict(src.into), 0.0), ()


def _scaled(heat: SourceHeat, factor: float) -> SourceHeat:
    if factor == 1.0:
        return heat
    return SourceHeat(heat.name, heat.power * factor, heat.into, heat.speed_rpm,
                      {**heat.details, "heat_factor": factor})


def _sliding_screw(name, src: SlidingScrewSource, point, axial_force, temperature, why) -> tuple[SourceHeat, tuple]:
    """``why(name)``: why the source is at ``temperature`` (the grease's viscosity check says it)."""
    if src.grease is not None:
        check_viscosity(f"sources.{name}.grease", src.grease.viscosity_at(temperature), temperature, why(name))
    force = axial_force + src.external_axial_load
    eta = src.grease_viscosity_at(temperature)
    torque = screw_nut.torque_screw_nut_sliding(
        force, src.preload, src.pitch_diameter, point.lead, src.friction_coefficient,
        src.flank_half_angle, eta, src.grease_gap, src.engaged_length,
        point.relative_rpm,
    )
    # The screw also pushes the table: the ideal torque F*lead/(2 pi) is work, not heat.
    drive = torque.total + torque_screw_drive(force, point.lead)
    on_shafts = _screw_and_nut(drive * _sign(point.relative_rpm))  # friction drags the nut along with the screw
    power = screw_nut.heat_screw_nut(torque.total, point.screw_rpm, point.nut_rpm)
    return SourceHeat(name, power, dict(src.into), point.relative_rpm, {
        "axial_load_N": force, "load_torque_Nm": torque.load, "preload_torque_Nm": torque.preload,
        "grease_viscosity_Pa_s": eta, "grease_torque_Nm": torque.grease, "friction_torque_Nm": torque.total,
    }), on_shafts


def _screw_and_nut(torque: float) -> tuple[tuple[str, float], tuple[str, float]]:
    """A screw-nut friction torque [N m] on the screw's shaft, and against it on the nut's."""
    return ("screw", torque), ("nut", -torque)


def _ball_screw(name, src: BallScrewSource, point, axial_force) -> tuple[SourceHeat, tuple]:
    force = axial_force + src.external_axial_load
    sets = ball_screw.axial_loads_preloaded_nut(force, src.preload) if src.preload > 0.0 else (force,)
    sliding, hysteresis, rolling = (sum(terms) for terms in zip(
        *(_ball_set_torques(src, set_load, point) for set_load in sets)))
    total = screw_nut_rolling.torque_screw_nut_rolling(sliding, hysteresis, rolling)
    # As for the sliding screw: the screw also pushes the table, and the friction drags the nut.
    drive = total + torque_screw_drive(force, point.lead)
    on_shafts = _screw_and_nut(drive * _sign(point.relative_rpm))
    power = screw_nut.heat_screw_nut(total, point.screw_rpm, point.nut_rpm)
    return SourceHeat(name, power, dict(src.into), point.relative_rpm, {
        "axial_load_N": force, **{f"ball_set_{i + 1}_load_N": load for i, load in enumerate(sets)},
        "differential_sliding_torque_Nm": sliding, "hysteresis_torque_Nm": hysteresis,
        "rolling_resistance_torque_Nm": rolling, "friction_torque_Nm": total,
    }), on_shafts


def _ball_set_torques(src: BallScrewSource, set_load, point) -> tuple[float, float, float]:
    """Screw torques [N·m] of one ball set's screw and nut contacts: sliding, hysteresis, EHL.

    Each term is a resistance at a ball contact turned into screw torque by power
    (physics.ball_screw.lever_arm_rolling_ball_screw): the EHL and hysteresis forces act over
    the rolling speed u = r_e·ω, Heathcote's sliding moment over the ball's spin Ω = (2r_e/D)·ω.
    Eq. 5's cos α (a thread flank's projection) has no place here.
    """
    if set_load == 0.0:  # a lifted-off set rolls unloaded
        return 0.0, 0.0, 0.0
    helix = screw_nut.helix_angle(point.lead, src.pitch_diameter)
    D, alpha, z = src.ball_diameter, src.contact_angle, src.loaded_balls
    Q = ball_screw.normal_load_ball(set_load, z, alpha, helix)
    lever = ball_screw.lever_arm_rolling_ball_screw(src.pitch_diameter, D, alpha, helix)
    u = lever * abs(angular_speed(point.relative_rpm))
    E, nu = src.youngs_modulus, src.poisson_ratio
    E_star = screw_nut_rolling.effective_modulus_Hertz(E, nu, E, nu)
    E_prime = screw_nut_rolling.effective_modulus_Hamrock_Dowson(E, nu, E, nu)
    rolling_lines = 2.0 * math.cos(math.radians(80.0))  # Heathcote: zero net tangential force
    sliding = hysteresis = rolling = 0.0
    for race, conformity in (("screw", src.screw_conformity), ("nut", src.nut_conformity)):
        Rx, Ry = ball_screw.radii_effective_ball_groove(D, src.pitch_diameter, alpha, conformity, race)
        k = screw_nut_rolling.ellipticity_Hamrock_Brewe(Ry, Rx)
        gamma = ball_screw.semi_minor_axis_coefficient(k, ball_screw.elliptic_integral_Hamrock_Brewe(Ry, Rx))
        b = screw_nut_rolling.semi_minor_axis_Hertz(gamma, Q, E_star, 1.0 / Rx + 1.0 / Ry)
        R_c = ball_screw.radius_contact_surface_ball_groove(D, conformity)
        M_slide = screw_nut_rolling.torque_differential_sliding_contact(
            src.slip_friction_coefficient, Q, k * b, R_c, -rolling_lines, rolling_lines)
        sliding += M_slide * 2.0 * lever / D
        hysteresis += screw_nut_rolling.torque_hysteresis_contact(src.hysteresis_loss_fraction, Q, b, D / 2.0, lever)
        U, G, W = screw_nut_rolling.dimensionless_groups_ehl(
            src.lubricant_dynamic_viscosity, src.pressure_viscosity_coefficient, u, Q, E_prime, Rx)
        rolling += screw_nut_rolling.rolling_resistance_ehl(E_prime, Rx, k, G, U, W) * lever
    return z * sliding, z * hysteresis, z * rolling


def _bearing(name, src: BearingSource, point, temperature, why) -> tuple[SourceHeat, tuple]:
    """``why(name)``: why the bearing is at ``temperature`` (its oil's viscosity check says it)."""
    if src.lubricant is not None:
        check_viscosity(f"sources.{name}.lubricant", src.lubricant.viscosity_at(temperature), temperature, why(name))
    n = point.shaft_rpm(src.shaft)
    nu = src.viscosity_at(temperature)
    if src.friction_model == "skf":
        return _bearing_skf(name, src, n, nu)
    if src.friction_model == "constant":
        return _bearing_constant(name, src, n)
    p0 = src.equivalent_static_load or max(src.axial_load, src.radial_load)
    if src.bearing_type == "angular_contact":
        f1 = bearings.f1_angular_contact_Palmgren(p0, src.static_load_rating)
        p1 = bearings.P1_angular_contact_Palmgren(src.axial_load, src.radial_load)
    else:
        z = src.f1_exponent_factor if src.f1_exponent_factor is not None else 5e-4
        f1 = bearings.f1_deep_groove_Palmgren(p0, src.static_load_rating, z=z)
        p1 = bearings.P1_deep_groove_Palmgren(src.axial_load, src.radial_load)
    torque = bearings.torque_bearing_Palmgren(f1, p1, src.dm, src.f0, nu, n)
    return SourceHeat(name, bearings.heat_bearing(torque.total, n), dict(src.into), n, {
        "lubricant_viscosity_m2_per_s": nu, "f1": f1, "P1_N": p1, "load_torque_Nm": torque.load,
        "viscous_torque_Nm": torque.viscous, "friction_torque_Nm": torque.total,
    }), ((src.shaft, torque.total * _sign(n)),)


def _bearing_constant(name, src: BearingSource, n) -> tuple[SourceHeat, tuple]:
    """Constant coefficient of friction: each of the set's bearings at P = F_a + F_r/k, the set's torque their sum."""
    k = src.bearings_in_set
    load = src.axial_load + src.radial_load / k
    total = k * bearings.torque_bearing_constant_friction(src.friction_coefficient, load, src.bore_diameter)
    return SourceHeat(name, bearings.heat_bearing(total, n), dict(src.into), n, {
        "bearings_in_set": k, "equivalent_load_N": load, "friction_torque_Nm": total,
    }), ((src.shaft, total * _sign(n)),)


def _bearing_skf(name, src: BearingSource, n, nu) -> tuple[SourceHeat, tuple]:
    """SKF model: each of the set's identical bearings on its share of the radial load and
    static rating, with the declared axial load; the set's torque is their sum."""
    k = src.bearings_in_set
    d, D, dm = src.bore_diameter, src.outer_diameter, src.dm
    Fr, Fa, C0 = src.radial_load / k, src.axial_load, src.static_load_rating / k
    R1, R2, R3, S1, S2, S3 = bearings_skf.GEOMETRIC_CONSTANTS_SKF[src.bearing_type][src.series]
    mu = bearings_skf.mu_sl(bearings_skf.phi_bl(n, nu, dm), bearings_skf.MU_BL_SKF, bearings_skf.MU_EHL_SKF[src.base_oil])
    if src.bearing_type == "deep_groove":
        rolling = bearings_skf.torque_bearing_rolling_deep_groove_SKF(R1, R2, dm, Fr, Fa, C0, nu, n)
        sliding = bearings_skf.torque_bearing_sliding_deep_groove_SKF(S1, S2, dm, Fr, Fa, C0, mu)
    else:
        rolling = bearings_skf.torque_bearing_rolling_angular_contact_SKF(R1, R2, R3, dm, Fr, Fa, nu, n)
        sliding = bearings_skf.torque_bearing_sliding_angular_contact_SKF(S1, S2, S3, dm, Fr, Fa, n, mu)
    K_rs = bearings_skf.K_RS_SKF[src.lubrication]
    phi_rs = 1.0 if K_rs is None else bearings_skf.phi_rs(K_rs, bearings_skf.K_Z_SKF[src.bearing_type][src.series], nu, n, d, D)
    seal = 0.0
    if src.seal is not None:
        beta, K_S1, K_S2 = bearings_skf.seal_constants_SKF(src.seal, src.bearing_type, D)
        # The catalogue takes an RSL seal's moment whole on bearings over 25 mm outside diameter.
        seal = bearings_skf.torque_bearing_seal_SKF(K_S1, beta, K_S2, src.seal_counterface_diameter,
                                                    src.seals_per_bearing, full_value=src.seal == "RSL")
    one = bearings_skf.torque_bearing_SKF(rolling, bearings_skf.phi_ish(n, dm, nu), phi_rs, sliding, seal, src.drag_torque)
    total = k * one.total
    return SourceHeat(name, bearings.heat_bearing(total, n), dict(src.into), n, {
        "lubricant_viscosity_m2_per_s": nu, "bearings_in_set": k, "rolling_torque_Nm": k * one.rolling,
        "phi_ish": one.phi_ish, "phi_rs": one.phi_rs, "mu_sl": mu, "sliding_torque_Nm": k * one.sliding,
        "seal_torque_Nm": k * one.seal, "drag_torque_Nm": k * one.drag, "friction_torque_Nm": total,
    }), ((src.shaft, total * _sign(n)),)


def _torque(name, src: TorqueSource, point, axial_force) -> tuple[SourceHeat, tuple]:
    n = point.shaft_rpm(src.shaft)
    if src.shaft == "relative":  # a screw-nut drag torque: the screw also pushes the table
        drive = src.torque + torque_screw_drive(axial_force, point.lead)
        on_shafts = _screw_and_nut(drive * _sign(n))
    else:
        on_shafts = ((src.shaft, src.torque * _sign(n)),)
    return SourceHeat(name, heat_friction(src.torque, n), dict(src.into), n, {"friction_torque_Nm": src.torque}), on_shafts


def _motor(name, src: MotorSource, point, load_torque, temperature) -> tuple[SourceHeat, tuple]:
    n = point.shaft_rpm(src.shaft)
    torque = load_torque + src.extra_torque * _sign(n)
    output = torque * n * 2.0 * math.pi / 60.0  # > 0 driving, < 0 braking (generating)
    details = {"torque_Nm": torque, "shaft_power_W": output}
    if src.continuous_torque is not None:
        details.update(continuous_torque_Nm=src.continuous_torque, torque_to_continuous=abs(torque) / src.continuous_torque)
        if isinstance(src.losses, DatasheetMotorLosses):
            details["continuous_current_A"] = src.continuous_torque / src.losses.torque_constant
    if src.shaft == "nut" and point.nut_motor_off:  # the brake holds the nut: no current
        return SourceHeat(name, 0.0, dict(src.into), n, {**details, "held_by_brake": True}), ()
    if src.losses is not None:
        # Copper loss from the torque, no-load loss from the speed, driving or braking alike; a
        # braking motor's shaft power goes back to the amplifier's DC bus, not into the motor.
        losses = src.losses
        if isinstance(losses, DatasheetMotorLosses):
            resistance = losses.resistance_at(temperature)
            copper = servo_motor.heat_motor_copper(torque, losses.torque_constant, resistance)
            details.update(current_A=abs(torque) / losses.torque_constant, terminal_resistance_ohm=resistance)
        else:
            copper = servo_motor.heat_motor_copper_rated(torque, losses.rated_torque, losses.rated_copper_loss)
        no_load = servo_motor.heat_motor_no_load(n, losses.friction_torque, losses.viscous_damping)
        details.update(copper_loss_W=copper, no_load_loss_W=no_load)
        return SourceHeat(name, copper + no_load, dict(src.into), n, details), ()
    if output >= 0.0:
        loss = motors.heat_motor(torque, n, src.efficiency)
    else:
        loss = motors.heat_motor_braking(torque, n, src.efficiency)
    return SourceHeat(name, loss, dict(src.into), n, details), ()

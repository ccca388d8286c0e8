"""Heat sources of a description: bearings, motors, guideways, screw-nut pairs, stated torques and heats."""

from __future__ import annotations

import math
from typing import Annotated, Literal, Union

from pydantic import (
    Field,
    field_validator,
    model_serializer,
    model_validator,
)

from ..physics.bearings_skf import GEOMETRIC_CONSTANTS_SKF, seal_constants_SKF
from ..physics.lubricant import (
    kinematic_viscosity_iso_vg,
    kinematic_viscosity_lubricant,
)
from ..physics.servo_motor import resistance_winding_copper
from .base import Strict
from .quantities import (
    Fraction,
    NonNegAngle,
    NonNegForce,
    NonNegRotationalDamping,
    NonNegTorque,
    PosDensity,
    Temperature,
    PosDimensionless,
    PosDynamicViscosity,
    PosFactor,
    PosForce,
    PosKinematicViscosity,
    PosLength,
    PosMass,
    PosModulus,
    PosPressureViscosityCoefficient,
    PosResistance,
    PosTorque,
    PosTorqueConstant,
    Power,
)

# --------------------------------------------------------------------------- heat sources

ShaftName = Literal["screw", "nut"]
#: The lowest efficiency a motor source may state: below it the loss P (1/eta - 1) is over nine
#: times the shaft power, a motor near standstill, whose loss ``losses`` gives (copper and no-load).
MIN_MOTOR_EFFICIENCY = 0.1
#: The flank half angle's range, [0, 45 deg): the thread-friction formula's (physics/screw_nut.py,
#: friction_angle_thread); a Tr thread has 15 deg, a metric V thread 30 deg, a square one 0.
MAX_FLANK_HALF_ANGLE = math.pi / 4.0


class _Source(Strict):
    into: dict[str, Fraction]  # part name -> share of the heat
    # The part the heat arises in, when it is neither of the parts that receive it: each share then
    # enters its part over that part's contact with ``through`` (a bearing's friction heat, made at
    # the ball-raceway contacts, into the shaft through the inner ring and into the housing through
    # the outer ring); ``through`` itself only conducts.  Every part in ``into`` must be joined to it.
    through: str | None = None
    description: str = ""
    # Multiplies the heat the source's model gives (not the torques it puts on its shaft): set by
    # perturbation studies ("another machine of the same design", analysis/machine_variants.py).
    # Left out of the serialised description at 1 (FeedSystem), so the benches' hashes stay.
    # 0.01 to 100 (quantities.FACTOR_LIMIT): further off, the model is another one.
    heat_factor: PosFactor = 1.0

    @field_validator("into")
    @classmethod
    def _shares_sum_to_one(cls, value: dict[str, float]) -> dict[str, float]:
        if not value:
            raise ValueError("name at least one part that receives the heat")
        total = sum(value.values())
        if abs(total - 1.0) > 1e-9:
            raise ValueError(f"the shares must add up to 1, they add up to {total:g}")
        return value


class Lubricant(Strict):
    """An oil, or a grease's base oil, by its ISO VG grade (ISO 3448 midpoint at 40 °C) and
    its ν at 100 °C as the oil's data sheet states it; ν(T) follows Walther's equation
    (ASTM D341) through the two points (physics/lubricant.py)."""

    grade: str  # "ISO VG 100"
    viscosity_100C: PosKinematicViscosity  # ν at 100 °C from the data sheet

    @field_validator("grade")
    @classmethod
    def _iso_3448_grade(cls, value: str) -> str:
        kinematic_viscosity_iso_vg(value)  # raises, naming the grades ISO 3448 defines
        return value

    @model_validator(mode="after")
    def _thinner_at_100C(self) -> "Lubricant":
        if not self.viscosity_100C < self.viscosity_40C:
            raise ValueError("viscosity_100C must be smaller than the grade's viscosity at 40 degC")
        return self

    @property
    def viscosity_40C(self) -> float:
        """ν at 40 °C [m²/s]: the grade's midpoint."""
        return kinematic_viscosity_iso_vg(self.grade)

    def viscosity_at(self, temperature: float) -> float:
        """ν [m²/s] at ``temperature`` [K], by Walther's equation through 40 and 100 °C."""
        return kinematic_viscosity_lubricant(temperature, self.viscosity_40C, self.viscosity_100C)


class BearingSource(_Source):
    """A rolling bearing (or a set of identical bearings) on a shaft.

    ``friction_model`` chooses the torque: ``"palmgren"`` (load and viscous torque, the paper's
    Eqs. 15–22 corrected; needs ``mean_diameter`` and ``f0``), ``"skf"`` (rolling with the
    inlet-shear and replenishment reductions, sliding, seals, drag; physics/bearings_skf.py;
    needs ``bore_diameter``, ``outer_diameter`` and ``series``) or ``"constant"`` (the catalogue's
    constant coefficient of friction, M = ½ μ P d per bearing with P = F_a + F_r/k, independent of
    the speed and of the lubricant: the preload drag of a grease-packed support pair after run-in;
    needs ``bore_diameter`` and ``friction_coefficient``, takes no lubricant).  Under ``"skf"`` each of the
    ``bearings_in_set`` identical bearings carries ``radial_load / bearings_in_set`` and
    ``axial_load``, and has ``static_load_rating / bearings_in_set`` (the catalogue: compute
    each bearing of a set and add them).

    The lubricant is either ``lubricant_viscosity`` (a fixed ν) or ``lubricant`` (an ISO VG
    grade whose ν is taken at the frozen temperature of the run: ambient plus
    ``temperatures.convection_delta_t``, the temperature the frozen CHTCs use).
    """

    model: Literal["bearing"]
    shaft: ShaftName  # which shaft's speed the bearing runs at
    bearing_type: Literal["angular_contact", "deep_groove"]
    friction_model: Literal["palmgren", "skf", "constant"] = "palmgren"
    mean_diameter: PosLength | None = None  # default (bore_diameter + outer_diameter)/2
    static_load_rating: PosForce
    axial_load: NonNegForce
    radial_load: NonNegForce
    equivalent_static_load: PosForce | None = None  # default: max(axial, radial) load
    f0: PosDimensionless | None = None  # Palmgren's f0
    lubricant_viscosity: PosKinematicViscosity | None = None  # fixed ν [m²/s]
    lubricant: Lubricant | None = None  # or a grade, evaluated at the frozen temperature
    f1_exponent_factor: PosDimensionless | None = None  # deep-groove z; default 5e-4
    # SKF model
    bore_diameter: PosLength | None = None  # d
    outer_diameter: PosLength | None = None  # D
    series: str | None = None  # deep groove: "62", "60", ...; angular contact: "single_row", "double_row", "four_point"
    bearings_in_set: Annotated[int, Field(ge=1)] = 1  # identical bearings the source stands for (a pair: 2)
    lubrication: Literal["grease", "oil_air", "oil_jet", "oil_bath_low_level", "oil_bath"] = "grease"
    base_oil: Literal["mineral", "synthetic", "transmission_fluid"] = "mineral"
    seal: Literal["RSL", "RZ", "RSH", "RS1"] | None = None  # contact seal type (SKF's seal constants); None: open or shielded
    seal_counterface_diameter: PosLength | None = None  # d_s: d1 or d2 of the product table, as SKF's seal constants name
    seals_per_bearing: Literal[1, 2] = 2
    drag_torque: NonNegTorque = 0.0  # M_drag per bearing of an oil bath or oil jet (SKF Diagram 2)
    # Constant-friction model: mu of the bearing type (the catalogue's table); each bearing of the
    # set carries P = axial_load + radial_load / bearings_in_set and M = 0.5 mu P d
    friction_coefficient: PosDimensionless | None = None

    @model_validator(mode="after")
    def _one_lubricant(self) -> "BearingSource":
        if self.friction_model == "constant":  # the catalogue's coefficient holds for its lubrication
            if self.lubricant_viscosity is not None or self.lubricant is not None:
                raise ValueError("lubricant, lubricant_viscosity: not used by friction_model = 'constant'")
            return self
        if (self.lubricant_viscosity is None) == (self.lubricant is None):
            raise ValueError(
                "lubricant_viscosity or lubricant: give one (lubricant_viscosity = \"100 mm^2/s\", "
                "or lubricant = { grade = \"ISO VG 100\", viscosity_100C = \"11 mm^2/s\" })"
            )
        return self

    @model_validator(mode="after")
    def _fields_of_the_friction_model(self) -> "BearingSource":
        if self.friction_model != "constant" and self.friction_coefficient is not None:
            raise ValueError("friction_coefficient: used only by friction_model = 'constant'")
        if self.friction_model == "constant":
            missing = [key for key in ("bore_diameter", "friction_coefficient") if getattr(self, key) is None]
            if missing:
                raise ValueError(f"{', '.join(missing)}: needed by friction_model = 'constant'")
            unused = [key for key in _SKF_ONLY_FIELDS if key not in ("bore_diameter", "outer_diameter", "bearings_in_set")
                      and getattr(self, key) != type(self).model_fields[key].default]
            unused += [key for key in ("f0", "f1_exponent_factor", "equivalent_static_load") if getattr(self, key) is not None]
            if unused:
                raise ValueError(f"{', '.join(unused)}: not used by friction_model = 'constant'")
            if not 0.0 < self.friction_coefficient < 0.1:
                raise ValueError(f"friction_coefficient: {self.friction_coefficient:g} is not a rolling bearing's "
                                 "constant coefficient of friction (catalogues give 0.001-0.005)")
        elif self.friction_model == "palmgren":
            missing = ["f0"] if self.f0 is None else []
            if self.mean_diameter is None and None in (self.bore_diameter, self.outer_diameter):
                missing.append("mean_diameter")
            if missing:
                raise ValueError(f"{', '.join(missing)}: needed by friction_model = 'palmgren'")
            skf_only = [
                key for key in _SKF_ONLY_FIELDS
                if key not in ("bore_diameter", "outer_diameter")
                and getattr(self, key) != type(self).model_fields[key].default
            ]
            if skf_only:
                raise ValueError(f"{', '.join(skf_only)}: used only by friction_model = 'skf'")
        else:
            missing = [key for key in ("bore_diameter", "outer_diameter", "series") if getattr(self, key) is None]
            if missing:
                raise ValueError(f"{', '.join(missing)}: needed by friction_model = 'skf'")
        if None not in (self.bore_diameter, self.outer_diameter):
            if self.outer_diameter <= self.bore_diameter:
                raise ValueError("outer_diameter must be larger than bore_diameter")
            if self.mean_diameter is not None and not math.isclose(
                self.mean_diameter, 0.5 * (self.bore_diameter + self.outer_diameter), rel_tol=1e-6
            ):
                raise ValueError("mean_diameter must be (bore_diameter + outer_diameter)/2; leave it out")
        if self.friction_model == "skf":
            _check_skf_bearing(self)
        return self

    @property
    def dm(self) -> float:
        """Mean diameter [m]: as declared, or (bore + outer diameter)/2."""
        if self.mean_diameter is not None:
            return self.mean_diameter
        return 0.5 * (self.bore_diameter + self.outer_diameter)

    def viscosity_at(self, temperature: float) -> float:
        """The lubricant's ν [m²/s] at ``temperature`` [K] (the fixed value if one is declared)."""
        if self.lubricant is None:
            return self.lubricant_viscosity
        return self.lubricant.viscosity_at(temperature)

    @model_serializer(mode="wrap")
    def _omit_the_unused_options(self, handler):
        # Options left at their defaults (the lubricant form not chosen, the SKF model's fields
        # of a Palmgren bearing) are left out, so a description written before they existed
        # keeps its serialised form and its hash (the benches' frozen provenance).
        data = handler(self)
        if isinstance(data, dict):
            for key in ("lubricant_viscosity", "lubricant", "friction_model", "mean_diameter", "f0", "friction_coefficient",
                        *_SKF_ONLY_FIELDS):
                if key in data and getattr(self, key) == type(self).model_fields[key].default:
                    del data[key]
        return data


#: Fields of a bearing source that only the SKF friction model reads.
_SKF_ONLY_FIELDS = (
    "bore_diameter", "outer_diameter", "series", "bearings_in_set", "lubrication", "base_oil",
    "seal", "seal_counterface_diameter", "seals_per_bearing", "drag_torque",
)


def _check_skf_bearing(src: BearingSource) -> None:
    """The SKF tables know the series, the seal fits the bearing, drag only with oil."""
    known = GEOMETRIC_CONSTANTS_SKF[src.bearing_type]
    if src.series not in known:
        raise ValueError(
            f"series: SKF gives no friction constants for {src.bearing_type} series {src.series!r}; "
            f"known: {', '.join(known)}"
        )
    if src.seal is not None:
        if src.seal_counterface_diameter is None:
            raise ValueError("seal_counterface_diameter: needed with a seal (d1 or d2 of the product table)")
        try:
            seal_constants_SKF(src.seal, src.bearing_type, src.outer_diameter)
        except ValueError as exc:
            raise ValueError(f"seal: {exc}") from None
    elif src.seal_counterface_diameter is not None or src.seals_per_bearing != 2:
        raise ValueError("seal_counterface_diameter, seals_per_bearing: used only with a seal")
    if src.drag_torque > 0.0 and src.lubrication not in ("oil_bath", "oil_bath_low_level", "oil_jet"):
        raise ValueError(f"drag_torque: an oil bath's or oil jet's drag, not for lubrication = {src.lubrication!r}")


class DatasheetMotorLosses(Strict):
    """Copper loss 1.5 (M/k_T)^2 R_tt plus the no-load loss (T_F + D w) w, from a data sheet."""

    model: Literal["datasheet"]
    torque_constant: PosTorqueConstant  # k_T, torque per A r.m.s. [N m/A]
    terminal_resistance: PosResistance  # R_tt, between two terminals ("phase to phase") [ohm], hot unless resistance_temperature says
    friction_torque: NonNegTorque  # T_F, speed-independent drag (friction, hysteresis) [N m]
    viscous_damping: NonNegRotationalDamping  # D, drag per angular speed (viscous, eddy current) [N m s/rad]
    # The winding temperature at which the data sheet states R_tt; given, R_tt follows the motor's
    # temperature (copper, IEC 60034-1); left out, R_tt is used as stated at every temperature.
    resistance_temperature: Temperature | None = None

    def resistance_at(self, temperature: float) -> float:
        """R_tt [ohm] with the winding at ``temperature`` [K]."""
        if self.resistance_temperature is None:
            return self.terminal_resistance
        return float(resistance_winding_copper(self.terminal_resistance, self.resistance_temperature, temperature))


class RatedMotorLosses(Strict):
    """Copper loss P_cu,N (M/M_N)^2 plus the no-load loss (T_F + D w) w."""

    model: Literal["rated"]
    rated_torque: PosTorque  # M_N, where the copper loss is known [N m]
    rated_copper_loss: Power  # P_cu,N at M_N [W]
    friction_torque: NonNegTorque  # T_F [N m]
    viscous_damping: NonNegRotationalDamping  # D [N m s/rad]


MotorLosses = Annotated[Union[DatasheetMotorLosses, RatedMotorLosses], Field(discriminator="model")]


class MotorSource(_Source):
    """A servo motor's heat at the torque its shaft needs: ``efficiency`` or ``losses``.

    ``efficiency``: loss ``P (1/eta - 1)`` driving, ``|P| (1 - eta)`` braking (proportional to the shaft
    power).  ``losses``: copper loss from the torque plus the no-load loss from the speed, driving
    or braking alike (physics/servo_motor.py).
    """

    model: Literal["motor"]
    shaft: ShaftName
    efficiency: Annotated[float, Field(gt=0.0, le=1.0)] | None = None
    losses: MotorLosses | None = None
    extra_torque: NonNegTorque = 0.0  # drag not modelled by the other sources
    # The data sheet's rated continuous (stall) torque M_0 [N m]: given, `check` and `run` refuse an
    # operating point whose shaft needs more (the motor could not hold it, so the description's
    # preloads and frictions are not a machine that can run there).
    continuous_torque: PosTorque | None = None

    @field_validator("efficiency")
    @classmethod
    def _a_motors_efficiency(cls, value: float | None) -> float | None:
        if value is not None and value < MIN_MOTOR_EFFICIENCY:
            raise ValueError(f"{value:g} is below {MIN_MOTOR_EFFICIENCY:g}: the loss P (1/eta - 1) would be over "
                             f"{1.0 / MIN_MOTOR_EFFICIENCY - 1.0:g} times the shaft power; a motor running that "
                             "inefficiently is near standstill, where losses = { model = \"datasheet\", ... } "
                             "gives its copper and no-load loss")
        return value

    @model_validator(mode="after")
    def _one_loss_model(self) -> "MotorSource":
        if self.efficiency is None and self.losses is None:
            raise ValueError("efficiency or losses: give one (efficiency = 0.85, or losses = { model = \"datasheet\", ... })")
        if self.efficiency is not None and self.losses is not None:
            raise ValueError("efficiency and losses: give one loss model, not both")
        return self

    @model_serializer(mode="wrap")
    def _omit_the_unused_loss_model(self, handler):
        # The loss model not chosen is left out, so a description written before `losses`
        # existed keeps its serialised form and its hash (the benches' frozen provenance).
        data = handler(self)
        for key in ("efficiency", "losses", "continuous_torque"):
            if isinstance(data, dict) and data.get(key, 0) is None:
                del data[key]
        return data


class GuidewaySource(_Source):
    model: Literal["guideway"]
    friction_coefficient: Annotated[float, Field(gt=0.0, lt=1.0)]
    moving_mass: PosMass
    external_load: NonNegForce = 0.0
    seal_drag_per_carriage: NonNegForce = 0.0
    carriages: Annotated[int, Field(ge=1)]


class SlidingScrewSource(_Source):
    """A sliding (trapezoidal) screw-nut pair: flank friction, preload and the grease's shear.

    The grease shears at ``grease_viscosity`` (a fixed η) or at its base oil's viscosity at
    the thread's temperature, η = ρ ν(T) from ``grease`` (an ISO VG grade) and
    ``grease_density``: at the thread's shear rates (10³–10⁴ 1/s) a grease thins towards its
    base oil.
    """

    model: Literal["sliding_screw"]
    pitch_diameter: PosLength
    flank_half_angle: NonNegAngle  # half the thread angle: 15 deg for a Tr (ISO 2904) thread
    friction_coefficient: Annotated[float, Field(gt=0.0, le=0.5)]
    preload: NonNegForce = 0.0
    external_axial_load: NonNegForce = 0.0
    grease_viscosity: PosDynamicViscosity | None = None  # fixed η [Pa s]
    grease: Lubricant | None = None  # or the base oil's grade, evaluated at the thread's temperature
    grease_density: PosDensity | None = None  # of the base oil [kg/m^3], with ``grease``
    grease_gap: PosLength
    engaged_length: PosLength

    @field_validator("flank_half_angle")
    @classmethod
    def _flank_below_45_deg(cls, value: float) -> float:
        if not value < MAX_FLANK_HALF_ANGLE:
            raise ValueError(f"must lie from 0 to under 45 deg, the thread-friction formula's range (a Tr thread "
                             f"has 15 deg, a metric V thread 30 deg), got {math.degrees(value):g} deg")
        return value

    @model_validator(mode="after")
    def _one_grease(self) -> "SlidingScrewSource":
        if (self.grease_viscosity is None) == (self.grease is None):
            raise ValueError('grease_viscosity or grease: give one (grease_viscosity = "1 Pa*s", or grease = '
                             '{ grade = "ISO VG 100", viscosity_100C = "11 mm^2/s" } with grease_density)')
        if (self.grease is None) != (self.grease_density is None):
            raise ValueError("grease_density: give it with grease, and only with grease")
        return self

    def grease_viscosity_at(self, temperature: float) -> float:
        """The grease's dynamic viscosity η [Pa s] at ``temperature`` [K]."""
        if self.grease is None:
            return self.grease_viscosity
        return self.grease_density * self.grease.viscosity_at(temperature)

    @model_serializer(mode="wrap")
    def _omit_the_unused_grease(self, handler):
        # The grease form not chosen is left out (a description written before it existed
        # keeps its serialised form and hash).
        data = handler(self)
        if isinstance(data, dict):
            for key in ("grease_viscosity", "grease", "grease_density"):
                if key in data and data[key] is None:
                    del data[key]
        return data


class BallScrewSource(_Source):
    """Rolling friction of a ball screw–nut pair at the relative speed ``|n_screw − n_nut|``.

    Every loaded ball touches the screw's and the nut's groove; each contact adds Heathcote's
    differential sliding, elastic hysteresis and EHL rolling resistance (the paper's Eqs. 1–12,
    corrected: docs/paper-audit.md §1).  The axial load is the guideways' friction plus
    ``external_axial_load``; the lead is the kinematics' lead.  Seals, ball recirculation and
    ball–ball contacts are not modelled (a catalogue drag torque includes them: use ``torque``).
    """

    model: Literal["ball_screw"]
    pitch_diameter: PosLength  # ball-centre (pitch circle) diameter d_m [m]
    ball_diameter: PosLength  # D [m]
    contact_angle: NonNegAngle  # between contact normal and a plane normal to the axis [rad]; 45 deg usual
    screw_conformity: Annotated[float, Field(gt=0.5, lt=1.0)]  # screw groove radius / D [-]; 0.52-0.56 usual
    nut_conformity: Annotated[float, Field(gt=0.5, lt=1.0)]  # nut groove radius / D [-]
    loaded_balls: Annotated[int, Field(ge=1)]  # balls of one load direction (of each half of a preloaded nut) [-]
    preload: NonNegForce = 0.0  # axial preload between the nut's two ball sets [N]; 0: one set carries the load
    external_axial_load: NonNegForce = 0.0  # axial load besides the guideways' friction (a cutting force) [N]
    slip_friction_coefficient: Annotated[float, Field(gt=0.0, le=0.5)]  # Coulomb mu in the micro-slip zones [-]
    hysteresis_loss_fraction: Annotated[float, Field(ge=0.0, le=1.0)]  # alpha_h of the rolling steel [-]
    lubricant_dynamic_viscosity: PosDynamicViscosity  # eta_0 at the nut's temperature, ambient pressure [Pa s]
    pressure_viscosity_coefficient: PosPressureViscosityCoefficient  # alpha_p [1/Pa]; ~2e-8 for mineral oils
    youngs_modulus: PosModulus  # of balls and grooves (one steel) [Pa]
    poisson_ratio: Annotated[float, Field(gt=0.0, lt=0.5)]  # of balls and grooves [-]

    @field_validator("contact_angle")
    @classmethod
    def _angle_between_0_and_90_deg(cls, value: float) -> float:
        if not 0.0 < value < math.pi / 2.0:
            raise ValueError(f"must lie between 0 and 90 deg, got {math.degrees(value):g} deg")
        return value

    @model_validator(mode="after")
    def _balls_fit_the_pitch_circle(self) -> "BallScrewSource":
        if self.ball_diameter >= self.pitch_diameter:
            raise ValueError("ball_diameter must be smaller than pitch_diameter")
        return self


class TorqueSource(_Source):
    """A drag torque stated directly (e.g. a catalogue's preload drag torque of a ball nut).

    ``shaft = "relative"`` means the torque acts between screw and nut at their relative speed.
    """

    model: Literal["torque"]
    shaft: Literal["screw", "nut", "relative"]
    torque: NonNegTorque


class FixedSource(_Source):
    """A heat flow stated directly (for example from a measurement or a catalogue)."""

    model: Literal["fixed"]
    power: Power


HeatSource = Annotated[
    Union[BearingSource, MotorSource, GuidewaySource, SlidingScrewSource, BallScrewSource, TorqueSource,
          FixedSource],
    Field(discriminator="model"),
]

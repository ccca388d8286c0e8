"""A joint is a contact: the overlap of the faces its two parts touch with, as drawn.

The contact is what :mod:`~feedtherm.system.areas` derives a joint's area from: a face on a
face, or a cylinder in a bore of its diameter (the moving group at the middle of the stroke).
Bounding boxes say nothing of it: a part's box may still reach another part when the face
that touched it has moved away (a motor's bracket drawn 540 mm below the base).

- No contact is an error naming the joint and both parts: a joint conducts heat and ties its
  parts over their contact, and parts apart have none (the models would have to invent one).
  Parts that overlap are in contact: a press fit (``fit = true``), or else the overlap is the
  error (system/topology.py).
- A declared ``area`` larger than either part's whole surface as drawn is an error: no contact
  can be larger than the parts it joins, so it is a slip of a unit (``m^2`` for ``mm^2``).
- A declared ``area`` more than :data:`JOINT_AREA_RATIO` times the contact is a warning, not an
  error: the drawing may leave out what touches (a coupling's hub clamped on a journal the
  drawing shows as the shaft's end face, a thread's flanks drawn as a cylinder), and the
  declared area is authoritative for every model.  The warning names both areas, so a unit or a
  face that is wrong shows.
"""

from __future__ import annotations

from . import topology
from .areas import joint_contact_area
from .finding import Finding
from .geometry import part_surface_area
from .schema import FeedSystem

#: A declared joint area more than this many times its contact as drawn is a warning.
JOINT_AREA_RATIO = 2.0


def joint_contacts(system: FeedSystem) -> list[Finding]:
    """The findings of every joint's contact (module docstring): errors and warnings."""
    findings = []
    for i, joint in enumerate(system.joints):
        a, b = joint.between
        if a == b:  # a joint of a part with itself is check's error already
            continue
        contact = joint_contact_area(system, i)
        # parts that overlap are in contact: a press fit, or else topology's error (one line for one mistake)
        if contact <= 0.0 and not topology.parts_overlap(system, a, b):
            findings.append(Finding(f"joints[{i}].between", f"{a!r} and {b!r} have no faces that touch as drawn (a "
                                    "face on a face, or a cylinder in a bore of its diameter; the moving group "
                                    "mid-stroke), so the joint has no contact to conduct or hold over; move one part "
                                    "onto the other, or remove the joint", "error"))
            continue
        area = joint.area
        if area is None:
            continue
        smaller = min((part_surface_area(system.parts[p]), p) for p in (a, b))
        if area > smaller[0]:
            findings.append(Finding(f"joints[{i}].area", f"{area:.4g} m^2 is larger than the whole surface of "
                                    f"{smaller[1]!r} as drawn ({smaller[0]:.4g} m^2): no contact is larger than the "
                                    "parts it joins (a unit slip, m^2 for mm^2?)", "error"))
        elif contact > 0.0 and area > JOINT_AREA_RATIO * contact:
            findings.append(Finding(f"joints[{i}].area", f"{area * 1e6:.4g} mm^2 is {area / contact:.3g} times the "
                                    f"contact of {a!r} and {b!r} as drawn ({contact * 1e6:.4g} mm^2): a unit or the "
                                    "geometry may be wrong (or the drawing leaves out what touches, a journal in a "
                                    "hub)"))
    return findings

"""Arch geometry: a chain of rigid voussoirs between two abutments.

* :mod:`~archrock.geometry.base` -- :class:`VoussoirArch`, what every arch provides downstream
  (joint contact segments, mass properties with loads, outlines), and :class:`Load`;
* :mod:`~archrock.geometry.circular` -- :class:`Arch`, circular voussoir arches (exact annular
  sectors), nominal or irregular;
* :mod:`~archrock.geometry.polygon` -- :class:`PolygonArch`, voussoirs of any shape as polygons;
* :mod:`~archrock.geometry.families` -- :func:`family_arch`: circular, pointed, elliptical,
  three-centred, parabolic and catenary arches from span, rise and thickness;
* :mod:`~archrock.geometry.piers` -- :func:`with_piers`: an arch on two piers of courses
  (:class:`ArchOnPiers`, blocks named "pier" or "voussoir");
* :mod:`~archrock.geometry.displaced` -- :class:`SupportMovement` and :class:`DisplacedArch`,
  an arch after its supports moved (open hinges as point contacts; docs/supports.md).

:func:`arch_from_dict` reads either geometry format (a family arch's dict, with its recipe
under ``"family"``, is rebuilt as the :class:`FamilyArch`).
"""

from .base import DEFAULT_DENSITY, Load, VoussoirArch, polygon_properties, power_of_two_near
from .circular import (OPPENHEIM, Arch, nominal_arch, oppenheim_arch, perturb_voussoirs,
                       random_spans_thicknesses_radii, sector_properties)
from .defect import Defect, apply_defect, apply_defects
from .displaced import DisplacedArch, SupportMovement
from .families import JOINTS, SHAPES, FamilyArch, family_arch
from .irregular import random_arch
from .piers import ArchOnPiers, with_piers
from .polygon import FACE_TOLERANCE, PolygonArch, as_polygon

__all__ = ["VoussoirArch", "Arch", "PolygonArch", "Load", "nominal_arch", "oppenheim_arch",
           "random_arch", "perturb_voussoirs", "random_spans_thicknesses_radii",
           "sector_properties", "polygon_properties", "power_of_two_near", "as_polygon",
           "family_arch", "FamilyArch", "SHAPES", "JOINTS", "arch_from_dict", "OPPENHEIM",
           "DEFAULT_DENSITY", "FACE_TOLERANCE", "Defect", "apply_defect", "apply_defects",
           "ArchOnPiers", "with_piers", "DisplacedArch", "SupportMovement"]


def arch_from_dict(data, name: str = "arch") -> VoussoirArch:
    """An arch from either JSON geometry format: voussoirs with span_deg/radius/thickness (a
    circular :class:`Arch`) or with intrados/extrados polylines (a :class:`PolygonArch`; a
    :class:`FamilyArch` rebuilt from its recipe when the dict holds one under ``"family"``, as
    ``FamilyArch.to_dict`` writes)."""
    from ..errors import ArchInputError

    if isinstance(data, dict) and data.get("family") is not None:
        from .base import _file_fc

        return FamilyArch.from_recipe(data["family"], name=name).with_fc(_file_fc(data))

    vs = data.get("voussoirs") if isinstance(data, dict) else None
    if isinstance(vs, list) and vs and all(isinstance(v, dict) and "intrados" in v for v in vs):
        return PolygonArch.from_dict(data, name=name)
    if isinstance(vs, list) and vs and any(isinstance(v, dict) and "intrados" in v for v in vs):
        raise ArchInputError("voussoirs: mixes polyline voussoirs (intrados/extrados) with "
                             "circular ones (span_deg/radius/thickness); allowed one form")
    return Arch.from_dict(data, name=name)

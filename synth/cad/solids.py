"""The parts of the simplified tensioner (thesis step 11, Fig. 75-76), one function per part.

Every function takes a :class:`~synth.cad.dimensions.TensionerGeometry` and
returns a ``cadquery.Shape`` placed in the assembly frame: ``z`` up from the
crankcase face along the pivot axis (``x = y = 0``), the bearing (working
arm) axis at ``x = working_arm_mm``, the bolt axis at ``x = -loading_arm_mm``.

The axial positions come from :func:`stack`, the thesis's stack-up read as a
chain of faces (eq. 50-53 and step 6):

* standard layout (eq. 52, spring side down): crankcase gap, support plate,
  spring-bushing flange, spring housing (height of eq. 52), damper pad,
  arm plate, bearing (mid-plane = belt plane), endcap spacer, endcap, calking;
* reverse layout (eq. 51/53, spring side up): pivot base, endcap spacer,
  bearing, arm plate, damper pad, spring housing, spring-bushing flange,
  endcap (the cover of the housing), calking.

Parts are built in a canonical frame ``u`` (spring side first) and mirrored
for the reverse layout, so one set of functions serves both.

>>> from synth.cad.dimensions import geometry_from, _example_values, _example_inputs
>>> g = geometry_from(_example_values(), inputs=_example_inputs())
>>> s = stack(g)
>>> round(s.z(s.bearing_centre_u), 6)     # the bearing mid-plane sits on the belt plane (29.5 mm)
29.5
>>> round(pivot(g).BoundingBox().zmax, 6)   # 29.5 + 6.5 + 1.5 + 1.2 + 1.0 (eq. 50 stack)
39.7
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import cadquery as cq

from synth import catalog
from synth.cad.dimensions import TensionerGeometry

__all__ = ["NotBuildable", "MAX_DRAWN_COILS", "Stack", "stack", "PART_FUNCTIONS", "support_plate", "pivot", "pivot_bushing", "arm", "ball_bearing",
           "pulley", "main_spring", "spring_bushing", "damper_pad", "endcap_spacer", "cone_spring", "endcap",
           "fixation_bolt", "spring_pitch_mm"]

_EPS = 1e-6

#: the most active coils the 3D model draws (a software limit, CAD only): the thesis's springs have 4-5, a
#: tensioner's torsion spring rarely more than 10; a spring of more cannot be assembled in a tensioner's housing
#: (its registry checks, the coil gap in the housing, fail already), OCCT's sweep of 70 coils fails outright
#: (StdFail_NotDone, issue 39) and the interference booleans of a long helix grow without bound: 4.5 s for case
#: 1's 4.09 coils, 66 s for 10, 146 s for 20 and 237 s for 40 (synth.cad.verify, one core, issue 39).
MAX_DRAWN_COILS = 30.0


class NotBuildable(ValueError):
    """A part whose dimensions describe no solid (a spring wire wider than its coil) or more than the model draws
    (:data:`MAX_DRAWN_COILS`): the part is not drawn, and the 3D model's ``cad_solids`` check fails naming it."""


@dataclass(frozen=True)
class Stack:
    """Axial faces in the canonical frame ``u`` and the map to ``z`` (mm)."""

    reverse: bool
    z0: float                    # reverse: z = z0 - u; standard: z = u
    closure_u: tuple             # spring-side closure plate (support plate / reverse: endcap)
    flange_top_u: float          # spring-bushing flange top = spring-housing floor
    cavity_top_u: float
    arm_plate_u: float           # spring-side face of the arm plate
    bearing_u: tuple
    bearing_centre_u: float
    far_hub_top_u: float
    hub_bottom_u: float
    damper_pad_u: tuple
    cone_spring_u: tuple
    collar_top_u: float
    endcap_spacer_u: tuple
    far_closure_u: tuple         # far-side closure (endcap / reverse: support plate)
    pivot_u: tuple

    def z(self, u: float) -> float:
        return self.z0 - u if self.reverse else u

    def z_span(self, u0: float, u1: float) -> tuple:
        a, b = self.z(u0), self.z(u1)
        return (min(a, b), max(a, b))


@functools.lru_cache(maxsize=64)
def stack(g: TensionerGeometry) -> Stack:
    """The axial stack of ``g`` (eq. 50-53 with the damper pad, step 6 gap), see the module docstring."""
    rev = g.layout == "reverse"
    h_dp = g.damper_pad_axial_height_mm if g.axial_damping else 0.0
    h_es = g.endcap_spacer_axial_height_mm if g.axial_damping else 0.0
    h_cs = g.cone_spring_installed_height_mm if g.axial_damping else 0.0
    if rev:  # the housing cover (endcap) sits under the calking at the top
        c0 = g.calking_height_mm
        c1 = c0 + g.endcap_height_mm
    else:
        c0 = g.crankcase_gap_mm
        c1 = c0 + g.support_plate_thickness_mm
    fl = c1 + g.spring_bushing_axial_thickness_mm
    cav = fl + g.spring_housing_height_mm
    ap = cav + h_dp
    b0 = ap + g.arm_bearing_support_thickness_mm
    b1 = b0 + g.bearing_width_mm
    bc = 0.5 * (b0 + b1)
    if rev:
        z0 = g.belt_plane_height_mm + bc
        far_hub = z0 - (g.pivot_base_height_mm + h_es)
        far = (far_hub + h_es, far_hub + h_es + g.support_plate_thickness_mm)
        piv = (0.0, z0)
    else:
        z0 = 0.0
        far_hub = b1
        far = (far_hub + h_es, far_hub + h_es + g.endcap_height_mm)
        piv = (0.0, far[1] + g.calking_height_mm)
    hub_h = max(g.pivot_bushing_length_mm, far_hub - ap)
    hb = far_hub - hub_h
    cone = (hb - h_dp - h_cs, hb - h_dp)
    return Stack(rev, z0, (c0, c1), fl, cav, ap, (b0, b1), bc, far_hub, hb, (hb - h_dp, hb), cone, cone[0],
                 (far_hub, far_hub + h_es), far, piv)


# --- helpers ------------------------------------------------------------------------------------

def _c(name: str) -> float:
    return catalog.constant(name)


def _ring(r_in: float, r_out: float, u0: float, u1: float, x: float = 0.0) -> cq.Shape:
    """An annulus (or disc if ``r_in <= 0``) between ``u0`` and ``u1`` around the axis at ``(x, 0)``."""
    h = max(u1 - u0, _EPS)
    s = cq.Solid.makeCylinder(r_out, h, cq.Vector(x, 0, u0))
    if r_in > 0:
        s = s.cut(cq.Solid.makeCylinder(r_in, h, cq.Vector(x, 0, u0)))
    return s


def _place(g: TensionerGeometry, shape: cq.Shape) -> cq.Shape:
    """Canonical frame -> assembly frame (mirror for the reverse layout)."""
    s = stack(g)
    if not s.reverse:
        return shape
    return shape.mirror("XY", (0, 0, 0)).translate(cq.Vector(0, 0, s.z0))


def _housing_radius(g):
    return 0.5 * g.spring_housing_outer_diameter_mm


def _bore_radius(g):
    return 0.5 * g.pivot_diameter_mm + g.pivot_bushing_radial_thickness_mm


def _hub_radius(g):
    return _bore_radius(g) + _c("cad_arm_hub_wall_mm")


def _far_radius(g):
    r = _hub_radius(g)
    if g.axial_damping:
        r = max(r, 0.5 * g.endcap_spacer_outer_diameter_mm)
    return r + _c("cad_endcap_overhang_mm")


def _closure_cup(g, r_flat: float) -> cq.Shape:
    """Spring-side closure: flat plate plus the housing wall up to the arm plate."""
    s = stack(g)
    rh, wall = _housing_radius(g), _c("cad_housing_wall_mm")
    plate = _ring(0.5 * g.pivot_diameter_mm, r_flat, *s.closure_u)
    w = _ring(rh, rh + wall, s.closure_u[1], s.arm_plate_u)
    return _place(g, plate.fuse(w).clean())


def _far_plate(g) -> cq.Shape:
    s = stack(g)
    return _place(g, _ring(0.5 * g.pivot_diameter_mm, _far_radius(g), *s.far_closure_u))


# --- parts ---------------------------------------------------------------------------------------

def support_plate(g: TensionerGeometry) -> cq.Shape:
    """Support plate (generic): standard, the spring-housing cup on the crankcase side (eq. 52: ``t_supp_plate``);
    reverse, the flat pivot-base plate under the endcap spacer (eq. 51: ``h_pivot_base``)."""
    if g.layout == "reverse":
        return _far_plate(g)
    return _closure_cup(g, _housing_radius(g) + _c("cad_housing_wall_mm") + _c("cad_support_plate_rim_mm"))


def endcap(g: TensionerGeometry) -> cq.Shape:
    """Endcap (eq. 50 ``h_e``, eq. 53 ``t_e``): standard, a flat cap under the calking; reverse, the housing cover cup."""
    if g.layout == "reverse":
        return _closure_cup(g, _housing_radius(g) + _c("cad_housing_wall_mm"))
    return _far_plate(g)


def pivot(g: TensionerGeometry) -> cq.Shape:
    """Pivot (step 2): cylinder of ``pivot_diameter_mm`` from the crankcase to the calking, with the bolt hole
    (``pivot_bolt_hole_diameter_mm``) eccentric by the loading arm (0 for a single-eccentric, autosetting pivot)."""
    s = stack(g)
    u0, u1 = s.pivot_u
    body = _ring(0.0, 0.5 * g.pivot_diameter_mm, u0, u1)
    hole = cq.Solid.makeCylinder(0.5 * g.bolt_hole_diameter_mm, u1 - u0 + 2.0, cq.Vector(-g.loading_arm_mm, 0, u0 - 1.0))
    return _place(g, body.cut(hole))


def pivot_bushing(g: TensionerGeometry) -> cq.Shape:
    """Pivot bushing (step 4): tube ``pivot_diameter_mm`` x radial thickness x catalog length, in the arm hub."""
    s = stack(g)
    r = 0.5 * g.pivot_diameter_mm
    return _place(g, _ring(r, r + g.pivot_bushing_radial_thickness_mm, s.hub_bottom_u,
                           s.hub_bottom_u + g.pivot_bushing_length_mm))


def arm(g: TensionerGeometry) -> cq.Shape:
    """Arm (working arm): plate closing the spring housing, eccentric bearing seat (``bearing_inner_diameter_mm``
    at ``working_arm_mm``) and the hub around the pivot bushing (step 2 arm wall, eq. 52 ``t_arm``)."""
    s = stack(g)
    e = g.working_arm_mm
    rb = 0.5 * g.bearing_inner_diameter_mm
    plate = _ring(0.0, _housing_radius(g) + _c("cad_housing_wall_mm"), s.arm_plate_u, s.bearing_u[0])
    plate = plate.fuse(_ring(0.0, rb + _c("cad_arm_seat_shoulder_mm"), s.arm_plate_u, s.bearing_u[0], x=e))
    body = plate.fuse(_ring(0.0, rb, s.bearing_u[0], s.bearing_u[1], x=e))
    if s.hub_bottom_u < s.arm_plate_u - _EPS:
        body = body.fuse(_ring(0.0, _hub_radius(g), s.hub_bottom_u, s.arm_plate_u))
    if s.far_hub_top_u > s.bearing_u[1] + _EPS:
        body = body.fuse(_ring(0.0, _hub_radius(g), s.bearing_u[1], s.far_hub_top_u))
    top = max(s.far_hub_top_u, s.bearing_u[1])
    bore = cq.Solid.makeCylinder(_bore_radius(g), top - s.hub_bottom_u + 2.0, cq.Vector(0, 0, s.hub_bottom_u - 1.0))
    return _place(g, body.cut(bore).clean())


def ball_bearing(g: TensionerGeometry) -> cq.Shape:
    """Deep-groove ball bearing (step 1): inner and outer rings and ``bearing_ball_count`` balls at catalog size."""
    s = stack(g)
    e = g.working_arm_mm
    rp = 0.25 * (g.bearing_inner_diameter_mm + g.bearing_outer_diameter_mm)
    rball = 0.5 * g.bearing_ball_diameter_mm
    c = _c("cad_bearing_ball_clearance_mm")
    u0, u1 = s.bearing_u
    inner = _ring(0.5 * g.bearing_inner_diameter_mm, rp - rball - c, u0, u1, x=e)
    outer = _ring(rp + rball + c, 0.5 * g.bearing_outer_diameter_mm, u0, u1, x=e)
    n = max(int(g.bearing_ball_count), 1)
    balls = [cq.Solid.makeSphere(rball, cq.Vector(e + rp * math.cos(2 * math.pi * k / n),
                                                  rp * math.sin(2 * math.pi * k / n), s.bearing_centre_u))
             for k in range(n)]
    return _place(g, cq.Compound.makeCompound([inner, outer, *balls]))


def pulley(g: TensionerGeometry) -> cq.Shape:
    """Pulley (step 0): ``pulley_diameter_mm`` x ``pulley_width_mm`` rim centred on the bearing mid-plane, body on
    the bearing outer ring; ``toothed``: simple rectangular grooves (tips on the pulley diameter)."""
    s = stack(g)
    e, rp = g.working_arm_mm, 0.5 * g.pulley_diameter_mm
    rb = 0.5 * g.bearing_outer_diameter_mm
    rim_in = max(rp - _c("cad_pulley_rim_thickness_mm"), rb)  # a pulley barely larger than the bearing is a shell
    u0, u1 = s.bearing_u
    w = g.pulley_width_mm
    rim = _ring(rim_in, rp, s.bearing_centre_u - w / 2, s.bearing_centre_u + w / 2, x=e)
    shape = rim.fuse(_ring(rb, rim_in, u0, u1, x=e)) if rim_in > rb + _EPS else rim
    if g.pulley_type == "toothed":
        pitch, depth = _c("cad_pulley_tooth_pitch_mm"), _c("cad_pulley_tooth_depth_mm")
        n = max(4, 4 * round(math.pi * g.pulley_diameter_mm / pitch / 4))
        groove = 0.5 * math.pi * g.pulley_diameter_mm / n
        cutter = (cq.Workplane("XY").workplane(offset=s.bearing_centre_u - w / 2 - 1.0).center(e, 0)
                  .polarArray(rp, 180.0 / n, 360.0, n).rect(2 * depth, groove).extrude(w + 2.0).val())
        shape = shape.cut(cutter)
    return _place(g, shape.clean())


def spring_pitch_mm(g: TensionerGeometry) -> float:
    """Coil pitch of the drawn main spring: the active coils spread over the housing height less a play
    (as eq. (89)-(93) spread them), never closer than ``cad_spring_min_coil_gap_mm``.

    >>> from synth.cad.dimensions import geometry_from, _example_values, _example_inputs
    >>> round(spring_pitch_mm(geometry_from(_example_values(), inputs=_example_inputs())), 4)  # (14.8-2.3-0.1)/4.09
    3.0318
    """
    b, n = g.spring_wire_axial_mm, max(g.spring_active_coils, 0.25)
    spread = (g.spring_housing_height_mm - b - _c("cad_spring_axial_clearance_mm")) / n
    return max(spread, b + _c("cad_spring_min_coil_gap_mm"))


def main_spring(g: TensionerGeometry) -> cq.Shape:
    """Main torsion spring (step 9): a helix of ``spring_active_coils`` turns at ``spring_mean_diameter_mm``,
    swept with the wire section (round ``d``, or rectangular ``b`` axial x ``h`` radial), on the bushing flange."""
    s = stack(g)
    b, h = g.spring_wire_axial_mm, g.spring_wire_radial_mm
    p = spring_pitch_mm(g)
    n = max(g.spring_active_coils, 0.25)
    rm = 0.5 * g.spring_mean_diameter_mm
    if not rm > 0.5 * h:  # the coil's inner radius rm - h/2 would be <= 0: the wire sweeps through itself
        raise NotBuildable(f"a {h:g} mm wire on a {g.spring_mean_diameter_mm:g} mm mean diameter intersects itself "
                           "(the mean diameter must exceed the radial wire size)")
    if not n <= MAX_DRAWN_COILS:
        raise NotBuildable(f"{g.spring_active_coils:.4g} active coils at a {p:.4g} mm pitch make a spring "
                           f"{p * n + b:.4g} mm tall in a {g.spring_housing_height_mm:.4g} mm housing: more than the "
                           f"{MAX_DRAWN_COILS:g} coils the 3D model draws")
    path = cq.Wire.makeHelix(p, p * n, rm, center=cq.Vector(0, 0, s.flange_top_u + b / 2))
    wp = cq.Workplane("XZ", origin=(0, 0, s.flange_top_u + b / 2)).center(rm, 0)
    prof = wp.circle(b / 2) if g.wire_section == "round" else wp.rect(h, b)
    solid = prof.sweep(cq.Workplane().add(path), isFrenet=True).val()
    return _place(g, solid)


def spring_bushing(g: TensionerGeometry) -> cq.Shape:
    """Spring bushing (eq. 52 ``t_spring_bush``): flange under the spring and the collar whose outer diameter is
    the housing inner diameter (``spring_support_inner_diameter_mm``), up to the cone spring / arm hub."""
    s = stack(g)
    rp = 0.5 * g.pivot_diameter_mm
    flange = _ring(rp, _housing_radius(g), s.closure_u[1], s.flange_top_u)
    if s.collar_top_u > s.flange_top_u + _EPS:
        flange = flange.fuse(_ring(rp, 0.5 * g.spring_support_inner_diameter_mm, s.flange_top_u, s.collar_top_u)).clean()
    return _place(g, flange)


def damper_pad(g: TensionerGeometry) -> cq.Shape:
    """Damper pad (Table 3): annulus of ``damper_pad_outer_diameter_mm`` and axial height under the arm hub."""
    s = stack(g)
    return _place(g, _ring(0.5 * g.damper_pad_inner_diameter_mm, 0.5 * g.damper_pad_outer_diameter_mm, *s.damper_pad_u))


def endcap_spacer(g: TensionerGeometry) -> cq.Shape:
    """Endcap spacer (Table 4): annulus from mean radius and contact area, between arm hub and the far closure."""
    s = stack(g)
    return _place(g, _ring(0.5 * g.endcap_spacer_inner_diameter_mm, 0.5 * g.endcap_spacer_outer_diameter_mm,
                           *s.endcap_spacer_u))


def cone_spring(g: TensionerGeometry) -> cq.Shape:
    """Cone (Belleville) spring (step 8) at its installed height: thickness ``t``, remaining cone height
    ``h0 - s_nominal``, diameters ``De``/``Di``; inner edge on the bushing collar, outer edge under the pad."""
    s = stack(g)
    ri, ro = 0.5 * g.cone_spring_inner_diameter_mm, 0.5 * g.cone_spring_outer_diameter_mm
    t = g.cone_spring_thickness_mm
    hc = max(g.cone_spring_installed_height_mm - t, 0.0)
    u0 = s.cone_spring_u[0]
    prof = (cq.Workplane("XZ").polyline([(ri, u0), (ro, u0 + hc), (ro, u0 + hc + t), (ri, u0 + t)]).close()
            .revolve(360.0, (0, 0, 0), (0, 1, 0)).val())
    return _place(g, prof)


def fixation_bolt(g: TensionerGeometry) -> cq.Shape:
    """Fixation bolt (step 10): shank ``bolt_diameter_mm`` through the pivot into the engine, head on the pivot top."""
    s = stack(g)
    top = max(s.z(s.pivot_u[0]), s.z(s.pivot_u[1]))
    d = g.bolt_diameter_mm
    below = _c("cad_bolt_engagement_factor") * d
    x = -g.loading_arm_mm
    shank = cq.Solid.makeCylinder(0.5 * d, top + below, cq.Vector(x, 0, -below))
    head = cq.Solid.makeCylinder(0.5 * g.bolt_head_diameter_mm, _c("cad_bolt_head_height_factor") * d, cq.Vector(x, 0, top))
    return shank.fuse(head).clean()


#: name -> part function, in the order of the thesis's Fig. 75 (bottom-up for the standard layout)
PART_FUNCTIONS = {
    "support_plate": support_plate, "pivot": pivot, "spring_bushing": spring_bushing, "main_spring": main_spring,
    "cone_spring": cone_spring, "damper_pad": damper_pad, "pivot_bushing": pivot_bushing, "arm": arm,
    "ball_bearing": ball_bearing, "pulley": pulley, "endcap_spacer": endcap_spacer, "endcap": endcap,
    "fixation_bolt": fixation_bolt,
}

#: parts present only with the axial damping group
AXIAL_PARTS = ("cone_spring", "damper_pad", "endcap_spacer")

"""The flowchart's output table, in the shape of the thesis's Tables 10 and 14.

:data:`ROWS` lists (section, label, key, unit) in the thesis's order; keys are
those of the case files' ``thesis_tool:`` block. The CLI, ``synth compare`` and
the Excel/HTML reports all print from this one list.
"""

from __future__ import annotations

from synth import formatting as fmt

__all__ = ["ROWS", "format_value"]

ROWS: tuple[tuple[str, str, str, str], ...] = (
    ("Tensioner architecture", "Tensioner architecture typology", "architecture", "-"),
    ("Pulley", "Pulley width", "pulley_width_mm", "mm"),
    ("Ball bearing", "Ball bearing typology", "ball_bearing", "-"),
    ("Pivot", "Pivot diameter", "pivot_diameter_mm", "mm"),
    ("Pivot", "Pivot bushing length", "pivot_bushing_length_mm", "mm"),
    ("Tensioner characterization", "Axial damping present", "axial_damping_present", "Y/N"),
    ("Tensioner characterization", "Axial damping", "axial_damping_nm", "Nm"),
    ("Tensioner characterization", "Radial damping", "radial_damping_nm", "Nm"),
    ("Tensioner characterization", "Spring torque @ nominal position", "spring_torque_nominal_nm", "Nm"),
    ("Plastic friction elements", "Damper pad contact area", "damper_pad_contact_area_mm2", "mm2"),
    ("Plastic friction elements", "Damper pad mean radius", "damper_pad_mean_radius_mm", "mm"),
    ("Plastic friction elements", "Damper pad axial height", "damper_pad_axial_height_mm", "mm"),
    ("Plastic friction elements", "Damper pad outer diameter", "damper_pad_outer_diameter_mm", "mm"),
    ("Plastic friction elements", "Endcap spacer contact area", "endcap_spacer_contact_area_mm2", "mm2"),
    ("Plastic friction elements", "Endcap spacer mean radius", "endcap_spacer_mean_radius_mm", "mm"),
    ("Plastic friction elements", "Endcap spacer axial height", "endcap_spacer_axial_height_mm", "mm"),
    ("Cone spring", "Fax max tolerance", "cone_spring_fax_max_tolerance_n", "N"),
    ("Cone spring", "Fax min tolerance", "cone_spring_fax_min_tolerance_n", "N"),
    ("Cone spring", "Minimum internal diameter", "cone_spring_min_internal_diameter_mm", "mm"),
    ("Cone spring", "Maximum external diameter", "cone_spring_max_external_diameter_mm", "mm"),
    ("Main spring", "Safety factor", "main_spring_safety_factor", "-"),
    ("Main spring", "sigma_a max", "main_spring_sigma_a_max_mpa", "MPa"),
    ("Main spring", "sigma_a min", "main_spring_sigma_a_min_mpa", "MPa"),
    ("Main spring", "sigma_inst", "main_spring_sigma_inst_mpa", "MPa"),
    ("Main spring", "Material", "main_spring_material", "-"),
    ("Main spring", "Working condition", "main_spring_working_condition", "-"),
    ("Main spring", "Wire section type", "main_spring_wire_section", "-"),
    ("Main spring", "Wire section sizes", "main_spring_wire_size_mm", "mm"),
    ("Main spring", "n_a (free state)", "main_spring_active_coils_free", "-"),
    ("Main spring", "Mean body diameter", "main_spring_mean_body_diameter_mm", "mm"),
    ("Main spring", "Spring housing height", "spring_housing_height_mm", "mm"),
    ("Main spring", "Angle between hooks (free state)", "hooks_angle_free_state_deg", "deg"),
    ("Main spring", "Angle between hooks (nominal)", "hooks_angle_nominal_deg", "deg"),
    ("Bolt", "Tightening torque", "bolt_tightening_torque_nm", "Nm"),
    ("Bolt", "Axial force", "bolt_axial_force_n", "N"),
    ("Bolt", "sigma", "bolt_sigma_mpa", "MPa"),
    ("Bolt", "tau", "bolt_tau_mpa", "MPa"),
    ("Bolt", "sigma_eqv", "bolt_sigma_eqv_mpa", "MPa"),
    ("Bolt", "Under-head stress", "bolt_under_head_stress_mpa", "MPa"),
    ("Bolt", "Thread stress", "bolt_thread_stress_mpa", "MPa"),
    ("Bolt", "Format", "bolt_format", "-"),
    ("Bolt", "Property class", "bolt_property_class", "-"),
    ("Tilting and sliding", "Pivot base contact surface", "pivot_base_contact_surface_mm2", "mm2"),
    ("Tilting and sliding", "Average contact pressure", "average_contact_pressure_mpa", "MPa"),
    ("Tilting and sliding", "Tilting safety factor", "tilting_safety_factor", "-"),
    ("Tilting and sliding", "Sliding safety factor", "sliding_safety_factor", "-"),
)


def format_value(v) -> str:
    """Human formatting: floats to 4 significant digits in plain notation (:func:`synth.formatting.number`), lists joined by ' x ', booleans Yes/No."""
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "Yes" if v else "No"
    if isinstance(v, float):
        return fmt.number(v)  # plain engineering notation: 22840, not 2.284e+04
    if isinstance(v, (list, tuple)):
        return " x ".join(format_value(x) for x in v)
    return str(v)

"""The STEP file of a synthesised tensioner: a named, coloured AP214 assembly whose header carries the design.

ISO 10303-21 header: ``FILE_NAME`` names the file ``synth tensioner <application>`` (also the
product of the root assembly), author and organisation ``synth <version>``; ``FILE_DESCRIPTION``
holds the result status and one ``key=value`` per key design value (:data:`DESIGN_KEYS`, the
thesis's own keys). FILE_DESCRIPTION is plain header text, so every STEP reader keeps it (OCP
reads it back, :func:`read_step_header`); OCCT 7.9's STEP writer exports no user-defined product
properties from the XCAF document, so the header is where the values go.

>>> from synth.cad.assembly import build
>>> from synth.cad.dimensions import geometry_from, _example_values, _example_inputs
>>> m = build(geometry_from(_example_values(), inputs=_example_inputs()))
>>> h = step_header(m, "case 1", design_values(m))
>>> h["name"], h["description"][2:4]
('synth tensioner case 1', ['ball_bearing=6006', 'pivot_diameter_mm=16'])
"""

from __future__ import annotations

from pathlib import Path

from synth.cad.assembly import TensionerModel
from synth.version import __version__
from synth.io.outputs import output_file, step_text

__all__ = ["DESIGN_KEYS", "design_values", "step_header", "export_step", "read_step_header"]


#: Design values written into the STEP header (thesis keys), and the older part names they may come under.
DESIGN_KEYS = ("ball_bearing", "pivot_class_diameter_mm", "pivot_diameter_mm", "pivot_bushing_supplier",
               "pivot_bushing_length_mm", "damper_pad_class", "endcap_spacer_class", "main_spring_material", "main_spring_wire",
               "main_spring_mean_body_diameter_mm", "bolt_format", "bolt_property_class")
def design_values(model: TensionerModel, result=None) -> dict:
    """The key design values of ``model`` (:data:`DESIGN_KEYS`): from the geometry, completed from ``result``.

    ``result`` (a flowchart or design result, or its JSON) adds what the geometry does not carry
    (spring material, bolt property class, bushing supplier, pad and spacer classes). Missing values and
    ``none`` classes are left out.
    """
    g = model.geometry
    wire = ("d " if g.wire_section == "round" else "b x h ") + (
        f"{g.spring_wire_axial_mm:g}" if g.wire_section == "round" else f"{g.spring_wire_axial_mm:g} x {g.spring_wire_radial_mm:g}")
    out = {"ball_bearing": g.bearing_designation, "pivot_diameter_mm": g.pivot_diameter_mm,
           "pivot_bushing_length_mm": g.pivot_bushing_length_mm, "main_spring_wire": f"{g.wire_section} {wire} mm",
           "main_spring_mean_body_diameter_mm": g.spring_mean_diameter_mm, "bolt_format": g.bolt_format}
    found: dict = {}
    if result is not None:
        if isinstance(result, dict):
            sources = [result.get("parts") or {}, result.get("values") or {}]
        else:
            sources = [getattr(result, "parts", None) or {}, getattr(result, "values", None) or {}]
        for src in sources:
            for k, v in dict(src).items():
                key = k
                if key in DESIGN_KEYS and key not in found and v is not None and str(v) not in ("", "none", "nan"):
                    found[key] = v
    for k in ("pivot_class_diameter_mm", "pivot_bushing_supplier", "damper_pad_class", "endcap_spacer_class",
              "main_spring_material", "bolt_property_class"):
        if k in found:
            out[k] = found[k]
    return {k: out[k] for k in DESIGN_KEYS if k in out}


def step_header(model: TensionerModel, application: str, design: dict) -> dict:
    """The STEP header (ISO 10303-21 FILE_NAME and FILE_DESCRIPTION) of a synth model.

    ``name`` (FILE_NAME and the root product) ``synth tensioner <application>``, ``author`` and
    ``organisation`` ``synth <version>``, ``description``: the status and one ``key=value`` per design value.
    """
    g = model.geometry
    fmt = {k: (f"{v:g}" if isinstance(v, float) else str(v)) for k, v in design.items()}
    status = f"status={g.verdict or g.status} ({g.status})" + ("" if g.feasible else " (infeasible: nearest design)")
    return {"name": f"synth tensioner {application}", "author": f"synth {__version__}",
            "organisation": f"synth {__version__}",
            "description": [f"synth tensioner design ({g.layout} layout, {g.name})", status]
            + [f"{k}={v}" for k, v in fmt.items()]}


def export_step(model: TensionerModel, path: str | Path, *, application: str | None = None,
                design: dict | None = None) -> Path:
    """Write the STEP assembly (AP214, names and colours kept) with :func:`step_header` as its header.

    The product of the root assembly is named ``synth tensioner <application>``; the design
    values are in FILE_DESCRIPTION, which every STEP reader keeps (OCP reads them back with
    ``APIHeaderSection_MakeHeader``).
    """
    from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.Interface import Interface_Static
    from OCP.STEPCAFControl import STEPCAFControl_Writer
    from OCP.STEPControl import STEPControl_StepModelType
    from OCP.TCollection import TCollection_HAsciiString
    from OCP.XSControl import XSControl_WorkSession
    from cadquery.occ_impl.exporters.assembly import toCAF

    path = Path(path)
    head = step_header(model, application or model.geometry.name, design or design_values(model))
    _, doc = toCAF(model.assembly(step_text(head["name"])), True)
    session = XSControl_WorkSession()
    writer = STEPCAFControl_Writer(session, False)
    writer.SetColorMode(True)
    writer.SetLayerMode(True)
    writer.SetNameMode(True)
    Interface_Static.SetCVal_s("xstep.cascade.unit", "MM")
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    writer.Transfer(doc, STEPControl_StepModelType.STEPControl_AsIs)
    header = APIHeaderSection_MakeHeader(writer.ChangeWriter().Model())
    header.SetName(TCollection_HAsciiString(step_text(head["name"])))
    header.SetAuthorValue(1, TCollection_HAsciiString(step_text(head["author"])))
    header.SetOrganizationValue(1, TCollection_HAsciiString(step_text(head["organisation"])))
    header.SetOriginatingSystem(TCollection_HAsciiString(step_text(head["author"])))
    header.SetAuthorisation(TCollection_HAsciiString(""))
    _set_description(header, head["description"])
    with output_file(path) as tmp:
        if writer.Write(str(tmp)) != IFSelect_ReturnStatus.IFSelect_RetDone:
            raise RuntimeError(f"STEP export failed: {path}")
    return path


def _set_description(header, lines: list[str]) -> None:
    from OCP.Interface import Interface_HArray1OfHAsciiString
    from OCP.TCollection import TCollection_HAsciiString
    arr = Interface_HArray1OfHAsciiString(1, len(lines))
    for i, line in enumerate(lines, start=1):
        arr.SetValue(i, TCollection_HAsciiString(step_text(line)))
    header.SetDescription(arr)


def read_step_header(path: str | Path) -> dict:
    """``{"name", "author", "organisation", "description": [...]}`` of a STEP file, read back with OCP."""
    from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
    from OCP.STEPControl import STEPControl_Reader
    reader = STEPControl_Reader()
    reader.ReadFile(str(path))
    h = APIHeaderSection_MakeHeader(reader.StepModel())
    text = (lambda s: s.ToCString() if s is not None else "")  # noqa: E731
    return {"name": text(h.Name()), "author": text(h.AuthorValue(1)) if h.NbAuthor() else "",
            "organisation": text(h.OrganizationValue(1)) if h.NbOrganization() else "",
            "description": [text(h.DescriptionValue(i)) for i in range(1, h.NbDescription() + 1)]}

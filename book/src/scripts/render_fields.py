"""Renders a case's fields_<case>.vtu as ParaView shows it: the bodies warped by their
displacement (displacement_mm, times a scale factor), mirrored about the axis of an
axisymmetric model, coloured by the von Mises stress (von_mises_mpa), the undeformed bodies in
light grey behind. The book's picture book/src/fields_punch.png was made so (see the chapter
"Fields in ParaView"); CI does not need it.

    xvfb-run -a pvpython book/src/scripts/render_fields.py FIELDS.vtu OUT.png \
        [--scale 200] [--max-mpa 300] [--no-mirror] [--window X0 X1 Y0 Y1]

Needs ParaView's pvpython (Debian: apt-get install paraview xvfb; tried with 5.11).
"""

import argparse

from paraview.simple import (
    ColorBy,
    CreateView,
    GetColorTransferFunction,
    GetScalarBar,
    Reflect,
    Render,
    SaveScreenshot,
    Show,
    Text,
    WarpByVector,
    XMLUnstructuredGridReader,
)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("fields", help="a fields_<case>.vtu written by contopt run")
    parser.add_argument("png", help="the screenshot to write")
    parser.add_argument("--scale", type=float, default=200.0, help="displacement scale")
    parser.add_argument("--max-mpa", type=float, default=None,
                        help="top of the colour range (a punch edge is singular)")
    parser.add_argument("--no-mirror", action="store_true",
                        help="draw the half section only (a plane model)")
    parser.add_argument("--size", type=int, nargs=2, default=[1200, 800])
    parser.add_argument("--window", type=float, nargs=4, metavar=("X0", "X1", "Y0", "Y1"),
                        help="show only this window of the undeformed coordinates [mm]")
    args = parser.parse_args()

    fields = XMLUnstructuredGridReader(FileName=[args.fields])
    fields.UpdatePipeline()
    warp = WarpByVector(Input=fields)
    warp.Vectors = ["POINTS", "displacement_mm"]
    warp.ScaleFactor = args.scale
    deformed, undeformed = warp, fields
    if not args.no_mirror:
        deformed = Reflect(Input=warp)
        deformed.Plane = "X"
        undeformed = Reflect(Input=fields, Plane="X")

    view = CreateView("RenderView")
    view.ViewSize = args.size
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]

    # The undeformed bodies in light grey behind the deformed ones: grey shows where they
    # moved away.
    before = Show(undeformed, view)
    before.ColorArrayName = ["POINTS", ""]
    before.AmbientColor = before.DiffuseColor = [0.85, 0.85, 0.85]
    before.Position = [0.0, 0.0, -0.01]

    note = Text(Text="displacements x%g; grey: undeformed" % args.scale)
    shown = Show(note, view)
    shown.Color = [0.0, 0.0, 0.0]
    shown.FontSize = 16
    shown.WindowLocation = "Lower Left Corner"

    body = Show(deformed, view)
    ColorBy(body, ("POINTS", "von_mises_mpa"))
    lut = GetColorTransferFunction("von_mises_mpa")
    lut.ApplyPreset("Turbo", True)
    low, high = fields.PointData["von_mises_mpa"].GetRange()
    lut.RescaleTransferFunction(0.0, args.max_mpa if args.max_mpa else high)
    body.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = "von Mises [MPa]"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    bar.TitleFontSize = bar.LabelFontSize = 18
    bar.AutomaticLabelFormat = 0
    bar.LabelFormat = bar.RangeLabelFormat = "%.0f"
    bar.WindowLocation = "Any Location"
    bar.Position = [0.88, 0.2]
    bar.ScalarBarLength = 0.6

    # Looking down −z at the model's plane, parallel projection.
    Render(view)
    view.InteractionMode = "2D"
    view.CameraParallelProjection = 1
    view.CameraPosition = [0.0, 0.0, 1.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.ResetCamera(False)
    if args.window:
        x0, x1, y0, y1 = args.window
        centre = [(x0 + x1) / 2, (y0 + y1) / 2]
        view.CameraFocalPoint = [centre[0], centre[1], 0.0]
        view.CameraPosition = [centre[0], centre[1], 1.0]
        aspect = args.size[0] / args.size[1]
        view.CameraParallelScale = max((y1 - y0) / 2, (x1 - x0) / (2 * aspect))
    Render(view)
    SaveScreenshot(args.png, view, ImageResolution=args.size)


if __name__ == "__main__":
    main()

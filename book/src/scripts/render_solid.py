"""Renders a solid's fields_<case>.vtu as ParaView would show it, with pyvista (VTK) off-screen:
the half y >= 0 of the solid (its cells whole) (the section through the contact), warped by its
displacement (displacement_mm times a scale factor) and coloured by the von Mises stress
(von_mises_mpa), the cut's outline in grey. The book's picture book/src/solid_block_fields.png
was made so (chapter "Parts in three dimensions"); CI does not need it.

    python3 -m venv .venv-render && .venv-render/bin/pip install pyvista   # once (VTK 9.7)
    .venv-render/bin/python book/src/scripts/render_solid.py FIELDS.vtu OUT.png \
        [--scale 100] [--max-mpa 1500] [--zoom 2.5]

ParaView's pvpython was not available where the picture was made; its filters Clip (plane
y = 0, crinkle clip), Warp By Vector and Color By von_mises_mpa give the same view.
"""

import argparse

import pyvista as pv


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("fields", help="a fields_<case>.vtu written by contopt run")
    parser.add_argument("png", help="the picture to write")
    parser.add_argument("--scale", type=float, default=100.0, help="displacement scale")
    parser.add_argument("--max-mpa", type=float, default=None, help="top of the colour range")
    parser.add_argument("--zoom", type=float, default=1.0, help="camera zoom")
    parser.add_argument("--size", type=int, nargs=2, default=[1200, 800])
    args = parser.parse_args()

    solid = pv.read(args.fields)
    # The cells on the side y >= 0 whole (a mesh plane y = 0 cuts none).
    half = solid.extract_cells(solid.cell_centers().points[:, 1] > 0.0)
    warped = half.warp_by_vector("displacement_mm", factor=args.scale)
    plotter = pv.Plotter(off_screen=True, window_size=args.size)
    plotter.set_background("white")
    top = args.max_mpa or float(solid["von_mises_mpa"].max())
    plotter.add_mesh(
        warped,
        scalars="von_mises_mpa",
        cmap="viridis",
        clim=(0.0, top),
        # Whole-MPa labels above the bar; its title goes left of it (VTK draws a horizontal
        # bar's title over its labels).
        scalar_bar_args={
            "title": "",
            "color": "black",
            "fmt": "%.0f",
            "n_labels": 5,
            "label_font_size": 16,
        },
    )
    plotter.add_text("von Mises, MPa", position=(150, 22), font_size=11, color="black")
    plotter.add_mesh(half.outline(), color="grey")
    plotter.camera_position = "xz"
    plotter.camera.azimuth = 25.0
    plotter.camera.elevation = 20.0
    plotter.camera.zoom(args.zoom)
    plotter.screenshot(args.png)


if __name__ == "__main__":
    main()

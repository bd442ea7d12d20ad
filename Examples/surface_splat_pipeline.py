#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The shortest Splat pipeline in Python (SurfaceSplatPipeline.cxx line by line): a PLY mesh or
point cloud rendered as EWA surface splats to a PNG.

    ./splat python Examples/surface_splat_pipeline.py input.ply output.png

or, by hand, Debian's Python (the one its VTK is wrapped for) with the build tree's package:

    PYTHONPATH=build/vtk/lib/python3/dist-packages /usr/bin/python3 \\
        Examples/surface_splat_pipeline.py input.ply output.png
"""
import sys

# The OpenGL render window and the other object-factory overrides, as in any VTK Python script.
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkRenderingCore import (
    vtkActor, vtkRenderer, vtkRenderWindow, vtkWindowToImageFilter)

from splat import vtkSplatBackend, vtkSurfaceSplatMapper, vtkSurfelGenerator


def render(input_ply, output_png):
    """Renders input_ply's surface splats to output_png; returns the mapper (its statistics)."""
    reader = vtkPLYReader()
    reader.SetFileName(input_ply)

    # Each vertex becomes a surfel: a normal and a radius that covers the gaps to its neighbors.
    surfels = vtkSurfelGenerator()
    surfels.SetInputConnection(reader.GetOutputPort())

    mapper = vtkSurfaceSplatMapper()
    mapper.SetInputConnection(surfels.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)

    renderer = vtkRenderer()
    renderer.AddActor(actor)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(800, 800)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    window.Render()

    image = vtkWindowToImageFilter()
    image.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetFileName(output_png)
    writer.SetInputConnection(image.GetOutputPort())
    writer.Write()
    return mapper


def main(argv):
    if len(argv) != 3 or not vtkPLYReader.CanReadFile(argv[1]):
        print("Usage: %s input.ply output.png (input.ply must be readable)" % argv[0],
              file=sys.stderr)
        return 1
    mapper = render(argv[1], argv[2])
    print("%s: drawn by the %s backend" % (
        argv[2], vtkSplatBackend.GetBackendAsString(mapper.GetLastBackend())))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

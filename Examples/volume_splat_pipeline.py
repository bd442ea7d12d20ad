#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""A volume through vtkVolumeSplatMapper in Python: one Gaussian kernel per voxel, composited by
EWA volume splatting with a transfer function over the scalar range, shaded, to a PNG.

    ./splat python Examples/volume_splat_pipeline.py [volume.nii.gz|volume.vti] output.png

With one argument it renders the MRI head of Debian's mricron-data.
"""
import sys

import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL render window)
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOImage import vtkNIFTIImageReader, vtkPNGWriter
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.vtkRenderingCore import (
    vtkColorTransferFunction, vtkRenderer, vtkRenderWindow, vtkVolume, vtkVolumeProperty,
    vtkWindowToImageFilter)

from splat import vtkSplatBackend, vtkVolumeSplatMapper

MRI_HEAD = "/usr/share/mricron/templates/ch2.nii.gz"


def range_property(image):
    """Transparent in the lowest fifth of the scalar range (background), then an opacity per
    voxel spacing rising to 0.1 and a color from dark red through orange to white, shaded."""
    low, high = image.GetPointData().GetScalars().GetFiniteRange()
    span = max(high - low, 1e-12)
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(low, 0.0)
    opacity.AddPoint(low + 0.2 * span, 0.0)
    opacity.AddPoint(high, 0.1)
    color = vtkColorTransferFunction()
    color.AddRGBPoint(low + 0.2 * span, 0.5, 0.1, 0.05)
    color.AddRGBPoint(low + 0.6 * span, 0.95, 0.55, 0.3)
    color.AddRGBPoint(high, 1.0, 1.0, 0.95)
    volume_property = vtkVolumeProperty()
    volume_property.SetScalarOpacity(opacity)
    volume_property.SetColor(color)
    volume_property.SetScalarOpacityUnitDistance(min(image.GetSpacing()))
    volume_property.ShadeOn()
    return volume_property


def render(input_file, output_png, size=512):
    """Renders input_file (.nii, .nii.gz or .vti) to output_png; returns the mapper."""
    reader = vtkXMLImageDataReader() if input_file.endswith(".vti") else vtkNIFTIImageReader()
    reader.SetFileName(input_file)
    reader.Update()

    mapper = vtkVolumeSplatMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(range_property(reader.GetOutput()))

    renderer = vtkRenderer()
    renderer.AddVolume(volume)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    # NIfTI's axes are right, anterior, up: the face from the front and a little to the side.
    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(0.0, 0.0, 0.0)
    camera.SetPosition(0.0, 1.0, 0.0)
    camera.SetViewUp(0.0, 0.0, 1.0)
    camera.Azimuth(35.0)
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
    if len(argv) not in (2, 3):
        print("Usage: %s [volume.nii.gz|volume.vti] output.png" % argv[0], file=sys.stderr)
        return 1
    input_file = argv[1] if len(argv) == 3 else MRI_HEAD
    mapper = render(input_file, argv[-1])
    print("%s: %d kernels (%d transparent voxels left out) drawn by the %s backend" % (
        argv[-1], mapper.GetNumberOfKernels(), mapper.GetNumberOfTransparentKernels(),
        vtkSplatBackend.GetBackendAsString(mapper.GetLastBackend())))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

"""The "Volume Splats" representation in pvpython, against a baseline image.

    pvpython TestVolumeSplatRepresentation.py --plugin PATH/SplatPlugin.so
        --baseline-dir Testing/Baseline [--output DIR]

Loads the plugin, shows the Wavelet source (21^3 image data) as Volume Splats in a 300x300
render view under an oblique camera, colored by RTData through ParaView's color map and an
opacity transfer function that hides values below 120, and compares the screenshot with
Testing/Baseline/TestVolumeSplatRepresentation.png (vtkTesting, threshold 0.15). Then checks,
through the mapper's statistics and information properties, that every voxel became a kernel
or was left out as transparent, that each setting exposed on the representation reaches the
mapper (the mapper's own settings by their values, the transfer functions, the unit distance
and shading by the kernels or the image changing), and that a point set of anisotropic Gaussian
kernels with direct colors and opacities (the arrays of a 3D Gaussian Splatting capture) is
drawn too.
"""

import argparse
import os
import sys

from splat_checks import check, exit_status
from splat_images import compare_baseline, mapper_info, mean_difference, test_view

NAME = "TestVolumeSplatRepresentation"
# Settings exposed on the representation: the default, another value, the mapper's information
# property that reads it back, and the value read back.
MAPPER_SETTINGS = [
    ("VolumeSplatOrderingMode", "Automatic", "Clipped", "OrderingModeInfo", 1),
    ("VolumeSplatFootprintFilter", "Automatic", "Antialiased", "FootprintFilterInfo", 2),
    ("VolumeSplatBlendThreshold", 0.85, 0.7, "BlendThresholdInfo", 0.7),
    ("VolumeSplatCutoff", 4.5, 3.0, "CutoffInfo", 3.0),
    ("VolumeSplatCovarianceArrayName", "Covariance", "C", "CovarianceArrayNameInfo", "C"),
    ("VolumeSplatScaleArrayName", "Scale", "S", "ScaleArrayNameInfo", "S"),
    ("VolumeSplatRotationArrayName", "Rotation", "R", "RotationArrayNameInfo", "R"),
    ("VolumeSplatColorArrayName", "Color", "RGB", "ColorArrayNameInfo", "RGB"),
    ("VolumeSplatOpacityArrayName", "Opacity", "A", "OpacityArrayNameInfo", "A"),
    ("VolumeSplatSphericalHarmonicsArrayName", "SphericalHarmonics", "SH",
     "SphericalHarmonicsArrayNameInfo", "SH"),
    ("VolumeSplatMaximumSphericalHarmonicsDegree", 3, 1,
     "MaximumSphericalHarmonicsDegreeInfo", 1),
]

# A point set of Gaussian kernels in the convention of 3D Gaussian Splatting files: a ring of
# elongated kernels, scales (standard deviations), rotation quaternions (w, x, y, z), RGB
# colors in [0, 1] and peak opacities.
GAUSSIANS_SCRIPT = """
import math
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray
output = self.GetPolyDataOutput()
points = vtkPoints()
arrays = {}
for name, components in (("Scale", 3), ("Rotation", 4), ("Color", 3), ("Opacity", 1)):
    arrays[name] = vtkFloatArray()
    arrays[name].SetName(name)
    arrays[name].SetNumberOfComponents(components)
count = 64
for i in range(count):
    angle = 2.0 * math.pi * i / count
    points.InsertNextPoint(math.cos(angle), math.sin(angle), 0.0)
    arrays["Scale"].InsertNextTuple3(0.12, 0.03, 0.03)
    # Each kernel's long axis along the ring's tangent: a rotation about z by angle + 90 deg.
    half = 0.5 * (angle + 0.5 * math.pi)
    arrays["Rotation"].InsertNextTuple4(math.cos(half), 0.0, 0.0, math.sin(half))
    arrays["Color"].InsertNextTuple3(0.5 + 0.5 * math.cos(angle), 0.3, 0.5 - 0.5 * math.cos(angle))
    arrays["Opacity"].InsertNextTuple1(0.8)
output.SetPoints(points)
for array in arrays.values():
    output.GetPointData().AddArray(array)
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--plugin", required=True, help="path of SplatPlugin.so")
    parser.add_argument("--baseline-dir", required=True, help="folder of the baseline images")
    parser.add_argument("--output", default=os.environ.get("SPLAT_TEST_OUTPUT_DIR", "."),
                        help="folder for the screenshots")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)

    from paraview import simple
    simple.LoadPlugin(args.plugin, remote=False, ns=globals())

    view = test_view(simple)

    def screenshot(suffix):
        path = os.path.join(args.output, NAME + suffix + ".png")
        simple.Render(view)
        simple.SaveScreenshot(path, view, ImageResolution=[300, 300])
        return path

    wavelet = simple.Wavelet()
    display = simple.Show(wavelet, view, Representation="Volume Splats")
    simple.ColorBy(display, ("POINTS", "RTData"))
    lut = simple.GetColorTransferFunction("RTData")
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(37.0, 277.0)
    opacity = simple.GetOpacityTransferFunction("RTData")
    opacity.Points = [37.0, 0.0, 0.5, 0.0, 120.0, 0.0, 0.5, 0.0, 277.0, 0.8, 0.5, 0.0]
    view.CameraPosition = [60.0, 45.0, 50.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30.0
    reference = screenshot("")
    compare_baseline(reference, args.baseline_dir, args.output)

    voxels = wavelet.GetDataInformation().GetNumberOfPoints()
    kernels = mapper_info(display, "VolumeSplatCutoff", "NumberOfKernels")
    transparent = mapper_info(display, "VolumeSplatCutoff", "NumberOfTransparentKernels")
    check(kernels > 0 and transparent > 0 and kernels + transparent == voxels,
          "every voxel is a kernel (%s) or transparent (%s): %d voxels"
          % (kernels, transparent, voxels))

    for name, default, value, info, expected in MAPPER_SETTINGS:
        display.SetPropertyWithName(name, value)
        simple.Render(view)
        got = mapper_info(display, "VolumeSplatCutoff", info)
        if isinstance(expected, float):
            ok = got is not None and abs(got - expected) < 1e-9
        else:
            ok = got == expected
        check(ok, "%s = %r reaches the mapper (%s %r)" % (name, value, info, got))
        display.SetPropertyWithName(name, default)

    for backend, last in (("OpenGL", 2), ("CPU", 1)):
        display.VolumeSplatBackend = backend
        simple.Render(view)
        got = mapper_info(display, "VolumeSplatCutoff", "LastBackend")
        check(got == last, "VolumeSplatBackend = %s draws with it (LastBackend %s)" % (backend, got))
    display.VolumeSplatBackend = "Auto"

    # The opacity transfer function decides which voxels are kernels.
    opacity.Points = [37.0, 0.0, 0.5, 0.0, 277.0, 0.0, 0.5, 0.0]
    simple.Render(view)
    got = mapper_info(display, "VolumeSplatCutoff", "NumberOfKernels")
    check(got == 0, "a zero opacity transfer function leaves no kernel (%s)" % got)
    opacity.Points = [37.0, 0.0, 0.5, 0.0, 120.0, 0.0, 0.5, 0.0, 277.0, 0.8, 0.5, 0.0]

    def changes_image(label, apply, undo, minimum=1.0):
        apply()
        path = screenshot("-" + label)
        undo()
        difference = mean_difference(reference, path)
        check(difference > minimum,
              "%s changes the image (mean difference %.2f > %g)" % (label, difference, minimum))

    changes_image("LookupTable", lambda: lut.ApplyPreset("Grayscale", True),
                  lambda: lut.ApplyPreset("Cool to Warm", True))
    # ParaView's default is the data's approximate cell length.
    distance = float(display.ScalarOpacityUnitDistance)
    changes_image("ScalarOpacityUnitDistance",
                  lambda: setattr(display, "ScalarOpacityUnitDistance", 10.0 * distance),
                  lambda: setattr(display, "ScalarOpacityUnitDistance", distance))
    changes_image("Shade", lambda: setattr(display, "Shade", 1),
                  lambda: setattr(display, "Shade", 0), minimum=0.5)
    unchanged = mean_difference(reference, screenshot("-restored"))
    check(unchanged < 0.5, "the defaults restored draw the reference again (%.2f)" % unchanged)
    simple.Hide(wavelet, view)

    # A multiblock holding the one image draws it as that image.
    group = simple.GroupDatasets(Input=[wavelet])
    group_display = simple.Show(group, view, Representation="Volume Splats")
    simple.ColorBy(group_display, ("POINTS", "RTData"))
    grouped = screenshot("-multiblock")
    got = (mapper_info(group_display, "VolumeSplatCutoff", "NumberOfKernels"),
           mapper_info(group_display, "VolumeSplatCutoff", "NumberOfTransparentKernels"))
    check(got[0] > 0 and sum(got) == voxels,
          "a multiblock of the one image draws its %d voxels (kernels, transparent %s)"
          % (voxels, got))
    difference = mean_difference(reference, grouped)
    check(difference < 0.5, "and draws the image's picture (mean difference %.2f)" % difference)
    simple.Hide(group, view)

    # Two images in a multiblock cannot be drawn as one: an error saying so, nothing drawn.
    from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
    messages, window = vtkStringOutputWindow(), vtkOutputWindow.GetInstance()
    vtkOutputWindow.SetInstance(messages)
    shifted = simple.Wavelet(WholeExtent=[20, 40, -10, 10, -10, 10])
    pair = simple.GroupDatasets(Input=[wavelet, shifted])
    pair_display = simple.Show(pair, view, Representation="Volume Splats")
    simple.ColorBy(pair_display, ("POINTS", "RTData"))
    simple.Render(view)
    vtkOutputWindow.SetInstance(window)
    got = mapper_info(pair_display, "VolumeSplatCutoff", "NumberOfKernels")
    check("2 image blocks" in messages.GetOutput() and not got,
          "a multiblock of two images is an error naming them (%r), no kernels (%s)"
          % (messages.GetOutput()[-160:], got))
    simple.Hide(pair, view)

    # Gaussian kernels with their own colors and opacities, no color array selected.
    gaussians = simple.ProgrammableSource(OutputDataSetType="vtkPolyData",
                                          Script=GAUSSIANS_SCRIPT)
    kernels_display = simple.Show(gaussians, view, Representation="Volume Splats")
    kernels_display.ColorArrayName = ["POINTS", ""]
    view.CameraPosition = [0.0, 0.0, 6.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    blank = os.path.join(args.output, NAME + "-blank.png")
    kernels_display.Visibility = 0
    simple.SaveScreenshot(blank, view, ImageResolution=[300, 300])
    kernels_display.Visibility = 1
    ring = screenshot("-gaussians")
    got = mapper_info(kernels_display, "VolumeSplatCutoff", "NumberOfKernels")
    invalid = mapper_info(kernels_display, "VolumeSplatCutoff", "NumberOfInvalidKernels")
    check(got == 64 and invalid == 0,
          "a point set of 64 Gaussians draws 64 kernels (%s, %s invalid)" % (got, invalid))
    difference = mean_difference(blank, ring)
    check(difference > 1.0, "the Gaussian ring is visible (mean difference %.2f)" % difference)

    # Views deleted before the interpreter exits, while their X display is still open.
    simple.Delete(view)
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())

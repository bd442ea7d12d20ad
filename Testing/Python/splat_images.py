"""Image and proxy helpers of the representation tests (pvpython): screenshots compared with
baselines by VTK's regression test, images compared with each other, and the statistics of the
splat mapper behind a representation."""

import os

from splat_checks import check

# vtkTesting's threshold for vtkRegressionTestImage (VTK's default).
BASELINE_THRESHOLD = 0.15


def test_view(simple):
    """A 300x300 render view on a fixed dark background without the orientation axes: the view
    of the representation tests' images."""
    view = simple.CreateView("RenderView")
    view.ViewSize = [300, 300]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.1, 0.1, 0.15]
    return view


def image_array(path):
    """The RGB pixels of a PNG file as a (height, width, 3) float array."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).astype(float)
    return pixels.reshape(height, width, -1)[:, :, :3]


def mean_difference(path_a, path_b):
    """Mean absolute difference per channel (0..255) between two images of the same size."""
    a, b = image_array(path_a), image_array(path_b)
    return float(abs(a - b).mean())


def compare_baseline(path, baseline_dir, temp_dir, threshold=BASELINE_THRESHOLD):
    """VTK's regression test of the screenshot PATH against baseline_dir/<its file name> (or
    the alternatives <name>_1.png ...); on failure a .diff.png is written to temp_dir."""
    from vtkmodules.vtkTestingRendering import vtkTesting
    name = os.path.basename(path)
    baseline = os.path.join(baseline_dir, name)
    testing = vtkTesting()
    for argument in ("-V", baseline, "-T", temp_dir):
        testing.AddArgument(argument)
    result = testing.RegressionTest(path, threshold)
    return check(result == vtkTesting.PASSED,
                 "%s matches the baseline %s (threshold %g)" % (name, baseline, threshold))


def splat_mapper(display, exposed_name):
    """The mapper proxy behind a representation: the owner of one of its exposed properties
    (e.g. SurfaceSplatCutoff, VolumeSplatCutoff)."""
    return display.SMProxy.GetProperty(exposed_name).GetParent()


def mapper_info(display, exposed_name, info_name):
    """An information property of that mapper, read from the VTK object."""
    mapper = splat_mapper(display, exposed_name)
    mapper.UpdatePropertyInformation()
    prop = mapper.GetProperty(info_name)
    return prop.GetElement(0) if prop.GetNumberOfElements() else None

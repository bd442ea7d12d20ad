"""Surface Splats and Volume Splats under ParaView's parallel rendering (pvbatch, IceT).

    mpirun -np N pvbatch --symmetric TestSplatRepresentationsMPI.py --plugin PATH/SplatPlugin.so
        --output DIR [--reference-dir DIR]

Every rank runs the script (--symmetric) and renders each scene from its own piece of the data (pvbatch
splits the sources' output among the ranks), four scenes into DIR/<scene>.png:
- surface: a Sphere source as opaque Surface Splats (IceT composites by depth);
- surface-translucent: the same at Opacity 0.5 (ordered compositing: the surfels are
  redistributed into a k-d tree and the ranks' images blended in order);
- volume-image: the Wavelet as Volume Splats (each rank keeps its extent; ordered compositing
  by the extents);
- volume-kernels: Gaussian kernels on a sphere's points (scale, rotation, color and opacity
  arrays) as Volume Splats (redistributed, ordered compositing).
Rank 0 checks that each rank drew part of the scene (the number of splats or kernels summed
over the ranks is the data's) and, with --reference-dir (the images of a 1-rank run), that each
image is within the bounds below of the 1-rank one.
"""

import argparse
import os
import sys

from splat_checks import check, exit_status
from splat_images import image_array, mapper_info, test_view

# Bounds on the difference from one rank, per scene: the mean absolute difference per channel
# (0..255) and the share of pixels differing by more than 40 in some channel.
# Measured with 2 ranks (Mesa llvmpipe, CPU backends): 0.09 / 0.0009, 0.72 / 0.011 (the seam
# at the k-d tree cut, where the surfels of either side are normalized apart), 0.06 / 0 and
# 0.20 / 0.
BOUNDS = {
    "surface": (0.5, 0.005),
    "surface-translucent": (1.5, 0.02),
    "volume-image": (0.5, 0.002),
    "volume-kernels": (0.5, 0.002),
}
LARGE_STEP = 40

KERNELS_SCRIPT = """
import numpy
from vtkmodules.numpy_interface import dataset_adapter as dsa
data = dsa.WrapDataObject(self.GetInput())
output = dsa.WrapDataObject(self.GetOutput())
n = data.GetNumberOfPoints()
points = numpy.asarray(data.Points)
output.PointData.append(numpy.tile(numpy.array([0.06, 0.02, 0.02], dtype=numpy.float32), (n, 1)), "Scale")
angle = numpy.arctan2(points[:, 1], points[:, 0])
rotation = numpy.zeros((n, 4), dtype=numpy.float32)
rotation[:, 0] = numpy.cos(0.5 * angle)
rotation[:, 3] = numpy.sin(0.5 * angle)
output.PointData.append(rotation, "Rotation")
color = numpy.stack([0.5 + 0.5 * points[:, 2], 0.4 + 0.0 * points[:, 2], 0.5 - 0.5 * points[:, 2]], axis=1)
output.PointData.append(color.astype(numpy.float32), "Color")
output.PointData.append(numpy.full(n, 0.6, dtype=numpy.float32), "Opacity")
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--plugin", required=True, help="path of SplatPlugin.so")
    parser.add_argument("--output", required=True, help="folder for the images")
    parser.add_argument("--reference-dir", help="folder of the 1-rank images to compare with")
    args = parser.parse_args()

    from paraview import simple, servermanager
    controller = servermanager.vtkProcessModule.GetProcessModule().GetGlobalController()
    rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
    if rank == 0:
        os.makedirs(args.output, exist_ok=True)
    simple.LoadPlugin(args.plugin, remote=False, ns=globals())

    view = test_view(simple)

    def reduce(value, operation):
        """VALUE reduced over the ranks (vtkCommunicator: 1 MIN_OP, 2 SUM_OP)."""
        from vtkmodules.vtkCommonCore import vtkIdTypeArray
        send, receive = vtkIdTypeArray(), vtkIdTypeArray()
        send.InsertNextValue(value)
        receive.SetNumberOfTuples(1)
        controller.AllReduce(send, receive, operation)
        return receive.GetValue(0)

    def render(name, display, exposed, statistics, expected, camera):
        """Renders and saves the scene; checks that every rank drew a part and that the
        statistics summed over the ranks are in EXPECTED (low, high)."""
        view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = camera
        view.CameraViewAngle = 30.0
        path = os.path.join(args.output, name + ".png")
        simple.SaveScreenshot(path, view, ImageResolution=[300, 300])
        local = 0
        for statistic in statistics:
            local += mapper_info(display, exposed, statistic) or 0
        summed, least = reduce(local, 2), reduce(local, 1)
        if rank != 0:
            return
        check(expected[0] <= summed <= expected[1] and least > 0,
              "%s on %d rank(s): every rank drew a part (least %d), %s summed over the ranks "
              "%d, in [%d, %d]" % (name, ranks, least, " + ".join(statistics), summed, *expected))
        if args.reference_dir:
            reference = image_array(os.path.join(args.reference_dir, name + ".png"))
            difference = abs(reference - image_array(path))
            mean = float(difference.mean())
            large = float((difference.max(axis=2) > LARGE_STEP).mean())
            mean_bound, large_bound = BOUNDS[name]
            check(mean <= mean_bound and large <= large_bound,
                  "%s: %d ranks against 1: mean difference %.3f (bound %g), pixels off by more "
                  "than %d: %.4f (bound %g)"
                  % (name, ranks, mean, mean_bound, LARGE_STEP, large, large_bound))

    front = ([0.0, 0.0, 4.0], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0])
    sphere = simple.Sphere(ThetaResolution=128, PhiResolution=64, Radius=1.0)
    surface = simple.Show(sphere, view, Representation="Surface Splats")
    simple.ColorBy(surface, ("POINTS", "Normals", "Z"))
    surface.RescaleTransferFunctionToDataRange(True)
    # The pieces' points summed over the ranks: the points on the seams between pieces are in
    # both. Ordered compositing redistributes the surfels and merges those duplicates.
    points = reduce(sphere.GetDataInformation().GetNumberOfPoints(), 2)
    render("surface", surface, "SurfaceSplatCutoff", ["NumberOfSplats"], (points, points), front)
    surface.Opacity = 0.5
    render("surface-translucent", surface, "SurfaceSplatCutoff", ["NumberOfSplats"],
           (int(0.98 * points), points), front)
    simple.Hide(sphere, view)

    wavelet = simple.Wavelet()
    volume = simple.Show(wavelet, view, Representation="Volume Splats")
    simple.ColorBy(volume, ("POINTS", "RTData"))
    lut = simple.GetColorTransferFunction("RTData")
    lut.RescaleTransferFunction(37.0, 277.0)
    opacity = simple.GetOpacityTransferFunction("RTData")
    opacity.Points = [37.0, 0.0, 0.5, 0.0, 120.0, 0.0, 0.5, 0.0, 277.0, 0.8, 0.5, 0.0]
    opacity.RescaleTransferFunction(37.0, 277.0)
    # Each voxel drawn by one rank: the pieces' shared planes are left to one side.
    render("volume-image", volume, "VolumeSplatCutoff",
           ["NumberOfKernels", "NumberOfTransparentKernels"], (21 ** 3, 21 ** 3),
           ([60.0, 45.0, 50.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]))
    simple.Hide(wavelet, view)

    kernels = simple.ProgrammableFilter(Input=sphere, Script=KERNELS_SCRIPT)
    kernel_display = simple.Show(kernels, view, Representation="Volume Splats")
    kernel_display.ColorArrayName = ["POINTS", ""]
    render("volume-kernels", kernel_display, "VolumeSplatCutoff", ["NumberOfKernels"],
           (int(0.98 * points), points), front)

    simple.Delete(view)
    return exit_status()


if __name__ == "__main__":
    # pvbatch finalizes MPI after the script: exit early only to report a failure.
    if main() != 0:
        sys.exit(1)

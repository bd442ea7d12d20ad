"""Plugin volume render test, run by pvpython (offscreen, ParaView's own VTK).

    pvpython TestPluginVolumeRender.py --plugin PATH/SplatPlugin.so [--output DIR]

Loads the plugin, fetches the Wavelet source's image data (RTData, about 37..277) and draws it
with the vtkVolumeSplatMapper made by the mappers/VolumeSplatMapper proxy, in a vtkVolume with an
opacity ramp that hides values below 100, in a plain VTK render window under an oblique camera
(azimuth 40, elevation 30: rays whose dominant axis changes across the image, so the orderings
use several axis lists). Every Backend (Auto, CPU, OpenGL) and every OrderingMode (Blended,
Clipped, SingleAxis, DepthSorted) is set through the proxy. Checks, through the proxy's
information properties, that the setting reached the mapper, that the mapper made kernels and
left the hidden voxels out (NumberOfKernels + NumberOfTransparentKernels is the voxel count,
both non-zero), that LastBackend is the backend asked for (CPU or OpenGL for Auto), that the CPU
counted its projected kernels and a per-frame sort for DepthSorted only, and that the image is
not empty; then that the orderings' images are close to the Blended one, the two backends' images
close to each other, and that on the CPU Clipped and Blended are not bit-identical (a mapper that
ignored OrderingMode would draw the same image). Writes DIR/SplatPluginVolumeRender.png (Auto,
Blended) and DIR/SplatPluginVolumeRender-<backend>-<ordering>.png.
This is a smoke test of the plugin under ParaView's VTK, not a regression-image test.
"""

import argparse
import os
import sys

from splat_checks import check, exit_status, info_value

BACKENDS = {"Auto": 0, "CPU": 1, "OpenGL": 2}
ORDERINGS = {"Blended": 0, "Clipped": 1, "SingleAxis": 2, "DepthSorted": 3}
SIZE = 256
# Image comparisons, on 8-bit RGB: the mean absolute difference per channel over the pixels
# either image covers, and the share of those pixels that differ by more than LARGE_STEP.
MEAN_BOUND = 6.0
LARGE_STEP = 48
LARGE_SHARE_BOUND = 0.02


def pixels(window):
    """The window's RGB pixels as a flat list, and the vtkImageData they came from."""
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    # The frame just rendered, whose statistics were read (a re-render would draw another).
    grab.ShouldRerenderOff()
    grab.ReadFrontBufferOff()
    grab.SetInputBufferTypeToRGB()
    grab.Update()
    image = grab.GetOutput()
    colors = image.GetPointData().GetScalars()
    values = [0] * (3 * colors.GetNumberOfTuples())
    for i in range(colors.GetNumberOfTuples()):
        values[3 * i:3 * i + 3] = colors.GetTuple3(i)
    return values, grab


def difference(a, b):
    """Mean absolute channel difference over the pixels either image covers, the share of those
    pixels with a channel differing by more than LARGE_STEP, and the number of pixels that
    differ at all (0: the images are bit-identical)."""
    covered = 0
    total = 0.0
    large = 0
    differing = 0
    for i in range(0, len(a), 3):
        pa, pb = a[i:i + 3], b[i:i + 3]
        if max(pa) == 0 and max(pb) == 0:
            continue
        covered += 1
        d = [abs(x - y) for x, y in zip(pa, pb)]
        total += sum(d) / 3.0
        differing += max(d) > 0
        if max(d) > LARGE_STEP:
            large += 1
    covered = max(covered, 1)
    return total / covered, large / float(covered), differing


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--plugin", required=True, help="path of SplatPlugin.so")
    parser.add_argument("--output", default=os.environ.get("SPLAT_TEST_OUTPUT_DIR", "."),
                        help="folder for the rendered images")
    args = parser.parse_args()

    from paraview import simple, servermanager
    from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
    from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderWindow,
                                             vtkRenderer, vtkVolume, vtkVolumeProperty)
    from vtkmodules.vtkIOImage import vtkPNGWriter
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (OpenGL object factory overrides)

    simple.LoadPlugin(args.plugin, remote=False, ns=globals())

    wavelet = simple.Wavelet()
    wavelet.UpdatePipeline()
    data = servermanager.Fetch(wavelet)
    if not check(data is not None and data.IsA("vtkImageData") and data.GetNumberOfPoints() > 0,
                 "Wavelet image data fetched"):
        return 1
    voxels = data.GetNumberOfPoints()
    scalars = data.GetPointData().GetScalars()
    low, high = scalars.GetRange()
    check(scalars.GetName() == "RTData" and low < 100.0 < high,
          "scalars %s over %.1f..%.1f straddle the opacity threshold 100"
          % (scalars.GetName(), low, high))
    hidden = sum(1 for i in range(voxels) if scalars.GetValue(i) <= 100.0)

    smproxy = servermanager.CreateProxy("mappers", "VolumeSplatMapper")
    if not check(smproxy is not None, "mappers/VolumeSplatMapper proxy is created"):
        return 1
    # Builds the VTK object and pushes the XML's defaults.
    smproxy.UpdateVTKObjects()
    mapper = smproxy.GetClientSideObject()
    # Python sees the nearest wrapped base class (vtkAbstractVolumeMapper); the object is the
    # splat mapper, whose own SetInputData is not wrapped: vtkAlgorithm's is.
    check(mapper.GetClassName() == "vtkVolumeSplatMapper", "mapper class")
    mapper.SetInputDataObject(0, data)

    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(low, 0.0)
    opacity.AddPoint(100.0, 0.0)
    opacity.AddPoint(high, 0.25)
    color = vtkColorTransferFunction()
    color.AddRGBPoint(100.0, 0.1, 0.3, 1.0)
    color.AddRGBPoint(170.0, 0.2, 1.0, 0.3)
    color.AddRGBPoint(high, 1.0, 0.3, 0.1)
    volume_property = vtkVolumeProperty()
    volume_property.SetScalarOpacity(opacity)
    volume_property.SetColor(color)
    volume_property.SetInterpolationTypeToLinear()
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(volume_property)

    renderer = vtkRenderer()
    renderer.SetBackground(0.0, 0.0, 0.0)
    renderer.AddVolume(volume)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(SIZE, SIZE)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    camera.Azimuth(40.0)
    camera.Elevation(30.0)
    camera.OrthogonalizeViewUp()
    renderer.ResetCamera()
    renderer.ResetCameraClippingRange()
    os.makedirs(args.output, exist_ok=True)

    images = {}
    auto_drew = {}
    for backend in ("Auto", "CPU", "OpenGL"):
        drawn_by = (1, 2) if backend == "Auto" else (BACKENDS[backend],)
        for ordering in ("Blended", "Clipped", "SingleAxis", "DepthSorted"):
            name = "%s/%s" % (backend, ordering)
            smproxy.GetProperty("Backend").SetElement(0, BACKENDS[backend])
            smproxy.GetProperty("OrderingMode").SetElement(0, ORDERINGS[ordering])
            smproxy.UpdateVTKObjects()
            check(info_value(smproxy, "BackendInfo") == BACKENDS[backend]
                  and info_value(smproxy, "OrderingModeInfo") == ORDERINGS[ordering],
                  "%s: the mapper holds the settings" % name)
            sorts_before = info_value(smproxy, "NumberOfSorts")
            window.Render()

            last = info_value(smproxy, "LastBackend")
            kernels = info_value(smproxy, "NumberOfKernels")
            transparent = info_value(smproxy, "NumberOfTransparentKernels")
            invalid = info_value(smproxy, "NumberOfInvalidKernels")
            projected = info_value(smproxy, "NumberOfProjectedKernels")
            near = info_value(smproxy, "NumberOfNearPlaneKernels")
            culled = info_value(smproxy, "NumberOfFrustumCulledKernels")
            sorts = info_value(smproxy, "NumberOfSorts")
            builds = info_value(smproxy, "NumberOfListBuilds")
            ms = info_value(smproxy, "LastRenderTimeInMilliseconds")
            print("%s: LastBackend %s kernels %s transparent %s invalid %s projected %s "
                  "near-plane %s frustum-culled %s sorts %s list builds %s, %.1f ms"
                  % (name, last, kernels, transparent, invalid, projected, near, culled, sorts,
                     builds, ms), flush=True)
            check(last in drawn_by, "%s: LastBackend is one of %s (got %s)"
                  % (name, drawn_by, last))
            check(kernels is not None and kernels > 0, "%s: NumberOfKernels > 0 (got %s)"
                  % (name, kernels))
            check(transparent is not None and transparent > 0,
                  "%s: NumberOfTransparentKernels > 0 (got %s)" % (name, transparent))
            check(kernels is not None and transparent is not None and invalid == 0
                  and kernels + transparent == voxels and transparent == hidden,
                  "%s: kernels + transparent = %d voxels, the %d at or below 100 hidden"
                  % (name, voxels, hidden))
            check(ms is not None and ms > 0.0, "%s: LastRenderTimeInMilliseconds > 0" % name)
            if last == 1:
                # The whole volume is in view and far from the near plane.
                check(projected is not None and projected > 0 and near == 0 and culled == 0,
                      "%s: the CPU projected kernels and culled none" % name)
                # Image data is never sorted except per frame in DepthSorted.
                if ordering == "DepthSorted":
                    check(sorts > sorts_before, "%s: a per-frame depth sort (%s -> %s)"
                          % (name, sorts_before, sorts))
                else:
                    check(sorts == sorts_before, "%s: no sort (%s -> %s)"
                          % (name, sorts_before, sorts))
            elif last == 2:
                check(projected == -1 and near == -1 and culled == -1,
                      "%s: OpenGL leaves the projected and culled counts uncounted (-1)" % name)

            values, grab = pixels(window)
            lit = sum(1 for i in range(0, len(values), 3) if max(values[i:i + 3]) > 8)
            fraction = lit / float(SIZE * SIZE)
            check(0.02 < fraction < 0.95, "%s: the volume covers %.1f%% of the image"
                  % (name, 100.0 * fraction))
            images[(backend, ordering)] = values
            if backend == "Auto":
                auto_drew[ordering] = last
            if backend == "Auto" and ordering == "Blended":
                files = ["SplatPluginVolumeRender.png"]
            else:
                files = []
            if backend != "Auto":
                files.append("SplatPluginVolumeRender-%s-%s.png" % (backend, ordering))
            for file_name in files:
                path = os.path.join(args.output, file_name)
                writer = vtkPNGWriter()
                writer.SetFileName(path)
                writer.SetInputConnection(grab.GetOutputPort())
                writer.Write()
                print("image: %s" % path)

    # The orderings against Blended, per backend, and the backends against each other.
    for backend in ("CPU", "OpenGL"):
        blended = images.get((backend, "Blended"))
        if not check(blended is not None, "%s drew a Blended image" % backend):
            continue
        for ordering in ("Clipped", "SingleAxis", "DepthSorted"):
            other = images.get((backend, ordering))
            if not check(other is not None, "%s drew a %s image" % (backend, ordering)):
                continue
            mean, share, differing = difference(blended, other)
            check(mean < MEAN_BOUND and share < LARGE_SHARE_BOUND,
                  "%s: %s is close to Blended (mean difference %.2f, %d pixels differ, %.2f%% "
                  "off by more than %d)"
                  % (backend, ordering, mean, differing, 100.0 * share, LARGE_STEP))
            if backend == "CPU" and ordering == "Clipped":
                check(differing > 0, "CPU: Clipped and Blended images are not bit-identical "
                      "(%d pixels differ: the ordering reached the mapper)" % differing)
    for ordering in ORDERINGS:
        cpu, gl = images.get(("CPU", ordering)), images.get(("OpenGL", ordering))
        if cpu is not None and gl is not None:
            mean, share, differing = difference(cpu, gl)
            check(mean < MEAN_BOUND and share < LARGE_SHARE_BOUND,
                  "%s: the CPU and OpenGL images are close (mean difference %.2f, %d pixels "
                  "differ, %.2f%% off by more than %d)"
                  % (ordering, mean, differing, 100.0 * share, LARGE_STEP))
        # Auto is one of the two: its image is that backend's, bit for bit.
        resolved = {1: "CPU", 2: "OpenGL"}.get(auto_drew.get(ordering))
        if resolved is not None:
            check(images.get(("Auto", ordering)) == images.get((resolved, ordering)),
                  "%s: Auto drew the same image as %s" % (ordering, resolved))

    return exit_status()


if __name__ == "__main__":
    sys.exit(main())

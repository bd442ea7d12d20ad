"""Plugin render smoke test, run by pvpython (offscreen, ParaView's own VTK).

    pvpython TestPluginRender.py --plugin PATH/SplatPlugin.so [--output DIR]

Loads the plugin, makes surfels of a sphere with the SurfelGenerator filter, and draws them with
the vtkSurfaceSplatMapper made by the mappers/SurfaceSplatMapper proxy in a plain VTK render
window. Checks that the mapper drew splats (its NumberOfSplats statistic, read through the
proxy) and that the image is not empty. Writes the image to DIR/SplatPluginRender.png.
This is a smoke test of the plugin under ParaView's VTK, not a regression-image test.
"""

import argparse
import os
import sys

from splat_checks import check, exit_status, info_value


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--plugin", required=True, help="path of SplatPlugin.so")
    parser.add_argument("--output", default=os.environ.get("SPLAT_TEST_OUTPUT_DIR", "."),
                        help="folder for the rendered image")
    args = parser.parse_args()

    from paraview import simple, servermanager
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkRenderWindow, vtkRenderer,
                                             vtkWindowToImageFilter)
    from vtkmodules.vtkIOImage import vtkPNGWriter
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (OpenGL object factory overrides)

    simple.LoadPlugin(args.plugin, remote=False, ns=globals())

    sphere = simple.Sphere(ThetaResolution=96, PhiResolution=48, Radius=1.0)
    # LoadPlugin(ns=globals()) put the plugin's filter constructors in this module's namespace.
    make_surfels = globals().get("SurfelGenerator")
    if not check(make_surfels is not None, "SurfelGenerator is defined by LoadPlugin"):
        return 1
    surfels = make_surfels(Input=sphere)
    surfels.UpdatePipeline()
    data = servermanager.Fetch(surfels)
    if not check(data is not None and data.GetNumberOfPoints() > 0, "surfels fetched"):
        return 1
    npts = data.GetNumberOfPoints()

    smproxy = servermanager.CreateProxy("mappers", "SurfaceSplatMapper")
    if not check(smproxy is not None, "mappers/SurfaceSplatMapper proxy is created"):
        return 1
    mapper = smproxy.GetClientSideObject()
    # Python sees the nearest wrapped base class (vtkPolyDataMapper); the object is the splat mapper.
    check(mapper.GetClassName() == "vtkSurfaceSplatMapper", "mapper class")
    mapper.SetInputData(data)
    mapper.ScalarVisibilityOff()

    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.9, 0.6, 0.3)
    renderer = vtkRenderer()
    renderer.SetBackground(0.0, 0.0, 0.0)
    renderer.AddActor(actor)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(256, 256)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    window.Render()

    splats = info_value(smproxy, "NumberOfSplats")
    skipped = info_value(smproxy, "NumberOfSkippedPoints")
    check(splats == npts, "mapper took all %d surfels (NumberOfSplats %s)" % (npts, splats))
    check(skipped == 0, "no point skipped (NumberOfSkippedPoints %s)" % (skipped,))

    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.Update()
    image = grab.GetOutput()
    colors = image.GetPointData().GetScalars()
    total = colors.GetNumberOfTuples()
    lit = sum(1 for i in range(total) if max(colors.GetTuple3(i)) > 8)
    fraction = lit / float(total)
    # A unit sphere filling a 30 degree view covers roughly a third of the image.
    check(0.1 < fraction < 0.9, "the splats cover %.1f%% of the image" % (100.0 * fraction))

    os.makedirs(args.output, exist_ok=True)
    path = os.path.join(args.output, "SplatPluginRender.png")
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print("image: %s" % path)

    return exit_status()


if __name__ == "__main__":
    sys.exit(main())

"""Plugin render smoke test, run by pvpython (offscreen, ParaView's own VTK).

    pvpython TestPluginRender.py --plugin PATH/SplatPlugin.so [--output DIR]

Loads the plugin, makes surfels of a sphere with the SurfelGenerator filter, and draws them with
the vtkSurfaceSplatMapper made by the mappers/SurfaceSplatMapper proxy in a plain VTK render
window, once per Backend setting (Auto, CPU, OpenGL, set through the proxy). Checks that the
mapper drew splats (its NumberOfSplats statistic, read through the proxy), that LastBackend is
the backend asked for (CPU or OpenGL for Auto) and that the image is not empty. Writes the
images to DIR/SplatPluginRender.png (Auto) and DIR/SplatPluginRender-<backend>.png.
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
    os.makedirs(args.output, exist_ok=True)

    # The Backend property's values, and what LastBackend may then say (1 CPU, 2 OpenGL).
    for backend, drawn_by, suffix in (("Auto", (1, 2), ""), ("CPU", (1,), "-CPU"),
                                      ("OpenGL", (2,), "-OpenGL")):
        smproxy.GetProperty("Backend").SetElement(0, {"Auto": 0, "CPU": 1, "OpenGL": 2}[backend])
        smproxy.UpdateVTKObjects()
        window.Render()

        last = info_value(smproxy, "LastBackend")
        check(last in drawn_by, "%s: LastBackend is one of %s (got %s)" % (backend, drawn_by, last))
        splats = info_value(smproxy, "NumberOfSplats")
        skipped = info_value(smproxy, "NumberOfSkippedPoints")
        check(splats == npts,
              "%s: mapper took all %d surfels (NumberOfSplats %s)" % (backend, npts, splats))
        check(skipped == 0, "%s: no point skipped (NumberOfSkippedPoints %s)" % (backend, skipped))

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
        check(0.1 < fraction < 0.9,
              "%s: the splats cover %.1f%% of the image" % (backend, 100.0 * fraction))

        path = os.path.join(args.output, "SplatPluginRender%s.png" % suffix)
        writer = vtkPNGWriter()
        writer.SetFileName(path)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()
        print("image: %s" % path)

    return exit_status()


if __name__ == "__main__":
    sys.exit(main())

"""The "Surface Splats" representation in pvpython, against a baseline image.

    pvpython TestSurfaceSplatRepresentation.py --plugin PATH/SplatPlugin.so
        --baseline-dir Testing/Baseline [--output DIR]

Loads the plugin, shows a Sphere source (a mesh with normals, no radii) as Surface Splats in a
300x300 render view, colored by its normals' Z through ParaView's color map, and compares the
screenshot with Testing/Baseline/TestSurfaceSplatRepresentation.png (vtkTesting, threshold
0.15). Then checks, through the mapper's statistics and information properties, that the
mapper drew every point, that each setting exposed on the representation reaches the mapper
(the mapper's own settings by their values, the representation's radius settings and the
coloring by the image changing), that a composite dataset is drawn as one scene and that a
point cloud without normals or radii gets them estimated.
"""

import argparse
import os
import sys

from splat_checks import check, exit_status
from splat_images import compare_baseline, mapper_info, mean_difference, test_view

NAME = "TestSurfaceSplatRepresentation"
# Settings exposed on the representation: the default, another value, the mapper's information
# property that reads it back, and the value read back.
MAPPER_SETTINGS = [
    ("SurfaceSplatCutoff", 0.0, 2.0, "CutoffInfo", 2.0),
    ("SurfaceSplatDepthThreshold", 1.0, 0.5, "DepthThresholdInfo", 0.5),
    ("SurfaceSplatFilterMode", "EWA", "Circular", "FilterModeInfo", 1),
    ("SurfaceSplatNumberOfLayers", 0, 5, "NumberOfLayersInfo", 5),
    ("SurfaceSplatEdgeAntialiasing", 1, 0, "EdgeAntialiasingInfo", 0),
    ("SurfaceSplatCoverageThreshold", 0.0, 0.6, "CoverageThresholdInfo", 0.6),
    ("SurfaceSplatRadius", 1.0, 0.25, "RadiusInfo", 0.25),
    ("SurfaceSplatOpacityArrayName", "Opacity", "Alpha", "OpacityArrayNameInfo", "Alpha"),
    # Set on the representation, which passes them to the mapper.
    ("SurfaceSplatRadiusArrayName", "Radius", "SurfelRadius", "RadiusArrayNameInfo",
     "SurfelRadius"),
    ("SurfaceSplatTangentAxis0ArrayName", "TangentAxis0", "U", "TangentAxis0ArrayNameInfo", "U"),
    ("SurfaceSplatTangentAxis1ArrayName", "TangentAxis1", "V", "TangentAxis1ArrayNameInfo", "V"),
]


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
    view.CameraPosition = [0.0, 0.0, 4.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraViewAngle = 30.0

    def screenshot(suffix):
        path = os.path.join(args.output, NAME + suffix + ".png")
        simple.Render(view)
        simple.SaveScreenshot(path, view, ImageResolution=[300, 300])
        return path

    sphere = simple.Sphere(ThetaResolution=48, PhiResolution=24, Radius=1.0)
    display = simple.Show(sphere, view, Representation="Surface Splats")
    simple.ColorBy(display, ("POINTS", "Normals", "Z"))
    display.RescaleTransferFunctionToDataRange(True)
    reference = screenshot("")
    compare_baseline(reference, args.baseline_dir, args.output)

    points = sphere.GetDataInformation().GetNumberOfPoints()
    check(mapper_info(display, "SurfaceSplatCutoff", "NumberOfSplats") == points,
          "the mapper took all %d points of the sphere" % points)
    check(mapper_info(display, "SurfaceSplatCutoff", "NumberOfSkippedPoints") == 0,
          "no point skipped (normals and estimated radii on every point)")
    check(mapper_info(display, "SurfaceSplatCutoff", "LastBackend") in (1, 2),
          "a backend drew the splats")

    for name, default, value, info, expected in MAPPER_SETTINGS:
        display.SetPropertyWithName(name, value)
        simple.Render(view)
        got = mapper_info(display, "SurfaceSplatCutoff", info)
        if isinstance(expected, float):
            ok = got is not None and abs(got - expected) < 1e-9
        else:
            ok = got == expected
        check(ok, "%s = %r reaches the mapper (%s %r)" % (name, value, info, got))
        display.SetPropertyWithName(name, default)
    simple.Render(view)

    for backend, last in (("OpenGL", 2), ("CPU", 1)):
        display.SurfaceSplatBackend = backend
        simple.Render(view)
        got = mapper_info(display, "SurfaceSplatCutoff", "LastBackend")
        check(got == last, "SurfaceSplatBackend = %s draws with it (LastBackend %s)" % (backend, got))
    display.SurfaceSplatBackend = "Auto"

    # The representation's own settings and the coloring, by the image they draw.
    def changes_image(label, apply, undo, minimum=1.0):
        apply()
        path = screenshot("-" + label)
        undo()
        difference = mean_difference(reference, path)
        check(difference > minimum,
              "%s changes the image (mean difference %.2f > %g)" % (label, difference, minimum))

    changes_image("RadiusScale", lambda: setattr(display, "SurfaceSplatRadiusScale", 0.3),
                  lambda: setattr(display, "SurfaceSplatRadiusScale", 1.0))

    def constant_radius():
        display.SurfaceSplatEstimateRadii = 0
        display.SurfaceSplatRadius = 0.02

    def estimated_radius():
        display.SurfaceSplatEstimateRadii = 1
        display.SurfaceSplatRadius = 1.0

    changes_image("EstimateRadii", constant_radius, estimated_radius)
    changes_image("SolidColor", lambda: simple.ColorBy(display, None),
                  lambda: simple.ColorBy(display, ("POINTS", "Normals", "Z")))
    changes_image("Opacity", lambda: setattr(display, "Opacity", 0.4),
                  lambda: setattr(display, "Opacity", 1.0))
    unchanged = mean_difference(reference, screenshot("-restored"))
    check(unchanged < 0.5, "the defaults restored draw the reference again (%.2f)" % unchanged)
    simple.Hide(sphere, view)

    # A multiblock of two spheres: one scene, every point of both.
    left = simple.Sphere(Center=[-0.6, 0.0, 0.0], Radius=0.5)
    right = simple.Sphere(Center=[0.6, 0.0, 0.0], Radius=0.5, ThetaResolution=16)
    group = simple.GroupDatasets(Input=[left, right])
    blocks = simple.Show(group, view, Representation="Surface Splats")
    simple.Render(view)
    total = (left.GetDataInformation().GetNumberOfPoints() +
             right.GetDataInformation().GetNumberOfPoints())
    got = mapper_info(blocks, "SurfaceSplatCutoff", "NumberOfSplats")
    check(got == total, "a multiblock is drawn as one scene: %s of %d points" % (got, total))
    simple.Hide(group, view)

    # A point cloud without normals or radii: vertices only, normals removed.
    cloud = simple.MaskPoints(Input=sphere, OnRatio=1, GenerateVertices=1,
                              SingleVertexPerCell=1, MaximumNumberofPoints=100000)
    bare = simple.PassArrays(Input=cloud, PointDataArrays=[], CellDataArrays=[])
    bare.UpdatePipeline()
    check(bare.GetDataInformation().GetPointDataInformation().GetArrayInformation("Normals")
          is None, "the point cloud has no normals")
    cloud_display = simple.Show(bare, view, Representation="Surface Splats")
    simple.Render(view)
    cloud_points = bare.GetDataInformation().GetNumberOfPoints()
    got = mapper_info(cloud_display, "SurfaceSplatCutoff", "NumberOfSplats")
    skipped = mapper_info(cloud_display, "SurfaceSplatCutoff", "NumberOfSkippedPoints")
    check(got == cloud_points and skipped == 0,
          "a point cloud gets normals and radii estimated (%s splats of %d, %s skipped)"
          % (got, cloud_points, skipped))
    cloud_reference = screenshot("-cloud")
    cloud_display.SurfaceSplatNumberOfNeighbors = 2
    neighbors = screenshot("-cloud-neighbors")
    cloud_display.SurfaceSplatNumberOfNeighbors = 6
    difference = mean_difference(cloud_reference, neighbors)
    check(difference > 0.2,
          "SurfaceSplatNumberOfNeighbors changes the estimated radii (mean difference %.2f)"
          % difference)
    # Views deleted before the interpreter exits, while their X display is still open.
    simple.Delete(view)
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())

"""Plugin test, run by pvpython: the Differential Point Generator filter (filters/
DifferentialPointGenerator, vtkDifferentialPointGenerator) through ParaView.

    pvpython TestPluginDifferentialPoints.py --plugin PATH/SplatPlugin.so

Checks that the filter is in paraview.simple and in the Splat category of the Filters menu, that
its properties have the documented defaults, and that on a sphere of radius 2 it outputs
polydata with the named arrays, curvatures near -1/2 (the sphere's, outward normals), extents
of the error bound sqrt(2 eps - eps^2) * 2 (within 3%), one point per vertex with Simplify off and fewer
with it on (fewer by Set Cover, the default SimplificationMode, than by Greedy Enclosure); and that the Surface Splats representation draws the simplified points as
differential points (Primitive "Differential Points"): every point taken, none skipped, the
sphere's disk covered without holes. Any failure exits non-zero.
"""

import argparse
import math
import os
import sys
import tempfile

import numpy

from splat_checks import check, info_value, load_plugin, run_tests
from splat_images import image_array, splat_mapper, test_view


def test_differential_points(simple, servermanager):
    make = globals().get("DifferentialPointGenerator")
    if not check(make is not None, "DifferentialPointGenerator is a paraview.simple function"):
        return
    pxm = servermanager.ProxyManager().SMProxyManager
    hints = pxm.GetProxyHints("filters", "DifferentialPointGenerator")
    menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
    check(menu is not None and menu.GetAttribute("category") == "Splat",
          "filters/DifferentialPointGenerator is in the Splat category of the Filters menu")

    sphere = simple.Sphere(ThetaResolution=64, PhiResolution=32, Radius=2.0)
    points = make(Input=sphere)
    defaults = {"MaximumPrincipalError": 0.01, "MaximumPrincipalWidth": 0.0,
                "NumberOfNeighbors": 16, "Simplify": 1, "SimplificationMargin": 0.15}
    for name, value in defaults.items():
        got = getattr(points, name)
        check(math.isclose(got, value), "default %s is %g (got %s)" % (name, value, got))
    check(points.SimplificationMode == "Set Cover",
          "default SimplificationMode is Set Cover (got %s)" % points.SimplificationMode)

    sphere.UpdatePipeline()
    vertices = sphere.GetDataInformation().GetNumberOfPoints()
    points.Simplify = 0
    points.UpdatePipeline()
    info = points.GetDataInformation()
    check(info.GetDataSetTypeAsString() == "vtkPolyData", "output is vtkPolyData")
    # vtkSphereSource's poles are single vertices: every vertex is a sample.
    check(info.GetNumberOfPoints() == vertices,
          "Simplify off: one point per vertex (%d vs %d)" % (info.GetNumberOfPoints(), vertices))
    arrays = {"Normals": 3, "PrincipalDirectionU": 3, "PrincipalDirectionV": 3,
              "PrincipalCurvatures": 2, "Extents": 2}
    for name, components in arrays.items():
        array = points.PointData[name] if name in points.PointData.keys() else None
        check(array is not None and array.GetNumberOfComponents() == components,
              "output has %s with %d components" % (name, components))
    if "PrincipalCurvatures" in points.PointData.keys():
        for component in (0, 1):
            lo, hi = points.PointData["PrincipalCurvatures"].GetRange(component)
            check(abs(lo + 0.5) < 0.02 and abs(hi + 0.5) < 0.02,
                  "curvature %d of the sphere is -1/2 (range [%g, %g])" % (component, lo, hi))
    if "Extents" in points.PointData.keys():
        # Within the curvatures' 3% (the quadric fit's bias on this coarse sphere is 1.7%).
        bound = math.sqrt(2 * 0.01 - 0.01 ** 2) * 2.0
        lo, hi = points.PointData["Extents"].GetRange(0)
        check(abs(lo - bound) < 0.03 * bound and abs(hi - bound) < 0.03 * bound,
              "extents are the error bound %g (range [%g, %g])" % (bound, lo, hi))

    points.Simplify = 1
    points.UpdatePipeline()
    kept = points.GetDataInformation().GetNumberOfPoints()
    check(0 < kept < vertices / 2, "Simplify on keeps fewer points (%d of %d)" % (kept, vertices))
    points.SimplificationMode = "Greedy Enclosure"
    points.UpdatePipeline()
    greedy = points.GetDataInformation().GetNumberOfPoints()
    check(kept < greedy < vertices / 2,
          "the set cover keeps fewer points than the greedy enclosure (%d, %d)" % (kept, greedy))
    points.SimplificationMode = "Set Cover"
    points.UpdatePipeline()
    data = servermanager.Fetch(points)
    check(data is not None and data.GetPointData().GetNormals() is not None
          and data.GetPointData().GetNormals().GetName() == "Normals",
          "fetched output has Normals as its active normals")
    test_display(simple, points, kept)
    simple.Delete(points)
    simple.Delete(sphere)


def test_display(simple, points, kept):
    """The simplified points drawn by the Surface Splats representation as differential points,
    both footprints: the mapper takes every point and the sphere's disk has no hole."""
    view = test_view(simple)
    display = simple.Show(points, view, Representation="Surface Splats")
    display.SurfaceSplatPrimitive = "Differential Points"
    mapper = splat_mapper(display, "SurfaceSplatPrimitive")
    background = [255 * c for c in view.Background]
    for filter_mode in ("EWA", "Unfiltered"):
        display.SurfaceSplatFilterMode = filter_mode
        simple.Render(view)
        check(info_value(mapper, "PrimitiveInfo") == 1,
              "%s: the mapper draws differential points" % filter_mode)
        check(info_value(mapper, "NumberOfSplats") == kept,
              "%s: the mapper took the %d points" % (filter_mode, kept))
        check(info_value(mapper, "NumberOfSkippedPoints") == 0,
              "%s: no point skipped (the generator's arrays found)" % filter_mode)
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "differential-points.png")
            simple.SaveScreenshot(path, view, ImageResolution=[300, 300])
            pixels = image_array(path)
        # The sphere's disk: its covered pixels' bounding box gives the center and radius; no
        # pixel within 0.9 of the radius may show the background.
        covered = abs(pixels - background).sum(axis=2) >= 3.0
        rows, columns = numpy.nonzero(covered)
        if not check(len(rows) > 0, "%s: the sphere is drawn" % filter_mode):
            continue
        center_row = (rows.min() + rows.max()) / 2
        center_column = (columns.min() + columns.max()) / 2
        radius = (columns.max() - columns.min()) / 2
        y, x = numpy.indices(covered.shape)
        inside = (y - center_row) ** 2 + (x - center_column) ** 2 < (0.9 * radius) ** 2
        holes = int((inside & ~covered).sum())
        check(radius > 50, "%s: the sphere is %d pixels wide" % (filter_mode, 2 * radius))
        check(holes == 0, "%s: no background pixel inside the sphere (%d)" % (filter_mode, holes))
    simple.Delete(display)
    simple.Delete(view)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--plugin", required=True, help="path of SplatPlugin.so")
    args = parser.parse_args()
    if not load_plugin(args.plugin, globals()):
        return 1
    from paraview import simple, servermanager
    return run_tests((lambda: test_differential_points(simple, servermanager),))


if __name__ == "__main__":
    sys.exit(main())

"""Plugin test, run by pvpython: loads the Splat ParaView plugin and uses its proxies.

    pvpython TestPluginLoad.py --plugin PATH/SplatPlugin.so

Checks that
- the plugin loads in the client (builtin) session;
- mappers/SurfaceSplatMapper creates a vtkSurfaceSplatMapper whose settings (Cutoff, Radius,
  DepthThreshold, RadiusArrayName, FilterMode, Backend, NumberOfLayers, EdgeAntialiasing,
  CoverageThreshold, OpacityArrayName, TangentAxis0ArrayName, TangentAxis1ArrayName) have their
  defaults and, set through the proxy, read back from the VTK object (through their information
  properties and the object's getters), and whose render statistics (LastBackend included) are
  exposed; a missing property fails;
- mappers/VolumeSplatMapper creates a vtkVolumeSplatMapper (a vtkAbstractVolumeMapper) whose
  settings (OrderingMode, FootprintFilter, BlendThreshold, Cutoff, Backend, CovarianceArrayName, ScaleArrayName,
  RotationArrayName, ColorArrayName, OpacityArrayName, SphericalHarmonicsArrayName,
  MaximumSphericalHarmonicsDegree) have their defaults and round-trip the
  same way, with their enumerations and ranges, and whose render statistics (LastBackend,
  NumberOfKernels, NumberOfTransparentKernels, NumberOfInvalidKernels, NumberOfProjectedKernels,
  NumberOfNearPlaneKernels, NumberOfFrustumCulledKernels, NumberOfSorts, NumberOfListBuilds,
  LastRenderTimeInMilliseconds) are information-only properties;
- filters/SurfelGenerator is in paraview.simple after LoadPlugin, runs on a Sphere source and
  produces points with normals and a radius array.
Any failure exits non-zero (a missing plugin, class or proxy included).
"""

import argparse
import math
import sys

from splat_checks import check, info_value, load_plugin, run_tests


def check_defaults_and_enumerations(smproxy, mapper, what, defaults, entries, texts):
    """Checks a mapper proxy's defaults (read back through the <Name>Info properties after
    UpdateVTKObjects), the entries of its enumerations, and the text its enumerations read as.
    `what` prefixes the messages."""
    for name, value in defaults.items():
        got = info_value(smproxy, name + "Info")
        if isinstance(value, str):
            ok = got == value
        else:
            ok = close(got, value, 1e-9)
        check(ok, "%sdefault %s is %r (got %r)" % (what, name, value, got))
    for name, text in texts.items():
        got = getattr(mapper, name)
        check(got == text, "%sdefault %s reads as %r (got %r)" % (what, name, text, got))
    for name, expected in entries.items():
        enum = smproxy.GetProperty(name).FindDomain("vtkSMEnumerationDomain")
        found = {}
        if check(enum is not None, "%s%s has an enumeration domain" % (what, name)):
            found = {enum.GetEntryText(i): enum.GetEntryValue(i)
                     for i in range(enum.GetNumberOfEntries())}
        check(found == expected, "%s%s entries are %s (got %s)" % (what, name, expected, found))


def close(a, b, tol=1e-12):
    return a is not None and b is not None and math.isclose(a, b, rel_tol=tol, abs_tol=tol)


def test_mapper(servermanager):
    smproxy = servermanager.CreateProxy("mappers", "SurfaceSplatMapper")
    if not check(smproxy is not None, "mappers/SurfaceSplatMapper proxy is created"):
        return
    check(smproxy.GetXMLName() == "SurfaceSplatMapper", "proxy XML name")

    # In the builtin session the VTK object lives in this process: ask it its class.
    vtk_object = smproxy.GetClientSideObject()
    check(vtk_object is not None, "the proxy has a VTK object")
    if vtk_object is not None:
        check(vtk_object.GetClassName() == "vtkSurfaceSplatMapper",
              "VTK object class is vtkSurfaceSplatMapper (got %s)" % vtk_object.GetClassName())
        check(vtk_object.IsA("vtkPolyDataMapper"), "vtkSurfaceSplatMapper is a vtkPolyDataMapper")

    mapper = servermanager._getPyProxy(smproxy)

    # Every setting has its property and its information (read-back) property; every statistic
    # its information-only property. A missing one fails here, before the round trips.
    settings = ["Radius", "RadiusArrayName", "Cutoff", "MagnifiedLowPassVariance",
                "MinifiedVariance", "LevelOfDetail",
                "DepthThreshold",
                "FilterMode", "Backend", "NumberOfLayers", "EdgeAntialiasing", "CoverageThreshold", "OpacityArrayName",
                "TangentAxis0ArrayName", "TangentAxis1ArrayName", "Primitive",
                "PrincipalDirectionUArrayName", "PrincipalDirectionVArrayName",
                "PrincipalCurvaturesArrayName", "ExtentsArrayName"]
    statistics = ["NumberOfSplats", "NumberOfRenderedSplats", "NumberOfMergedSplats",
                  "NumberOfCulledSplats",
                  "NumberOfFrustumCulledSplats", "NumberOfBackfaceCulledSplats",
                  "NumberOfNegligibleSplats", "NumberOfSkippedPoints",
                  "LastRenderTimeInMilliseconds", "LastBackend"]
    for name in settings:
        prop = smproxy.GetProperty(name)
        check(prop is not None and not prop.GetInformationOnly(),
              "property %s exists and is settable" % name)
        info = smproxy.GetProperty(name + "Info")
        check(info is not None and info.GetInformationOnly(),
              "information property %sInfo exists" % name)
        check(prop is not None and prop.GetInformationProperty() is not None
              and prop.GetInformationProperty() == info,
              "%s reads back through %sInfo" % (name, name))
    for name in statistics:
        prop = smproxy.GetProperty(name)
        check(prop is not None and prop.GetInformationOnly(),
              "statistic %s is an information-only property" % name)

    # Defaults: the VTK object's state after the XML's defaults are pushed, read back through the
    # information properties (they call the object's getters; the plugin has client-server
    # wrapping only, so Python sees the object as its nearest Python-wrapped base class and cannot
    # call them itself), agrees with the mapper's documented defaults.
    smproxy.UpdateVTKObjects()
    check_defaults_and_enumerations(
        smproxy, mapper, "",
        {"Cutoff": 0.0, "MagnifiedLowPassVariance": 0.0, "MinifiedVariance": 0.75,
         "LevelOfDetail": 1, "Radius": 1.0,
         "DepthThreshold": 1.0,
         "FilterMode": 0,
         "Backend": 0, "NumberOfLayers": 0, "EdgeAntialiasing": 1, "CoverageThreshold": 0.0,
         "RadiusArrayName": "Radius", "OpacityArrayName": "Opacity",
         "TangentAxis0ArrayName": "TangentAxis0",
         "TangentAxis1ArrayName": "TangentAxis1", "Primitive": 0,
         "PrincipalDirectionUArrayName": "PrincipalDirectionU",
         "PrincipalDirectionVArrayName": "PrincipalDirectionV",
         "PrincipalCurvaturesArrayName": "PrincipalCurvatures",
         "ExtentsArrayName": "Extents"},
        {"FilterMode": {"EWA": 0, "Circular": 1, "Unfiltered": 2, "Approximate": 3},
         "Backend": {"Auto": 0, "CPU": 1, "OpenGL": 2},
         "Primitive": {"Surfels": 0, "Differential Points": 1}},
        {"FilterMode": "EWA", "Backend": "Auto", "Primitive": "Surfels"})

    # The NumberOfLayers range.
    layers = smproxy.GetProperty("NumberOfLayers").FindDomain("vtkSMIntRangeDomain")
    if check(layers is not None, "NumberOfLayers has a range domain"):
        check(layers.GetMinimum(0) == 0 and layers.GetMaximum(0) == 8,
              "NumberOfLayers ranges over 0 (automatic)..8 (got %d..%d)"
              % (layers.GetMinimum(0), layers.GetMaximum(0)))
    check(smproxy.GetProperty("EdgeAntialiasing").FindDomain("vtkSMBooleanDomain") is not None,
          "EdgeAntialiasing is a boolean")

    # Round trips: proxy property -> VTK object -> information property.
    values = {"Cutoff": 2.5, "MagnifiedLowPassVariance": 0.5, "MinifiedVariance": 0.0,
              "LevelOfDetail": 0, "Radius": 0.125,
              "DepthThreshold": 0.75,
              "NumberOfLayers": 5, "EdgeAntialiasing": 0, "CoverageThreshold": 0.25}
    strings = {"RadiusArrayName": "SplatRadius", "OpacityArrayName": "SplatOpacity",
               "TangentAxis0ArrayName": "MajorAxis", "TangentAxis1ArrayName": "MinorAxis",
               "PrincipalDirectionUArrayName": "MaxDirection",
               "PrincipalDirectionVArrayName": "MinDirection",
               "PrincipalCurvaturesArrayName": "Curvatures", "ExtentsArrayName": "HalfWidths"}
    for name, value in list(values.items()) + list(strings.items()):
        setattr(mapper, name, value)
    mapper.FilterMode = "Unfiltered"
    mapper.Backend = "OpenGL"
    mapper.Primitive = "Differential Points"
    smproxy.UpdateVTKObjects()
    values["FilterMode"] = 2
    values["Backend"] = 2
    values["Primitive"] = 1
    for name, value in values.items():
        got = info_value(smproxy, name + "Info")
        check(close(got, value), "%s round-trips (set %g, got %s)" % (name, value, got))
    for name, value in strings.items():
        got = info_value(smproxy, name + "Info")
        check(got == value, "%s round-trips (set %r, got %r)" % (name, value, got))

    # Back again, through the other values: a setting that only ever holds one value proves
    # nothing.
    mapper.FilterMode = "Circular"
    mapper.Backend = "CPU"
    mapper.EdgeAntialiasing = 1
    mapper.NumberOfLayers = 8
    mapper.Primitive = "Surfels"
    smproxy.UpdateVTKObjects()
    for name, value in {"FilterMode": 1, "Backend": 1, "EdgeAntialiasing": 1,
                        "NumberOfLayers": 8, "Primitive": 0}.items():
        got = info_value(smproxy, name + "Info")
        check(close(got, value), "%s round-trips (set %g, got %s)" % (name, value, got))
    check(mapper.FilterMode == "Circular", "FilterMode reads as 'Circular' (got %r)"
          % (mapper.FilterMode,))
    # And the values only the new entries hold.
    mapper.FilterMode = "Approximate"
    mapper.Backend = "Auto"
    smproxy.UpdateVTKObjects()
    for name, value in {"FilterMode": 3, "Backend": 0}.items():
        got = info_value(smproxy, name + "Info")
        check(close(got, value), "%s round-trips (set %g, got %s)" % (name, value, got))

    # Render statistics are exposed before any render (LastBackend is then Auto, 0).
    for name in statistics:
        got = info_value(smproxy, name)
        check(got == 0, "%s is 0 before a render (got %s)" % (name, got))


def check_domain_range(smproxy, name, domain_class, low, high):
    """The property's range domain spans low..high."""
    domain = smproxy.GetProperty(name).FindDomain(domain_class)
    if check(domain is not None, "%s has a range domain" % name):
        got = (domain.GetMinimum(0), domain.GetMaximum(0))
        check(close(got[0], low) and close(got[1], high),
              "%s ranges over %g..%g (got %g..%g)" % (name, low, high, got[0], got[1]))


def test_volume_mapper(servermanager):
    smproxy = servermanager.CreateProxy("mappers", "VolumeSplatMapper")
    if not check(smproxy is not None, "mappers/VolumeSplatMapper proxy is created"):
        return
    check(smproxy.GetXMLName() == "VolumeSplatMapper", "volume proxy XML name")

    vtk_object = smproxy.GetClientSideObject()
    check(vtk_object is not None, "the volume proxy has a VTK object")
    if vtk_object is not None:
        check(vtk_object.GetClassName() == "vtkVolumeSplatMapper",
              "VTK object class is vtkVolumeSplatMapper (got %s)" % vtk_object.GetClassName())
        check(vtk_object.IsA("vtkAbstractVolumeMapper"),
              "vtkVolumeSplatMapper is a vtkAbstractVolumeMapper")

    mapper = servermanager._getPyProxy(smproxy)

    settings = ["OrderingMode", "FootprintFilter", "BlendThreshold", "Cutoff", "Backend",
                "CovarianceArrayName",
                "ScaleArrayName", "RotationArrayName", "ColorArrayName", "OpacityArrayName",
                "SphericalHarmonicsArrayName", "MaximumSphericalHarmonicsDegree"]
    counts = ["NumberOfKernels", "NumberOfTransparentKernels", "NumberOfInvalidKernels",
              "NumberOfProjectedKernels", "NumberOfNearPlaneKernels",
              "NumberOfFrustumCulledKernels", "NumberOfSorts", "NumberOfListBuilds",
              "LastRenderTimeInMilliseconds"]
    statistics = counts + ["LastBackend"]
    for name in settings:
        prop = smproxy.GetProperty(name)
        check(prop is not None and not prop.GetInformationOnly(),
              "volume property %s exists and is settable" % name)
        info = smproxy.GetProperty(name + "Info")
        check(info is not None and info.GetInformationOnly(),
              "volume information property %sInfo exists" % name)
        check(prop is not None and prop.GetInformationProperty() is not None
              and prop.GetInformationProperty() == info,
              "volume %s reads back through %sInfo" % (name, name))
    for name in statistics:
        prop = smproxy.GetProperty(name)
        check(prop is not None and prop.GetInformationOnly(),
              "volume statistic %s is an information-only property" % name)

    # Defaults, as the VTK object reports them after the XML's defaults are pushed.
    smproxy.UpdateVTKObjects()
    expected_entries = {
        "OrderingMode": {"Automatic": 4, "Blended": 0, "Clipped": 1, "SingleAxis": 2,
                         "DepthSorted": 3},
        "FootprintFilter": {"Automatic": 3, "LowPass": 0, "Dilation": 1, "Antialiased": 2,
                            "BandLimit": 4},
        "Backend": {"Auto": 0, "CPU": 1, "OpenGL": 2},
    }
    check_defaults_and_enumerations(
        smproxy, mapper, "volume ",
        {"OrderingMode": 4, "FootprintFilter": 3, "BlendThreshold": 0.85, "Cutoff": 4.5,
         "Backend": 0,
         "CovarianceArrayName": "Covariance", "ScaleArrayName": "Scale",
         "RotationArrayName": "Rotation", "ColorArrayName": "Color",
         "OpacityArrayName": "Opacity", "SphericalHarmonicsArrayName": "SphericalHarmonics",
         "MaximumSphericalHarmonicsDegree": 3},
        expected_entries, {"OrderingMode": "Automatic", "FootprintFilter": "Automatic",
                           "Backend": "Auto"})
    check_domain_range(smproxy, "BlendThreshold", "vtkSMDoubleRangeDomain", 0.0, 0.99)
    check_domain_range(smproxy, "Cutoff", "vtkSMDoubleRangeDomain", 0.001, 50.0)
    check_domain_range(smproxy, "MaximumSphericalHarmonicsDegree", "vtkSMIntRangeDomain", 0, 3)

    # Round trips: proxy property -> VTK object -> information property.
    values = {"BlendThreshold": 0.5, "Cutoff": 2.0, "MaximumSphericalHarmonicsDegree": 1}
    strings = {"CovarianceArrayName": "Sigma", "ScaleArrayName": "Scales",
               "RotationArrayName": "Quaternion", "ColorArrayName": "RGB",
               "OpacityArrayName": "Alpha", "SphericalHarmonicsArrayName": "SH"}
    for name, value in list(values.items()) + list(strings.items()):
        setattr(mapper, name, value)
    mapper.OrderingMode = "Clipped"
    mapper.FootprintFilter = "BandLimit"
    mapper.Backend = "OpenGL"
    smproxy.UpdateVTKObjects()
    values["OrderingMode"] = 1
    values["FootprintFilter"] = 4
    values["Backend"] = 2
    for name, value in values.items():
        got = info_value(smproxy, name + "Info")
        check(close(got, value), "volume %s round-trips (set %g, got %s)" % (name, value, got))
    for name, value in strings.items():
        got = info_value(smproxy, name + "Info")
        check(got == value, "volume %s round-trips (set %r, got %r)" % (name, value, got))

    # Every other enumeration value, and other numbers.
    for mode, backend, threshold, cutoff in (("SingleAxis", "CPU", 0.99, 8.0),
                                             ("DepthSorted", "Auto", 0.0, 4.5),
                                             ("Blended", "CPU", 0.85, 0.001)):
        mapper.OrderingMode = mode
        mapper.Backend = backend
        mapper.BlendThreshold = threshold
        mapper.Cutoff = cutoff
        smproxy.UpdateVTKObjects()
        expected = {"OrderingMode": expected_entries["OrderingMode"][mode],
                    "Backend": expected_entries["Backend"][backend],
                    "BlendThreshold": threshold, "Cutoff": cutoff}
        for name, value in expected.items():
            got = info_value(smproxy, name + "Info")
            check(close(got, value), "volume %s round-trips (set %g, got %s)"
                  % (name, value, got))
        check(mapper.OrderingMode == mode, "OrderingMode reads as %r (got %r)"
              % (mode, mapper.OrderingMode))

    # Render statistics are exposed before any render: the counts are 0 (the mapper has no
    # input), LastBackend is Auto (0): no backend drew yet.
    for name in counts:
        got = info_value(smproxy, name)
        check(got == 0, "volume %s is 0 before a render (got %s)" % (name, got))
    got = info_value(smproxy, "LastBackend")
    check(got == 0, "volume LastBackend before a render is 0 (got %s)" % (got,))


def test_surfel_generator(simple, servermanager):
    check("SurfelGenerator" in dir(simple) or "SurfelGenerator" in globals(),
          "SurfelGenerator is a paraview.simple function after LoadPlugin")
    make = globals().get("SurfelGenerator") or getattr(simple, "SurfelGenerator", None)
    if make is None:
        return

    sphere = simple.Sphere(ThetaResolution=32, PhiResolution=16, Radius=1.0)
    surfels = make(Input=sphere)
    check(surfels.GetXMLName() == "SurfelGenerator", "filter proxy XML name")
    check(surfels.SMProxy.GetXMLGroup() == "filters", "filter proxy is in the filters group")
    check(surfels.NumberOfNeighbors == 6, "default NumberOfNeighbors is 6")
    surfels.NumberOfNeighbors = 8
    surfels.UpdatePipeline()

    expected = sphere.GetDataInformation().GetNumberOfPoints()
    info = surfels.GetDataInformation()
    npts = info.GetNumberOfPoints()
    check(npts > 0, "SurfelGenerator produces points (%d)" % npts)
    check(npts == expected, "one surfel per input point (%d vs %d)" % (npts, expected))
    check(info.GetDataSetTypeAsString() == "vtkPolyData",
          "output is vtkPolyData (got %s)" % info.GetDataSetTypeAsString())

    point_arrays = surfels.PointData
    names = point_arrays.keys()
    check("Radius" in names, "output has the Radius array (arrays: %s)" % ", ".join(names))
    if "Radius" in names:
        lo, hi = point_arrays["Radius"].GetRange()
        check(lo > 0.0 and math.isfinite(hi), "radii are positive and finite [%g, %g]" % (lo, hi))
    check("Normals" in names and point_arrays["Normals"].GetNumberOfComponents() == 3,
          "output has 3-component point Normals")

    # The data as the client gets it.
    data = servermanager.Fetch(surfels)
    check(data is not None and data.GetNumberOfPoints() == npts, "fetched output has the points")
    if data is not None:
        check(data.GetPointData().GetNormals() is not None, "fetched output has normals set")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--plugin", required=True, help="path of SplatPlugin.so")
    args = parser.parse_args()

    if not load_plugin(args.plugin, globals()):
        return 1
    from paraview import simple, servermanager
    return run_tests((lambda: test_mapper(servermanager),
                      lambda: test_volume_mapper(servermanager),
                      lambda: test_surfel_generator(simple, servermanager)))


if __name__ == "__main__":
    sys.exit(main())

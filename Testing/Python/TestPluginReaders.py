"""Plugin test, run by pvpython: the Splat readers through ParaView's reader factory (File > Open,
OpenDataFile) and their proxies, and the Splat filters and sources in their menus.

    pvpython TestPluginReaders.py --plugin PATH/SplatPlugin.so \
        --vdb-writer PATH/splat_write_test_vdb [--capture-tools NPM_PREFIX]

Every file is written by the test in a temporary directory: the .vdb by splat_write_test_vdb
(SplatWriteTestVdb.cxx: Debian has no OpenVDB Python module), the PLY and .splat files here.
Checks that
- OpenDataFile picks Splat OpenVDB Reader for a .vdb; its GridName drop-down lists the file's
  supported grids (not the bool grid), defaults to the first, and selects what is read: the fog
  grid's 24 voxel kernels and one tile's TileSubdivision^3 kernels with Covariance, SampleVolume
  and the values (VoxelIndex while the tile is its voxels, TileSubdivision 8), the level
  set's surfels with Normals and SurfelRadiusScale x voxel size radii,
  the point grid's 5 points and their attribute; ProduceDenseOutput and DenseIndexBounds give
  the 4 x 3 x 2 image of the fog's values on port 1; the fog's kernels have a vertex cell each,
  so that Surface draws them; Show picks Volume Splats for the fog (unless given a
  representation), with the white color map and the opacity of splat_render's first view of a
  fog from the reader's DensityStatistics, and Surface for the level set;
- the reader sends progress events from 0 to 1 and ParaView's progress handler (what the
  progress bar shows) relays them;
- a truncated .vdb and a text file named .vdb give an error naming the file and empty output;
- OpenDataFile picks Gaussian Splat Reader for a 3D Gaussian Splatting .ply (and for .splat;
  with --capture-tools, for the .spz, .sog and its meta.json, glTF and compressed .ply that
  splat-transform converts the capture to), and its File > Open lines name each format,
  with the Scale, Rotation, Opacity and Color arrays decoded, and Show picking Volume Splats
  for it (the reader's hint: a capture has no cells), and ParaView's PLY Reader for a
  PLY mesh, which Gaussian Splat Reader declines; Splat PLY Reader, created explicitly, reads the
  mesh; a truncated capture and a truncated mesh give errors naming the file, not crashes;
- every class of the SplatFilters and SplatOpenVDB modules has a proxy, the filter and the
  source under the Splat category of their menus, and the Surfel Sphere source runs.
Any failure exits non-zero.
"""

import argparse
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time

from splat_checks import check, info_value, load_plugin, run_tests


def close(a, b, tol=1e-5):
    return a is not None and b is not None and math.isclose(a, b, rel_tol=tol, abs_tol=tol)


def close_range(got, low, high, tol=1e-5):
    return got is not None and close(got[0], low, tol) and close(got[1], high, tol)


class Errors:
    """Collects the error messages a proxy's VTK object reports (vtkErrorMacro sends them to
    its ErrorEvent observers)."""

    def __init__(self, proxy):
        from vtkmodules.util.misc import calldata_type
        from vtkmodules.util.vtkConstants import VTK_STRING
        self.messages = []

        @calldata_type(VTK_STRING)
        def on_error(obj, event, message):
            self.messages.append(message)
        self.callback = on_error  # kept alive as long as the observer
        proxy.GetClientSideObject().AddObserver("ErrorEvent", on_error)

    def naming(self, path):
        return [m for m in self.messages if path in m]


def point_count(proxy, port=0):
    return proxy.GetDataInformation(port).GetNumberOfPoints()


def array_range(proxy, name, component=0):
    array = proxy.PointData[name] if name in proxy.PointData.keys() else None
    return array.GetRange(component) if array is not None else None


def factory_choice(servermanager, path):
    """(group, name) of the reader OpenDataFile would create, and the names of all the readers
    the GUI would offer for the file."""
    session = servermanager.ActiveConnection.Session
    factory = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
    choice = None
    if factory.CanReadFile(path, session):
        choice = (factory.GetReaderGroup(), factory.GetReaderName())
    readers = factory.GetReaders(path, session)
    names = [readers.GetString(i) for i in range(1, readers.GetLength(), 3)]
    return choice, names


def reader_accepts(servermanager, path, name):
    """The reader proxy's own answer (its class's CanReadFile), as the factory asks it."""
    session = servermanager.ActiveConnection.Session
    factory = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
    return factory.CanReadFile(path, "sources", name, session)


# -- OpenVDB ----------------------------------------------------------------------------------
def shown_as(simple, reader, **properties):
    """The representation Show gives the reader's output in a new render view."""
    view = simple.CreateRenderView()
    display = simple.Show(reader, view, **properties)
    representation = display.Representation
    simple.Delete(display)
    simple.Delete(view)
    return representation


def fog_statistics(reader):
    """The mean and largest positive density and their kernels' volume, from the data."""
    data = reader.GetClientSideObject().GetOutputDataObject(0)
    densities = data.GetPointData().GetScalars()
    volumes = data.GetPointData().GetArray("SampleVolume")
    positive = [(densities.GetValue(i), volumes.GetValue(i))
                for i in range(data.GetNumberOfPoints()) if densities.GetValue(i) > 0]
    return (sum(d for d, _ in positive) / len(positive), max(d for d, _ in positive),
            sum(v for _, v in positive))


def first_view_of_fog(simple, reader):
    """Fog kernels come with one vertex cell each, so that Surface draws them; Show picks Volume
    Splats for them (their Covariance array: vtkSMVolumeSplatInitializationHelper) unless told
    otherwise, with splat_render's first view of a fog (SplatFogOpacity.h): from the reader's
    DensityStatistics, a white color map over 0 to the largest density that is never rescaled,
    alpha 1 - exp(-tau u) with tau = 2 d / (mean cbrt(V)) at densities d from 0, and the unit
    distance u = cbrt(V) / 100."""
    cells = reader.GetDataInformation().GetNumberOfCells()
    check(cells == point_count(reader),
          "fog: one vertex cell per kernel (%d cells, %d kernels)" % (cells, point_count(reader)))
    picked = shown_as(simple, reader, Representation="Surface")
    check(picked == "Surface", "fog: Show with Representation='Surface' keeps it (got %s)" % picked)
    mean, largest, volume = fog_statistics(reader)
    given = reader.GetClientSideObject().GetOutputDataObject(0).GetFieldData().GetArray(
        "DensityStatistics")
    check(given is not None and all(close(a, b) for a, b in zip(given.GetTuple(0),
                                                                (mean, largest, volume))),
          "fog: the reader's DensityStatistics are (%g, %g, %g) (got %s)"
          % (mean, largest, volume, given.GetTuple(0) if given else None))
    view = simple.CreateRenderView()
    display = simple.Show(reader, view)
    check(display.Representation == "Volume Splats",
          "fog: Show picks Volume Splats (got %s)" % display.Representation)
    check(list(display.ColorArrayName) == ["POINTS", "density"],
          "fog: colored by its densities (got %s)" % list(display.ColorArrayName))
    unit = volume ** (1 / 3) / 100
    check(close(display.ScalarOpacityUnitDistance, unit, 1e-6),
          "fog: opacity unit distance cbrt(V) / 100 = %g (got %g)"
          % (unit, display.ScalarOpacityUnitDistance))
    lut = simple.GetColorTransferFunction("density")
    rgb = list(lut.RGBPoints)
    check(rgb[0::4] == [0.0, largest] and set(rgb[1::4] + rgb[2::4] + rgb[3::4]) == {1.0},
          "fog: a white color map over 0..%g (got %s)" % (largest, rgb))
    check(lut.AutomaticRescaleRangeMode == "Never",
          "fog: the color map is never rescaled (got %s)" % lut.AutomaticRescaleRangeMode)
    points = list(simple.GetOpacityTransferFunction("density").Points)
    expected = [(largest * i / 32, 1 - math.exp(-2 * largest * i / 32 / (mean * 100)))
                for i in range(33)]
    got = list(zip(points[0::4], points[1::4]))
    check(len(got) == 33 and all(close(x, ex) and close(a, ea) for (x, a), (ex, ea)
                                 in zip(got, expected)),
          "fog: alpha 1 - exp(-2 d / (100 mean)) at 33 densities 0..%g (got %s)" % (largest, got))
    simple.Delete(display)
    simple.Delete(view)


def test_vdb(simple, servermanager, writer, tmp):
    path = os.path.join(tmp, "scene.vdb")
    result = subprocess.run([writer, path], capture_output=True, text=True)
    if not check(result.returncode == 0 and os.path.isfile(path),
                 "splat_write_test_vdb wrote %s %s" % (path, result.stderr.strip())):
        return

    choice, _ = factory_choice(servermanager, path)
    check(choice == ("sources", "SplatOpenVDBReader"),
          "the reader factory picks SplatOpenVDBReader for .vdb (got %s)" % (choice,))
    reader = simple.OpenDataFile(path)
    check(reader.GetXMLName() == "SplatOpenVDBReader",
          "OpenDataFile creates SplatOpenVDBReader (got %s)" % reader.GetXMLName())

    # The drop-down: the supported grids in the reader's listing order; "mask" (bool) is left out.
    domain = reader.GetProperty("GridName").FindDomain("vtkSMStringListDomain")
    grids = [domain.GetString(i) for i in range(domain.GetNumberOfStrings())] if domain else []
    check(grids == ["cloud", "density", "surface"],
          "GridName lists the supported grids (got %s)" % grids)
    check(reader.GridName == "cloud", "GridName defaults to the first (got %r)" % reader.GridName)

    # The point data grid.
    reader.UpdatePipeline()
    check(point_count(reader) == 5, "grid 'cloud': 5 points (got %d)" % point_count(reader))
    check(close_range(array_range(reader, "height"), 0.0, 2.0),
          "grid 'cloud': attribute 'height' spans 0..2 (got %s)" % (array_range(reader, "height"),))

    # The fog volume: 24 voxel kernels and one 8^3 tile, by default as its voxels (a lattice:
    # VoxelIndex), or as TileSubdivision^3 kernels.
    reader.GridName = "density"
    reader.UpdatePipeline()
    check(point_count(reader) == 24 + 8 ** 3,
          "grid 'density': 24 voxel + 8^3 tile voxel kernels (got %d)" % point_count(reader))
    arrays = reader.PointData.keys()
    for name in ("Covariance", "SampleVolume", "density", "VoxelIndex"):
        check(name in arrays, "grid 'density': array %s (arrays %s)" % (name, arrays))
    check(close_range(array_range(reader, "density"), 1.0, 12.0),
          "grid 'density': values 1..12 (got %s)" % (array_range(reader, "density"),))
    check(info_value(reader.SMProxy, "NumberOfVoxelKernels") == 24
          and info_value(reader.SMProxy, "NumberOfTiles") == 1,
          "the reader's statistics: 24 voxel kernels, 1 tile")
    first_view_of_fog(simple, reader)
    reader.TileSubdivision = 3
    reader.UpdatePipeline()
    check(point_count(reader) == 24 + 27,
          "TileSubdivision 3: 24 + 3^3 kernels (got %d)" % point_count(reader))
    check("VoxelIndex" not in reader.PointData.keys(),
          "TileSubdivision 3: kernels off the lattice, no VoxelIndex")
    check(info_value(reader.SMProxy, "NumberOfTileKernels") == 27,
          "NumberOfTileKernels is 27 (got %s)" % info_value(reader.SMProxy, "NumberOfTileKernels"))

    # The level set: surfels of radius SurfelRadiusScale x voxel size (0.1).
    reader.GridName = "surface"
    reader.SurfelRadiusScale = 2.0
    reader.UpdatePipeline()
    check(point_count(reader) > 100, "grid 'surface': surfels (%d)" % point_count(reader))
    check("Normals" in reader.PointData.keys(), "grid 'surface': Normals")
    check(close_range(array_range(reader, "Radius"), 0.2, 0.2),
          "SurfelRadiusScale 2: radius 0.2 (got %s)" % (array_range(reader, "Radius"),))
    picked = shown_as(simple, reader)
    check(picked == "Surface", "grid 'surface': Show picks Surface (got %s)" % picked)

    # The dense image on port 1.
    reader.GridName = "density"
    reader.ProduceDenseOutput = 1
    reader.DenseIndexBounds = [0, 3, 0, 2, 0, 1]
    reader.UpdatePipeline()
    dense = reader.GetDataInformation(1)
    check(dense.GetNumberOfPoints() == 24,
          "dense output: 4 x 3 x 2 voxels (got %d)" % dense.GetNumberOfPoints())
    image = reader.GetClientSideObject().GetOutputDataObject(1)
    scalars = image.GetPointData().GetScalars() if image is not None else None
    check(scalars is not None and close_range(scalars.GetRange(), 1.0, 12.0),
          "dense output: the fog's values 1..12 (got %s)"
          % (scalars.GetRange() if scalars is not None else None,))
    check(reader.SMProxy.GetOutputPortName(1) == "Dense Image",
          "port 1 is named 'Dense Image' (got %s)" % reader.SMProxy.GetOutputPortName(1))

    # Progress: the reader's VTK object sends progress events from 0 to 1, and the session's
    # progress handler relays them, named after the reader, to what draws ParaView's progress
    # bar (at most one per ProgressInterval, at least 10 ms: this fast read may relay only the
    # first, so that one must come an interval after the last relayed event).
    values = []
    vtk_reader = reader.GetClientSideObject()
    vtk_observer = vtk_reader.AddObserver(
        "ProgressEvent", lambda obj, event: values.append(obj.GetProgress()))
    handler = servermanager.ActiveConnection.Session.GetProgressHandler()
    relayed = []

    def on_relayed(obj, event):
        relayed.append((obj.GetLastProgressText(), obj.GetLastProgress()))
    observer = handler.AddObserver("ProgressEvent", on_relayed)
    handler.SetProgressInterval(0.01)
    time.sleep(0.05)
    reader.GridName = "surface"
    reader.UpdatePipeline()
    handler.RemoveObserver(observer)
    vtk_reader.RemoveObserver(vtk_observer)
    check(len(values) >= 3 and values[0] == 0.0 and values[-1] == 1.0
          and any(0.0 < v < 1.0 for v in values),
          "the reader sends progress events from 0 through 1 (got %s)" % values)
    check(any(text and "vtkOpenVDBReader" in text for text, _ in relayed),
          "the progress handler relays the reader's progress (got %s)" % relayed)

    # Damaged files: an error naming the file, an empty output, no crash.
    good = open(path, "rb").read()
    truncated = os.path.join(tmp, "truncated.vdb")
    with open(truncated, "wb") as f:
        f.write(good[:len(good) // 3])
    text = os.path.join(tmp, "text.vdb")
    with open(text, "w") as f:
        f.write("not an OpenVDB file\n" * 20)
    for damaged in (truncated, text):
        bad = simple.OpenDataFile(damaged)
        check(bad.GetXMLName() == "SplatOpenVDBReader",
              "%s: opened with SplatOpenVDBReader" % os.path.basename(damaged))
        errors = Errors(bad)
        bad.UpdatePipeline()
        check(errors.naming(damaged), "%s: an error naming the file (got %s)"
              % (os.path.basename(damaged), errors.messages))
        check(point_count(bad) == 0, "%s: empty output" % os.path.basename(damaged))
        simple.Delete(bad)
    simple.Delete(reader)


# -- 3D Gaussian Splatting and PLY --------------------------------------------------------------
CAPTURE_PROPERTIES = (["x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2", "opacity"]
                      + ["scale_%d" % i for i in range(3)] + ["rot_%d" % i for i in range(4)])


def write_capture(path, count):
    """A binary 3DGS capture in the INRIA layout: vertex i at (i, 0, 0), base color 0.5 (f_dc 0),
    opacity 0.8 (logit), scales 0.1 (i + 1) (logarithms), rotation (2, 0, 0, 0) (normalized to
    the identity on reading)."""
    header = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % count
    header += "".join("property float %s\n" % name for name in CAPTURE_PROPERTIES)
    header += "end_header\n"
    body = b""
    for i in range(count):
        scale = math.log(0.1 * (i + 1))
        values = [i, 0, 0, 0, 0, 1, 0, 0, 0, math.log(0.8 / 0.2), scale, scale, scale, 2, 0, 0, 0]
        body += struct.pack("<%df" % len(values), *values)
    with open(path, "wb") as f:
        f.write(header.encode("ascii") + body)


def write_splat(path, count):
    """The antimatter15 .splat layout: 32-byte records of position, linear scale (0.2), RGBA
    bytes (opacity 204/255 = 0.8) and rotation bytes ((q + 1) 128, the identity)."""
    with open(path, "wb") as f:
        for i in range(count):
            f.write(struct.pack("<3f3f4B4B", i, 0, 0, 0.2, 0.2, 0.2, 255, 0, 0, 204,
                                255, 128, 128, 128))


def write_mesh(path):
    """An ascii PLY mesh: a unit square (4 vertices with colors, 1 quad)."""
    with open(path, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                "0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 255 255 255\n4 0 1 2 3\n")


def truncate(path, keep_fraction, out):
    data = open(path, "rb").read()
    with open(out, "wb") as f:
        f.write(data[:int(len(data) * keep_fraction)])


def test_gaussian_splats(simple, servermanager, tmp):
    capture = os.path.join(tmp, "capture.ply")
    write_capture(capture, 4)
    choice, offered = factory_choice(servermanager, capture)
    check(choice == ("sources", "GaussianSplatReader"),
          "the reader factory picks GaussianSplatReader for a 3DGS .ply (got %s)" % (choice,))
    # Only one reader accepts it, so the GUI opens it without the Open Data With... question.
    check(offered == ["GaussianSplatReader"],
          "the GUI offers GaussianSplatReader alone for a 3DGS .ply (got %s)" % offered)
    reader = simple.OpenDataFile(capture)
    check(reader.GetXMLName() == "GaussianSplatReader",
          "OpenDataFile creates GaussianSplatReader (got %s)" % reader.GetXMLName())
    # Progress events of the reader's own VTK object.
    progress = []
    vtk_reader = reader.GetClientSideObject()
    vtk_reader.AddObserver("ProgressEvent", lambda obj, event: progress.append(obj.GetProgress()))
    reader.UpdatePipeline()
    check(point_count(reader) == 4, "capture: 4 Gaussians (got %d)" % point_count(reader))
    check(len(progress) >= 2 and progress[-1] == 1.0,
          "GaussianSplatReader sends progress events up to 1 (got %s)" % progress)
    expected = {"Opacity": (0.8, 0.8), "Color": (0.5, 0.5), "Scale": (0.1, 0.4),
                "Rotation": (1.0, 1.0)}
    for name, (low, high) in expected.items():
        got = array_range(reader, name)
        check(close_range(got, low, high), "capture: %s spans %g..%g (got %s)"
              % (name, low, high, got))
    check(info_value(reader.SMProxy, "SphericalHarmonicsDegree") == 0,
          "capture: spherical harmonics degree 0")
    # Captures have no cells: Show picks Volume Splats (the reader's hint), not Surface.
    view = simple.CreateRenderView()
    display = simple.Show(reader, view)
    check(display.Representation == "Volume Splats",
          "capture: Show picks Volume Splats (got %s)" % display.Representation)
    simple.Delete(display)
    simple.Delete(view)

    splat = os.path.join(tmp, "capture.splat")
    write_splat(splat, 3)
    choice, _ = factory_choice(servermanager, splat)
    check(choice == ("sources", "GaussianSplatReader"),
          "the reader factory picks GaussianSplatReader for .splat (got %s)" % (choice,))
    splats = simple.OpenDataFile(splat)
    splats.UpdatePipeline()
    check(point_count(splats) == 3, ".splat: 3 Gaussians (got %d)" % point_count(splats))
    check(close_range(array_range(splats, "Scale"), 0.2, 0.2)
          and close_range(array_range(splats, "Opacity"), 0.8, 0.8),
          ".splat: scale 0.2, opacity 0.8 (got %s, %s)"
          % (array_range(splats, "Scale"), array_range(splats, "Opacity")))

    # A PLY mesh: Gaussian Splat Reader declines it, ParaView's PLY Reader is OpenDataFile's
    # choice, Splat PLY Reader reads it when asked for.
    mesh = os.path.join(tmp, "mesh.ply")
    write_mesh(mesh)
    choice, offered = factory_choice(servermanager, mesh)
    check(not reader_accepts(servermanager, mesh, "GaussianSplatReader"),
          "GaussianSplatReader declines a PLY mesh")
    check(reader_accepts(servermanager, mesh, "SplatPLYReader"),
          "SplatPLYReader accepts a PLY mesh")
    check(choice == ("sources", "PLYReader"),
          "the reader factory picks ParaView's PLYReader for a PLY mesh (got %s)" % (choice,))
    check(sorted(offered) == ["PLYReader", "SplatPLYReader"],
          "the GUI offers PLYReader and SplatPLYReader for a mesh (got %s)" % offered)
    # ParaView's PLY Reader, on the plugin's core, still reads meshes.
    paraview_ply = simple.PLYReader(FileNames=[mesh])
    paraview_ply.UpdatePipeline()
    check(point_count(paraview_ply) == 4
          and paraview_ply.GetDataInformation().GetNumberOfCells() == 1,
          "PLYReader on the plugin's core: 4 points, 1 polygon (got %d points)"
          % point_count(paraview_ply))
    simple.Delete(paraview_ply)
    ply = globals()["SplatPLYReader"](FileName=mesh)
    ply.UpdatePipeline()
    info = ply.GetDataInformation()
    check(info.GetNumberOfPoints() == 4 and info.GetNumberOfCells() == 1,
          "SplatPLYReader: 4 points, 1 polygon (got %d, %d)"
          % (info.GetNumberOfPoints(), info.GetNumberOfCells()))
    check("RGB" in ply.PointData.keys(), "SplatPLYReader: RGB colors (%s)" % ply.PointData.keys())

    # Truncated files: errors naming the file, empty outputs.
    for source, make, name in ((capture, "GaussianSplatReader", "capture-cut.ply"),
                               (mesh, "SplatPLYReader", "mesh-cut.ply")):
        cut = os.path.join(tmp, name)
        truncate(source, 0.9, cut)
        bad = globals()[make](FileName=cut)
        errors = Errors(bad)
        bad.UpdatePipeline()
        check(errors.naming(cut), "%s on %s: an error naming the file (got %s)"
              % (make, name, errors.messages))
        check(point_count(bad) == 0, "%s on %s: empty output" % (make, name))
        simple.Delete(bad)
    for proxy in (ply, splats, reader):
        simple.Delete(proxy)


def test_capture_formats(simple, servermanager, tools, tmp):
    """The compressed formats, converted from the 4-Gaussian capture by splat-transform when it is
    installed: each opens with Gaussian Splat Reader and reads the 4 Gaussians."""
    st = os.path.join(tools or "", "node_modules", ".bin", "splat-transform")
    if not os.path.isfile(st) or shutil.which("node") is None:
        print("the capture converters or Node.js are absent (%s): formats not tested" % tools)
        return
    capture = os.path.join(tmp, "formats.ply")
    write_capture(capture, 4)
    folder = os.path.join(tmp, "sog-folder")
    os.makedirs(folder, exist_ok=True)
    formats = ("capture.spz", "capture.compressed.ply", "capture.sog",
               os.path.join("sog-folder", "meta.json"), "capture.glb")
    proxy = "GaussianSplatReader"
    for name in formats:
        path = os.path.join(tmp, name)
        result = subprocess.run([st, "-q", "-w", "-g", "cpu", capture, path],
                                capture_output=True, text=True)
        if not check(result.returncode == 0, "splat-transform wrote %s %s"
                     % (name, result.stderr.strip()[-300:])):
            continue
        choice, _ = factory_choice(servermanager, path)
        check(choice == ("sources", proxy),
              "the reader factory picks %s for %s (got %s)" % (proxy, name, choice))
        reader = simple.OpenDataFile(path)
        reader.UpdatePipeline()
        check(point_count(reader) == 4, "%s: 4 Gaussians (got %d)" % (name, point_count(reader)))
        check(close_range(array_range(reader, "Opacity"), 0.8, 0.8, 0.01),
              "%s: opacity 0.8 (got %s)" % (name, array_range(reader, "Opacity")))
        simple.Delete(reader)


# -- Menus --------------------------------------------------------------------------------------
def test_menus(simple, servermanager):
    pxm = servermanager.ProxyManager().SMProxyManager
    definitions = pxm.GetProxyDefinitionManager()
    expected = {"vtkSurfelGenerator": ("filters", "SurfelGenerator"),
                "vtkSurfelSphereSource": ("sources", "SurfelSphereSource"),
                "vtkGaussianSplatReader": ("sources", "GaussianSplatReader"),
                "vtkSplatPLYReader": ("sources", "SplatPLYReader"),
                "vtkOpenVDBReader": ("sources", "SplatOpenVDBReader")}
    for cls, (group, name) in expected.items():
        definition = definitions.GetProxyDefinition(group, name)
        check(definition is not None and definition.GetAttribute("class") == cls,
              "%s/%s is the proxy of %s" % (group, name, cls))
    for group, name in (("filters", "SurfelGenerator"), ("sources", "SurfelSphereSource")):
        hints = pxm.GetProxyHints(group, name)
        menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
        check(menu is not None and menu.GetAttribute("category") == "Splat",
              "%s/%s is in the Splat category of its menu" % (group, name))
    for name in ("GaussianSplatReader", "SplatPLYReader", "SplatOpenVDBReader"):
        hints = pxm.GetProxyHints("sources", name)
        check(hints is not None and hints.FindNestedElementByName("ReaderFactory") is not None,
              "%s is in File > Open" % name)
    # Gaussian Splat Reader: a File > Open line per capture format.
    hints = pxm.GetProxyHints("sources", "GaussianSplatReader")
    lines = [hints.GetNestedElement(i) for i in range(hints.GetNumberOfNestedElements())]
    extensions = [e.GetAttribute("extensions") for e in lines if e.GetName() == "ReaderFactory"]
    check(extensions == ["ply", "spz", "sog", "ksplat", "splat", "glb gltf"],
          "Gaussian Splat Reader has a File > Open line per format (got %s)" % extensions)

    sphere = globals()["SurfelSphere"](NumberOfPoints=500, Radius=2.0)
    sphere.UpdatePipeline()
    check(point_count(sphere) == 500, "Surfel Sphere: 500 points (got %d)" % point_count(sphere))
    spacing = math.sqrt(4 * math.pi * 4.0 / 500)
    check(close_range(array_range(sphere, "Radius"), spacing, spacing),
          "Surfel Sphere: radius %g (got %s)" % (spacing, array_range(sphere, "Radius")))
    check("Normals" in sphere.PointData.keys(), "Surfel Sphere: Normals")
    simple.Delete(sphere)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--plugin", required=True, help="path of SplatPlugin.so")
    parser.add_argument("--vdb-writer", required=True, help="path of splat_write_test_vdb")
    parser.add_argument("--capture-tools", help="npm prefix of splat-transform (scripts/setup.sh)")
    args = parser.parse_args()

    if not load_plugin(args.plugin, globals()):
        return 1
    from paraview import simple, servermanager
    with tempfile.TemporaryDirectory(prefix="splat-readers-") as tmp:
        return run_tests((lambda: test_vdb(simple, servermanager, args.vdb_writer, tmp),
                          lambda: test_gaussian_splats(simple, servermanager, tmp),
                          lambda: test_capture_formats(simple, servermanager,
                                                       args.capture_tools, tmp),
                          lambda: test_menus(simple, servermanager)))


if __name__ == "__main__":
    sys.exit(main())

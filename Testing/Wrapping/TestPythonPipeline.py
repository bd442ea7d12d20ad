"""The Python front door, in Debian's /usr/bin/python3 with Debian's VTK: the wrapped pipeline
(Examples/surface_splat_pipeline.py) renders a non-trivial image equal to the C++ pipeline's
(surface_splat_pipeline) on the same PLY, the volume example (Examples/volume_splat_pipeline.py)
renders VTK's wavelet, a capture written by vtkGaussianSplatWriter reads back through
vtkGaussianSplatReader, and a fresh interpreter still imports `vtk`.

    TestPythonPipeline.py --example surface_splat_pipeline.py --cxx-pipeline EXE
                          --volume-example volume_splat_pipeline.py --output DIR

Exits 125 (skipped) when this interpreter cannot import vtkmodules.
"""
import argparse
import importlib.util
import os
import subprocess
import sys

try:
    import vtkmodules.vtkCommonCore  # noqa: F401
except ImportError as error:
    print("skipped: %s cannot import vtkmodules: %s" % (sys.executable, error))
    sys.exit(125)

from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOPLY import vtkPLYWriter
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData

from splat import vtkGaussianSplatReader, vtkGaussianSplatWriter, vtkSplatBackend

failures = []


def check(condition, message):
    print("%s %s" % ("ok  " if condition else "FAIL", message), flush=True)
    if not condition:
        failures.append(message)


def load(path, name):
    """The example program at path, imported as a module."""
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def coverage(pixels, components):
    """The number of pixels that are not black, and the set of their distinct colors."""
    covered = 0
    colors = set()
    for i in range(0, len(pixels), components):
        rgb = pixels[i:i + 3]
        if any(rgb):
            covered += 1
            colors.add(rgb)
    return covered, colors


def read_rgb(path):
    """The PNG's pixels as (width, height, bytes of RGB or RGBA, components)."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    width, height, _ = image.GetDimensions()
    return width, height, bytes(memoryview(scalars)), scalars.GetNumberOfComponents()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--example", required=True)
    parser.add_argument("--cxx-pipeline", required=True)
    parser.add_argument("--volume-example", required=True)
    parser.add_argument("--output", required=True)
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)

    # The input: a triangulated sphere of 64 x 32 facets (1922 vertices) as a PLY file.
    ply = os.path.join(args.output, "TestPythonPipeline.ply")
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(64)
    sphere.SetPhiResolution(32)
    writer = vtkPLYWriter()
    writer.SetFileName(ply)
    writer.SetInputConnection(sphere.GetOutputPort())
    check(writer.Write() == 1, "wrote %s" % ply)
    points = sphere.GetOutput().GetNumberOfPoints()

    # The Python pipeline, imported from the example file.
    example = load(args.example, "surface_splat_pipeline")
    python_png = os.path.join(args.output, "TestPythonPipeline-python.png")
    mapper = example.render(ply, python_png)
    backend = mapper.GetLastBackend()
    check(backend in (vtkSplatBackend.CPU, vtkSplatBackend.OPENGL),
          "the wrapped mapper drew (backend %s)" % vtkSplatBackend.GetBackendAsString(backend))
    check(mapper.GetNumberOfSkippedPoints() in (0, -1),
          "no point skipped (%d)" % mapper.GetNumberOfSkippedPoints())
    if backend == vtkSplatBackend.CPU:
        # Measured: all 1922 drawn (no culling by default, the whole sphere in view).
        drawn = mapper.GetNumberOfRenderedSplats()
        check(drawn == points, "%d of %d splats drawn" % (drawn, points))

    width, height, pixels, components = read_rgb(python_png)
    check((width, height) == (800, 800), "the image is 800 x 800 (%d x %d)" % (width, height))
    covered, levels = coverage(pixels, components)
    fraction = covered / float(width * height)
    # Measured: 0.196 of the pixels covered (the disc of radius 200 pixels that ResetCamera
    # gives) and 204 distinct shades.
    check(0.15 < fraction < 0.25, "the sphere covers %.3f of the image" % fraction)
    check(len(levels) > 50, "%d distinct colors: the splats are shaded" % len(levels))

    # The C++ pipeline on the same file: the same code draws, so the same bytes.
    cxx_png = os.path.join(args.output, "TestPythonPipeline-cxx.png")
    status = subprocess.run([args.cxx_pipeline, ply, cxx_png]).returncode
    check(status == 0, "the C++ pipeline ran (exit %d)" % status)
    if status == 0:
        cxx = read_rgb(cxx_png)
        differing = sum(a != b for a, b in zip(pixels, cxx[2]))
        # Measured: 0 bytes differ (the bunny too).
        check(cxx[:2] == (width, height) and differing == 0,
              "Python and C++ images equal (%d bytes differ)" % differing)

    # The volume example on VTK's wavelet (21^3 voxels) as a .vti file.
    vti = os.path.join(args.output, "TestPythonPipeline.vti")
    wavelet = vtkRTAnalyticSource()
    wavelet.SetWholeExtent(-10, 10, -10, 10, -10, 10)
    image_writer = vtkXMLImageDataWriter()
    image_writer.SetFileName(vti)
    image_writer.SetInputConnection(wavelet.GetOutputPort())
    check(image_writer.Write() == 1, "wrote %s" % vti)
    volume_png = os.path.join(args.output, "TestPythonPipeline-volume.png")
    volume_mapper = load(args.volume_example, "volume_splat_pipeline").render(vti, volume_png)
    kernels = volume_mapper.GetNumberOfKernels()
    transparent = volume_mapper.GetNumberOfTransparentKernels()
    # Measured: 8785 kernels, 476 voxels left out as transparent (the lowest fifth of the range).
    check(kernels > 0 and kernels + transparent == 21 ** 3,
          "%d kernels and %d transparent voxels make the 21^3 grid" % (kernels, transparent))
    width, height, pixels, components = read_rgb(volume_png)
    covered, colors = coverage(pixels, components)
    fraction = covered / float(width * height)
    # Measured: 0.356 of the pixels covered (any non-black value), 904 distinct colors.
    check(0.1 < fraction < 0.9, "the wavelet covers %.3f of the image" % fraction)
    check(len(colors) > 50, "%d distinct colors in the volume" % len(colors))

    # A capture through the wrapped writer and reader: 3 Gaussians with degree-1 harmonics,
    # written as an INRIA .ply and read back to float precision.
    capture_path = os.path.join(args.output, "TestPythonPipeline-capture.ply")
    kernels = vtkPolyData()
    kernel_points = vtkPoints()
    arrays = {"Scale": 3, "Rotation": 4, "Opacity": 1, "SphericalHarmonics": 12}
    for name, components in arrays.items():
        array = vtkFloatArray()
        array.SetName(name)
        array.SetNumberOfComponents(components)
        kernels.GetPointData().AddArray(array)
    for i in range(3):
        kernel_points.InsertNextPoint(i, 0.5 * i, -i)
        data = kernels.GetPointData()
        data.GetArray("Scale").InsertNextTuple((0.1, 0.2, 0.05 * (i + 1)))
        data.GetArray("Rotation").InsertNextTuple((1, 0, 0, 0))
        data.GetArray("Opacity").InsertNextTuple((0.3 + 0.2 * i,))
        data.GetArray("SphericalHarmonics").InsertNextTuple([0.1 * (k - i) for k in range(12)])
    kernels.SetPoints(kernel_points)
    capture_writer = vtkGaussianSplatWriter()
    capture_writer.SetInputData(kernels)
    capture_writer.SetFileName(capture_path)
    check(capture_writer.Write() == 1, "vtkGaussianSplatWriter wrote %s" % capture_path)
    capture_reader = vtkGaussianSplatReader()
    capture_reader.SetFileName(capture_path)
    capture_reader.Update()
    back = capture_reader.GetOutput()
    check(back.GetNumberOfPoints() == 3 and capture_reader.GetSphericalHarmonicsDegree() == 1,
          "the capture reads back: %d Gaussians, SH degree %d"
          % (back.GetNumberOfPoints(), capture_reader.GetSphericalHarmonicsDegree()))
    if back.GetNumberOfPoints() == 3:
        worst = max(abs(a - b) for name in arrays for i in range(3)
                    for a, b in zip(kernels.GetPointData().GetArray(name).GetTuple(i),
                                    back.GetPointData().GetArray(name).GetTuple(i)))
        check(worst < 1e-6, "the capture's arrays read back within 1e-6 (%.2g)" % worst)

    # The system's own VTK Python still works: a fresh interpreter without this build's path.
    environment = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    result = subprocess.run(
        [sys.executable, "-c", "import vtk; print(vtk.vtkVersion.GetVTKVersion())"],
        env=environment, capture_output=True, text=True)
    check(result.returncode == 0, "%s -c 'import vtk' works afterwards: %s" % (
        sys.executable, (result.stdout or result.stderr).strip().splitlines()[-1:]))

    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())

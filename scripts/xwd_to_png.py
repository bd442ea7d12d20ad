"""Converts the screen dump `xwd -root` writes on Xvfb (ZPixmap, 4 bytes per pixel, BGRX) to a
PNG, with VTK's writer: xwd_to_png.py IN.xwd OUT.png."""
import struct
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter

data = open(sys.argv[1], "rb").read()
header = struct.unpack(">25I", data[:100])
size, width, height, byte_order, bytes_per_line, colors = (
    header[0], header[4], header[5], header[7], header[12], header[19])
if bytes_per_line < 4 * width or byte_order != 0:
    sys.exit("%s: not a 4-byte little-endian ZPixmap dump" % sys.argv[1])
start = size + 12 * colors
pixels = np.frombuffer(data[start:start + bytes_per_line * height], dtype=np.uint8)
rgb = pixels.reshape(height, bytes_per_line)[:, :4 * width].reshape(height, width, 4)[:, :, 2::-1]
image = vtkImageData()
image.SetDimensions(width, height, 1)
image.GetPointData().SetScalars(
    numpy_to_vtk(np.ascontiguousarray(rgb[::-1]).reshape(-1, 3), deep=True))
writer = vtkPNGWriter()
writer.SetFileName(sys.argv[2])
writer.SetInputData(image)
writer.Write()

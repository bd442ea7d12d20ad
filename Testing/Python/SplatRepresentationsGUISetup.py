"""Start-up script of the GUI test (paraview --script): the data and the camera.

Creates a Sphere (the first item of the Pipeline Browser) and a Wavelet (the second), shown as
ParaView shows them (Surface, Outline), and a camera that sees both side by side.
TestSplatRepresentationsGUI.xml then switches their representations in the toolbar.
"""

from paraview import simple

sphere = simple.Sphere(Center=[24.0, 0.0, 0.0], Radius=8.0, ThetaResolution=64,
                       PhiResolution=32)
simple.Show(sphere)
wavelet = simple.Wavelet()
simple.Show(wavelet)
view = simple.GetActiveViewOrCreate("RenderView")
view.OrientationAxesVisibility = 0
view.CameraPosition = [7.0, -90.0, 40.0]
view.CameraFocalPoint = [7.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.CameraViewAngle = 30.0
simple.Render(view)
